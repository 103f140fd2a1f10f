//! Beer–Lambert transmittance. Twin of `shaders/atmos/transmittance.wgsl`.

use crate::real::Real;

/// exp(−optical_depth) per channel (generic: the f64 instantiation is the reference).
pub fn transmittance_from_optical_depth<F: Real>(optical_depth: [F; 3]) -> [F; 3] {
    optical_depth.map(|tau| (-tau).exp())
}

/// 1 − exp(−x), accurate for all x including x → 0 (Horner series for |x| < 0.5).
pub fn one_minus_exp_neg(x: f32) -> f32 {
    if x.abs() < 0.5 {
        return x
            * (1.0
                - x * 0.5
                    * (1.0
                        - x * (1.0 / 3.0)
                            * (1.0
                                - x * 0.25
                                    * (1.0
                                        - x * 0.2
                                            * (1.0
                                                - x * (1.0 / 6.0)
                                                    * (1.0
                                                        - x * (1.0 / 7.0)
                                                            * (1.0 - x * 0.125)))))));
    }
    1.0 - (-x).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_arguments_keep_their_digits() {
        for x in [
            1e-8f32, 1e-6, 3.7e-4, 0.01, 0.2, 0.49999, 0.5, 0.7, 3.0, 40.0,
        ] {
            let exact = -(-f64::from(x)).exp_m1();
            let got = f64::from(one_minus_exp_neg(x));
            assert!(
                ((got - exact) / exact).abs() < 4.0 * f64::from(f32::EPSILON),
                "x = {x}: {got} vs {exact}"
            );
        }
        // The direct form would return exactly 0 here.
        assert_eq!(1.0 - (-1e-8f32).exp(), 0.0);
    }

    #[test]
    fn transmittance_limits() {
        assert_eq!(transmittance_from_optical_depth([0.0; 3]), [1.0; 3]);
        assert_eq!(transmittance_from_optical_depth([1e4; 3]), [0.0; 3]);
    }
}
