//! The baked maps: one azimuth, the east/west pair, or N azimuths.

use crate::TerrainError;

/// One horizon angle per texel for one azimuth.
#[derive(Debug, Clone, PartialEq)]
pub struct HorizonMap {
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) azimuth: f64,
    pub(super) angles: Vec<f32>,
}

impl HorizonMap {
    pub(crate) fn from_angles(width: usize, height: usize, azimuth: f64, angles: Vec<f32>) -> Self {
        debug_assert_eq!(angles.len(), width * height);
        Self {
            width,
            height,
            azimuth,
            angles,
        }
    }

    /// Columns.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Rows.
    pub fn height(&self) -> usize {
        self.height
    }
    /// Azimuth, radians clockwise from north, in `[0, 2π)`.
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }
    /// Angles in radians, row-major.
    pub fn angles(&self) -> &[f32] {
        &self.angles
    }
    /// The angle at `(x, y)`, radians; [`TerrainError::OutOfRange`] naming `x` or `y`
    /// outside the map (an unchecked `x` would read the next row's texel).
    pub fn angle(&self, x: usize, y: usize) -> Result<f32, TerrainError> {
        TerrainError::check_index("x", x, self.width)?;
        TerrainError::check_index("y", y, self.height)?;
        Ok(self.angles[y * self.width + x])
    }
}

/// The horizon maps towards the east and the west.
#[derive(Debug, Clone, PartialEq)]
pub struct EastWestHorizon {
    /// Horizon towards the east (used while the sun is in the east).
    pub east: HorizonMap,
    /// Horizon towards the west.
    pub west: HorizonMap,
}

/// Horizon maps for `N` equally spaced azimuths `k · 2π / N`, `k = 0..N`
/// (layer 0 is north), with interpolation for any azimuth.
#[derive(Debug, Clone, PartialEq)]
pub struct AzimuthHorizonMaps {
    pub(crate) layers: Vec<HorizonMap>,
}

impl AzimuthHorizonMaps {
    /// The layers, layer `k` at azimuth `k · 2π / N`.
    pub fn layers(&self) -> &[HorizonMap] {
        &self.layers
    }

    /// Number of azimuths `N`.
    pub fn count(&self) -> usize {
        self.layers.len()
    }

    /// Horizon angle at `(x, y)` for any azimuth (radians clockwise from north),
    /// linearly interpolated between the two neighbouring layers with
    /// [`crate::shadow::azimuth_layers`] (the WGSL twin does the same).
    ///
    /// Errors for `(x, y)` outside the maps or a non-finite `sun_azimuth`.
    pub fn horizon_angle(&self, x: usize, y: usize, sun_azimuth: f32) -> Result<f32, TerrainError> {
        let l = crate::shadow::azimuth_layers(sun_azimuth, self.layers.len() as u32)?;
        let a = self.layers[l.lower as usize].angle(x, y)?;
        let b = self.layers[l.upper as usize].angle(x, y)?;
        Ok(a + (b - a) * l.weight)
    }
}
