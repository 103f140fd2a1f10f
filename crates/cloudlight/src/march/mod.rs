//! The view ray-march through a cloud (after Schneider's Nubis talks, SIGGRAPH 2015 and
//! 2017), lit by a light march toward the sun at every sample, over any
//! [`DensityField`](crate::density::DensityField) (a [`CloudVolume`](crate::CloudVolume)
//! grid or a procedural shell). Written once over the float type: `march_view::<f64>` is the
//! reference-precision march, `march_view::<f32>` the twin of the WGSL march
//! (`shaders/cloudlight/march.wgsl` holds the per-sample functions, `field_march.wgsl`
//! the march over any GPU density source, `march_pass.wgsl` its pass over a volume).
//!
//! # The model
//!
//! Along the view ray `x(t) = origin + t·direction`, inside the field's
//! [`ray_spans`](crate::density::DensityField::ray_spans), the march takes `view_steps` steps of equal
//! length `Δ = (total span length) / view_steps` (the spans are concatenated: the gap
//! between two spans holds no density, so skipping it changes nothing). Step `k` is
//! sampled at `(k + j)·Δ` of the concatenated length, with the start offset `j ∈ [0, 1)`:
//! ½ (the midpoint rule) for [`march_view`], the pixel's [`Jitter`] for
//! [`march_view_at_pixel`]. At a sample of density `ρ` the extinction is `σ_t = k_e·ρ`
//! (1/m, `k_e` the field's [`extinction_per_density`](crate::density::DensityField::extinction_per_density))
//! and the scattering `σ_s = albedo·σ_t`. Its source (radiance per metre) is
//!
//! `S = σ_s · (E_sun · P(τ_l, cos θ) · [powder(τ_l)] + L_amb · V_amb)`
//!
//! * `τ_l`: the optical depth toward the sun, from the [`LightMarch`] setting — Schneider's
//!   6 + 1 cone ([`crate::cone::cone_optical_depth`], raw or partitioned weights) or the full
//!   `N`-step march ([`crate::cone::march_optical_depth`], the accurate option), both to the last
//!   exit of the field's spans along the sun direction;
//! * `P` = [`octave_scattering`]: multiple scattering approximated by octaves
//!   (Wrenninge 2013, Hillaire 2016): `Σ_{n<N} bⁿ · e^{−aⁿτ_l} · p(cⁿg, cos θ)` with `p`
//!   the dual-lobe Henyey–Greenstein phase of [`crate::cone::dual_lobe_henyey_greenstein`]
//!   (`atmos`' lobe). `N = 1` is single scattering (Beer–Lambert toward the sun times the
//!   phase). Hillaire 2016 gives `a ≤ b` as the condition for the approximation to stay
//!   energy-conserving; `a > b` is accepted. It is an approximation, not derived here:
//!   in the optically thin limit (`τ_l → 0`) the sum is `Σ bⁿ ≥ 1` times single
//!   scattering, so thin edges are brightened whatever `a` and `b` — measure it against
//!   the Monte Carlo reference. `cos θ = direction · sun_direction` (1 looking
//!   straight at the sun: forward scattering);
//! * `powder(τ_l) = 1 − e^{−2τ_l}` ([`crate::cone::powder`]), Schneider's darkening of the sun
//!   term near sunward edges: **not physical** (no radiative-transfer law gives it; it is
//!   an art-directed option), off by default;
//! * `L_amb · V_amb`: an isotropic ambient sky radiance `L_amb` (its phase integrates to 1
//!   over the sphere) times the density-weighted visibility `V_amb = e^{−τ_up}`, `τ_up`
//!   the optical depth from the sample to the field's exit along the lighting's `up`
//!   direction by `ambient_steps` midpoint steps (0 steps: `V_amb = 1`). An approximation:
//!   the sky is taken as uniform and reaching the sample only from straight above.
//!
//! Each step integrates the source against the view transmittance with the
//! energy-conserving form of Hillaire 2016, `S_int = (S − S·e^{−σ_tΔ})/σ_t`, evaluated as
//! `S·`[`step_integral`]`(σ_t, Δ)` = `S·Δ·(1 − e^{−σ_tΔ})/(σ_tΔ)` with `atmos`'
//! `one_minus_exp_neg` (stable as `σ_t → 0`, where it tends to `S·Δ`); then the radiance
//! gains `T·S_int` and `T` is multiplied by `e^{−σ_tΔ}` ([`scatter_step`]). The march
//! stops early once `T < transmittance_epsilon` (0 disables the early exit).
//!
//! Units: radiance in the unit of `sun_irradiance` (and of the ambient radiance) per
//! steradian; distances in metres; directions unit vectors in the field's frame.
//!
//! [`MarchResult::depth`] is the transmittance-weighted distance of the cloud along the
//! ray, `Σ tₖ·wₖ / Σ wₖ` with `wₖ = T_k·(1 − e^{−σ_tΔ})` the opacity step `k` adds; it is
//! where [`apply_aerial_perspective`] puts the cloud for the air between it and the camera.
//!
//! # Lighting from `atmos`
//!
//! [`atmos_light`] gives, at a point of a planet's atmosphere, the sun's irradiance (the
//! atmosphere's `sun_irradiance` times the transmittance toward the sun of any `atmos`
//! [`SkyModel`](atmos::SkyModel), zero behind the planet) and the ambient sky radiance (`atmos`' sky
//! irradiance on a horizontal surface from [`ground_irradiance`](atmos::ground_irradiance::ground_irradiance) divided by π: the
//! uniform radiance with the same irradiance). [`apply_aerial_perspective`] composites the
//! marched cloud through the air in front of it with the model's transmittance and
//! in-scattering up to [`MarchResult::depth`]. The march itself needs none of it: a
//! [`Lighting`] is an explicit sun direction, sun irradiance, ambient radiance and up.
//!
//! ```
//! use cloudlight::CloudVolume;
//! use cloudlight::march::{Lighting, MarchConfig, MarchSettings, march_view};
//!
//! // A 4×4×4 block of unit density, 25 m cells, σ_t 0.02 /m, seen from below.
//! let volume = CloudVolume::new([4, 4, 4], [0.0; 3], 25.0, 0.02, vec![1.0; 64])?;
//! let settings = MarchSettings::new(MarchConfig::default())?;
//! let lighting = Lighting::new([0.0, 0.0, 1.0], [1.0; 3], [0.0; 3], [0.0, 0.0, 1.0])?;
//! let r = march_view::<f64>(&volume, [50.0, 50.0, -10.0], [0.0, 0.0, 1.0], &settings, &lighting);
//! // 100 m at 0.02 /m: transmittance e^{-2} (the midpoint rule is exact for a constant).
//! assert!((r.transmittance - (-2.0f64).exp()).abs() < 1e-12);
//! assert!(r.radiance[0] > 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod atmos_light;
mod image;
mod lighting;
mod settings;
mod step;
pub mod temporal;
mod view;

pub use atmos_light::{AtmosLight, apply_aerial_perspective, atmos_light};
pub use image::{PinholeCamera, faded, pixel_direction, render_image, render_image_limited};
pub use lighting::Lighting;
pub use settings::{Jitter, LightMarch, MarchConfig, MarchSettings, Octaves};
pub use step::{
    MarchResult, ambient_visibility, light_optical_depth, octave_scattering, scatter_step,
    step_integral,
};
pub use view::{
    clip_spans, march_view, march_view_at_pixel, march_view_at_pixel_limited, march_view_limited,
    march_view_lit_through, march_view_with_offset,
};

/// Errors of the march's settings and lighting, naming the field and value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MarchError {
    /// A setting or lighting value outside its range (or NaN).
    #[error("{field} = {value}: {reason}")]
    Invalid {
        /// The field, e.g. `view_steps` or `octaves.a`.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// `atmos` refused a query (a point below the ground, a non-unit direction).
    #[error("atmos: {0}")]
    Atmos(#[from] atmos::AtmosError),
}

pub(super) fn invalid(field: &'static str, value: f64, reason: &'static str) -> MarchError {
    MarchError::Invalid {
        field,
        value,
        reason,
    }
}
