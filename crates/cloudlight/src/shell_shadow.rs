//! The ground's cloud shadow map of a procedural cloud shell ([`crate::CloudShell`] with
//! procedural weather): the [`crate::shadow_map`] march with the shell's density
//! evaluated per sample, as `shaders/cloudlight/shell_shadow.wgsl` does on a GPU
//! ([`crate::gpu::ShellShadowMapPass`]).
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
//! march (`cloudlight::gpu::MarchShellPass`, `march_shell_pass.wgsl`) does, so the map
//! and the march see the same deck.

use atmos::real::Real;

use crate::cone;
use crate::shadow_map::{
    SATURATION, ShadowMapPlan, shadow_accumulate, shadow_march_point, shadow_span_optical_depth,
    shadow_texel_centre,
};
use crate::shell::{CloudShell, WeatherMap, procedural_weather, shell_density, shell_ray_spans};

/// A shell with procedural weather, its parameters in the float type (WGSL struct
/// `ShellField`; the f32 instantiation is what the GPU pass uploads). Lengths in metres,
/// planet-centred.
#[derive(Debug, Clone, Copy, PartialEq)]
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
}

/// Why a shell has no [`ShellField`]: its weather is a grid (the GPU shell passes compute
/// procedural weather only).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("weather = Grid: the shell's shadow map on the GPU supports procedural weather only")]
pub struct GridWeather;

impl<F: Real> ShellField<F> {
    /// `shell`'s parameters rounded to `F`; an error for a grid weather map.
    pub fn of(shell: &CloudShell) -> Result<Self, GridWeather> {
        let s = shell.settings();
        let WeatherMap::Procedural(w) = &s.weather else {
            return Err(GridWeather);
        };
        Ok(Self {
            planet_radius: F::of(shell.planet_radius()),
            inner_radius: F::of(s.inner_radius),
            outer_radius: F::of(s.outer_radius),
            shape_period: F::of(s.shape_period),
            detail_period: F::of(s.detail_period),
            erosion: F::of(s.erosion),
            extinction_per_density: F::of(s.extinction_per_density),
            weather_period: F::of(w.period),
            coverage_mean: F::of(w.coverage_mean),
            coverage_contrast: F::of(w.coverage_contrast),
            cloud_type_mean: F::of(w.cloud_type_mean),
            cloud_type_contrast: F::of(w.cloud_type_contrast),
            seed: s.seed,
            weather_seed: w.seed,
            weather_cells: w.cells,
        })
    }
}

/// The shell's density at planet-centred `p`: zero outside `(inner, outer)`, else
/// [`shell_density`] with the procedural weather at `(x, y)` (the shell's
/// [`crate::DensityField::density`], op for op). WGSL twin `shell_field_density`.
pub fn shell_field_density<F: Real>(field: &ShellField<F>, p: [F; 3]) -> F {
    let (inner, outer) = (field.inner_radius, field.outer_radius);
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if !(r > inner && r < outer) {
        return F::zero();
    }
    let [coverage, cloud_type] = procedural_weather(
        [p[0], p[1]],
        field.weather_period,
        field.weather_cells,
        field.weather_seed,
        field.coverage_mean,
        field.coverage_contrast,
        field.cloud_type_mean,
        field.cloud_type_contrast,
    );
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
/// shell). WGSL twin `shell_shadow_texel`.
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
        let field = ShellField::<f32>::of(&shell).unwrap();
        let field64 = ShellField::<f64>::of(&shell).unwrap();
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
    fn a_grid_weather_has_no_field() {
        let earth = atmos::Atmosphere::earth();
        let mut s = ShellSettings::cumulus_over(earth.planet_radius);
        s.weather = WeatherMap::Grid(WeatherGrid {
            size: [1, 1],
            cell_size: 1000.0,
            coverage: vec![0.5],
            cloud_type: vec![0.5],
            precipitation: None,
        });
        let shell = CloudShell::new(&earth, s).unwrap();
        let err = ShellField::<f32>::of(&shell).unwrap_err();
        assert!(err.to_string().starts_with("weather = Grid"), "{err}");
    }
}
