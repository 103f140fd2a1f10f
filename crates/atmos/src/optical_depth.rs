//! Optical length through an exponential density layer.
//! Twin of `shaders/atmos/optical_depth.wgsl`.

use crate::geometry::altitude_along_ray;
use crate::real::{Real, count};

/// ∫₀^`ray_length` exp(−altitude(t)/`scale_height`) dt (m), midpoint rule with
/// `sample_count` samples (at least one). Multiply by the sea-level extinction
/// coefficient (1/m) for the optical depth. Generic: the f64 instantiation is the
/// reference.
pub fn optical_length_exponential<F: Real>(
    r: F,
    mu: F,
    ray_length: F,
    planet_radius: F,
    scale_height: F,
    sample_count: u32,
) -> F {
    let n = sample_count.max(1);
    let dt = ray_length / count::<F>(n);
    let mut sum = F::zero();
    for i in 0..n {
        let t = (count::<F>(i) + F::of(0.5)) * dt;
        sum = sum + (-altitude_along_ray(r, mu, t, planet_radius) / scale_height).exp();
    }
    sum * dt
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference;

    #[test]
    fn vertical_ray_matches_closed_form() {
        // Straight up from altitude h0 over length L:
        // ∫ exp(−(h0+s)/H) ds ≈ H e^{−h0/H} (1 − e^{−L/H}) (curvature-free for μ = 1).
        let (planet, h0, big_h, len): (f64, f64, f64, f64) = (6_360_000.0, 500.0, 8000.0, 60_000.0);
        let exact = big_h * (-h0 / big_h).exp() * (1.0 - (-len / big_h).exp());
        let estimate =
            reference::optical_length_exponential(planet + h0, 1.0, len, planet, big_h, 4096);
        // Midpoint error ≈ (L/H)²/(24 n²) = 1.4e−7 here.
        approx::assert_relative_eq!(estimate, exact, max_relative = 3e-7);
        let f32_estimate = optical_length_exponential(
            (planet + h0) as f32,
            1.0,
            len as f32,
            planet as f32,
            big_h as f32,
            256,
        );
        approx::assert_relative_eq!(f64::from(f32_estimate), exact, max_relative = 1e-4);
    }

    #[test]
    fn zero_length_and_zero_samples() {
        assert_eq!(
            optical_length_exponential(6.4e6f32, 0.3, 0.0, 6.36e6, 8000.0, 16),
            0.0
        );
        // sample_count 0 is treated as 1, never a division by zero.
        assert!(optical_length_exponential(6.4e6f32, 0.3, 100.0, 6.36e6, 8000.0, 0).is_finite());
    }
}
