// Phase functions, normalised over the sphere (unit: 1/sr).
// Twin: atmos::phase (f32) and atmos::reference (f64). Same names, same arguments.
#import common::constants

// Rayleigh: 3/(16π) (1 + cos²θ).
fn rayleigh_phase(cos_theta: f32) -> f32 {
    return 3.0 / (16.0 * PI) * (1.0 + cos_theta * cos_theta);
}

// 1 + g² − 2 g cosθ, written as a sum of non-negative terms so it keeps full
// relative accuracy as |g| → 1 (the naive form cancels when g cosθ ≈ 1).
//   g ≥ 0: (1 − g)² + 2 g (1 − cosθ)
//   g < 0: (1 + g)² − 2 g (1 + cosθ)
// The max with the first term is a no-op where + and × round correctly (the second
// term is ≥ 0); it keeps the base off 0 where a compiler rewrites the sum so that
// (1 − g)² is lost (e.g. as 2g + (1 − g)² − 2g·cosθ). On an NVIDIA H100 (Vulkan)
// single scattering with g = 0.9999 gave inf at cosθ = 1 (NaN where the sun was
// extinguished), as a base of 0 would; the base there is 1e-8.
fn phase_denominator_base(cos_theta: f32, g: f32) -> f32 {
    if g >= 0.0 {
        let one_minus_g = 1.0 - g;
        let floor = one_minus_g * one_minus_g;
        return max(floor + 2.0 * g * (1.0 - cos_theta), floor);
    }
    let one_plus_g = 1.0 + g;
    let floor = one_plus_g * one_plus_g;
    return max(floor - 2.0 * g * (1.0 + cos_theta), floor);
}

// Henyey–Greenstein: (1 − g²) / (4π (1 + g² − 2 g cosθ)^{3/2}).
fn henyey_greenstein_phase(cos_theta: f32, g: f32) -> f32 {
    let base = phase_denominator_base(cos_theta, g);
    // 1 − g² as (1 − g)(1 + g): exact factors, no cancellation near |g| = 1.
    return (1.0 - g) * (1.0 + g) / (4.0 * PI * base * sqrt(base));
}

// Cornette–Shanks: 3/(8π) (1 − g²)(1 + cos²θ) / ((2 + g²)(1 + g² − 2 g cosθ)^{3/2}).
fn cornette_shanks_phase(cos_theta: f32, g: f32) -> f32 {
    let base = phase_denominator_base(cos_theta, g);
    return 3.0 / (8.0 * PI) * (1.0 - g) * (1.0 + g) * (1.0 + cos_theta * cos_theta)
        / ((2.0 + g * g) * base * sqrt(base));
}

// The first two Legendre moments (g1, g2) of the Cornette–Shanks phase function,
// g_l = 2π ∫ p(μ) P_l(μ) dμ; g = 0 gives Rayleigh's (0, 1/10).
fn cornette_shanks_legendre_moments(g: f32) -> vec2<f32> {
    let g2 = g * g;
    let normalisation = 3.0 / (2.0 * (2.0 + g2));
    let first = normalisation * g * (8.0 + 2.0 * g2) / 5.0;
    let second = normalisation * (2.0 / 15.0 + 32.0 / 21.0 * g2 + 12.0 / 35.0 * g2 * g2);
    return vec2<f32>(first, second);
}
