//! Heightfields and their loaders.
//!
//! Layout (see `docs/architecture.md`): row-major, `x` (columns) increases to the
//! east, `y` (rows) increases to the south. Texel `(x, y)` is a point sample at
//! horizontal position `(x * spacing, -y * spacing)` metres (east, north) with
//! elevation `vertical_scale * samples[y * width + x]` metres.

use std::io::Cursor;
use std::path::Path;

use image::{ColorType, ImageDecoder};

use crate::TerrainError;

/// Largest accepted width or height, in texels.
pub const MAX_SIDE: usize = 32_768;
/// Largest accepted texel count (`width * height`): 2²⁸ (1 GiB of `f32`).
pub const MAX_TEXELS: usize = 1 << 28;

/// A regular grid of elevations.
#[derive(Debug, Clone, PartialEq)]
pub struct Heightfield {
    width: usize,
    height: usize,
    spacing: f64,
    vertical_scale: f64,
    samples: Vec<f32>,
}

/// Checks a pair of dimensions against zero and the limits.
pub(crate) fn check_dimensions(width: u64, height: u64) -> Result<(), TerrainError> {
    if width == 0 {
        return Err(TerrainError::ZeroSize { field: "width" });
    }
    if height == 0 {
        return Err(TerrainError::ZeroSize { field: "height" });
    }
    for (field, value) in [("width", width), ("height", height)] {
        if value > MAX_SIDE as u64 {
            return Err(TerrainError::TooLarge {
                field,
                value,
                limit: MAX_SIDE as u64,
            });
        }
    }
    let texels = width * height;
    if texels > MAX_TEXELS as u64 {
        return Err(TerrainError::TooLarge {
            field: "width * height",
            value: texels,
            limit: MAX_TEXELS as u64,
        });
    }
    Ok(())
}

fn check_spacing(spacing: f64) -> Result<(), TerrainError> {
    if spacing.is_finite() && spacing > 0.0 {
        Ok(())
    } else {
        Err(TerrainError::param(
            "spacing",
            spacing,
            "must be finite and > 0 (metres per texel)",
        ))
    }
}

fn check_scale(field: &'static str, scale: f64) -> Result<(), TerrainError> {
    if scale.is_finite() && scale > 0.0 {
        Ok(())
    } else {
        Err(TerrainError::param(field, scale, "must be finite and > 0"))
    }
}

fn png_error(operation: &'static str, source: image::ImageError) -> TerrainError {
    TerrainError::Png { operation, source }
}

fn read_file(path: &Path) -> Result<Vec<u8>, TerrainError> {
    std::fs::read(path).map_err(|source| TerrainError::Io {
        path: path.to_owned(),
        source,
    })
}

/// Decodes a greyscale PNG of the expected type after checking its header against
/// the limits (so a huge header cannot trigger a huge allocation).
fn decode_grey_png(
    bytes: &[u8],
    expected: ColorType,
    expected_name: &'static str,
) -> Result<(usize, usize, Vec<u8>), TerrainError> {
    let decoder = image::codecs::png::PngDecoder::new(Cursor::new(bytes))
        .map_err(|e| png_error("decode", e))?;
    let (width, height) = decoder.dimensions();
    let color = decoder.color_type();
    if color != expected {
        return Err(TerrainError::PixelFormat {
            expected: expected_name,
            found: format!("{color:?}"),
        });
    }
    check_dimensions(u64::from(width), u64::from(height))?;
    let mut buf = vec![0u8; decoder.total_bytes() as usize];
    decoder
        .read_image(&mut buf)
        .map_err(|e| png_error("decode", e))?;
    Ok((width as usize, height as usize, buf))
}

impl Heightfield {
    /// A heightfield from raw samples (row-major, `width * height` of them).
    ///
    /// Elevation in metres is `vertical_scale * sample`. Errors on zero or oversized
    /// dimensions, a length mismatch, a non-positive or non-finite `spacing` or
    /// `vertical_scale`, and on any sample whose elevation is not finite.
    pub fn new(
        width: usize,
        height: usize,
        spacing: f64,
        vertical_scale: f64,
        samples: Vec<f32>,
    ) -> Result<Self, TerrainError> {
        check_dimensions(width as u64, height as u64)?;
        check_spacing(spacing)?;
        check_scale("vertical_scale", vertical_scale)?;
        if samples.len() != width * height {
            return Err(TerrainError::SizeMismatch {
                field: "samples",
                expected: (width * height) as u64,
                found: samples.len() as u64,
            });
        }
        for (i, &s) in samples.iter().enumerate() {
            let elevation = f64::from(s) * vertical_scale;
            if !elevation.is_finite() {
                return Err(TerrainError::NonFiniteHeight {
                    x: i % width,
                    y: i / width,
                    value: f64::from(s),
                });
            }
        }
        Ok(Self {
            width,
            height,
            spacing,
            vertical_scale,
            samples,
        })
    }

    /// A heightfield whose sample at `(x, y)` is `f(x, y)` metres (`vertical_scale` 1).
    pub fn from_fn(
        width: usize,
        height: usize,
        spacing: f64,
        mut f: impl FnMut(usize, usize) -> f32,
    ) -> Result<Self, TerrainError> {
        check_dimensions(width as u64, height as u64)?;
        let mut samples = Vec::with_capacity(width * height);
        for y in 0..height {
            for x in 0..width {
                samples.push(f(x, y));
            }
        }
        Self::new(width, height, spacing, 1.0, samples)
    }

    /// Loads a 16-bit greyscale PNG (`L16`): the sample for a pixel value `v` is
    /// `offset + scale * v` metres (`scale` in metres per count, `> 0`).
    ///
    /// Any other pixel format (8-bit, RGB, alpha) is a [`TerrainError::PixelFormat`].
    pub fn from_png16(
        bytes: &[u8],
        spacing: f64,
        scale: f64,
        offset: f64,
    ) -> Result<Self, TerrainError> {
        Self::from_png(bytes, spacing, scale, offset, 16)
    }

    /// Loads an 8-bit greyscale PNG (`L8`): the sample is `offset + scale * v` metres.
    pub fn from_png8(
        bytes: &[u8],
        spacing: f64,
        scale: f64,
        offset: f64,
    ) -> Result<Self, TerrainError> {
        Self::from_png(bytes, spacing, scale, offset, 8)
    }

    /// [`Heightfield::from_png16`] on the contents of a file.
    pub fn open_png16(
        path: impl AsRef<Path>,
        spacing: f64,
        scale: f64,
        offset: f64,
    ) -> Result<Self, TerrainError> {
        Self::from_png16(&read_file(path.as_ref())?, spacing, scale, offset)
    }

    /// [`Heightfield::from_png8`] on the contents of a file.
    pub fn open_png8(
        path: impl AsRef<Path>,
        spacing: f64,
        scale: f64,
        offset: f64,
    ) -> Result<Self, TerrainError> {
        Self::from_png8(&read_file(path.as_ref())?, spacing, scale, offset)
    }

    fn from_png(
        bytes: &[u8],
        spacing: f64,
        scale: f64,
        offset: f64,
        bits: u8,
    ) -> Result<Self, TerrainError> {
        check_spacing(spacing)?;
        check_scale("scale", scale)?;
        if !offset.is_finite() {
            return Err(TerrainError::param("offset", offset, "must be finite"));
        }
        let (width, height, buf) = if bits == 16 {
            decode_grey_png(bytes, ColorType::L16, "16-bit greyscale (L16)")?
        } else {
            decode_grey_png(bytes, ColorType::L8, "8-bit greyscale (L8)")?
        };
        let samples: Vec<f32> = if bits == 16 {
            // The decoder writes native-endian u16.
            buf.chunks_exact(2)
                .map(|c| (offset + scale * f64::from(u16::from_ne_bytes([c[0], c[1]]))) as f32)
                .collect()
        } else {
            buf.iter()
                .map(|&v| (offset + scale * f64::from(v)) as f32)
                .collect()
        };
        Self::new(width, height, spacing, 1.0, samples)
    }

    /// Loads raw little-endian `f32` samples (metres), row-major, with the given
    /// dimensions. The byte length must be exactly `4 * width * height`.
    pub fn from_raw_f32_le(
        bytes: &[u8],
        width: usize,
        height: usize,
        spacing: f64,
    ) -> Result<Self, TerrainError> {
        check_dimensions(width as u64, height as u64)?;
        let expected = 4 * (width as u64) * (height as u64);
        if bytes.len() as u64 != expected {
            return Err(TerrainError::SizeMismatch {
                field: "raw f32 bytes",
                expected,
                found: bytes.len() as u64,
            });
        }
        let samples = bytes
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        Self::new(width, height, spacing, 1.0, samples)
    }

    /// [`Heightfield::from_raw_f32_le`] on the contents of a file.
    pub fn open_raw_f32_le(
        path: impl AsRef<Path>,
        width: usize,
        height: usize,
        spacing: f64,
    ) -> Result<Self, TerrainError> {
        Self::from_raw_f32_le(&read_file(path.as_ref())?, width, height, spacing)
    }

    /// Returns the same heightfield with another vertical scale (exaggeration).
    pub fn with_vertical_scale(self, vertical_scale: f64) -> Result<Self, TerrainError> {
        Self::new(
            self.width,
            self.height,
            self.spacing,
            vertical_scale,
            self.samples,
        )
    }

    /// Columns (east–west extent in texels).
    pub fn width(&self) -> usize {
        self.width
    }

    /// Rows (north–south extent in texels).
    pub fn height(&self) -> usize {
        self.height
    }

    /// Horizontal distance between neighbouring texels, metres.
    pub fn spacing(&self) -> f64 {
        self.spacing
    }

    /// Metres per sample unit.
    pub fn vertical_scale(&self) -> f64 {
        self.vertical_scale
    }

    /// The raw samples, row-major.
    pub fn samples(&self) -> &[f32] {
        &self.samples
    }

    /// Elevation of texel `(x, y)` in metres; [`TerrainError::OutOfRange`] naming `x`
    /// or `y` outside the map.
    pub fn elevation(&self, x: usize, y: usize) -> Result<f64, TerrainError> {
        TerrainError::check_index("x", x, self.width)?;
        TerrainError::check_index("y", y, self.height)?;
        Ok(self.elevation_at(x, y))
    }

    /// [`Heightfield::elevation`] for the crate's inner loops, whose indices are in
    /// range by construction (checked in debug builds).
    pub(crate) fn elevation_at(&self, x: usize, y: usize) -> f64 {
        debug_assert!(x < self.width && y < self.height);
        f64::from(self.samples[y * self.width + x]) * self.vertical_scale
    }

    /// The elevation (metres) of the bilinear surface through the texels at map
    /// position `(x, y)` in texel units (texel `(i, j)` at `(i, j)`); a position
    /// outside the map extends its edge cells.
    pub fn bilinear_elevation(&self, x: f64, y: f64) -> f64 {
        let (w, h) = (self.width, self.height);
        let i = (x.floor().max(0.0) as usize).min(w.saturating_sub(2));
        let j = (y.floor().max(0.0) as usize).min(h.saturating_sub(2));
        let (i1, j1) = ((i + 1).min(w - 1), (j + 1).min(h - 1));
        let (fx, fy) = (x - i as f64, y - j as f64);
        let h00 = self.elevation_at(i, j);
        let h10 = self.elevation_at(i1, j);
        let h01 = self.elevation_at(i, j1);
        let h11 = self.elevation_at(i1, j1);
        let top = h00 + (h10 - h00) * fx;
        let bottom = h01 + (h11 - h01) * fx;
        top + (bottom - top) * fy
    }

    /// All elevations in metres, row-major, as `f64`.
    pub fn elevations(&self) -> Vec<f64> {
        self.samples
            .iter()
            .map(|&s| f64::from(s) * self.vertical_scale)
            .collect()
    }

    /// Encodes the elevations as a 16-bit greyscale PNG: `v = round((e - offset) / scale)`
    /// (the inverse of [`Heightfield::from_png16`]).
    ///
    /// An elevation whose `v` falls outside `0..=65535` is
    /// [`TerrainError::ElevationNotRepresentable`] (naming the texel and the range the
    /// given `scale` and `offset` hold), never clamped.
    pub fn to_png16(&self, scale: f64, offset: f64) -> Result<Vec<u8>, TerrainError> {
        check_scale("scale", scale)?;
        if !offset.is_finite() {
            return Err(TerrainError::param("offset", offset, "must be finite"));
        }
        let mut bytes = Vec::with_capacity(self.samples.len() * 2);
        for (i, e) in self.elevations().into_iter().enumerate() {
            let v = ((e - offset) / scale).round();
            if !(0.0..=65535.0).contains(&v) {
                return Err(TerrainError::ElevationNotRepresentable {
                    field: "scale, offset",
                    x: i % self.width,
                    y: i / self.width,
                    value: e,
                    min: offset - 0.5 * scale,
                    max: offset + 65535.5 * scale,
                });
            }
            bytes.extend_from_slice(&(v as u16).to_be_bytes());
        }
        encode_png(
            &bytes,
            self.width,
            self.height,
            image::ExtendedColorType::L16,
        )
    }
}

/// Encodes big-endian pixel bytes as a PNG (the layout the `png` encoder expects
/// for 16-bit data is big-endian; 8-bit data has no byte order).
pub(crate) fn encode_png(
    bytes_be: &[u8],
    width: usize,
    height: usize,
    color: image::ExtendedColorType,
) -> Result<Vec<u8>, TerrainError> {
    use image::ImageEncoder as _;
    let mut out = Vec::new();
    // image's PNG encoder takes 16-bit samples in native endianness.
    let native: Vec<u8>;
    let data = if matches!(
        color,
        image::ExtendedColorType::L16
            | image::ExtendedColorType::Rgb16
            | image::ExtendedColorType::Rgba16
    ) {
        native = bytes_be
            .chunks_exact(2)
            .flat_map(|c| u16::from_be_bytes([c[0], c[1]]).to_ne_bytes())
            .collect();
        &native[..]
    } else {
        bytes_be
    };
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(data, width as u32, height as u32, color)
        .map_err(|e| png_error("encode", e))?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::Heightfield;

    #[test]
    fn the_bilinear_surface_passes_through_the_scaled_texels() {
        let hf = Heightfield::from_fn(3, 2, 10.0, |x, y| (x + 10 * y) as f32)
            .unwrap()
            .with_vertical_scale(2.0)
            .unwrap();
        for (x, y) in [(0, 0), (2, 0), (1, 1), (2, 1)] {
            let at = hf.bilinear_elevation(x as f64, y as f64);
            assert_eq!(at, hf.elevation(x, y).unwrap(), "({x}, {y})");
        }
        // Between texels: the plane through them (x + 10 y, doubled).
        assert!((hf.bilinear_elevation(0.5, 0.25) - 2.0 * (0.5 + 2.5)).abs() < 1e-12);
        // Outside: the edge cells extended.
        assert!((hf.bilinear_elevation(3.0, 0.0) - 2.0 * 3.0).abs() < 1e-12);
    }
}
