//! Normal maps from heightfields, and their export (RGB, or RGBA with a horizon
//! angle in alpha, as Hoffman & Preetham 2002 store them).
//!
//! Frame: normals are unit vectors in the local **east–north–up** frame
//! (`x` east, `y` north, `z` up). Because rows run south, `∂h/∂north = -∂h/∂row`.

use crate::heightfield::encode_png;
use crate::horizon::HorizonMap;
use crate::{Heightfield, TerrainError};

/// Bit depth of an exported PNG.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BitDepth {
    /// 8 bits per channel.
    Eight,
    /// 16 bits per channel.
    Sixteen,
}

/// Per-texel unit normals, row-major like the heightfield.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMap {
    width: usize,
    height: usize,
    normals: Vec<[f32; 3]>,
}

/// Derivative along one axis at index `i` of `n` samples given by `at`, with the
/// true spacing: central differences inside, one-sided at the edges, 0 when `n == 1`.
fn derivative(n: usize, i: usize, spacing: f64, at: impl Fn(usize) -> f64) -> f64 {
    if n == 1 {
        0.0
    } else if i == 0 {
        (at(1) - at(0)) / spacing
    } else if i == n - 1 {
        (at(n - 1) - at(n - 2)) / spacing
    } else {
        (at(i + 1) - at(i - 1)) / (2.0 * spacing)
    }
}

/// Maps a component in [-1, 1] to [0, max], rounded.
fn quantise(v: f64, max: f64) -> f64 {
    ((v.clamp(-1.0, 1.0) * 0.5 + 0.5) * max).round()
}

/// Encodes a horizon angle (radians, [-π/2, π/2]) as a normalised value in [0, 1]:
/// `(angle + π/2) / π`. A unorm texture holding `round(value * (2^bits - 1))` decodes
/// with [`crate::twins::decode_horizon_angle`].
///
/// A NaN or an angle beyond `±f32::FRAC_PI_2` (which no bake produces) is
/// [`TerrainError::HorizonAngle`]. `f32::FRAC_PI_2` itself lies 4.4e-8 above π/2;
/// that rounding excess, and only it, maps to the end of the range.
pub fn encode_horizon_angle(angle: f32) -> Result<f64, TerrainError> {
    encode_horizon_angle_named(angle, || "angle".to_owned())
}

/// [`encode_horizon_angle`] with the rejected field's name built on failure.
pub(crate) fn encode_horizon_angle_named(
    angle: f32,
    field: impl FnOnce() -> String,
) -> Result<f64, TerrainError> {
    if angle.is_nan() || angle.abs() > std::f32::consts::FRAC_PI_2 {
        return Err(TerrainError::HorizonAngle {
            field: field(),
            value: angle,
        });
    }
    let half_pi = std::f64::consts::FRAC_PI_2;
    Ok(((f64::from(angle) + half_pi) / std::f64::consts::PI).clamp(0.0, 1.0))
}

impl NormalMap {
    /// Normals `normalize(-∂h/∂east, -∂h/∂north, 1)` with central differences over
    /// the true spacing (one-sided at the edges; a 1-texel axis has zero slope).
    pub fn from_heightfield(hf: &Heightfield) -> Self {
        let (w, h, s) = (hf.width(), hf.height(), hf.spacing());
        let e = hf.elevations();
        let mut normals = Vec::with_capacity(w * h);
        for y in 0..h {
            for x in 0..w {
                let dh_dx = derivative(w, x, s, |i| e[y * w + i]);
                let dh_drow = derivative(h, y, s, |j| e[j * w + x]);
                let (nx, ny, nz) = (-dh_dx, dh_drow, 1.0);
                let len = (nx * nx + ny * ny + nz * nz).sqrt();
                normals.push([(nx / len) as f32, (ny / len) as f32, (nz / len) as f32]);
            }
        }
        Self {
            width: w,
            height: h,
            normals,
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

    /// The normals (east, north, up), row-major.
    pub fn normals(&self) -> &[[f32; 3]] {
        &self.normals
    }

    /// The normal at `(x, y)`; [`TerrainError::OutOfRange`] naming `x` or `y` outside
    /// the map.
    pub fn normal(&self, x: usize, y: usize) -> Result<[f32; 3], TerrainError> {
        TerrainError::check_index("x", x, self.width)?;
        TerrainError::check_index("y", y, self.height)?;
        Ok(self.normals[y * self.width + x])
    }

    /// RGB PNG, each component mapped from [-1, 1] to the full unorm range.
    pub fn to_png(&self, depth: BitDepth) -> Result<Vec<u8>, TerrainError> {
        self.encode(None, depth)
    }

    /// RGBA PNG as Hoffman & Preetham 2002 store it: RGB the normal (as [`NormalMap::to_png`]), A the
    /// horizon angle encoded with [`encode_horizon_angle`].
    pub fn to_rgba_png(
        &self,
        horizon: &HorizonMap,
        depth: BitDepth,
    ) -> Result<Vec<u8>, TerrainError> {
        self.check_horizon(horizon)?;
        self.encode(Some(horizon.angles()), depth)
    }

    /// Raw little-endian `f32` RGB (the normal itself, 12 bytes per texel).
    pub fn to_f32_le(&self) -> Vec<u8> {
        self.normals
            .iter()
            .flat_map(|n| n.iter().flat_map(|c| c.to_le_bytes()))
            .collect()
    }

    /// RGBA `f32` texels (`Rgba32Float` layout): the normal and the horizon angle in
    /// radians, unencoded.
    pub fn to_rgba_f32(&self, horizon: &HorizonMap) -> Result<Vec<[f32; 4]>, TerrainError> {
        self.check_horizon(horizon)?;
        Ok(self
            .normals
            .iter()
            .zip(horizon.angles())
            .map(|(n, &a)| [n[0], n[1], n[2], a])
            .collect())
    }

    fn check_horizon(&self, horizon: &HorizonMap) -> Result<(), TerrainError> {
        if horizon.width() != self.width || horizon.height() != self.height {
            return Err(TerrainError::SizeMismatch {
                field: "horizon map texels",
                expected: (self.width * self.height) as u64,
                found: (horizon.width() * horizon.height()) as u64,
            });
        }
        Ok(())
    }

    fn encode(&self, alpha: Option<&[f32]>, depth: BitDepth) -> Result<Vec<u8>, TerrainError> {
        let channels = if alpha.is_some() { 4 } else { 3 };
        let max = match depth {
            BitDepth::Eight => 255.0,
            BitDepth::Sixteen => 65535.0,
        };
        let mut values = Vec::with_capacity(self.normals.len() * channels);
        for (i, n) in self.normals.iter().enumerate() {
            for &c in n {
                values.push(quantise(f64::from(c), max));
            }
            if let Some(a) = alpha {
                let encoded = encode_horizon_angle_named(a[i], || {
                    format!("horizon (x = {}, y = {})", i % self.width, i / self.width)
                })?;
                values.push((encoded * max).round());
            }
        }
        let (bytes, color) = match (depth, channels) {
            (BitDepth::Eight, c) => (
                values.iter().map(|&v| v as u8).collect::<Vec<u8>>(),
                if c == 4 {
                    image::ExtendedColorType::Rgba8
                } else {
                    image::ExtendedColorType::Rgb8
                },
            ),
            (BitDepth::Sixteen, c) => (
                values
                    .iter()
                    .flat_map(|&v| (v as u16).to_be_bytes())
                    .collect(),
                if c == 4 {
                    image::ExtendedColorType::Rgba16
                } else {
                    image::ExtendedColorType::Rgb16
                },
            ),
        };
        encode_png(&bytes, self.width, self.height, color)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rgba_png_names_the_texel_whose_horizon_angle_is_nan() {
        let hf = Heightfield::from_fn(3, 2, 1.0, |_, _| 0.0).unwrap();
        let mut angles = vec![0.0; 6];
        angles[4] = f32::NAN; // texel (1, 1)
        let horizon = HorizonMap::from_angles(3, 2, 0.0, angles);
        let error = NormalMap::from_heightfield(&hf)
            .to_rgba_png(&horizon, BitDepth::Sixteen)
            .unwrap_err();
        assert!(
            error.to_string().contains("`horizon (x = 1, y = 1)`"),
            "{error}"
        );
    }
}
