//! The shell's settings and weather, and their validation.

use super::*;

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

pub(super) fn finite(field: &'static str, value: f64) -> Result<f64, ShellError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(ShellError::NotFinite { field, value })
    }
}

pub(super) fn positive(field: &'static str, value: f64) -> Result<f64, ShellError> {
    if finite(field, value)? > 0.0 {
        Ok(value)
    } else {
        Err(ShellError::NotPositive { field, value })
    }
}

pub(super) fn unit(field: &'static str, value: f64) -> Result<f64, ShellError> {
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

pub(super) fn non_negative(field: &'static str, value: f64) -> Result<f64, ShellError> {
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

pub(super) fn check_layer(
    field: &'static str,
    values: &[f32],
    nx: u32,
    ny: u32,
) -> Result<(), ShellError> {
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
