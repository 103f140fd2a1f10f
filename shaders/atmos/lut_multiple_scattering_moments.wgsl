// The smooth part (spherical-harmonic bands 0–2) of a radiance field that the
// multiple-scattering LUT stores, and what a phase function and the ground do with it.
// Twin: atmos::lut::multiple_scattering_moments (Rust f32), same names, arguments and
// units. No bindings here: every function is a parity case.

// Per channel, per unit sun irradiance, in a point's sun frame (z up, x towards the
// sun's horizontal direction); ⟨·⟩ is the mean over the sphere of directions ω.
struct MultipleScatteringMoments {
    mean: vec3<f32>,            // Ψ = ⟨F⟩
    first_moment_x: vec3<f32>,  // ⟨F ω_x⟩
    first_moment_z: vec3<f32>,  // ⟨F ω_z⟩
    anisotropy_xx: vec3<f32>,   // ⟨F (ω_x² − 1/3)⟩
    anisotropy_zz: vec3<f32>,   // ⟨F (ω_z² − 1/3)⟩
    anisotropy_xz: vec3<f32>,   // ⟨F ω_x ω_z⟩
}

// Legendre moments (g1, g2) of the Rayleigh phase function.
const RAYLEIGH_LEGENDRE_MOMENTS: vec2<f32> = vec2<f32>(0.0, 0.1);

// A view direction (zenith cosine mu, sun cosine nu) in the sun frame of a point where
// the sun's zenith cosine is mu_s; v_y ≥ 0 (the field is mirror-symmetric in y), and
// v_x = 0 with the sun at the zenith (the frame's x is arbitrary there).
fn sun_frame_direction(mu: f32, mu_s: f32, nu: f32) -> vec3<f32> {
    let horizontal = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    var x = 0.0;
    if sin_s > 1e-4 {
        x = clamp((nu - mu * mu_s) / sin_s, -horizontal, horizontal);
    }
    let y = sqrt(max((horizontal - x) * (horizontal + x), 0.0));
    return vec3<f32>(x, y, mu);
}

// ∮ p(ω·v) F(ω) dω for a phase function with Legendre moments (g1, g2):
// Ψ + 3 g1 d·v + (15/2) g2 vᵀA v, floored at 0 (a forward-peaked phase's bands 0–2 dip
// below zero sideways; radiance cannot).
fn scattered_multiple_scattering(moments: MultipleScatteringMoments, direction: vec3<f32>, legendre: vec2<f32>) -> vec3<f32> {
    let x = direction.x;
    let y = direction.y;
    let z = direction.z;
    let first = moments.first_moment_x * x + moments.first_moment_z * z;
    let second = moments.anisotropy_xx * (x * x - y * y)
        + moments.anisotropy_zz * (z * z - y * y)
        + 2.0 * moments.anisotropy_xz * x * z;
    return max(moments.mean + 3.0 * legendre.x * first + 7.5 * legendre.y * second, vec3<f32>(0.0));
}

// Irradiance over π on a horizontal surface from the field's upper hemisphere:
// Ψ + 2 d_z + (15/8) A_zz (bands ≤ 2 of the clamped cosine), ≥ 0.
fn multiple_scattering_ground_irradiance(moments: MultipleScatteringMoments) -> vec3<f32> {
    return max(moments.mean + 2.0 * moments.first_moment_z + 1.875 * moments.anisotropy_zz, vec3<f32>(0.0));
}

// Zenith sample i of k (k ≥ 2) of the bake's direction quadrature at radius r:
// (μ, share of dμ). ⌊k/2⌋ samples on the ground part [−1, μ_h], the rest on the sky
// part [μ_h, 1], each crowding quadratically towards the horizon μ_h.
fn direction_zenith_sample(r: f32, planet_radius: f32, i: u32, k: u32) -> vec2<f32> {
    let ratio = min(planet_radius / r, 1.0);
    let mu_h = -sqrt(max((1.0 - ratio) * (1.0 + ratio), 0.0));
    let ground = k / 2u;
    if i < ground {
        let u = (f32(i) + 0.5) / f32(ground);
        return vec2<f32>(mu_h - (1.0 + mu_h) * u * u, (1.0 + mu_h) * 2.0 * u / f32(ground));
    }
    let sky = k - ground;
    let u = (f32(i - ground) + 0.5) / f32(sky);
    return vec2<f32>(mu_h + (1.0 - mu_h) * u * u, (1.0 - mu_h) * 2.0 * u / f32(sky));
}
