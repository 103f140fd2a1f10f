//! Closed-form scattering in a homogeneous medium (Hoffman & Preetham 2002,
//! `docs/references.md#hoffman-preetham-2002`).
//! Twin of `shaders/atmos/closed_form.wgsl`. Radiance per unit sun irradiance (1/sr).
//!
//! Written once, generic over [`Real`]: the f64 instantiation is the parity reference
//! (its 1 − e^{−x} is the independent `expm1` form, see [`Real::one_minus_exp_neg`]).

use crate::phase::{henyey_greenstein_phase, rayleigh_phase};
use crate::real::Real;
use crate::transmittance::transmittance_from_optical_depth;

/// Extinction exp(−(βR + βM)·s) along a path of `path_length` metres.
pub fn closed_form_extinction<F: Real>(
    beta_rayleigh: [F; 3],
    beta_mie: [F; 3],
    path_length: F,
) -> [F; 3] {
    transmittance_from_optical_depth(std::array::from_fn(|i| {
        (beta_rayleigh[i] + beta_mie[i]) * path_length
    }))
}

/// In-scattered radiance per unit sun irradiance,
/// (βR·P_R(θ) + βM·P_HG(θ,g))/(βR + βM) · (1 − exp(−(βR + βM)·s)); 0 where βR + βM = 0.
pub fn closed_form_inscatter<F: Real>(
    beta_rayleigh: [F; 3],
    beta_mie: [F; 3],
    cos_theta: F,
    g: F,
    path_length: F,
) -> [F; 3] {
    let p_r = rayleigh_phase(cos_theta);
    let p_m = henyey_greenstein_phase(cos_theta, g);
    std::array::from_fn(|i| {
        let extinction = beta_rayleigh[i] + beta_mie[i];
        if extinction <= F::zero() {
            return F::zero();
        }
        let angular = beta_rayleigh[i] * p_r + beta_mie[i] * p_m;
        angular * F::one_minus_exp_neg(extinction * path_length) / extinction
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::phase::rayleigh_phase;

    const BETA_R: [f32; 3] = [5.802e-6, 13.558e-6, 33.1e-6];

    #[test]
    fn thin_path_is_single_scattering_times_length() {
        // For βs ≪ 1: L ≈ βR·P_R·s.
        let s = 10.0;
        let l = closed_form_inscatter(BETA_R, [0.0; 3], 0.0, 0.8, s);
        for i in 0..3 {
            approx::assert_relative_eq!(
                l[i],
                BETA_R[i] * rayleigh_phase(0.0) * s,
                max_relative = 1e-4
            );
        }
    }

    #[test]
    fn thick_path_saturates_to_phase_ratio() {
        let l = closed_form_inscatter(BETA_R, [0.0; 3], 0.0, 0.8, 1e9);
        for v in l {
            approx::assert_relative_eq!(v, rayleigh_phase(0.0), max_relative = 1e-6);
        }
    }

    #[test]
    fn rayleigh_only_zenith_is_blue() {
        // Hoffman & Preetham 2002: without Mie the sky is blue.
        let l = closed_form_inscatter(BETA_R, [0.0; 3], 0.5, 0.8, 8000.0);
        assert!(l[2] > l[1] && l[1] > l[0], "{l:?}");
    }

    #[test]
    fn empty_medium_is_dark_and_clear() {
        assert_eq!(
            closed_form_inscatter([0.0; 3], [0.0; 3], 1.0, 0.8, 1e5),
            [0.0; 3]
        );
        assert_eq!(closed_form_extinction([0.0; 3], [0.0; 3], 1e5), [1.0; 3]);
    }
}
