// The view ray-march (Schneider 2015), per-sample functions: Hillaire's energy-conserving step,
// the multiple-scattering octaves of the sun light, and the pinhole camera's pixel
// direction. Twin: cloudlight::march (Rust, generic over the float type: the f32
// instantiation mirrors these operations).
#import atmos::transmittance
#import cloudlight::cone

// dt·(1 − e^{−σ_t·dt})/(σ_t·dt) (m): Hillaire's (1 − e^{−σ_tΔ})/σ_t, stable as σ_t → 0.
fn step_integral(sigma_t: f32, dt: f32) -> f32 {
    let x = sigma_t * dt;
    if x == 0.0 {
        return dt;
    }
    return dt * (one_minus_exp_neg(x) / x);
}

// One view step: (radiance gained, transmittance after) from the transmittance at the
// step's start, the source (radiance per metre), the extinction (1/m) and the length (m).
fn scatter_step(transmittance: f32, source: f32, sigma_t: f32, dt: f32) -> vec2<f32> {
    return vec2<f32>(
        transmittance * (source * step_integral(sigma_t, dt)),
        transmittance * beer_lambert(sigma_t * dt),
    );
}

// Σ_{n<octaves} bⁿ·e^{−aⁿτ}·p(cⁿg_forward, cⁿg_back, back_weight; cos θ) (1/sr), p the
// dual-lobe Henyey–Greenstein phase. octaves = 1: single scattering.
fn octave_scattering(
    light_optical_depth: f32,
    cos_theta: f32,
    g_forward: f32,
    g_back: f32,
    back_weight: f32,
    octaves: u32,
    a: f32,
    b: f32,
    c: f32,
) -> f32 {
    var sum = 0.0;
    var an = 1.0;
    var bn = 1.0;
    var cn = 1.0;
    for (var n = 0u; n < octaves; n++) {
        let phase = dual_lobe_henyey_greenstein(cos_theta, cn * g_forward, cn * g_back, back_weight);
        sum = sum + bn * (beer_lambert(an * light_optical_depth) * phase);
        an = an * a;
        bn = bn * b;
        cn = cn * c;
    }
    return sum;
}

// The unit view direction through the centre of pixel (x, y) of a size.x × size.y image
// (y down) of a pinhole camera looking along unit `forward` with unit `right` and `up`,
// tan_half the tangents of the half fields of view (horizontal, vertical).
fn pixel_direction(
    pixel: vec2<u32>,
    size: vec2<u32>,
    forward: vec3<f32>,
    right: vec3<f32>,
    up: vec3<f32>,
    tan_half: vec2<f32>,
) -> vec3<f32> {
    let sx = (2.0 * (f32(pixel.x) + 0.5) / f32(size.x) - 1.0) * tan_half.x;
    let sy = (1.0 - 2.0 * (f32(pixel.y) + 0.5) / f32(size.y)) * tan_half.y;
    let v = vec3<f32>(
        forward.x + sx * right.x + sy * up.x,
        forward.y + sx * right.y + sy * up.y,
        forward.z + sx * right.z + sy * up.z,
    );
    let n = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return vec3<f32>(v.x / n, v.y / n, v.z / n);
}
