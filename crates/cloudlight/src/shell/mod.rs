//! The procedural cloud shell: clouds between two spheres about the planet
//! centre, shaped by tileable noise ([`crate::noise`]), a weather map and a height
//! profile per cloud type, after Schneider (GPU Pro 7, "Real-Time Volumetric
//! Cloudscapes"; SIGGRAPH 2015, Horizon Zero Dawn).
//!
//! **Frame.** Points are planet-centred, in metres, with the camera near the +z pole (the
//! frame `atmos` uses). The shell's noise and weather are sampled in a local frame
//! `q = (x, y, r − inner_radius)`: the point's planet-centred `x`, `y` (its projection on
//! the tangent plane at the pole, accurate for the few hundred kilometres a view of the
//! shell spans) and its height above the inner sphere, so cloud layers follow the
//! planet's curvature.
//!
//! **Density** ([`shell_density`], [`shell_density_from_noise`]), dimensionless in [0, 1]:
//!
//! 1. height fraction `h = (r − inner)/(outer − inner)`; zero outside `(inner, outer)`;
//! 2. base shape `b = remap(shape₀, −(1 − fbm), 1, 0, 1) = (shape₀ + 1 − fbm)/(2 − fbm)`
//!    with `fbm` the Worley fBm of `shape₁..₃` (Schneider's low-frequency erosion);
//! 3. height profile `g = height_gradient(h, cloud_type)` (below);
//! 4. coverage `c = max(b·g + coverage − 1, 0)`: Schneider's
//!    `remap(b·g, 1 − coverage, 1, 0, 1)·coverage`, which simplifies to this and is
//!    defined at coverage 0 (where it is exactly 0, since `b·g ≤ 1`);
//! 5. detail erosion `e = erosion·mix(dfbm, 1 − dfbm, clamp(10h, 0, 1))` with `dfbm` the
//!    Worley fBm of the detail channels (billowy at the base, wispy above), and the
//!    density `max(c − e, 0)/(1 − e)` (Schneider's `remap(c, e, 1, 0, 1)`).
//!
//! The noise is looked up only where the density depends on it (steps 2–4, then step 5):
//! the shape noise not where `g + coverage − 1` is clearly negative (then `c = 0`, since
//! `b ≤ 1`), the detail noise only where `c > 0`. The result is the same, bit for bit, as
//! looking both up.
//!
//! **Height profiles** ([`height_gradient`]): a trapezoid `smoothstep(a, b, h) −
//! smoothstep(c, d, h)` over the height fraction, with the corner fractions
//! [`STRATUS_GRADIENT`] `(0, 0.1, 0.2, 0.3)` (a thin layer at the shell's base),
//! [`STRATOCUMULUS_GRADIENT`] `(0.02, 0.2, 0.48, 0.625)` (the lower half) and
//! [`CUMULUS_GRADIENT`] `(0, 0.1625, 0.88, 0.98)` (almost the whole shell). The cloud
//! type `t ∈ [0, 1]` blends the corners: stratus at 0, stratocumulus at ½, cumulus at 1,
//! with weights `1 − clamp(2t, 0, 1)`, `1 − 2|t − ½|`, `2·clamp(t − ½, 0, 1)`. (These
//! are the corners of the widely used open implementations of Schneider's profiles,
//! e.g. fede-vaccaro's TerrainEngine `volumetric_clouds.comp`.)
//!
//! **Weather** ([`WeatherMap`]): coverage and cloud type (and optionally precipitation,
//! which the density does not use; it is carried for the lighting) either procedural
//! ([`ProceduralWeather`]: Perlin fBm, seeded, tileable over a stated horizontal period)
//! or a user grid ([`WeatherGrid`]: bilinear, repeating over its extent).
//!
//! **Horizon fade** ([`horizon_fade`]): a view-dependent factor, `1 − smoothstep(start,
//! end, t)` of the distance `t` along the view ray. It is not part of the density (a
//! light march toward the sun must not fade), so the view march multiplies its samples'
//! density by it.
//!
//! **Spans** ([`shell_ray_spans`]): where a ray is inside the shell, from `atmos`'
//! stable ray–sphere roots ([`atmos::geometry::ray_sphere_intersect`]); one span, or two
//! when the ray crosses the inner sphere from above; a ray that meets the planet stops
//! there.
//!
//! Every function is written once over the float type: `f32` mirrors
//! `shaders/cloudlight/shell.wgsl`, `f64` is the parity reference.
//!
//! ```
//! use cloudlight::{CloudShell, DensityField, ShellSettings};
//!
//! let earth = atmos::Atmosphere::earth();
//! // Cumulus between 1.5 km and 4 km, procedural weather.
//! let shell = CloudShell::new(&earth, ShellSettings::cumulus_over(earth.planet_radius))?;
//! // A camera 2 m above the ground looking straight up meets the layer once.
//! let camera = [0.0, 0.0, earth.planet_radius + 2.0];
//! let spans = DensityField::<f64>::ray_spans(&shell, camera, [0.0, 0.0, 1.0]);
//! assert_eq!(spans.count, 1);
//! assert!((spans.spans[0].0 - 1498.0).abs() < 1e-6);
//! // No cloud below the layer.
//! assert_eq!(DensityField::<f64>::density(&shell, camera), 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod baked;
mod cloud_shell;
mod grid;
mod model;
mod settings;

pub use baked::BakedShell;
pub use cloud_shell::CloudShell;
pub use grid::{WeatherGridTaps, bilinear_wrapped, weather_grid_bilinear, weather_grid_taps};
pub use model::{
    CUMULUS_GRADIENT, STRATOCUMULUS_GRADIENT, STRATUS_GRADIENT, height_gradient, horizon_fade,
    procedural_weather, shell_density, shell_density_from_noise, shell_density_textured,
    shell_ray_spans, shell_smoothstep,
};
pub use settings::{ProceduralWeather, ShellSettings, WeatherGrid, WeatherMap, WeatherSample};

/// Why a [`CloudShell`] could not be made: the field and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ShellError {
    /// A parameter is NaN or infinite.
    #[error("{field} = {value}: must be finite")]
    NotFinite {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A length, scale or coefficient is zero or negative.
    #[error("{field} = {value}: must be > 0")]
    NotPositive {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// The inner radius is not below the outer one.
    #[error("inner_radius = {inner} m must be below outer_radius = {outer} m")]
    RadiiOrder {
        /// The inner radius, metres.
        inner: f64,
        /// The outer radius, metres.
        outer: f64,
    },
    /// The inner sphere is at or below the ground.
    #[error("inner_radius = {inner} m must be above the planet radius {planet} m")]
    InnerBelowGround {
        /// The inner radius, metres.
        inner: f64,
        /// The atmosphere's planet radius, metres.
        planet: f64,
    },
    /// A value that must lie in a range does not.
    #[error("{field} = {value}: must be in {range}")]
    OutOfRange {
        /// The parameter.
        field: &'static str,
        /// Its value.
        value: f64,
        /// The allowed range, as text.
        range: &'static str,
    },
    /// The fade's start is not below its end.
    #[error("horizon_fade_start = {start} m must be below horizon_fade_end = {end} m")]
    FadeOrder {
        /// Start of the fade, metres.
        start: f64,
        /// End of the fade, metres.
        end: f64,
    },
    /// A weather grid's layer has the wrong number of values.
    #[error("weather grid {field} has {len} values but nx · ny = {nx} · {ny}")]
    GridSize {
        /// The layer.
        field: &'static str,
        /// Its length.
        len: usize,
        /// Cells along x.
        nx: u32,
        /// Cells along y.
        ny: u32,
    },
    /// A weather grid value is outside [0, 1] or NaN.
    #[error("weather grid {field}[{index}] = {value}: must be in [0, 1]")]
    GridValue {
        /// The layer.
        field: &'static str,
        /// The flat index (x fastest).
        index: usize,
        /// The value.
        value: f32,
    },
    /// A count that must be at least one is zero.
    #[error("{field} = 0: must be ≥ 1")]
    ZeroCount {
        /// The parameter.
        field: &'static str,
    },
}
