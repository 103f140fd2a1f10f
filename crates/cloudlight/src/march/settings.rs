//! The march's settings: jitter, light march, octaves, steps.

use std::num::NonZeroU32;

use super::*;
use crate::cone::ConeWeights;
use crate::jitter::{bayer_jitter_4x4, interleaved_gradient_noise};

/// Where each view step is sampled inside its step (fraction `j` of a step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Jitter {
    /// `j = ½` everywhere: the midpoint rule (layering artefacts at few steps).
    #[default]
    None,
    /// A 4×4 Bayer matrix ([`bayer_jitter_4x4`]).
    Bayer4x4,
    /// Jimenez's interleaved gradient noise ([`interleaved_gradient_noise`]).
    InterleavedGradient,
}

impl Jitter {
    /// The start offset of `pixel` in `[0, 1)`.
    pub fn offset(self, pixel: [u32; 2]) -> f32 {
        match self {
            Jitter::None => 0.5,
            Jitter::Bayer4x4 => bayer_jitter_4x4(pixel),
            Jitter::InterleavedGradient => interleaved_gradient_noise(pixel),
        }
    }
}

/// How the optical depth toward the sun is estimated at each view sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightMarch {
    /// Schneider's 6 cone + 1 far samples ([`crate::cone::cone_optical_depth`]).
    Cone {
        /// The cone's step Δ, metres (> 0). With [`ConeWeights::Partitioned`] the step
        /// used is `min(step, L/7)`, `L` the path to the field's exit.
        step: f64,
        /// Sideways spread per metre of distance (≥ 0; 0 is a straight line).
        spread: f64,
        /// Raw (Schneider, biased bright) or partitioned (a quadrature of the path).
        weights: ConeWeights,
    },
    /// `steps` midpoint steps over the path to the field's exit
    /// ([`crate::cone::march_optical_depth`]).
    Full {
        /// Steps along the light ray.
        steps: NonZeroU32,
    },
}

impl LightMarch {
    /// Schneider's 6 + 1 cone as seven equal steps of `L/7` over the path to the field's
    /// exit, no spread: the march's form of [`ConeSettings::sevenths`](crate::cone::ConeSettings::sevenths),
    /// where the sources and the layout are documented.
    pub const fn cone_sevenths() -> Self {
        LightMarch::Cone {
            step: crate::cone::MAX_LENGTH,
            spread: 0.0,
            weights: ConeWeights::Partitioned,
        }
    }
}

/// Multiple-scattering octaves (module documentation): `count` terms with extinction
/// `aⁿ`, contribution `bⁿ` and phase eccentricity `cⁿ`. `count = 1` is single scattering.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Octaves {
    /// Number of octaves (≥ 1).
    pub count: u32,
    /// Extinction factor per octave, in [0, 1].
    pub a: f64,
    /// Contribution factor per octave, in [0, 1]; Hillaire 2016 asks for `a ≤ b`.
    pub b: f64,
    /// Phase eccentricity factor per octave, in [0, 1].
    pub c: f64,
}

impl Octaves {
    /// Single scattering (one octave).
    pub const SINGLE: Self = Self {
        count: 1,
        a: 0.5,
        b: 0.5,
        c: 0.5,
    };
}

/// The march's settings as plain fields; [`MarchSettings::new`] validates them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchConfig {
    /// View steps over the ray's spans (≥ 1).
    pub view_steps: u32,
    /// Start-offset jitter (used by [`march_view_at_pixel`]).
    pub jitter: Jitter,
    /// Stop once the view transmittance falls below this (≥ 0, < 1; 0: never).
    pub transmittance_epsilon: f64,
    /// The light march toward the sun.
    pub light: LightMarch,
    /// Single-scattering albedo σ_s/σ_t, in [0, 1] (clouds: ≈ 1).
    pub albedo: f64,
    /// Forward lobe anisotropy of the dual-lobe phase, in (−1, 1).
    pub g_forward: f64,
    /// Backward lobe anisotropy, in (−1, 1).
    pub g_back: f64,
    /// Weight of the backward lobe, in [0, 1].
    pub back_weight: f64,
    /// Multiple-scattering octaves.
    pub octaves: Octaves,
    /// Schneider's powder term on the sun light (not physical; default off).
    pub powder: bool,
    /// Midpoint steps of the ambient visibility march along `up` (0: visibility 1).
    pub ambient_steps: u32,
}

impl Default for MarchConfig {
    /// 64 view steps, midpoint sampling, early exit at 1e-3, a 16-step full light march,
    /// albedo 1, dual-lobe HG (0.8, −0.3, back weight 0.2), single scattering, no powder,
    /// 4 ambient steps.
    fn default() -> Self {
        Self {
            view_steps: 64,
            jitter: Jitter::None,
            transmittance_epsilon: 1e-3,
            light: LightMarch::Full {
                steps: NonZeroU32::new(16).expect("16 > 0"),
            },
            albedo: 1.0,
            g_forward: 0.8,
            g_back: -0.3,
            back_weight: 0.2,
            octaves: Octaves::SINGLE,
            powder: false,
            ambient_steps: 4,
        }
    }
}

impl MarchConfig {
    /// The march to compare against [`crate::reference`]: [`MarchConfig::default`] with
    /// no early exit (`transmittance_epsilon` 0) and no ambient light (`ambient_steps` 0).
    /// The references (exact single scattering, the path tracer) integrate the whole ray
    /// and light it by the sun alone; the default's early exit drops the ray's tail once
    /// the transmittance is below 1e-3 and its ambient term adds sky light, both of which
    /// the references do not have.
    pub fn reference_comparison() -> Self {
        Self {
            transmittance_epsilon: 0.0,
            ambient_steps: 0,
            ..Self::default()
        }
    }
}

/// Validated [`MarchConfig`] (the default is [`MarchConfig::default`], valid).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MarchSettings {
    pub(super) config: MarchConfig,
}

impl MarchSettings {
    /// Checks every field: zero steps or octaves, a negative or ≥ 1 ε, coefficients out of
    /// range, NaN → [`MarchError::Invalid`] naming the field and value.
    pub fn new(config: MarchConfig) -> Result<Self, MarchError> {
        let c = &config;
        if c.view_steps == 0 {
            return Err(invalid("view_steps", 0.0, "must be ≥ 1"));
        }
        let eps = c.transmittance_epsilon;
        if !(0.0..1.0).contains(&eps) {
            return Err(invalid("transmittance_epsilon", eps, "must be in [0, 1)"));
        }
        if let LightMarch::Cone { step, spread, .. } = c.light {
            if !(step > 0.0 && step.is_finite()) {
                return Err(invalid("light.step", step, "must be finite and > 0"));
            }
            if !(spread >= 0.0 && spread.is_finite()) {
                return Err(invalid("light.spread", spread, "must be finite and ≥ 0"));
            }
        }
        let unit = |field, v: f64| {
            if (0.0..=1.0).contains(&v) {
                Ok(())
            } else {
                Err(invalid(field, v, "must be in [0, 1]"))
            }
        };
        let anisotropy = |field, g: f64| {
            if g > -1.0 && g < 1.0 {
                Ok(())
            } else {
                Err(invalid(field, g, "must be in (−1, 1)"))
            }
        };
        unit("albedo", c.albedo)?;
        anisotropy("g_forward", c.g_forward)?;
        anisotropy("g_back", c.g_back)?;
        unit("back_weight", c.back_weight)?;
        if c.octaves.count == 0 {
            return Err(invalid("octaves.count", 0.0, "must be ≥ 1"));
        }
        unit("octaves.a", c.octaves.a)?;
        unit("octaves.b", c.octaves.b)?;
        unit("octaves.c", c.octaves.c)?;
        Ok(Self { config })
    }

    /// The validated fields.
    pub fn config(&self) -> &MarchConfig {
        &self.config
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The reference comparison differs from the default in exactly the early exit and the
    /// ambient march, and is valid.
    #[test]
    fn reference_comparison_is_the_default_without_early_exit_or_ambient() {
        let reference = MarchConfig::reference_comparison();
        assert_eq!(reference.transmittance_epsilon, 0.0);
        assert_eq!(reference.ambient_steps, 0);
        assert_eq!(
            MarchConfig {
                transmittance_epsilon: MarchConfig::default().transmittance_epsilon,
                ambient_steps: MarchConfig::default().ambient_steps,
                ..reference
            },
            MarchConfig::default()
        );
        assert!(MarchSettings::new(reference).is_ok());
    }
}
