//! `[terrain]`'s colour keys: `[terrain.colour]` (a colour image over the heightfield's
//! ground), `materials` (the ramp or the procedural materials) and
//! `[terrain.procedural_materials]` (their parameters).
//!
//! The default albedos are published spectral reflectances reduced to linear sRGB by
//! averaging each over the band where its sRGB primary dominates (blue 430–490 nm,
//! green 500–580 nm, red 600–680 nm):
//! - rock: granite and gneiss in the ASTER spectral library (Baldridge et al. 2009),
//!   grey to slightly warm, about 0.2 across the visible, a little higher in the red;
//! - grass: green grass canopy (Bowker et al. 1985), the chlorophyll peak near 550 nm
//!   over absorption in the blue and red;
//! - snow: aged snow of about 1 mm grains (Wiscombe & Warren 1980; Warren 1982), above
//!   0.9 across the visible and falling toward the red, lowered a few percent for the
//!   soot and dust of a mountain snowpack (Warren & Wiscombe 1980).

use std::path::PathBuf;

use serde::Deserialize;

use crate::terrain_materials::MaterialParams;

/// `[terrain.colour]`: an 8-bit sRGB PNG over the heightfield's ground. Pixel `(i, j)`
/// lies at `(i, j) × cell_size` east and south of the heightfield's texel (0, 0) (the
/// top row north, as the heightfield's), so the image's extent
/// `(width − 1, height − 1) × cell_size` must be the heightfield's.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ColourSection {
    /// The PNG (relative to the scene file's folder).
    pub path: PathBuf,
    /// Metres per pixel.
    pub cell_size: f64,
}

/// Where the terrain's albedo comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum MaterialsModel {
    /// `[terrain.albedo]`'s ramp by elevation and slope.
    #[default]
    Ramp,
    /// Rock, grass and snow by slope, altitude and aspect, with detail up close.
    Procedural,
}

/// `[terrain.procedural_materials]`: the rock, grass and snow of
/// `materials = "procedural"` (`crate::terrain_materials`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProceduralMaterialsSection {
    /// Elevation of the snow line on flat ground, metres.
    pub snow_line_m: f64,
    /// Metres the snow line lies lower per unit of the normal's horizontal component
    /// toward the pole (a slope facing the pole sees less of the sun's mean path).
    pub snow_line_aspect_m: f64,
    /// Elevation above which grass gives way to rock and scree, metres.
    pub grass_line_m: f64,
    /// Width of the altitude transitions, metres.
    pub transition_m: f64,
    /// Slope (degrees) above which the ground is rock, blended in over the 10° below.
    pub rock_slope_deg: f64,
    /// Slope (degrees) above which snow does not lie, sliding off over the 10° below.
    pub snow_slope_deg: f64,
    /// Metres by which the detail noise moves the snow and grass lines.
    pub line_noise_m: f64,
    /// Relative albedo variation of the detail noise, in [0, 1).
    pub albedo_noise: f64,
    /// The detail noise's seed.
    pub seed: u32,
    /// Linear RGB albedo of rock.
    pub rock_albedo: [f64; 3],
    /// Linear RGB albedo of grass (a colour texture replaces it).
    pub grass_albedo: [f64; 3],
    /// Linear RGB albedo of snow.
    pub snow_albedo: [f64; 3],
}

impl Default for ProceduralMaterialsSection {
    /// An alpine range in autumn (the default scene's 1,200–3,000 m): the albedos of
    /// the module documentation.
    fn default() -> Self {
        Self {
            snow_line_m: 2850.0,
            snow_line_aspect_m: 400.0,
            grass_line_m: 2500.0,
            transition_m: 150.0,
            rock_slope_deg: 40.0,
            snow_slope_deg: 55.0,
            line_noise_m: 60.0,
            albedo_noise: 0.25,
            seed: 0,
            rock_albedo: [0.21, 0.20, 0.18],
            grass_albedo: [0.06, 0.10, 0.04],
            snow_albedo: [0.88, 0.91, 0.93],
        }
    }
}

/// The width of the slope blends, degrees.
const SLOPE_BLEND_DEG: f64 = 10.0;

impl ProceduralMaterialsSection {
    /// Checks and converts the section for a scene whose pole is north (`pole_north` =
    /// 1) or south (−1); the error is (key, value as typed, rule).
    pub fn params(
        &self,
        pole_north: f32,
    ) -> Result<MaterialParams<f32>, (&'static str, String, String)> {
        let finite = |key: &'static str, value: f64| {
            if value.is_finite() {
                Ok(value as f32)
            } else {
                Err((key, format!("{value} m"), "must be finite".into()))
            }
        };
        let slope = |key: &'static str, value: f64| {
            if value > SLOPE_BLEND_DEG && value <= 90.0 {
                Ok((
                    (value - SLOPE_BLEND_DEG).to_radians().cos() as f32,
                    value.to_radians().cos() as f32,
                ))
            } else {
                Err((
                    key,
                    format!("{value}°"),
                    format!("must be in ({SLOPE_BLEND_DEG}°, 90°]"),
                ))
            }
        };
        let albedo = |key: &'static str, c: [f64; 3]| {
            if c.iter().all(|v| (0.0..=1.0).contains(v)) {
                Ok(c.map(|v| v as f32))
            } else {
                Err((
                    key,
                    format!("{c:?}"),
                    "each channel must be an albedo in [0, 1]".into(),
                ))
            }
        };
        if !(self.transition_m.is_finite() && self.transition_m > 0.0) {
            return Err((
                "transition_m",
                format!("{} m", self.transition_m),
                "must be finite and > 0".into(),
            ));
        }
        if !(0.0..1.0).contains(&self.albedo_noise) {
            return Err((
                "albedo_noise",
                self.albedo_noise.to_string(),
                "must be in [0, 1)".into(),
            ));
        }
        let (cos_rock_gentle, cos_rock_steep) = slope("rock_slope_deg", self.rock_slope_deg)?;
        let (cos_snow_gentle, cos_snow_steep) = slope("snow_slope_deg", self.snow_slope_deg)?;
        Ok(MaterialParams {
            rock_albedo: albedo("rock_albedo", self.rock_albedo)?,
            snow_line: finite("snow_line_m", self.snow_line_m)?,
            grass_albedo: albedo("grass_albedo", self.grass_albedo)?,
            snow_line_aspect: finite("snow_line_aspect_m", self.snow_line_aspect_m)?,
            snow_albedo: albedo("snow_albedo", self.snow_albedo)?,
            grass_line: finite("grass_line_m", self.grass_line_m)?,
            transition: self.transition_m as f32,
            cos_rock_gentle,
            cos_rock_steep,
            cos_snow_gentle,
            cos_snow_steep,
            line_noise: finite("line_noise_m", self.line_noise_m)?,
            albedo_noise: self.albedo_noise as f32,
            seed: self.seed,
            pole_north,
        })
    }
}
