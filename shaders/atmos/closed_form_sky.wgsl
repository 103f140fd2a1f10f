// Rung 1 of the ladder: seed 000's closed form in spherical geometry. Earth's
// exponential layers are replaced by one homogeneous shell of thickness H_R (the
// Rayleigh scale height) with the Mie coefficient scaled by H_M / H_R, so both keep
// their vertical optical depth; sunlight driving the in-scatter is attenuated by the
// transmittance averaged over the sun's path through the shell.
// Twin: atmos::closed_form_sky (Rust). Units: metres, 1/m; radiance per unit sun
// irradiance times `sun_irradiance`.

#import atmos::geometry
#import atmos::closed_form
#import atmos::transmittance

struct ClosedFormSkyParameters {
    beta_rayleigh: vec3<f32>,
    mie_g: f32,
    // Homogeneous-equivalent Mie scattering (1/m).
    beta_mie: vec3<f32>,
    planet_radius: f32,
    sun_irradiance: vec3<f32>,
    // planet_radius + H_R (m).
    shell_radius: f32,
}

// Sunlight driving the in-scatter at a viewer at radius r with sun zenith cosine mu_s:
// irradiance × (1 − e^{−τ})/τ over the sun's path through the shell; 0 when the planet
// hides the sun's centre.
fn closed_form_sunlight(r: f32, mu_s: f32, params: ClosedFormSkyParameters) -> vec3<f32> {
    let sun_ground = ray_sphere_intersect(r, mu_s, params.planet_radius);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu_s < 0.0 && sun_ground.x >= 0.0 {
        return vec3<f32>(0.0);
    }
    let sun_shell = ray_sphere_intersect(r, mu_s, params.shell_radius);
    let path = max(sun_shell.y - max(sun_shell.x, 0.0), 0.0);
    let optical_depth = (params.beta_rayleigh + params.beta_mie) * path;
    var average = vec3<f32>(1.0);
    for (var i = 0; i < 3; i++) {
        if optical_depth[i] > 0.0 {
            average[i] = one_minus_exp_neg(optical_depth[i]) / optical_depth[i];
        }
    }
    return params.sun_irradiance * average;
}

// Length (m) of the view ray's segment inside the shell, from the viewer (or where the
// ray enters the shell) to where it leaves it, hits the ground, or max_distance.
fn closed_form_path_length(r: f32, mu: f32, max_distance: f32, params: ClosedFormSkyParameters) -> f32 {
    let shell = ray_sphere_intersect(r, mu, params.shell_radius);
    if shell.y < 0.0 {
        return 0.0;
    }
    let ground = ray_sphere_intersect(r, mu, params.planet_radius);
    var end = min(shell.y, max_distance);
    if mu < 0.0 && ground.x >= 0.0 {
        end = min(end, ground.x);
    }
    return max(end - max(shell.x, 0.0), 0.0);
}

// In-scattered radiance along the view ray (r, mu) with view–sun cosine nu, given the
// sunlight from closed_form_sunlight.
fn closed_form_sky_radiance(r: f32, mu: f32, nu: f32, max_distance: f32, sunlight: vec3<f32>, params: ClosedFormSkyParameters) -> vec3<f32> {
    let path = closed_form_path_length(r, mu, max_distance, params);
    return sunlight * closed_form_inscatter(params.beta_rayleigh, params.beta_mie, nu, params.mie_g, path);
}

// Transmittance of the same segment.
fn closed_form_sky_transmittance(r: f32, mu: f32, max_distance: f32, params: ClosedFormSkyParameters) -> vec3<f32> {
    let path = closed_form_path_length(r, mu, max_distance, params);
    return closed_form_extinction(params.beta_rayleigh, params.beta_mie, path);
}
