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

    /// 1 − e^{−x}. Not one formula: the `f32` twin is the WGSL's Horner series below
    /// |x| = 0.5 ([`crate::transmittance::one_minus_exp_neg`]); the `f64` reference is
    /// `−expm1(−x)`, correctly rounded and independent of it.
    fn one_minus_exp_neg(x: Self) -> Self;
}

impl Real for f32 {
    fn of(x: f64) -> Self {
        x as f32
    }

    fn one_minus_exp_neg(x: Self) -> Self {
        crate::transmittance::one_minus_exp_neg(x)
    }
}

impl Real for f64 {
    fn of(x: f64) -> Self {
        x
    }

    fn one_minus_exp_neg(x: Self) -> Self {
        -(-x).exp_m1()
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
