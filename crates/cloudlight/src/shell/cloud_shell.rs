//! [`CloudShell`]: validated settings and the density they give.

use atmos::real::Real;

use super::settings::*;
use super::*;
use crate::density::{DensityField, RaySpans};

/// The procedural cloud shell about a planet (module documentation): a
/// [`DensityField`] in the planet-centred frame.
#[derive(Debug, Clone, PartialEq)]
pub struct CloudShell {
    planet_radius: f64,
    pub(super) settings: ShellSettings,
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
