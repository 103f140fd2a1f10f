//! Seed 003's procedural cloud shell: clouds between two spheres about the planet
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

use atmos::geometry::ray_sphere_intersect;
use atmos::real::Real;

use crate::density::{DensityField, RaySpans};
use crate::noise::{
    NoiseTexture, cloud_detail_noise, cloud_shape_noise, perlin_fbm, worley_channels_fbm,
};

/// Stratus height profile corners `(a, b, c, d)` over the height fraction.
pub const STRATUS_GRADIENT: [f64; 4] = [0.0, 0.1, 0.2, 0.3];
/// Stratocumulus height profile corners.
pub const STRATOCUMULUS_GRADIENT: [f64; 4] = [0.02, 0.2, 0.48, 0.625];
/// Cumulus height profile corners.
pub const CUMULUS_GRADIENT: [f64; 4] = [0.0, 0.1625, 0.88, 0.98];

/// Hermite `smoothstep`: `t²(3 − 2t)` with `t = clamp((x − lo)/(hi − lo), 0, 1)`
/// (`lo < hi`). Spelled out in WGSL as `shell_smoothstep` (not the built-in, whose
/// evaluation order is the driver's).
pub fn shell_smoothstep<F: Real>(lo: F, hi: F, x: F) -> F {
    let t = ((x - lo) / (hi - lo)).max(F::zero()).min(F::one());
    t * t * (F::of(3.0) - F::of(2.0) * t)
}

/// The height profile in [0, 1] at height fraction `h` for cloud type `cloud_type`
/// (0 stratus, ½ stratocumulus, 1 cumulus; module documentation). WGSL twin
/// `height_gradient`.
pub fn height_gradient<F: Real>(h: F, cloud_type: F) -> F {
    let (zero, one, two, half) = (F::zero(), F::one(), F::of(2.0), F::of(0.5));
    let stratus = one - (cloud_type * two).max(zero).min(one);
    let stratocumulus = one - (cloud_type - half).abs() * two;
    let cumulus = (cloud_type - half).max(zero).min(one) * two;
    let corner = |k: usize| {
        stratus * F::of(STRATUS_GRADIENT[k])
            + stratocumulus * F::of(STRATOCUMULUS_GRADIENT[k])
            + cumulus * F::of(CUMULUS_GRADIENT[k])
    };
    let (a, b, c, d) = (corner(0), corner(1), corner(2), corner(3));
    (shell_smoothstep(a, b, h) - shell_smoothstep(c, d, h)).max(zero)
}

/// The density (module documentation, steps 2–5) from the height fraction `h` (in
/// [0, 1]), the weather's `coverage` and `cloud_type`, the shape noise's four channels,
/// the detail noise's three and the detail `erosion` strength (in [0, 1)). WGSL twin
/// `shell_density_from_noise`.
pub fn shell_density_from_noise<F: Real>(
    h: F,
    coverage: F,
    cloud_type: F,
    shape: [F; 4],
    detail: [F; 3],
    erosion: F,
) -> F {
    let (zero, one) = (F::zero(), F::one());
    let fbm = worley_channels_fbm([shape[1], shape[2], shape[3]]);
    let base = (shape[0] + one - fbm) / (F::of(2.0) - fbm);
    let gradient = height_gradient(h, cloud_type);
    let covered = (base * gradient + coverage - one).max(zero);
    if covered <= zero {
        return zero;
    }
    let detail_fbm = worley_channels_fbm(detail);
    let wisp = (h * F::of(10.0)).max(zero).min(one);
    let modifier = detail_fbm + wisp * ((one - detail_fbm) - detail_fbm);
    let e = erosion * modifier;
    (covered - e).max(zero) / (one - e)
}

/// The shell's density at the planet-centred point `p` (metres) for the weather
/// `coverage` and `cloud_type` there: zero unless `inner_radius < |p| < outer_radius`,
/// else [`shell_density_from_noise`] of the shape noise at `q / shape_period` and the
/// detail noise at `q / detail_period` (`q = (x, y, |p| − inner_radius)`, periods in
/// metres; `seed` seeds both). WGSL twin `shell_density`.
#[allow(clippy::too_many_arguments)]
pub fn shell_density<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    shape_period: F,
    detail_period: F,
    erosion: F,
    seed: u32,
) -> F {
    density_with(
        p,
        inner_radius,
        outer_radius,
        coverage,
        cloud_type,
        erosion,
        |q| {
            let shape = cloud_shape_noise(q.map(|c| c / shape_period), seed);
            let detail = cloud_detail_noise(q.map(|c| c / detail_period), seed);
            (shape, detail)
        },
    )
}

/// [`shell_density`] with the noise looked up in baked textures (trilinear, repeating:
/// [`NoiseTexture::sample_trilinear`]) instead of evaluated: what a GPU march over
/// [`crate::gpu::NoiseBake`]'s textures computes. WGSL twin `shell_density_textured`.
#[allow(clippy::too_many_arguments)]
pub fn shell_density_textured<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    shape_period: F,
    detail_period: F,
    erosion: F,
    shape: &NoiseTexture,
    detail: &NoiseTexture,
) -> F {
    density_with(
        p,
        inner_radius,
        outer_radius,
        coverage,
        cloud_type,
        erosion,
        |q| {
            let s = shape.sample_trilinear(q.map(|c| c / shape_period));
            let d = detail.sample_trilinear(q.map(|c| c / detail_period));
            (s, [d[0], d[1], d[2]])
        },
    )
}

/// The shell density's steps around the noise lookup `noise(q)` (shape, detail).
fn density_with<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    erosion: F,
    noise: impl Fn([F; 3]) -> ([F; 4], [F; 3]),
) -> F {
    let zero = F::zero();
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if !(r > inner_radius && r < outer_radius) || coverage <= zero {
        return zero;
    }
    let height = r - inner_radius;
    let h = height / (outer_radius - inner_radius);
    if height_gradient(h, cloud_type) <= zero {
        return zero;
    }
    let (shape, detail) = noise([p[0], p[1], height]);
    shell_density_from_noise(h, coverage, cloud_type, shape, detail, erosion)
}

/// The horizon fade at distance `t` (metres) along a view ray: 1 up to `fade_start`,
/// 0 from `fade_end` on, `1 − smoothstep` between (`fade_start < fade_end`). The view
/// march multiplies each sample's density by it (module documentation). WGSL twin
/// `horizon_fade`.
pub fn horizon_fade<F: Real>(t: F, fade_start: F, fade_end: F) -> F {
    F::one() - shell_smoothstep(fade_start, fade_end, t)
}

/// Procedural weather at horizontal position `(x, y)` (metres): `[coverage, cloud_type]`,
/// each `clamp(mean + contrast·(2n − 1), 0, 1)` with `n` the [`perlin_fbm`] on the plane
/// `z = 0` at `(x, y)·cells/period` with lattice period `cells`, so the map repeats every
/// `period` metres; coverage uses seed `noise_octave_seed(seed, 7)`, the type
/// `noise_octave_seed(seed, 8)`. WGSL twin `procedural_weather`.
#[allow(clippy::too_many_arguments)]
pub fn procedural_weather<F: Real>(
    xy: [F; 2],
    period: F,
    cells: u32,
    seed: u32,
    coverage_mean: F,
    coverage_contrast: F,
    type_mean: F,
    type_contrast: F,
) -> [F; 2] {
    let scale = F::of(f64::from(cells)) / period;
    let p = [xy[0] * scale, xy[1] * scale, F::zero()];
    let (zero, one, two) = (F::zero(), F::one(), F::of(2.0));
    let n_coverage = perlin_fbm(p, cells, crate::noise::noise_octave_seed(seed, 7));
    let n_type = perlin_fbm(p, cells, crate::noise::noise_octave_seed(seed, 8));
    let coverage = (coverage_mean + coverage_contrast * (two * n_coverage - one))
        .max(zero)
        .min(one);
    let cloud_type = (type_mean + type_contrast * (two * n_type - one))
        .max(zero)
        .min(one);
    [coverage, cloud_type]
}

/// The spans of the ray `origin + t·direction` (planet-centred metres, unit `direction`,
/// `t ≥ 0`) inside the shell `inner_radius < r < outer_radius`, the ray stopping where it
/// meets the planet (`planet_radius`). From `atmos`' stable ray–sphere roots with
/// `r = |origin|`, `μ = origin·direction / r`. Zero-length spans (a tangent ray) are
/// dropped. WGSL twin `shell_ray_spans`.
pub fn shell_ray_spans<F: Real>(
    origin: [F; 3],
    direction: [F; 3],
    planet_radius: F,
    inner_radius: F,
    outer_radius: F,
) -> RaySpans<F> {
    let zero = F::zero();
    let r = (origin[0] * origin[0] + origin[1] * origin[1] + origin[2] * origin[2]).sqrt();
    let mu = (origin[0] * direction[0] + origin[1] * direction[1] + origin[2] * direction[2]) / r;
    let outer = ray_sphere_intersect(r, mu, outer_radius);
    if outer[1].is_nan() || outer[1] <= zero {
        return RaySpans::none();
    }
    let enter = outer[0].max(zero);
    let mut exit = outer[1];
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    if ground[1] > zero {
        // The ray's line meets the planet ahead: it stops at the first hit (or at once
        // if the origin is inside the planet).
        exit = exit.min(ground[0].max(zero));
    }
    let inner = ray_sphere_intersect(r, mu, inner_radius);
    let mut spans = RaySpans::none();
    let mut push = |a: F, b: F| {
        if b > a {
            spans.spans[spans.count] = (a, b);
            spans.count += 1;
        }
    };
    if inner[1] > zero {
        push(enter, exit.min(inner[0]));
        push(enter.max(inner[1]), exit);
    } else {
        push(enter, exit);
    }
    spans
}

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

/// Procedural weather (see [`procedural_weather`]): Perlin fBm, tileable over `period`
/// metres horizontally.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProceduralWeather {
    /// Seed of the two noise layers.
    pub seed: u32,
    /// The horizontal period of the map, metres (> 0).
    pub period: f64,
    /// Lattice cells of the lowest Perlin octave per period (≥ 1): larger makes smaller
    /// weather features.
    pub cells: u32,
    /// Mean coverage, in [0, 1].
    pub coverage_mean: f64,
    /// Coverage contrast, ≥ 0: the coverage is `clamp(mean + contrast·(2n − 1), 0, 1)`.
    pub coverage_contrast: f64,
    /// Mean cloud type, in [0, 1] (0 stratus, ½ stratocumulus, 1 cumulus).
    pub cloud_type_mean: f64,
    /// Cloud type contrast, ≥ 0.
    pub cloud_type_contrast: f64,
}

impl Default for ProceduralWeather {
    /// Scattered cumulus: 50 km period, 4 cells, coverage 0.5 ± 1·(2n − 1), type 0.8 ± 0.5.
    fn default() -> Self {
        Self {
            seed: 2026,
            period: 50_000.0,
            cells: 4,
            coverage_mean: 0.5,
            coverage_contrast: 1.0,
            cloud_type_mean: 0.8,
            cloud_type_contrast: 0.5,
        }
    }
}

/// A user weather grid: `size[0] × size[1]` cells of `cell_size` metres, x fastest, the
/// first cell's centre at `(cell_size/2, cell_size/2)`; sampled bilinearly between cell
/// centres and repeating over `size·cell_size` metres. Values in [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct WeatherGrid {
    /// Cells along x and y (≥ 1).
    pub size: [u32; 2],
    /// Cell edge, metres (> 0).
    pub cell_size: f64,
    /// Coverage per cell.
    pub coverage: Vec<f32>,
    /// Cloud type per cell (0 stratus, ½ stratocumulus, 1 cumulus).
    pub cloud_type: Vec<f32>,
    /// Precipitation per cell, if any (carried for the lighting; not in the density).
    pub precipitation: Option<Vec<f32>>,
}

/// Where the shell's coverage and cloud type come from.
#[derive(Debug, Clone, PartialEq)]
pub enum WeatherMap {
    /// Procedural, seeded, tileable.
    Procedural(ProceduralWeather),
    /// A user grid.
    Grid(WeatherGrid),
}

/// The weather at a horizontal position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeatherSample<F> {
    /// Coverage in [0, 1].
    pub coverage: F,
    /// Cloud type in [0, 1].
    pub cloud_type: F,
    /// Precipitation in [0, 1] (0 where the map has none).
    pub precipitation: F,
}

/// What a [`CloudShell`] is made from (all lengths in metres).
#[derive(Debug, Clone, PartialEq)]
pub struct ShellSettings {
    /// Radius of the shell's inner sphere about the planet centre (> planet radius).
    pub inner_radius: f64,
    /// Radius of the outer sphere (> inner_radius).
    pub outer_radius: f64,
    /// The weather map.
    pub weather: WeatherMap,
    /// Horizontal and vertical period of the shape noise (one 128³ tile), metres.
    pub shape_period: f64,
    /// Period of the detail noise (one 32³ tile), metres.
    pub detail_period: f64,
    /// Detail erosion strength in [0, 1) (Schneider: 0.2).
    pub erosion: f64,
    /// Extinction per unit density σ_t, 1/m (> 0).
    pub extinction_per_density: f64,
    /// Seed of the shape and detail noise.
    pub seed: u32,
    /// Distance along a view ray where the horizon fade begins, metres (≥ 0).
    pub horizon_fade_start: f64,
    /// Distance where the clouds have faded out, metres (> start).
    pub horizon_fade_end: f64,
}

impl ShellSettings {
    /// A cumulus layer from 1.5 km to 4 km above `planet_radius`: shape noise over
    /// 20 km, detail over 2 km, erosion 0.2, σ_t 0.04 /m, procedural weather
    /// ([`ProceduralWeather::default`]), fading from 60 km to 120 km.
    pub fn cumulus_over(planet_radius: f64) -> Self {
        Self {
            inner_radius: planet_radius + 1_500.0,
            outer_radius: planet_radius + 4_000.0,
            weather: WeatherMap::Procedural(ProceduralWeather::default()),
            shape_period: 20_000.0,
            detail_period: 2_000.0,
            erosion: 0.2,
            extinction_per_density: 0.04,
            seed: 3,
            horizon_fade_start: 60_000.0,
            horizon_fade_end: 120_000.0,
        }
    }

    /// A stratocumulus deck from 1 km to 1.8 km above `planet_radius`: procedural
    /// weather of coverage 0.35 ± 0.25 and cloud type ½ (no contrast), shape noise over
    /// 6 km, detail over 800 m, σ_t 0.04 /m, the rest [`Self::cumulus_over`]'s. The deck
    /// of render's shipped `stratocumulus` scene (`scenes/stratocumulus.toml`; render's
    /// `tests/shell_clouds.rs` checks they are the same).
    pub fn stratocumulus_deck(planet_radius: f64) -> Self {
        Self {
            inner_radius: planet_radius + 1_000.0,
            outer_radius: planet_radius + 1_800.0,
            weather: WeatherMap::Procedural(ProceduralWeather {
                coverage_mean: 0.35,
                coverage_contrast: 0.25,
                cloud_type_mean: 0.5,
                cloud_type_contrast: 0.0,
                ..ProceduralWeather::default()
            }),
            shape_period: 6_000.0,
            detail_period: 800.0,
            extinction_per_density: 0.04,
            ..Self::cumulus_over(planet_radius)
        }
    }
}

/// Seed 003's procedural cloud shell about a planet (module documentation): a
/// [`DensityField`] in the planet-centred frame.
#[derive(Debug, Clone, PartialEq)]
pub struct CloudShell {
    planet_radius: f64,
    settings: ShellSettings,
}

fn finite(field: &'static str, value: f64) -> Result<f64, ShellError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ShellError::NotFinite { field, value })
    }
}

fn positive(field: &'static str, value: f64) -> Result<f64, ShellError> {
    if finite(field, value)? > 0.0 {
        Ok(value)
    } else {
        Err(ShellError::NotPositive { field, value })
    }
}

fn unit(field: &'static str, value: f64) -> Result<f64, ShellError> {
    if (0.0..=1.0).contains(&finite(field, value)?) {
        Ok(value)
    } else {
        Err(ShellError::OutOfRange {
            field,
            value,
            range: "[0, 1]",
        })
    }
}

fn non_negative(field: &'static str, value: f64) -> Result<f64, ShellError> {
    if finite(field, value)? >= 0.0 {
        Ok(value)
    } else {
        Err(ShellError::OutOfRange {
            field,
            value,
            range: "[0, ∞)",
        })
    }
}

fn check_layer(field: &'static str, values: &[f32], nx: u32, ny: u32) -> Result<(), ShellError> {
    if values.len() != nx as usize * ny as usize {
        return Err(ShellError::GridSize {
            field,
            len: values.len(),
            nx,
            ny,
        });
    }
    match values.iter().position(|v| !(0.0..=1.0).contains(v)) {
        Some(index) => Err(ShellError::GridValue {
            field,
            index,
            value: values[index],
        }),
        None => Ok(()),
    }
}

impl CloudShell {
    /// A shell about `atmosphere`'s planet, every parameter checked: radii finite with
    /// `planet < inner < outer`, periods, σ_t and the grid's cell size > 0, erosion in
    /// [0, 1), weather values in [0, 1], the grid's layers `nx·ny` long, the fade's start
    /// ≥ 0 and below its end.
    pub fn new(
        atmosphere: &atmos::Atmosphere,
        settings: ShellSettings,
    ) -> Result<Self, ShellError> {
        let planet = finite("planet_radius", atmosphere.planet_radius)?;
        let inner = positive("inner_radius", settings.inner_radius)?;
        let outer = positive("outer_radius", settings.outer_radius)?;
        if inner >= outer {
            return Err(ShellError::RadiiOrder { inner, outer });
        }
        if inner <= planet {
            return Err(ShellError::InnerBelowGround { inner, planet });
        }
        positive("shape_period", settings.shape_period)?;
        positive("detail_period", settings.detail_period)?;
        positive("extinction_per_density", settings.extinction_per_density)?;
        let erosion = finite("erosion", settings.erosion)?;
        if !(0.0..1.0).contains(&erosion) {
            return Err(ShellError::OutOfRange {
                field: "erosion",
                value: erosion,
                range: "[0, 1)",
            });
        }
        let start = non_negative("horizon_fade_start", settings.horizon_fade_start)?;
        let end = finite("horizon_fade_end", settings.horizon_fade_end)?;
        if start >= end {
            return Err(ShellError::FadeOrder { start, end });
        }
        match &settings.weather {
            WeatherMap::Procedural(w) => {
                positive("weather.period", w.period)?;
                if w.cells == 0 {
                    return Err(ShellError::ZeroCount {
                        field: "weather.cells",
                    });
                }
                unit("weather.coverage_mean", w.coverage_mean)?;
                non_negative("weather.coverage_contrast", w.coverage_contrast)?;
                unit("weather.cloud_type_mean", w.cloud_type_mean)?;
                non_negative("weather.cloud_type_contrast", w.cloud_type_contrast)?;
            }
            WeatherMap::Grid(g) => {
                let [nx, ny] = g.size;
                if nx == 0 {
                    return Err(ShellError::ZeroCount {
                        field: "weather.size[0]",
                    });
                }
                if ny == 0 {
                    return Err(ShellError::ZeroCount {
                        field: "weather.size[1]",
                    });
                }
                positive("weather.cell_size", g.cell_size)?;
                check_layer("coverage", &g.coverage, nx, ny)?;
                check_layer("cloud_type", &g.cloud_type, nx, ny)?;
                if let Some(p) = &g.precipitation {
                    check_layer("precipitation", p, nx, ny)?;
                }
            }
        }
        Ok(Self {
            planet_radius: planet,
            settings,
        })
    }

    /// The settings the shell was made from.
    pub fn settings(&self) -> &ShellSettings {
        &self.settings
    }

    /// The planet radius, metres.
    pub fn planet_radius(&self) -> f64 {
        self.planet_radius
    }

    /// The weather at horizontal position `(x, y)` (planet-centred metres).
    pub fn weather_at<F: Real>(&self, xy: [F; 2]) -> WeatherSample<F> {
        match &self.settings.weather {
            WeatherMap::Procedural(w) => {
                let [coverage, cloud_type] = procedural_weather(
                    xy,
                    F::of(w.period),
                    w.cells,
                    w.seed,
                    F::of(w.coverage_mean),
                    F::of(w.coverage_contrast),
                    F::of(w.cloud_type_mean),
                    F::of(w.cloud_type_contrast),
                );
                WeatherSample {
                    coverage,
                    cloud_type,
                    precipitation: F::zero(),
                }
            }
            WeatherMap::Grid(g) => {
                let sample =
                    |layer: &[f32]| bilinear_wrapped(layer, g.size, F::of(g.cell_size), xy);
                WeatherSample {
                    coverage: sample(&g.coverage),
                    cloud_type: sample(&g.cloud_type),
                    precipitation: g.precipitation.as_deref().map_or(F::zero(), sample),
                }
            }
        }
    }

    /// The horizon fade at distance `t` along a view ray ([`horizon_fade`] with this
    /// shell's start and end).
    pub fn horizon_fade<F: Real>(&self, t: F) -> F {
        horizon_fade(
            t,
            F::of(self.settings.horizon_fade_start),
            F::of(self.settings.horizon_fade_end),
        )
    }
}

/// The four cells a weather grid's bilinear lookup reads ([`weather_grid_taps`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeatherGridTaps<F> {
    /// Flat indices (x fastest) of cells `(i, j)`, `(i + 1, j)`, `(i, j + 1)`,
    /// `(i + 1, j + 1)` wrapped into the grid, `i = ⌊x/cell − ½⌋`, `j = ⌊y/cell − ½⌋`.
    pub index: [u32; 4],
    /// `(x/cell − ½ − ⌊x/cell − ½⌋, y/cell − ½ − ⌊y/cell − ½⌋)`, each in [0, 1].
    pub fraction: [F; 2],
}

/// The cells and fractions of a bilinear lookup of a repeating grid of `size` cells of
/// `cell` metres at horizontal position `xy` (metres; cell `(i, j)`'s centre at
/// `((i + ½)·cell, (j + ½)·cell)`, the grid repeating every `size·cell` metres). The
/// caller reads each index's value (on the GPU from its storage binding) and blends
/// them with [`weather_grid_bilinear`]; [`bilinear_wrapped`] is the two over a slice.
/// The cell coordinate `⌊xy/cell − ½⌋` is taken to `i32` saturating (as WGSL's `i32()`
/// does), then wrapped into the grid: exact for `|xy/cell| < 2³¹`. WGSL twin
/// `weather_grid_taps` (same arguments, same order).
pub fn weather_grid_taps<F: Real>(size: [u32; 2], cell: F, xy: [F; 2]) -> WeatherGridTaps<F> {
    let half = F::of(0.5);
    let gx = xy[0] / cell - half;
    let gy = xy[1] / cell - half;
    let (fx, fy) = (gx.floor(), gy.floor());
    // f → i32 saturating (NaN → 0), then into [0, n).
    let wrap = |f: F, n: u32| -> u32 {
        let i = f.to_f64().unwrap_or(0.0) as i32;
        i64::from(i).rem_euclid(i64::from(n)) as u32
    };
    let one = F::one();
    let (x0, x1) = (wrap(fx, size[0]), wrap(fx + one, size[0]));
    let (y0, y1) = (wrap(fy, size[1]), wrap(fy + one, size[1]));
    let nx = size[0];
    WeatherGridTaps {
        index: [x0 + nx * y0, x1 + nx * y0, x0 + nx * y1, x1 + nx * y1],
        fraction: [gx - fx, gy - fy],
    }
}

/// One layer's bilinear blend of its four cells (in [`WeatherGridTaps::index`]'s order)
/// at `fraction`: `a + ty·(b − a)` with `a = v₀₀ + tx·(v₁₀ − v₀₀)`, `b = v₀₁ + tx·(v₁₁ − v₀₁)`.
fn grid_lerp<F: Real>(v: [F; 4], t: [F; 2]) -> F {
    let a = v[0] + t[0] * (v[1] - v[0]);
    let b = v[2] + t[0] * (v[3] - v[2]);
    a + t[1] * (b - a)
}

/// The weather grid's `[coverage, cloud_type]` at a lookup's `fraction` from its four
/// cells' `values` (each `[coverage, cloud_type]`, in [`WeatherGridTaps::index`]'s
/// order): per layer `a + ty·(b − a)`, `a = v₀₀ + tx·(v₁₀ − v₀₀)`,
/// `b = v₀₁ + tx·(v₁₁ − v₀₁)`. WGSL twin `weather_grid_bilinear` (`vec2` per cell).
pub fn weather_grid_bilinear<F: Real>(values: [[F; 2]; 4], fraction: [F; 2]) -> [F; 2] {
    [0, 1].map(|k| grid_lerp(values.map(|v| v[k]), fraction))
}

/// Bilinear sample of one layer (`size[0]·size[1]` values, x fastest) of a repeating grid
/// of `cell` metres at `xy` (metres): [`weather_grid_taps`], then the blend of
/// [`weather_grid_bilinear`] on this layer. What [`CloudShell::weather_at`] computes per
/// layer of a [`WeatherGrid`]; on the GPU each pass reads its own binding between the two
/// (WGSL passes no storage array to a function).
pub fn bilinear_wrapped<F: Real>(layer: &[f32], size: [u32; 2], cell: F, xy: [F; 2]) -> F {
    let taps = weather_grid_taps(size, cell, xy);
    let at = |k: u32| F::of(f64::from(layer[k as usize]));
    grid_lerp(taps.index.map(at), taps.fraction)
}

impl<F: Real> DensityField<F> for CloudShell {
    /// [`shell_density`] with this shell's weather at `(x, y)`.
    fn density(&self, p: [F; 3]) -> F {
        let s = &self.settings;
        let (inner, outer) = (F::of(s.inner_radius), F::of(s.outer_radius));
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if !(r > inner && r < outer) {
            return F::zero();
        }
        let weather = self.weather_at([p[0], p[1]]);
        shell_density(
            p,
            inner,
            outer,
            weather.coverage,
            weather.cloud_type,
            F::of(s.shape_period),
            F::of(s.detail_period),
            F::of(s.erosion),
            s.seed,
        )
    }

    fn extinction_per_density(&self) -> F {
        F::of(self.settings.extinction_per_density)
    }

    /// [`shell_ray_spans`] with this shell's radii and the planet's.
    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> RaySpans<F> {
        shell_ray_spans(
            origin,
            direction,
            F::of(self.planet_radius),
            F::of(self.settings.inner_radius),
            F::of(self.settings.outer_radius),
        )
    }
}

/// A [`CloudShell`] whose noise is looked up in baked textures ([`NoiseTexture`], the CPU
/// twins of [`crate::gpu::NoiseBake`]'s) instead of evaluated: the density a GPU march
/// over the baked textures sees, as a [`DensityField`] (the spans and σ_t are the
/// shell's).
#[derive(Debug, Clone, PartialEq)]
pub struct BakedShell {
    shell: CloudShell,
    shape: NoiseTexture,
    detail: NoiseTexture,
}

impl BakedShell {
    /// Bakes `shell`'s noise (its seed) into a `shape_size`³ shape and a `detail_size`³
    /// detail texture on the CPU (128³ is about 2 million noise evaluations: seconds in
    /// a release build). Sizes of 0 are an error naming the field.
    pub fn new(shell: CloudShell, shape_size: u32, detail_size: u32) -> Result<Self, ShellError> {
        if shape_size == 0 {
            return Err(ShellError::ZeroCount {
                field: "shape_size",
            });
        }
        if detail_size == 0 {
            return Err(ShellError::ZeroCount {
                field: "detail_size",
            });
        }
        let seed = shell.settings.seed;
        Ok(Self {
            shape: NoiseTexture::shape(seed, shape_size),
            detail: NoiseTexture::detail(seed, detail_size),
            shell,
        })
    }

    /// The shell.
    pub fn shell(&self) -> &CloudShell {
        &self.shell
    }

    /// The baked shape texture.
    pub fn shape(&self) -> &NoiseTexture {
        &self.shape
    }

    /// The baked detail texture.
    pub fn detail(&self) -> &NoiseTexture {
        &self.detail
    }
}

impl<F: Real> DensityField<F> for BakedShell {
    /// [`shell_density_textured`] with the shell's weather at `(x, y)`.
    fn density(&self, p: [F; 3]) -> F {
        let s = &self.shell.settings;
        let (inner, outer) = (F::of(s.inner_radius), F::of(s.outer_radius));
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        if !(r > inner && r < outer) {
            return F::zero();
        }
        let weather = self.shell.weather_at([p[0], p[1]]);
        shell_density_textured(
            p,
            inner,
            outer,
            weather.coverage,
            weather.cloud_type,
            F::of(s.shape_period),
            F::of(s.detail_period),
            F::of(s.erosion),
            &self.shape,
            &self.detail,
        )
    }

    fn extinction_per_density(&self) -> F {
        DensityField::<F>::extinction_per_density(&self.shell)
    }

    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> RaySpans<F> {
        self.shell.ray_spans(origin, direction)
    }
}
