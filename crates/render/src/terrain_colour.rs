//! `[terrain.colour]`: a colour image over the heightfield's ground, decoded to linear
//! albedo and looked up bilinearly in linear space (the CPU twin of WGSL
//! `terrain_colour_at` in `shaders/render/terrain.wgsl`: the same taps,
//! `terrain_materials::colour_taps`, on the same linear `f32` texels).
//!
//! The image is georeferenced as the heightfield is: pixel `(i, j)` lies at
//! `(i, j) × cell_size` east and south of the heightfield's texel (0, 0), the top row
//! north, so its extent `(width − 1, height − 1) × cell_size` must equal the
//! heightfield's (within half a pixel).

use std::path::Path;

use glam::Vec3;

use crate::terrain_materials::colour_taps;

/// A colour texture of linear albedos.
#[derive(Debug, Clone, PartialEq)]
pub struct ColourTexture {
    /// Pixels east × south.
    pub size: [u32; 2],
    /// Pixels per metre (1 / cell size).
    pub texels_per_metre: f32,
    /// Linear RGB albedo per pixel (x fastest, row 0 north), alpha 0.
    pub texels: Vec<[f32; 4]>,
}

/// The sRGB transfer function's inverse (IEC 61966-2-1): an encoded value in [0, 1] to
/// linear.
pub fn srgb_to_linear(encoded: f64) -> f64 {
    if encoded <= 0.040_45 {
        encoded / 12.92
    } else {
        ((encoded + 0.055) / 1.055).powf(2.4)
    }
}

impl ColourTexture {
    /// The texture of 8-bit sRGB `pixels` (x fastest, row 0 north), `width` wide,
    /// `cell_size` metres per pixel.
    pub fn from_srgb8(width: u32, pixels: &[[u8; 3]], cell_size: f64) -> Self {
        let table: Vec<f32> = (0..256)
            .map(|v| srgb_to_linear(f64::from(v) / 255.0) as f32)
            .collect();
        Self {
            size: [width, pixels.len() as u32 / width.max(1)],
            texels_per_metre: (1.0 / cell_size) as f32,
            texels: pixels
                .iter()
                .map(|p| {
                    [
                        table[usize::from(p[0])],
                        table[usize::from(p[1])],
                        table[usize::from(p[2])],
                        0.0,
                    ]
                })
                .collect(),
        }
    }

    /// The linear albedo at map position `map` (metres east and south of the
    /// heightfield's texel (0, 0)), bilinear between pixel centres, clamped at the edges.
    pub fn colour_at(&self, map: [f32; 2]) -> Vec3 {
        let texel = [
            map[0] * self.texels_per_metre,
            map[1] * self.texels_per_metre,
        ];
        let (index, weight) = colour_taps(texel, self.size);
        let mut colour = Vec3::ZERO;
        for (&i, &w) in index.iter().zip(&weight) {
            colour += Vec3::from_slice(&self.texels[i as usize][..3]) * w;
        }
        colour
    }
}

/// Reads `[terrain.colour]`'s PNG at `path` with `cell_size` metres per pixel over a
/// heightfield of `extent` metres (east, south). The error is (key, value, reason) for
/// the caller to name the key.
pub fn read_colour_png(
    path: &Path,
    cell_size: f64,
    extent: [f64; 2],
) -> Result<ColourTexture, (&'static str, String, String)> {
    if !(cell_size.is_finite() && cell_size > 0.0) {
        return Err((
            "cell_size",
            format!("{cell_size} m"),
            "must be finite and > 0".into(),
        ));
    }
    let shown = format!("\"{}\"", path.display());
    let (width, pixels) = decode_srgb8(path).map_err(|reason| ("path", shown.clone(), reason))?;
    let height = pixels.len() as u32 / width;
    if width < 2 || height < 2 {
        return Err((
            "path",
            shown,
            format!("the image is {width}×{height} pixels: must be at least 2×2"),
        ));
    }
    let image_extent = [
        f64::from(width - 1) * cell_size,
        f64::from(height - 1) * cell_size,
    ];
    let mismatch = (0..2).any(|k| (image_extent[k] - extent[k]).abs() > 0.5 * cell_size);
    if mismatch {
        return Err((
            "cell_size",
            format!("{cell_size} m"),
            format!(
                "the {width}×{height}-pixel image then spans {:.1} m × {:.1} m, the \
                 heightfield {:.1} m × {:.1} m: the extents must match (pixel centres from \
                 corner texel to corner texel)",
                image_extent[0], image_extent[1], extent[0], extent[1]
            ),
        ));
    }
    Ok(ColourTexture::from_srgb8(width, &pixels, cell_size))
}

/// The PNG's width and its 8-bit RGB pixels; the error is the reason.
fn decode_srgb8(path: &Path) -> Result<(u32, Vec<[u8; 3]>), String> {
    #[cfg(feature = "png")]
    {
        let bytes =
            std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let image = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .map_err(|e| format!("not a readable PNG ({}): {e}", path.display()))?;
        let width = image.width();
        let pixels: Vec<[u8; 3]> = match image {
            image::DynamicImage::ImageRgb8(i) => i.pixels().map(|p| p.0).collect(),
            image::DynamicImage::ImageRgba8(i) => {
                i.pixels().map(|p| [p.0[0], p.0[1], p.0[2]]).collect()
            }
            other => {
                return Err(format!(
                    "colour type {:?}: must be 8-bit sRGB RGB or RGBA",
                    other.color()
                ));
            }
        };
        Ok((width.max(1), pixels))
    }
    #[cfg(not(feature = "png"))]
    {
        Err(format!(
            "cannot read {}: render was built without its `png` feature",
            path.display()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decodes_to_linear_at_the_ends_and_the_knee() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-15);
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-6);
        let below = srgb_to_linear(0.040_45);
        let above = srgb_to_linear(0.040_450_01);
        assert!((above - below).abs() < 1e-8);
    }

    #[test]
    fn the_lookup_is_bilinear_in_linear_space() {
        let texture = ColourTexture::from_srgb8(2, &[[0; 3], [255; 3], [0; 3], [255; 3]], 10.0);
        let mid = texture.colour_at([5.0, 3.0]);
        assert!((mid - Vec3::splat(0.5)).length() < 1e-6, "{mid}");
        assert_eq!(texture.colour_at([-4.0, 0.0]), Vec3::ZERO);
        assert_eq!(texture.colour_at([40.0, 20.0]), Vec3::ONE);
    }
}
