//! Ray geometry in the planet-centred frame. Twin of `shaders/atmos/geometry.wgsl`.
//!
//! Written once, generic over [`Real`]: the `f32` instantiation mirrors the WGSL, the
//! `f64` one is the parity reference (`crate::reference` re-exports these functions).

use crate::real::Real;

/// Sentinel for "the ray's line misses the sphere".
pub const RAY_MISS: f32 = -1.0;

/// Signed distances (m) to the two intersections of the ray (origin at distance `r`
/// from the planet centre, zenith cosine `mu`) with a sphere of radius
/// `sphere_radius`: `[near, far]`, both [`RAY_MISS`] when the line misses.
///
/// The stable form: `q = −(b + sign(b)·√D)`, roots `q` and `c/q`, so neither root is a
/// difference of nearly equal numbers.
pub fn ray_sphere_intersect<F: Real>(r: F, mu: F, sphere_radius: F) -> [F; 2] {
    let b = r * mu;
    let c = (r - sphere_radius) * (r + sphere_radius);
    let discriminant = b * b - c;
    if discriminant < F::zero() {
        let miss = F::of(f64::from(RAY_MISS));
        return [miss, miss];
    }
    let sign_b = if b >= F::zero() { F::one() } else { -F::one() };
    let q = -(b + sign_b * discriminant.sqrt());
    if q == F::zero() {
        return [F::zero(), F::zero()];
    }
    let t0 = q;
    let t1 = c / q;
    [t0.min(t1), t0.max(t1)]
}

/// Altitude (m) above a sphere of radius `planet_radius` of the point at distance `t`
/// along the ray, without subtracting nearly equal radii.
pub fn altitude_along_ray<F: Real>(r: F, mu: F, t: F, planet_radius: F) -> F {
    let two = F::of(2.0);
    let radius_squared_excess = (r - planet_radius) * (r + planet_radius) + t * (two * r * mu + t);
    let r_t = (r * r + t * (two * r * mu + t)).max(F::zero()).sqrt();
    radius_squared_excess / (r_t + planet_radius)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference;

    const R_GROUND: f32 = 6_360_000.0;
    const R_TOP: f32 = 6_460_000.0;

    #[test]
    fn vertical_rays() {
        let r = R_GROUND + 1000.0;
        assert_eq!(
            ray_sphere_intersect(r, 1.0, R_TOP),
            [-(R_TOP + r), R_TOP - r]
        );
        // The near root comes from c/q: one rounding of c = 1000·(2R + 1000) → ≤ 2 ULP.
        let down = ray_sphere_intersect(r, -1.0, R_GROUND);
        approx::assert_relative_eq!(down[0], 1000.0, max_relative = 2.0 * f32::EPSILON);
        assert_eq!(down[1], 2.0 * R_GROUND + 1000.0);
    }

    #[test]
    fn camera_exactly_on_the_sphere() {
        let up = ray_sphere_intersect(R_TOP, 0.5, R_TOP);
        assert_eq!(up[1], 0.0, "looking up from the top: far hit is here");
        let down = ray_sphere_intersect(R_TOP, -0.5, R_TOP);
        assert_eq!(down[0], 0.0, "looking down from the top: near hit is here");
        approx::assert_relative_eq!(down[1], R_TOP, max_relative = 1e-6);
    }

    #[test]
    fn grazing_ray_one_metre_above_ground() {
        // Horizontal ray 1 m above the ground: the ground sphere is missed (barely),
        // and the distance to the horizon of a sphere 1 m lower is sqrt(2 R·1 + 1).
        let r = R_GROUND + 1.0;
        assert_eq!(ray_sphere_intersect(r, 0.0, R_GROUND), [RAY_MISS, RAY_MISS]);
        let dip = -(2.0f64 / f64::from(r)).sqrt() * 1.0001; // slightly below the geometric horizon
        let hit = ray_sphere_intersect(r, dip as f32, R_GROUND);
        let exact = reference::ray_sphere_intersect(
            f64::from(r),
            f64::from(dip as f32),
            f64::from(R_GROUND),
        );
        approx::assert_relative_eq!(f64::from(hit[0]), exact[0], max_relative = 1e-5);
    }

    #[test]
    fn altitude_is_accurate_where_radii_cancel() {
        // 1 km along a horizontal ray from 1 m altitude: altitude ≈ 1 + 1000²/(2R).
        let r = R_GROUND + 1.0;
        let h = altitude_along_ray(r, 0.0, 1000.0, R_GROUND);
        let exact = reference::altitude_along_ray(f64::from(r), 0.0, 1000.0, f64::from(R_GROUND));
        approx::assert_relative_eq!(f64::from(h), exact, max_relative = 1e-6);
        // The naive subtraction loses ~0.5 m here.
        let naive = (r * r + 1000.0 * 1000.0).sqrt() - R_GROUND;
        assert!((f64::from(naive) - exact).abs() > 1e-2);
    }
}
