//! [`Real`]: the float types `atmos`' formulas are written for once.
//!
//! Where the f32 twin (which mirrors the WGSL operation for operation) and the f64
//! reference are the same formula in two precisions, the formula is one generic
//! function over `F: Real`, instantiated at `f32` (the twin) and `f64` (the reference):
//! a fix lands in both, and the parity report's error is rounding alone. Where the
//! reference is meant to be an independent algorithm (the multiple-scattering
//! reference's orders, converged quadratures, `exp_m1` forms) it stays separate and its
//! documentation says so.
//!
//! `Real` is [`num_traits::Float`] (the arithmetic and `std`'s elementary functions)
//! plus the few `atmos` primitives whose f32 and f64 versions are still separate
//! functions, so generic code can call the right one.

use std::fmt::Debug;

/// A float type `atmos`' generic formulas are instantiated at: `f32` or `f64`.
pub trait Real: num_traits::Float + Debug + Default + Send + Sync + 'static {
    /// The constant `x` in this precision (rounded once, as a literal would be).
    fn of(x: f64) -> Self;

    /// Distances along a ray from radius `r` with zenith cosine `mu` to the two
    /// intersections with a sphere of `sphere_radius` (see
    /// [`crate::geometry::ray_sphere_intersect`] and its f64 reference).
    fn ray_sphere_intersect(r: Self, mu: Self, sphere_radius: Self) -> [Self; 2];
}

impl Real for f32 {
    fn of(x: f64) -> Self {
        x as f32
    }

    fn ray_sphere_intersect(r: Self, mu: Self, sphere_radius: Self) -> [Self; 2] {
        crate::geometry::ray_sphere_intersect(r, mu, sphere_radius)
    }
}

impl Real for f64 {
    fn of(x: f64) -> Self {
        x
    }

    fn ray_sphere_intersect(r: Self, mu: Self, sphere_radius: Self) -> [Self; 2] {
        crate::reference::ray_sphere_intersect(r, mu, sphere_radius)
    }
}

/// `n` (a texel count, a sample index) in the float type `F`, as `n as F` would.
pub fn count<F: Real>(n: u32) -> F {
    F::of(f64::from(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_round_once() {
        assert_eq!(f32::of(0.1), 0.1f32);
        assert_eq!(f32::of(std::f64::consts::PI), std::f32::consts::PI);
        assert_eq!(count::<f32>(16_777_217), 16_777_216.0);
        assert_eq!(count::<f64>(16_777_217), 16_777_217.0);
    }
}
