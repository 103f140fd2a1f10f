//! The `[clouds.shell]` section of a scene file and its defaults.

use cloudlight::ShellSettings;
use cloudlight::march::MarchConfig;
use cloudlight::shell::{ProceduralWeather, WeatherMap};
use serde::Deserialize;

/// `[clouds.shell]`: Schneider's (GPU Pro 7) procedural cloud shell (`cloudlight::CloudShell`)
/// between two altitudes, its coverage and cloud type from cloudlight's procedural
/// weather or a weather grid from a PNG ([`crate::shell_clouds`]), marched by `cloudlight` (Schneider's (GPU Pro 7) lighting). Defaults not given here are
/// cloudlight's (`ShellSettings::cumulus_over`, `ProceduralWeather::default`,
/// `MarchConfig::default`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudShellSection {
    /// Altitude of the shell's bottom (its inner sphere) above the planet's surface
    /// (world `y = 0`), metres.
    pub bottom_m: f64,
    /// Altitude of the shell's top (its outer sphere), metres.
    pub top_m: f64,
    /// Mean coverage of the weather, in [0, 1].
    #[serde(default = "default_coverage")]
    pub coverage: f64,
    /// Coverage contrast (≥ 0): coverage `clamp(mean + contrast·(2n − 1), 0, 1)`.
    #[serde(default = "default_coverage_contrast")]
    pub coverage_contrast: f64,
    /// Mean cloud type, in [0, 1]: the height profile, 0 stratus, ½ stratocumulus,
    /// 1 cumulus (blended between).
    #[serde(default = "default_cloud_type")]
    pub cloud_type: f64,
    /// Cloud type contrast, ≥ 0.
    #[serde(default = "default_cloud_type_contrast")]
    pub cloud_type_contrast: f64,
    /// The weather map's horizontal period, metres.
    #[serde(default = "default_weather_period")]
    pub weather_period_m: f64,
    /// Lattice cells of the weather's lowest octave per period (≥ 1).
    #[serde(default = "default_weather_cells")]
    pub weather_cells: u32,
    /// Seed of the weather map.
    #[serde(default = "default_weather_seed")]
    pub weather_seed: u32,
    /// Period of the shape noise (one 128³ tile), metres.
    #[serde(default = "default_shape_period")]
    pub shape_period_m: f64,
    /// Period of the detail noise (one 32³ tile), metres.
    #[serde(default = "default_detail_period")]
    pub detail_period_m: f64,
    /// Detail erosion strength, in [0, 1).
    #[serde(default = "default_erosion")]
    pub erosion: f64,
    /// Extinction per unit density σ_t, 1/m.
    #[serde(default = "default_sigma_t")]
    pub sigma_t_per_density: f64,
    /// Seed of the shape and detail noise.
    #[serde(default = "default_seed")]
    pub seed: u32,
    /// Distance along a view ray where the horizon fade begins, metres.
    #[serde(default = "default_fade_start")]
    pub horizon_fade_start_m: f64,
    /// Distance where the clouds have faded out, metres.
    #[serde(default = "default_fade_end")]
    pub horizon_fade_end_m: f64,
    /// View-march steps per pixel (1..=1024).
    #[serde(default = "default_view_steps")]
    pub view_steps: u32,
    /// Light-march steps toward the sun per sample (1..=256).
    #[serde(default = "default_light_steps")]
    pub light_steps: u32,
    /// Ambient-visibility steps along up per sample (0..=64; 0: visibility 1).
    #[serde(default = "default_ambient_steps")]
    pub ambient_steps: u32,
    /// Multiple-scattering octaves (1: single scattering; 1..=8).
    #[serde(default = "default_octaves")]
    pub octaves: u32,
    /// The octaves' extinction factor `a` in [0, 1].
    #[serde(default = "half")]
    pub octave_a: f64,
    /// The octaves' contribution factor `b` in [0, 1].
    #[serde(default = "half")]
    pub octave_b: f64,
    /// The octaves' phase eccentricity factor `c` in [0, 1].
    #[serde(default = "half")]
    pub octave_c: f64,
    /// A weather grid from a PNG (relative to the scene file's folder; R coverage,
    /// G cloud type, B precipitation; [`crate::shell_clouds`]) instead of the
    /// procedural weather (whose keys are then unused).
    #[serde(default)]
    pub weather_image: Option<std::path::PathBuf>,
    /// The weather image's pixel edge on the ground, metres (> 0; with `weather_image`).
    #[serde(default)]
    pub weather_cell_m: Option<f64>,
}

fn default_shell() -> ShellSettings {
    ShellSettings::cumulus_over(0.0)
}
fn default_coverage() -> f64 {
    ProceduralWeather::default().coverage_mean
}
fn default_coverage_contrast() -> f64 {
    ProceduralWeather::default().coverage_contrast
}
fn default_cloud_type() -> f64 {
    ProceduralWeather::default().cloud_type_mean
}
fn default_cloud_type_contrast() -> f64 {
    ProceduralWeather::default().cloud_type_contrast
}
fn default_weather_period() -> f64 {
    ProceduralWeather::default().period
}
fn default_weather_cells() -> u32 {
    ProceduralWeather::default().cells
}
fn default_weather_seed() -> u32 {
    ProceduralWeather::default().seed
}
fn default_shape_period() -> f64 {
    default_shell().shape_period
}
fn default_detail_period() -> f64 {
    default_shell().detail_period
}
fn default_erosion() -> f64 {
    default_shell().erosion
}
fn default_sigma_t() -> f64 {
    default_shell().extinction_per_density
}
fn default_seed() -> u32 {
    default_shell().seed
}
fn default_fade_start() -> f64 {
    default_shell().horizon_fade_start
}
fn default_fade_end() -> f64 {
    default_shell().horizon_fade_end
}
fn default_view_steps() -> u32 {
    48
}
fn default_light_steps() -> u32 {
    8
}
fn default_ambient_steps() -> u32 {
    MarchConfig::default().ambient_steps
}
fn default_octaves() -> u32 {
    8
}
fn half() -> f64 {
    0.5
}

impl CloudShellSection {
    /// The value of key `key` as typed, with its unit.
    pub(super) fn value_of(&self, key: &str) -> String {
        let metres = |v: f64| format!("{v} m");
        match key {
            "bottom_m" => metres(self.bottom_m),
            "top_m" => metres(self.top_m),
            "coverage" => self.coverage.to_string(),
            "coverage_contrast" => self.coverage_contrast.to_string(),
            "cloud_type" => self.cloud_type.to_string(),
            "cloud_type_contrast" => self.cloud_type_contrast.to_string(),
            "weather_period_m" => metres(self.weather_period_m),
            "weather_cells" => self.weather_cells.to_string(),
            "shape_period_m" => metres(self.shape_period_m),
            "detail_period_m" => metres(self.detail_period_m),
            "erosion" => self.erosion.to_string(),
            "sigma_t_per_density" => format!("{} /m", self.sigma_t_per_density),
            "horizon_fade_start_m" => metres(self.horizon_fade_start_m),
            "horizon_fade_end_m" => metres(self.horizon_fade_end_m),
            "view_steps" => self.view_steps.to_string(),
            "light_steps" => self.light_steps.to_string(),
            "ambient_steps" => self.ambient_steps.to_string(),
            "octaves" => self.octaves.to_string(),
            "octave_a" => self.octave_a.to_string(),
            "octave_b" => self.octave_b.to_string(),
            "octave_c" => self.octave_c.to_string(),
            "weather_image" => format!("{:?}", self.weather_image),
            "weather_cell_m" => format!("{:?} m", self.weather_cell_m),
            _ => String::new(),
        }
    }

    /// cloudlight's shell settings about a planet of `planet_radius` metres.
    pub(super) fn shell_settings(&self, planet_radius: f64) -> ShellSettings {
        ShellSettings {
            inner_radius: planet_radius + self.bottom_m,
            outer_radius: planet_radius + self.top_m,
            weather: WeatherMap::Procedural(ProceduralWeather {
                seed: self.weather_seed,
                period: self.weather_period_m,
                cells: self.weather_cells,
                coverage_mean: self.coverage,
                coverage_contrast: self.coverage_contrast,
                cloud_type_mean: self.cloud_type,
                cloud_type_contrast: self.cloud_type_contrast,
            }),
            shape_period: self.shape_period_m,
            detail_period: self.detail_period_m,
            erosion: self.erosion,
            extinction_per_density: self.sigma_t_per_density,
            seed: self.seed,
            horizon_fade_start: self.horizon_fade_start_m,
            horizon_fade_end: self.horizon_fade_end_m,
        }
    }
}
