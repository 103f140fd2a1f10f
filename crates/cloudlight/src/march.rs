//! Seed 003's view ray-march through a cloud, lit by a light march toward the sun at every
//! sample, over any [`DensityField`] (a [`CloudVolume`](crate::CloudVolume) grid or a
//! procedural shell). Written once over the float type: `march_view::<f64>` is the
//! reference-precision march, `march_view::<f32>` the twin of the WGSL march
//! (`shaders/cloudlight/march.wgsl` holds the per-sample functions, `march_pass.wgsl` the
//! GPU pass over a volume).
//!
//! # The model
//!
//! Along the view ray `x(t) = origin + t·direction`, inside the field's
//! [`ray_spans`](DensityField::ray_spans), the march takes `view_steps` steps of equal
//! length `Δ = (total span length) / view_steps` (the spans are concatenated: the gap
//! between two spans holds no density, so skipping it changes nothing). Step `k` is
//! sampled at `(k + j)·Δ` of the concatenated length, with the start offset `j ∈ [0, 1)`:
//! ½ (the midpoint rule) for [`march_view`], the pixel's [`Jitter`] for
//! [`march_view_at_pixel`]. At a sample of density `ρ` the extinction is `σ_t = k_e·ρ`
//! (1/m, `k_e` the field's [`extinction_per_density`](DensityField::extinction_per_density))
//! and the scattering `σ_s = albedo·σ_t`. Its source (radiance per metre) is
//!
//! `S = σ_s · (E_sun · P(τ_l, cos θ) · [powder(τ_l)] + L_amb · V_amb)`
//!
//! * `τ_l`: the optical depth toward the sun, from the [`LightMarch`] setting — seed 003's
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
//! [`SkyModel`], zero behind the planet) and the ambient sky radiance (`atmos`' sky
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

use std::num::NonZeroU32;

use atmos::real::{Real, count};
use atmos::{Atmosphere, SkyModel, SkyQuery};
use glam::DVec3;

use crate::cone::{
    ConeWeights, beer_lambert, cone_optical_depth, dual_lobe_henyey_greenstein,
    march_optical_depth, powder,
};
use crate::density::{DensityField, RaySpans};
use crate::jitter::{bayer_jitter_4x4, interleaved_gradient_noise};

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

fn invalid(field: &'static str, value: f64, reason: &'static str) -> MarchError {
    MarchError::Invalid {
        field,
        value,
        reason,
    }
}

/// Where each view step is sampled inside its step (fraction `j` of a step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Jitter {
    /// `j = ½` everywhere: the midpoint rule (layering artefacts at few steps).
    #[default]
    None,
    /// Seed 003's 4×4 Bayer matrix ([`bayer_jitter_4x4`]).
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
    /// Seed 003's 6 cone + 1 far samples ([`crate::cone::cone_optical_depth`]).
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

/// Validated [`MarchConfig`] (the default is [`MarchConfig::default`], valid).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MarchSettings {
    config: MarchConfig,
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

/// The light of a march without `atmos`: explicit sun direction and irradiance, ambient
/// radiance and the up direction of the ambient visibility (field frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lighting<F> {
    sun_direction: [F; 3],
    sun_irradiance: [F; 3],
    ambient_radiance: [F; 3],
    up: [F; 3],
}

fn check_unit(field: &'static str, v: [f64; 3]) -> Result<[f64; 3], MarchError> {
    for c in v {
        if !c.is_finite() {
            return Err(invalid(field, c, "components must be finite"));
        }
    }
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if (n - 1.0).abs() > 1e-3 {
        return Err(invalid(field, n, "length must be 1 (within 1e-3)"));
    }
    Ok(v.map(|c| c / n))
}

fn check_colour(field: &'static str, v: [f64; 3]) -> Result<(), MarchError> {
    for c in v {
        if !(c >= 0.0 && c.is_finite()) {
            return Err(invalid(field, c, "components must be finite and ≥ 0"));
        }
    }
    Ok(())
}

impl<F: Real> Lighting<F> {
    /// `sun_direction` (unit, toward the sun; may point below the horizon),
    /// `sun_irradiance` (per channel, ≥ 0, on a surface facing the sun, at the cloud),
    /// `ambient_radiance` (isotropic sky radiance per channel, ≥ 0, same unit per sr),
    /// `up` (unit; the direction the ambient light is taken to come from).
    /// Directions are renormalised; errors name the field and value.
    pub fn new(
        sun_direction: [f64; 3],
        sun_irradiance: [f64; 3],
        ambient_radiance: [f64; 3],
        up: [f64; 3],
    ) -> Result<Self, MarchError> {
        let sun_direction = check_unit("sun_direction", sun_direction)?;
        let up = check_unit("up", up)?;
        check_colour("sun_irradiance", sun_irradiance)?;
        check_colour("ambient_radiance", ambient_radiance)?;
        Ok(Self {
            sun_direction: sun_direction.map(F::of),
            sun_irradiance: sun_irradiance.map(F::of),
            ambient_radiance: ambient_radiance.map(F::of),
            up: up.map(F::of),
        })
    }

    /// A white sun of irradiance 1 along `sun_direction`, no ambient light (the Monte
    /// Carlo reference's lighting).
    pub fn white_sun(sun_direction: [f64; 3]) -> Result<Self, MarchError> {
        Self::new(sun_direction, [1.0; 3], [0.0; 3], [0.0, 0.0, 1.0])
    }

    /// Unit vector toward the sun.
    pub fn sun_direction(&self) -> [F; 3] {
        self.sun_direction
    }

    /// Sun irradiance per channel.
    pub fn sun_irradiance(&self) -> [F; 3] {
        self.sun_irradiance
    }

    /// Ambient radiance per channel.
    pub fn ambient_radiance(&self) -> [F; 3] {
        self.ambient_radiance
    }

    /// Unit up direction of the ambient visibility.
    pub fn up(&self) -> [F; 3] {
        self.up
    }
}

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

/// The view march with midpoint samples (start offset ½). `direction` is a unit vector
/// in the field's frame; `settings.config().jitter` is not used (see
/// [`march_view_at_pixel`]).
pub fn march_view<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
) -> MarchResult<F> {
    march_view_with_offset(field, origin, direction, settings, lighting, F::of(0.5))
}

/// The view march of pixel `pixel`, its start offset from the settings' [`Jitter`].
pub fn march_view_at_pixel<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    pixel: [u32; 2],
) -> MarchResult<F> {
    let offset = F::of(f64::from(settings.config.jitter.offset(pixel)));
    march_view_with_offset(field, origin, direction, settings, lighting, offset)
}

/// [`march_view_at_pixel`] stopped at `max_distance` metres along the ray
/// ([`march_view_limited`]).
pub fn march_view_at_pixel_limited<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    pixel: [u32; 2],
    max_distance: F,
) -> MarchResult<F> {
    let offset = F::of(f64::from(settings.config.jitter.offset(pixel)));
    march_view_limited(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        max_distance,
    )
}

/// The view march with step `k` sampled at `(k + offset)·Δ` (`offset` in [0, 1); other
/// values are wrapped into it). Unlimited: [`march_view_limited`] with `max_distance = ∞`.
pub fn march_view_with_offset<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    offset: F,
) -> MarchResult<F> {
    march_view_limited(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        F::infinity(),
    )
}

/// The field's spans along a ray clipped to `[0, max_distance]` (WGSL twins: the clip in
/// `march_pass.wgsl` and `march_shell_pass.wgsl`). A span starting at or beyond the limit
/// is dropped, one crossing it ends there. `max_distance` of `+∞` (or at least the
/// largest finite `f32`, the WGSL's "infinite") or NaN means no limit; a negative one
/// clips everything, as 0 does.
pub fn clip_spans<F: Real>(spans: RaySpans<F>, max_distance: F) -> RaySpans<F> {
    // `!(limit < MAX)` as the WGSL writes it: NaN is no limit too.
    if max_distance.is_nan() || max_distance >= F::of(f64::from(f32::MAX)) {
        return spans;
    }
    let limit = max_distance.max(F::zero());
    let mut out = RaySpans::none();
    for &(enter, exit) in spans.as_slice() {
        if enter < limit {
            out.spans[out.count] = (enter, if exit > limit { limit } else { exit });
            out.count += 1;
        }
    }
    out
}

/// The view march stopped at `max_distance` metres along the ray (an opaque surface
/// there: terrain in front of or inside the cloud). The field's spans are clipped to
/// `[0, max_distance]` ([`clip_spans`]) and the `view_steps` steps spread over the
/// clipped length, so a limited march is the unlimited march of the field cut at that
/// distance; a limit of 0 (or below) gives radiance 0 and transmittance 1, and a limit of
/// `+∞` or NaN is no limit ([`march_view_with_offset`]). Step offsets as
/// [`march_view_with_offset`].
pub fn march_view_limited<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    offset: F,
    max_distance: F,
) -> MarchResult<F> {
    march_view_lit_through(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        max_distance,
        |_| F::zero(),
    )
}

/// [`march_view_limited`] with the light crossing something outside the field too:
/// `outside_depth(p)` (≥ 0, finite) is the optical depth toward the sun of what lies
/// outside the field at view sample `p` (another cloud's shadow, read from its map:
/// `render::mutual_shadow`), added to the light march's `τ_l` before the octaves and the
/// powder, as one march over both would add it (`crate::union::UnionField`). The sun
/// term only: the ambient visibility stays the field's own. With `|_| 0` it is
/// [`march_view_limited`] exactly. WGSL twins: the `outside_depth` hooks of
/// `march_pass.wgsl` and `march_shell_pass.wgsl`.
#[allow(clippy::too_many_arguments)] // the limited march's seven inputs and the hook
pub fn march_view_lit_through<F: Real>(
    field: &impl DensityField<F>,
    origin: [F; 3],
    direction: [F; 3],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    offset: F,
    max_distance: F,
    outside_depth: impl Fn([F; 3]) -> F,
) -> MarchResult<F> {
    let c = &settings.config;
    let zero = F::zero();
    let offset = if offset.is_finite() {
        offset - offset.floor()
    } else {
        F::of(0.5)
    };
    let mut result = MarchResult {
        radiance: [zero; 3],
        transmittance: F::one(),
        depth: zero,
    };
    let spans = clip_spans(field.ray_spans(origin, direction), max_distance);
    let total = spans.length();
    if total <= zero || !total.is_finite() {
        return result;
    }
    let dt = total / count::<F>(c.view_steps);
    let sigma_per_density = field.extinction_per_density();
    let albedo = F::of(c.albedo);
    let to_sun = lighting.sun_direction;
    let cos_theta = direction[0] * to_sun[0] + direction[1] * to_sun[1] + direction[2] * to_sun[2];
    let (g_forward, g_back, back_weight) =
        (F::of(c.g_forward), F::of(c.g_back), F::of(c.back_weight));
    let (a, b, cc) = (F::of(c.octaves.a), F::of(c.octaves.b), F::of(c.octaves.c));
    let epsilon = F::of(c.transmittance_epsilon);
    let sun_lit = lighting.sun_irradiance.iter().any(|&e| e > zero);
    let ambient_lit = lighting.ambient_radiance.iter().any(|&e| e > zero);
    let mut weight_sum = zero;
    let mut depth_sum = zero;
    let mut span = 0usize;
    let mut span_start = zero; // concatenated length before `span`
    for k in 0..c.view_steps {
        let u = (count::<F>(k) + offset) * dt;
        while span + 1 < spans.count
            && u >= span_start + (spans.spans[span].1 - spans.spans[span].0)
        {
            span_start = span_start + (spans.spans[span].1 - spans.spans[span].0);
            span += 1;
        }
        let t = spans.spans[span].0 + (u - span_start);
        let p = [
            origin[0] + t * direction[0],
            origin[1] + t * direction[1],
            origin[2] + t * direction[2],
        ];
        let density = field.density(p);
        if density <= zero || density.is_nan() {
            continue;
        }
        let sigma_t = sigma_per_density * density;
        let sigma_s = albedo * sigma_t;
        let mut sun_term = zero;
        if sun_lit {
            let tau = light_optical_depth(field, p, to_sun, &c.light) + outside_depth(p);
            sun_term = octave_scattering(
                tau,
                cos_theta,
                g_forward,
                g_back,
                back_weight,
                c.octaves.count,
                a,
                b,
                cc,
            );
            if c.powder {
                sun_term = sun_term * powder(tau);
            }
        }
        let visibility = if ambient_lit {
            ambient_visibility(field, p, lighting.up, c.ambient_steps)
        } else {
            zero
        };
        let mut next = result.transmittance;
        for ch in 0..3 {
            let source = sigma_s
                * (lighting.sun_irradiance[ch] * sun_term
                    + lighting.ambient_radiance[ch] * visibility);
            let [gain, after] = scatter_step(result.transmittance, source, sigma_t, dt);
            result.radiance[ch] = result.radiance[ch] + gain;
            next = after;
        }
        let opacity = result.transmittance - next;
        weight_sum = weight_sum + opacity;
        depth_sum = depth_sum + opacity * t;
        result.transmittance = next;
        if result.transmittance < epsilon {
            break;
        }
    }
    if weight_sum > zero {
        result.depth = depth_sum / weight_sum;
    }
    result
}

/// Sun irradiance and ambient sky radiance at a point of a planet's atmosphere, from
/// `atmos` ([`atmos_light`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AtmosLight {
    /// The sun's irradiance on a surface facing it at the point: `sun_irradiance` times
    /// the model's transmittance toward the sun; zero behind the planet.
    pub sun_irradiance: [f64; 3],
    /// The uniform sky radiance with the sky's irradiance on a horizontal surface at the
    /// point (`atmos` [`ground_irradiance`](atmos::ground_irradiance::ground_irradiance)`.sky / π`).
    pub ambient_radiance: [f64; 3],
}

/// The sun light and the ambient sky at `point` (planet-centred, metres) with the sun
/// along unit `sun` (planet-centred frame), from any `atmos` [`SkyModel`] of
/// `atmosphere`: `quadrature` is the hemisphere integral of the sky irradiance. Build a
/// [`Lighting`] from it with the sun and up directions expressed in the field's frame.
pub fn atmos_light(
    model: &impl SkyModel,
    atmosphere: &Atmosphere,
    point: DVec3,
    sun: DVec3,
    quadrature: atmos::ground_irradiance::HemisphereQuadrature,
) -> Result<AtmosLight, MarchError> {
    let irradiance =
        atmos::ground_irradiance::ground_irradiance(model, atmosphere, point, sun, quadrature)?;
    let query = SkyQuery::new(atmosphere.planet_radius, point, sun, sun)?;
    let r = query.r().max(atmosphere.planet_radius);
    let mu_s = query.mu_s();
    let behind_planet = mu_s < 0.0
        && atmos::reference::ray_sphere_intersect(r, mu_s, atmosphere.planet_radius)[1] > 0.0;
    let sun_irradiance = if behind_planet {
        [0.0; 3]
    } else {
        let t = model.evaluate(&query).transmittance;
        std::array::from_fn(|k| t[k] * atmosphere.sun_irradiance[k])
    };
    Ok(AtmosLight {
        sun_irradiance,
        ambient_radiance: irradiance.sky.map(|e| e / std::f64::consts::PI),
    })
}

/// The cloud seen through the air in front of it: `cloud.radiance · T_air + L_air ·
/// (1 − cloud.transmittance)`, where `(L_air, T_air)` are `model`'s in-scattered radiance
/// and transmittance from `camera` (planet-centred, m) along unit `view` to the cloud's
/// [`depth`](MarchResult::depth), sun along unit `sun`. The air's own light in front of
/// the cloud replaces, in proportion to the cloud's opacity, what the sky behind would
/// have added (the sky behind is composited by the caller with `cloud.transmittance`).
pub fn apply_aerial_perspective(
    model: &impl SkyModel,
    atmosphere: &Atmosphere,
    camera: DVec3,
    view: DVec3,
    sun: DVec3,
    cloud: &MarchResult<f64>,
) -> Result<[f64; 3], MarchError> {
    let query =
        SkyQuery::with_max_distance(atmosphere.planet_radius, camera, view, sun, cloud.depth)?;
    let air = model.evaluate(&query);
    let opacity = 1.0 - cloud.transmittance;
    Ok(std::array::from_fn(|k| {
        cloud.radiance[k] * air.transmittance[k] + air.radiance[k] * opacity
    }))
}

/// The unit view direction through the centre of pixel `pixel` of a `size[0] × size[1]`
/// image (row 0 at the top) of a pinhole camera looking along unit `forward` with unit
/// `right` and `up`; `tan_half` the tangents of the horizontal and vertical half fields of
/// view. WGSL twin `pixel_direction`.
pub fn pixel_direction<F: Real>(
    pixel: [u32; 2],
    size: [u32; 2],
    forward: [F; 3],
    right: [F; 3],
    up: [F; 3],
    tan_half: [F; 2],
) -> [F; 3] {
    let (one, two, half) = (F::one(), F::of(2.0), F::of(0.5));
    let sx = (two * (count::<F>(pixel[0]) + half) / count::<F>(size[0]) - one) * tan_half[0];
    let sy = (one - two * (count::<F>(pixel[1]) + half) / count::<F>(size[1])) * tan_half[1];
    let v: [F; 3] = std::array::from_fn(|a| forward[a] + sx * right[a] + sy * up[a]);
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n)
}

/// A pinhole camera in the field's frame: position, orthonormal forward / right / up and
/// the horizontal field of view (the vertical one follows from the image's aspect).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinholeCamera {
    origin: [f64; 3],
    forward: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    horizontal_fov: f64,
}

impl PinholeCamera {
    /// A camera at `origin` (m) looking at `target` (m) with `up_hint` roughly up and a
    /// horizontal field of view `horizontal_fov` in radians (0, π). Errors name the field
    /// (a target at the origin, an up hint along the view, NaN, a field of view out of
    /// range).
    pub fn look_at(
        origin: [f64; 3],
        target: [f64; 3],
        up_hint: [f64; 3],
        horizontal_fov: f64,
    ) -> Result<Self, MarchError> {
        let o = DVec3::from_array(origin);
        let t = DVec3::from_array(target);
        for c in origin.into_iter().chain(target).chain(up_hint) {
            if !c.is_finite() {
                return Err(invalid("camera position/target/up", c, "must be finite"));
            }
        }
        if !(horizontal_fov > 0.0 && horizontal_fov < std::f64::consts::PI) {
            return Err(invalid(
                "horizontal_fov",
                horizontal_fov,
                "must be in (0, π) rad",
            ));
        }
        let forward = (t - o).normalize_or_zero();
        if forward == DVec3::ZERO {
            return Err(invalid(
                "target",
                (t - o).length(),
                "must differ from the origin",
            ));
        }
        let right = forward
            .cross(DVec3::from_array(up_hint))
            .normalize_or_zero();
        if right == DVec3::ZERO {
            return Err(invalid("up_hint", 0.0, "must not be parallel to the view"));
        }
        let up = right.cross(forward);
        Ok(Self {
            origin,
            forward: forward.to_array(),
            right: right.to_array(),
            up: up.to_array(),
            horizontal_fov,
        })
    }

    /// Position (m).
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }

    /// Unit forward, right and up.
    pub fn basis(&self) -> [[f64; 3]; 3] {
        [self.forward, self.right, self.up]
    }

    /// `[tan(h/2), tan(h/2)·height/width]` for an image of `size`.
    pub fn tan_half(&self, size: [u32; 2]) -> [f64; 2] {
        let t = (0.5 * self.horizontal_fov).tan();
        [t, t * f64::from(size[1]) / f64::from(size[0])]
    }
}

/// The CPU image of the view march (rows top to bottom, x fastest): each pixel marched by
/// [`march_view_at_pixel`] along [`pixel_direction`]. `render_image::<f32>` on a
/// [`CloudVolume`](crate::CloudVolume) is the twin of the GPU pass
/// `gpu::MarchPass`; a zero-sized image is empty.
pub fn render_image<F: Real>(
    field: &impl DensityField<F>,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
) -> Vec<MarchResult<F>> {
    let [forward, right, up] = camera.basis().map(|v| v.map(F::of));
    let tan_half = camera.tan_half(size).map(F::of);
    let origin = camera.origin.map(F::of);
    let mut out = Vec::with_capacity(size[0] as usize * size[1] as usize);
    for y in 0..size[1] {
        for x in 0..size[0] {
            let d = pixel_direction([x, y], size, forward, right, up, tan_half);
            out.push(march_view_at_pixel(
                field,
                origin,
                d,
                settings,
                lighting,
                [x, y],
            ));
        }
    }
    out
}

/// [`render_image`] with each pixel's march stopped at its `max_distance` (metres along
/// the pixel's ray, x fastest, row 0 at the top: [`march_view_at_pixel_limited`]); the
/// twin of `gpu::MarchPass::prepare_limited`. `max_distance` must hold one value per
/// pixel (`+∞` or NaN: no limit).
pub fn render_image_limited<F: Real>(
    field: &impl DensityField<F>,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    max_distance: &[F],
) -> Result<Vec<MarchResult<F>>, MarchError> {
    let pixels = size[0] as usize * size[1] as usize;
    if max_distance.len() != pixels {
        return Err(invalid(
            "max_distance.len()",
            max_distance.len() as f64,
            "must be size[0]·size[1] (one distance per pixel)",
        ));
    }
    let [forward, right, up] = camera.basis().map(|v| v.map(F::of));
    let tan_half = camera.tan_half(size).map(F::of);
    let origin = camera.origin.map(F::of);
    let mut out = Vec::with_capacity(pixels);
    for y in 0..size[1] {
        for x in 0..size[0] {
            let d = pixel_direction([x, y], size, forward, right, up, tan_half);
            let limit = max_distance[x as usize + size[0] as usize * y as usize];
            out.push(march_view_at_pixel_limited(
                field,
                origin,
                d,
                settings,
                lighting,
                [x, y],
                limit,
            ));
        }
    }
    Ok(out)
}

/// A march result faded by `fade` in [0, 1] (e.g. a shell's horizon fade at the result's
/// [`depth`](MarchResult::depth)): the cloud's radiance times `fade` and its opacity
/// times `fade`, i.e. transmittance `1 − fade·(1 − T)`. The GPU shell pass applies it
/// with [`CloudShell::horizon_fade`](crate::CloudShell::horizon_fade).
pub fn faded<F: Real>(result: MarchResult<F>, fade: F) -> MarchResult<F> {
    MarchResult {
        radiance: result.radiance.map(|c| c * fade),
        transmittance: F::one() - fade * (F::one() - result.transmittance),
        depth: result.depth,
    }
}
