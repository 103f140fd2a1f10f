//! Phase functions, normalised over the sphere (1/sr). Twin of `shaders/atmos/phase.wgsl`.
//!
//! Each formula is written once, generic over [`Real`]: the `f32` instantiation mirrors
//! the WGSL operation for operation, the `f64` one is the parity reference
//! (`crate::reference` re-exports these functions).

use crate::real::Real;

/// π in the float type (rounded once, as WGSL's `PI` constant is).
fn pi<F: Real>() -> F {
    F::of(std::f64::consts::PI)
}

/// Rayleigh phase function 3/(16π)(1 + cos²θ).
pub fn rayleigh_phase<F: Real>(cos_theta: F) -> F {
    F::of(3.0) / (F::of(16.0) * pi::<F>()) * (F::one() + cos_theta * cos_theta)
}

/// 1 + g² − 2g·cosθ as a sum of non-negative terms (accurate as |g| → 1), never
/// below its first term (1 ∓ g)²: a no-op in correctly rounded arithmetic, kept
/// op for op with the WGSL, where it stops a compiler's rewrite of the sum from
/// cancelling the base to 0 (single scattering with g = 0.9999 gave inf at cosθ = 1
/// on an NVIDIA H100, as a base of 0 would).
pub fn phase_denominator_base<F: Real>(cos_theta: F, g: F) -> F {
    let two = F::of(2.0);
    if g >= F::zero() {
        let one_minus_g = F::one() - g;
        let floor = one_minus_g * one_minus_g;
        (floor + two * g * (F::one() - cos_theta)).max(floor)
    } else {
        let one_plus_g = F::one() + g;
        let floor = one_plus_g * one_plus_g;
        (floor - two * g * (F::one() + cos_theta)).max(floor)
    }
}

/// Henyey–Greenstein phase function (1 − g²)/(4π(1 + g² − 2g·cosθ)^{3/2}).
pub fn henyey_greenstein_phase<F: Real>(cos_theta: F, g: F) -> F {
    let base = phase_denominator_base(cos_theta, g);
    (F::one() - g) * (F::one() + g) / (F::of(4.0) * pi::<F>() * base * base.sqrt())
}

/// Cornette–Shanks phase function
/// 3/(8π)(1 − g²)(1 + cos²θ)/((2 + g²)(1 + g² − 2g·cosθ)^{3/2}).
pub fn cornette_shanks_phase<F: Real>(cos_theta: F, g: F) -> F {
    let base = phase_denominator_base(cos_theta, g);
    F::of(3.0) / (F::of(8.0) * pi::<F>())
        * (F::one() - g)
        * (F::one() + g)
        * (F::one() + cos_theta * cos_theta)
        / ((F::of(2.0) + g * g) * base * base.sqrt())
}

/// The first two Legendre moments (g₁, g₂) of the Cornette–Shanks phase function,
/// g_l = 2π ∫₋₁¹ p(μ) P_l(μ) dμ: p = Σ_l (2l + 1) g_l P_l(μ) / 4π. Closed form from
/// p_CS = 3(1 + μ²) p_HG / (2(2 + g²)), the Henyey–Greenstein moments g^l and μ²
/// written in Legendre polynomials: g₁ = 3g(4 + g²)/(5(2 + g²)),
/// g₂ = 3(2/15 + 32g²/21 + 12g⁴/35)/(2(2 + g²)). g = 0 gives Rayleigh's (0, 1/10).
///
/// They are what a phase function does to the smooth (degree ≤ 2) part of a
/// radiance field: the multiple-scattering LUT stores that part
/// ([`crate::lut::multiple_scattering_lut`]).
pub fn cornette_shanks_legendre_moments<F: Real>(g: F) -> [F; 2] {
    let c = F::of;
    let g2 = g * g;
    let normalisation = c(3.0) / (c(2.0) * (c(2.0) + g2));
    let first = normalisation * g * (c(8.0) + c(2.0) * g2) / c(5.0);
    let second =
        normalisation * (c(2.0) / c(15.0) + c(32.0) / c(21.0) * g2 + c(12.0) / c(35.0) * g2 * g2);
    [first, second]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference;
    use skyscape_wgsl::common::PI;

    /// ∫ p dΩ = 2π ∫₋₁¹ p(μ) dμ, by composite Simpson in f64.
    fn sphere_integral(p: impl Fn(f64) -> f64) -> f64 {
        let n = 200_000;
        let h = 2.0 / n as f64;
        let mut sum = p(-1.0) + p(1.0);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            sum += w * p(-1.0 + i as f64 * h);
        }
        2.0 * std::f64::consts::PI * sum * h / 3.0
    }

    #[test]
    fn phases_are_normalised() {
        approx::assert_relative_eq!(
            sphere_integral(reference::rayleigh_phase),
            1.0,
            max_relative = 1e-9
        );
        for g in [-0.9, -0.5, 0.0, 0.3, 0.76, 0.9] {
            approx::assert_relative_eq!(
                sphere_integral(|mu| reference::henyey_greenstein_phase(mu, g)),
                1.0,
                max_relative = 1e-6
            );
            approx::assert_relative_eq!(
                sphere_integral(|mu| reference::cornette_shanks_phase(mu, g)),
                1.0,
                max_relative = 1e-6
            );
        }
    }

    #[test]
    fn cornette_shanks_legendre_moments_match_quadrature() {
        for g in [-0.9f32, -0.3, 0.0, 0.5, 0.8, 0.95] {
            let gd = f64::from(g);
            let first = sphere_integral(|mu| mu * reference::cornette_shanks_phase(mu, gd));
            let second = sphere_integral(|mu| {
                0.5 * (3.0 * mu * mu - 1.0) * reference::cornette_shanks_phase(mu, gd)
            });
            let [g1, g2] = cornette_shanks_legendre_moments(g);
            approx::assert_abs_diff_eq!(f64::from(g1), first, epsilon = 2e-6);
            approx::assert_abs_diff_eq!(f64::from(g2), second, epsilon = 2e-6);
        }
        // Rayleigh = Cornette–Shanks at g = 0: p = (1 + P₂/2)/4π.
        let [g1, g2] = cornette_shanks_legendre_moments(0.0);
        assert_eq!(g1, 0.0);
        approx::assert_abs_diff_eq!(g2, 0.1, epsilon = 1e-7);
    }

    #[test]
    fn mean_cosine_of_henyey_greenstein_is_g() {
        for g in [-0.7, 0.2, 0.8] {
            let mean = sphere_integral(|mu| mu * reference::henyey_greenstein_phase(mu, g));
            approx::assert_abs_diff_eq!(mean, g, epsilon = 1e-6);
        }
    }

    #[test]
    fn analytic_values() {
        approx::assert_relative_eq!(rayleigh_phase(0.0), 3.0 / (16.0 * PI), max_relative = 1e-7);
        approx::assert_relative_eq!(rayleigh_phase(1.0), 3.0 / (8.0 * PI), max_relative = 1e-7);
        // g = 0 is isotropic.
        approx::assert_relative_eq!(
            henyey_greenstein_phase(0.3, 0.0),
            1.0 / (4.0 * PI),
            max_relative = 1e-7
        );
        // Forward peak (1+g)/(4π(1−g)²).
        let g = 0.9f32;
        approx::assert_relative_eq!(
            henyey_greenstein_phase(1.0, g),
            (1.0 + g) / (4.0 * PI * (1.0 - g) * (1.0 - g)),
            max_relative = 1e-5
        );
    }

    #[test]
    fn stable_denominator_beats_naive_form_near_unit_g() {
        // g = 0.9999, θ = 0: exact 1 + g² − 2g = (1 − g)² = 1e−8.
        let (mu, g) = (1.0f32, 0.9999f32);
        let naive = 1.0 + g * g - 2.0 * g * mu;
        let stable = phase_denominator_base(mu, g);
        let exact = reference::phase_denominator_base(f64::from(mu), f64::from(g));
        let rel = |x: f32| ((f64::from(x) - exact) / exact).abs();
        assert!(rel(stable) < 1e-6, "stable form error {}", rel(stable));
        assert!(
            rel(naive) > 1e-2,
            "naive form unexpectedly accurate: {}",
            rel(naive)
        );
    }
}
