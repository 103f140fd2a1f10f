//! The ground's cloud shadow map of a procedural cloud shell ([`crate::CloudShell`], its
//! weather procedural or a user grid): the [`crate::shadow_map`] march with the shell's density
//! evaluated per sample, as the GPU does ([`crate::gpu::ShellShadowMapPass`]:
//! `shaders/cloudlight/field_march.wgsl`'s `shadow_texel` over `density_shell.wgsl`).
//!
//! The shell's parameters travel as one [`ShellField`] (WGSL struct `ShellField`);
//! [`shell_field_density`] is [`crate::DensityField::density`] of the shell written out
//! (the weather, then [`crate::shell::shell_density`]), and [`shell_shadow_texel`] is
//! [`crate::shadow_map::shadow_texel`] over the shell's spans
//! ([`crate::shell::shell_ray_spans`]), the same operations in the same order: the f32
//! instantiation equals `shadow_texel::<f32, CloudShell>` bit for bit (a unit test
//! checks it), so a CPU renderer that bakes through the generic march and a GPU that
//! bakes through this pass compute one formula.
//!
//! The noise is evaluated, not looked up in baked textures: that is what the GPU shell
//! march (`cloudlight::gpu::MarchShellPass`, the same `density_shell.wgsl`) does, so the map
//! and the march see the same deck.

use atmos::real::Real;

use crate::cone;
use crate::shadow_map::{
    SATURATION, ShadowMapPlan, shadow_accumulate, shadow_march_point, shadow_span_optical_depth,
    shadow_texel_centre,
};
use crate::shell::{
    CloudShell, WeatherMap, procedural_weather, shell_density, shell_ray_spans,
    weather_grid_bilinear, weather_grid_taps,
};

/// [`ShellField::weather_kind`] of a procedural weather (the `weather_*`, `coverage_*` and
/// `cloud_type_*` fields).
pub const WEATHER_PROCEDURAL: u32 = 0;
/// [`ShellField::weather_kind`] of a user weather grid (the `grid_*` fields).
pub const WEATHER_GRID: u32 = 1;

/// A shell, its parameters in the float type (WGSL struct `ShellField`; the f32
/// instantiation is what the GPU pass uploads, the grid's cells going to a storage
/// buffer). Lengths in metres, planet-centred. The weather is procedural or a user grid
/// ([`ShellField::weather_kind`]); the other kind's fields are zero.
#[derive(Debug, Clone, PartialEq)]
pub struct ShellField<F> {
    /// The planet's radius (a ray stops where it meets the planet).
    pub planet_radius: F,
    /// The shell's inner radius.
    pub inner_radius: F,
    /// The shell's outer radius.
    pub outer_radius: F,
    /// The shape noise's period.
    pub shape_period: F,
    /// The detail noise's period.
    pub detail_period: F,
    /// Detail erosion strength in [0, 1).
    pub erosion: F,
    /// σ_t per unit density, 1/m.
    pub extinction_per_density: F,
    /// The procedural weather's period.
    pub weather_period: F,
    /// Mean coverage.
    pub coverage_mean: F,
    /// Coverage contrast.
    pub coverage_contrast: F,
    /// Mean cloud type.
    pub cloud_type_mean: F,
    /// Cloud type contrast.
    pub cloud_type_contrast: F,
    /// The noise's seed.
    pub seed: u32,
    /// The weather's seed.
    pub weather_seed: u32,
    /// The weather's lattice cells per period.
    pub weather_cells: u32,
    /// [`WEATHER_PROCEDURAL`] or [`WEATHER_GRID`].
    pub weather_kind: u32,
    /// The weather grid's cells along x and y.
    pub grid_size: [u32; 2],
    /// The weather grid's cell edge, metres.
    pub grid_cell_size: F,
    /// The weather grid's `[coverage, cloud_type]` per cell, x fastest (empty for a
    /// procedural weather); on the GPU the storage binding `shell_weather_grid`
    /// (`density_shell.wgsl`).
    pub grid_cells: Vec<[f32; 2]>,
}

impl<F: Real> ShellField<F> {
    /// `shell`'s parameters rounded to `F` (a grid's cells stay f32, as stored).
    pub fn of(shell: &CloudShell) -> Self {
        let s = shell.settings();
        let zero = F::zero();
        let mut field = Self {
            planet_radius: F::of(shell.planet_radius()),
            inner_radius: F::of(s.inner_radius),
            outer_radius: F::of(s.outer_radius),
            shape_period: F::of(s.shape_period),
            detail_period: F::of(s.detail_period),
            erosion: F::of(s.erosion),
            extinction_per_density: F::of(s.extinction_per_density),
            weather_period: zero,
            coverage_mean: zero,
            coverage_contrast: zero,
            cloud_type_mean: zero,
            cloud_type_contrast: zero,
            seed: s.seed,
            weather_seed: 0,
            weather_cells: 0,
            weather_kind: WEATHER_PROCEDURAL,
            grid_size: [0, 0],
            grid_cell_size: zero,
            grid_cells: Vec::new(),
        };
        match &s.weather {
            WeatherMap::Procedural(w) => {
                field.weather_period = F::of(w.period);
                field.coverage_mean = F::of(w.coverage_mean);
                field.coverage_contrast = F::of(w.coverage_contrast);
                field.cloud_type_mean = F::of(w.cloud_type_mean);
                field.cloud_type_contrast = F::of(w.cloud_type_contrast);
                field.weather_seed = w.seed;
                field.weather_cells = w.cells;
            }
            WeatherMap::Grid(g) => {
                field.weather_kind = WEATHER_GRID;
                field.grid_size = g.size;
                field.grid_cell_size = F::of(g.cell_size);
                field.grid_cells = g
                    .coverage
                    .iter()
                    .zip(&g.cloud_type)
                    .map(|(&c, &t)| [c, t])
                    .collect();
            }
        }
        field
    }
}

/// The shell's `[coverage, cloud_type]` at horizontal position `xy` (metres): the
/// procedural weather, or the grid's [`weather_grid_taps`] read from
/// [`ShellField::grid_cells`] then [`weather_grid_bilinear`] (what
/// [`CloudShell::weather_at`] computes, op for op). WGSL twin `shell_field_weather` (the
/// cells from its storage binding).
pub fn shell_field_weather<F: Real>(field: &ShellField<F>, xy: [F; 2]) -> [F; 2] {
    if field.weather_kind == WEATHER_GRID {
        let taps = weather_grid_taps(field.grid_size, field.grid_cell_size, xy);
        let values = taps
            .index
            .map(|k| field.grid_cells[k as usize].map(|v| F::of(f64::from(v))));
        return weather_grid_bilinear(values, taps.fraction);
    }
    procedural_weather(
        xy,
        field.weather_period,
        field.weather_cells,
        field.weather_seed,
        field.coverage_mean,
        field.coverage_contrast,
        field.cloud_type_mean,
        field.cloud_type_contrast,
    )
}

/// The shell's density at planet-centred `p`: zero outside `(inner, outer)`, else
/// [`shell_density`] with the weather at `(x, y)` ([`shell_field_weather`]; the shell's
/// [`crate::DensityField::density`], op for op). WGSL twin `shell_field_density`.
pub fn shell_field_density<F: Real>(field: &ShellField<F>, p: [F; 3]) -> F {
    let (inner, outer) = (field.inner_radius, field.outer_radius);
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if !(r > inner && r < outer) {
        return F::zero();
    }
    let [coverage, cloud_type] = shell_field_weather(field, [p[0], p[1]]);
    shell_density(
        p,
        inner,
        outer,
        coverage,
        cloud_type,
        field.shape_period,
        field.detail_period,
        field.erosion,
        field.seed,
    )
}

/// The marched transmittance toward the sun (unit `to_sun`) from `ground`
/// (planet-centred) through the shell: `steps` midpoint samples on each of its spans
/// ([`shell_ray_spans`]), `exp(−Σ τ)` ([`crate::shadow_map::shadow_texel`] over the
/// shell). WGSL twin: `field_march.wgsl`'s `shadow_texel` with `density_shell.wgsl`'s
/// field.
pub fn shell_shadow_texel<F: Real>(
    field: &ShellField<F>,
    ground: [F; 3],
    to_sun: [F; 3],
    steps: u32,
) -> F {
    let spans = shell_ray_spans(
        ground,
        to_sun,
        field.planet_radius,
        field.inner_radius,
        field.outer_radius,
    );
    let sigma_t = field.extinction_per_density;
    let mut tau = F::zero();
    for &(enter, exit) in spans.as_slice() {
        let span = [enter, exit];
        let mut sum = F::zero();
        for k in 0..steps {
            let rho =
                shell_field_density(field, shadow_march_point(ground, to_sun, span, k, steps));
            sum = shadow_accumulate(sum, rho);
        }
        tau = (tau + shadow_span_optical_depth(sum, span, steps, sigma_t)).min(F::of(SATURATION));
    }
    cone::beer_lambert(tau)
}

/// The shell's shadow map for `plan` (its grid in the shell's planet-centred frame: the
/// ground height is a radius-scale z): one transmittance per texel, `i` fastest. The f32
/// instantiation is the CPU twin of [`crate::gpu::ShellShadowMapPass`].
pub fn shell_shadow_map<F: Real>(field: &ShellField<F>, plan: &ShadowMapPlan) -> Vec<F> {
    let grid = &plan.grid;
    let [nx, ny] = grid.resolution();
    let origin = grid.origin().map(F::of);
    let (cell, ground) = (F::of(grid.cell_size()), F::of(grid.ground_height()));
    let to_sun = plan.to_sun().map(F::of);
    let mut out = Vec::with_capacity(grid.texels());
    for j in 0..ny {
        for i in 0..nx {
            let p = shadow_texel_centre([i, j], origin, cell, ground);
            out.push(shell_shadow_texel(field, p, to_sun, plan.steps()));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shadow_map::{ShadowGrid, shadow_map};
    use crate::shell::{ProceduralWeather, ShellSettings, WeatherGrid};

    fn shell() -> CloudShell {
        let earth = atmos::Atmosphere::earth();
        let mut s = ShellSettings::cumulus_over(earth.planet_radius);
        s.detail_period = 800.0;
        s.weather = WeatherMap::Procedural(ProceduralWeather {
            coverage_mean: 0.6,
            ..ProceduralWeather::default()
        });
        CloudShell::new(&earth, s).unwrap()
    }

    fn plan(shell: &CloudShell, elevation_deg: f64) -> ShadowMapPlan {
        let (e, a) = (elevation_deg.to_radians(), 0.7f64);
        let to_sun = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
        let base = shell.settings().inner_radius;
        let grid = ShadowGrid::new([-6000.0, -5000.0], 250.0, [40, 36], base).unwrap();
        ShadowMapPlan::new(grid, to_sun, 16).unwrap()
    }

    #[test]
    fn the_twin_is_the_generic_march_bit_for_bit() {
        let shell = shell();
        let field = ShellField::<f32>::of(&shell);
        let field64 = ShellField::<f64>::of(&shell);
        for elevation in [70.0, 25.0, 3.0] {
            let plan = plan(&shell, elevation);
            let generic = shadow_map::<f32, _>(&shell, &plan);
            let twin = shell_shadow_map(&field, &plan);
            assert_eq!(generic, twin, "sun {elevation}°");
            assert!(twin.iter().any(|&t| t < 0.5), "sun {elevation}°: no shadow");
            assert_eq!(
                shadow_map::<f64, _>(&shell, &plan),
                shell_shadow_map(&field64, &plan)
            );
        }
    }

    #[test]
    fn a_grid_weather_twin_is_the_generic_march_bit_for_bit() {
        let earth = atmos::Atmosphere::earth();
        let mut s = ShellSettings::cumulus_over(earth.planet_radius);
        s.detail_period = 800.0;
        let (nx, ny) = (5u32, 3u32);
        let n = (nx * ny) as usize;
        s.weather = WeatherMap::Grid(WeatherGrid {
            size: [nx, ny],
            cell_size: 1700.0,
            coverage: (0..n).map(|k| [0.9, 0.2, 0.7, 1.0][k % 4]).collect(),
            cloud_type: (0..n).map(|k| [0.5, 1.0, 0.8][k % 3]).collect(),
            precipitation: None,
        });
        let shell = CloudShell::new(&earth, s).unwrap();
        let field = ShellField::<f32>::of(&shell);
        assert_eq!(field.weather_kind, WEATHER_GRID);
        assert_eq!(field.grid_cells.len(), n);
        for elevation in [70.0, 25.0] {
            let plan = plan(&shell, elevation);
            let twin = shell_shadow_map(&field, &plan);
            assert_eq!(
                shadow_map::<f32, _>(&shell, &plan),
                twin,
                "sun {elevation}°"
            );
            assert!(twin.iter().any(|&t| t < 0.5), "sun {elevation}°: no shadow");
        }
    }
}
