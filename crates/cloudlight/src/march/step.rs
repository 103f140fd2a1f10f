//! One step of the march: the step integral, the light toward the sun, the ambient
//! visibility.

use std::num::NonZeroU32;

use atmos::real::Real;

use super::*;
use crate::cone::{
    beer_lambert, cone_optical_depth, dual_lobe_henyey_greenstein, march_optical_depth,
};
use crate::density::DensityField;

/// What a view march returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchResult<F> {
    /// Radiance scattered toward the camera by the cloud, per channel (≥ 0; unit of the
    /// lighting's irradiance per sr).
    pub radiance: [F; 3],
    /// View transmittance through the cloud, in [0, 1] (the light from behind that
    /// arrives; at an early exit, the value when the march stopped, < ε).
    pub transmittance: F,
    /// Transmittance-weighted distance of the cloud along the ray (m); 0 where the ray
    /// met no density.
    pub depth: F,
}

/// `Δ·(1 − e^{−σ_tΔ})/(σ_tΔ)` (m): the integral over a step of length `dt` of the
/// transmittance from the step's start, i.e. Hillaire's `(1 − e^{−σ_tΔ})/σ_t`, stable as
/// `σ_t → 0` (→ `Δ`). WGSL twin `step_integral`.
pub fn step_integral<F: Real>(sigma_t: F, dt: F) -> F {
    let x = sigma_t * dt;
    if x == F::zero() {
        dt
    } else {
        dt * (F::one_minus_exp_neg(x) / x)
    }
}

/// One energy-conserving view step: with transmittance `transmittance` at the step's
/// start, source `source` (radiance per metre, one channel), extinction `sigma_t` (1/m)
/// and length `dt` (m), returns `[radiance gained, transmittance after]`. WGSL twin
/// `scatter_step`.
pub fn scatter_step<F: Real>(transmittance: F, source: F, sigma_t: F, dt: F) -> [F; 2] {
    [
        transmittance * (source * step_integral(sigma_t, dt)),
        transmittance * beer_lambert(sigma_t * dt),
    ]
}

/// The octave sum `Σ_{n<octaves} bⁿ · e^{−aⁿτ} · p(cⁿ·g_forward, cⁿ·g_back, back_weight;
/// cos θ)` (1/sr) of the light with optical depth `light_optical_depth` toward the sun,
/// `p` the dual-lobe Henyey–Greenstein phase. `octaves = 1`: Beer–Lambert times the
/// phase (single scattering). WGSL twin `octave_scattering`.
#[allow(clippy::too_many_arguments)]
pub fn octave_scattering<F: Real>(
    light_optical_depth: F,
    cos_theta: F,
    g_forward: F,
    g_back: F,
    back_weight: F,
    octaves: u32,
    a: F,
    b: F,
    c: F,
) -> F {
    let mut sum = F::zero();
    let (mut an, mut bn, mut cn) = (F::one(), F::one(), F::one());
    for _ in 0..octaves {
        let phase =
            dual_lobe_henyey_greenstein(cos_theta, cn * g_forward, cn * g_back, back_weight);
        sum = sum + bn * (beer_lambert(an * light_optical_depth) * phase);
        an = an * a;
        bn = bn * b;
        cn = cn * c;
    }
    sum
}

/// The distance from `p` to the last exit of the field's spans along `dir` (0 if none).
fn exit_distance<F: Real>(field: &impl DensityField<F>, p: [F; 3], dir: [F; 3]) -> F {
    let spans = field.ray_spans(p, dir);
    spans
        .as_slice()
        .last()
        .map_or(F::zero(), |&(_, exit)| exit.max(F::zero()))
}

/// The optical depth toward the sun at `p` by the settings' light march.
pub fn light_optical_depth<F: Real>(
    field: &impl DensityField<F>,
    p: [F; 3],
    to_sun: [F; 3],
    light: &LightMarch,
) -> F {
    let exit = exit_distance(field, p, to_sun);
    if exit == F::zero() {
        return F::zero();
    }
    let sigma = field.extinction_per_density();
    let density = |q: [F; 3]| field.density(q);
    match *light {
        LightMarch::Cone {
            step,
            spread,
            weights,
        } => cone_optical_depth(
            density,
            sigma,
            p,
            to_sun,
            F::of(step),
            exit,
            F::of(spread),
            weights,
        ),
        LightMarch::Full { steps } => march_optical_depth(density, sigma, p, to_sun, exit, steps),
    }
}

/// The ambient sky's visibility at `p`: `e^{−τ_up}`, `τ_up` the optical depth from `p`
/// to the field's last exit along unit `up` by `steps` midpoint steps (0 steps, or `p`
/// already at the exit: 1). The march's `V_amb` (module docs); also the visibility of the
/// sky from a billboard particle ([`crate::billboard::particle_radiance`]).
pub fn ambient_visibility<F: Real>(
    field: &impl DensityField<F>,
    p: [F; 3],
    up: [F; 3],
    steps: u32,
) -> F {
    let Some(steps) = NonZeroU32::new(steps) else {
        return F::one();
    };
    let exit = exit_distance(field, p, up);
    if exit == F::zero() {
        return F::one();
    }
    let sigma = field.extinction_per_density();
    beer_lambert(march_optical_depth(
        |q| field.density(q),
        sigma,
        p,
        up,
        exit,
        steps,
    ))
}
