// Closed-form scattering (Hoffman & Preetham 2002): a homogeneous medium with
// Rayleigh and Mie scattering along a path of length path_length (m).
// Twin: atmos::closed_form (f32). Radiance is per unit sun irradiance (1/sr).
#import atmos::phase
#import atmos::transmittance

// Extinction along the path: exp(−(βR + βM) s).
fn closed_form_extinction(beta_rayleigh: vec3<f32>, beta_mie: vec3<f32>, path_length: f32) -> vec3<f32> {
    return transmittance_from_optical_depth((beta_rayleigh + beta_mie) * path_length);
}

// In-scattered radiance per unit sun irradiance:
//   (βR·P_R(θ) + βM·P_HG(θ, g)) / (βR + βM) · (1 − exp(−(βR + βM) s)).
// Where βR + βM = 0 the limit (βR·P_R + βM·P_HG)·s = 0 is returned rather than 0/0.
fn closed_form_inscatter(
    beta_rayleigh: vec3<f32>,
    beta_mie: vec3<f32>,
    cos_theta: f32,
    g: f32,
    path_length: f32,
) -> vec3<f32> {
    let angular = beta_rayleigh * rayleigh_phase(cos_theta) + beta_mie * henyey_greenstein_phase(cos_theta, g);
    let extinction = beta_rayleigh + beta_mie;
    let optical_depth = extinction * path_length;
    let fraction = vec3<f32>(
        one_minus_exp_neg(optical_depth.x),
        one_minus_exp_neg(optical_depth.y),
        one_minus_exp_neg(optical_depth.z),
    );
    let safe_extinction = select(extinction, vec3<f32>(1.0), extinction <= vec3<f32>(0.0));
    return select(angular * fraction / safe_extinction, vec3<f32>(0.0), extinction <= vec3<f32>(0.0));
}
