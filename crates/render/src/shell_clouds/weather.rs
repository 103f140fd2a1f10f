//! `[clouds.shell]`'s user weather grid from an image file: `weather_image = "path.png"`
//! (relative to the scene file's folder) with `weather_cell_m` (each pixel's edge on the
//! ground, metres) replaces the procedural weather by a `cloudlight::shell::WeatherGrid`.
//!
//! The PNG's red channel is the coverage, green the cloud type (0 stratus, ½
//! stratocumulus, 1 cumulus), blue the precipitation (carried, not in the density); 8- or
//! 16-bit RGB or RGBA (alpha ignored), each value divided by 255 or 65535. Pixel column
//! `i` is cell `i` along the shell's x (east), and the image's bottom row is cell row 0
//! along y (north), so the image reads as a map with north up. Cell `(i, j)`'s centre is
//! at `((i + ½)·cell, (j + ½)·cell)` east and north of the scene's world origin (the
//! terrain's centre: the shell's horizontal frame is the world's, `x` east and `y = −z`
//! north), and the grid repeats over its extent; cloudlight looks it up bilinearly
//! (`CloudShell::weather_at`, on the GPU `weather_grid_taps` / `weather_grid_bilinear`).
//!
//! Errors name the field and its value: a missing or unreadable file, a file that is not
//! a PNG or not RGB(A), a zero-sized image, a cell size that is missing, not finite or
//! not positive, a cell size without an image.

use std::path::Path;

use cloudlight::shell::WeatherGrid;

use super::CloudShellSection;
use crate::scene::{Scene, SceneError};

impl Scene {
    /// `[clouds.shell]`'s weather grid from `weather_image` and `weather_cell_m`, or
    /// `None` when the section has no `weather_image` (procedural weather).
    pub(crate) fn shell_weather_grid(
        &self,
        section: &CloudShellSection,
    ) -> Result<Option<WeatherGrid>, SceneError> {
        let field = |key: &str| ["clouds", "shell", key].map(str::to_owned);
        let invalid = |key: &str, value: String, reason: String| {
            let path = field(key);
            let path: Vec<&str> = path.iter().map(String::as_str).collect();
            self.invalid(&path, value, reason)
        };
        let Some(image) = &section.weather_image else {
            return match section.weather_cell_m {
                Some(cell) => Err(invalid(
                    "weather_cell_m",
                    format!("{cell} m"),
                    "needs weather_image (the grid it sizes)".into(),
                )),
                None => Ok(None),
            };
        };
        let shown = format!("\"{}\"", image.display());
        let cell = match section.weather_cell_m {
            None => {
                return Err(invalid(
                    "weather_image",
                    shown,
                    "needs weather_cell_m (each pixel's edge on the ground, metres)".into(),
                ));
            }
            Some(cell) if !(cell.is_finite() && cell > 0.0) => {
                return Err(invalid(
                    "weather_cell_m",
                    format!("{cell} m"),
                    "must be finite and > 0".into(),
                ));
            }
            Some(cell) => cell,
        };
        let path = self.resolve(image);
        let grid = read_weather_png(&path, cell)
            .map_err(|reason| invalid("weather_image", shown, reason))?;
        Ok(Some(grid))
    }
}

/// The weather grid of the PNG at `path` with cells of `cell` metres (module
/// documentation); the error is the reason, for the caller to name the field.
fn read_weather_png(path: &Path, cell: f64) -> Result<WeatherGrid, String> {
    #[cfg(feature = "png")]
    {
        let bytes =
            std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let image = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .map_err(|e| format!("not a readable PNG ({}): {e}", path.display()))?;
        let (width, height) = (image.width(), image.height());
        if width == 0 || height == 0 {
            return Err(format!(
                "the image is {width}×{height} pixels: must be ≥ 1×1"
            ));
        }
        // Each pixel's (r, g, b) in [0, 1], row 0 the image's top.
        let pixels: Vec<[f32; 3]> = match image {
            image::DynamicImage::ImageRgb8(i) => i
                .pixels()
                .map(|p| p.0.map(|v| f32::from(v) / 255.0))
                .collect(),
            image::DynamicImage::ImageRgba8(i) => i
                .pixels()
                .map(|p| [p.0[0], p.0[1], p.0[2]].map(|v| f32::from(v) / 255.0))
                .collect(),
            image::DynamicImage::ImageRgb16(i) => i
                .pixels()
                .map(|p| p.0.map(|v| f32::from(v) / 65535.0))
                .collect(),
            image::DynamicImage::ImageRgba16(i) => i
                .pixels()
                .map(|p| [p.0[0], p.0[1], p.0[2]].map(|v| f32::from(v) / 65535.0))
                .collect(),
            other => {
                return Err(format!(
                    "colour type {:?}: must be 8- or 16-bit RGB or RGBA (R coverage, G cloud \
                     type, B precipitation)",
                    other.color()
                ));
            }
        };
        let (nx, ny) = (width as usize, height as usize);
        // Cell (i, j) is pixel (i, ny − 1 − j): north (+y) up.
        let layer = |channel: usize| -> Vec<f32> {
            (0..ny)
                .flat_map(|j| {
                    let row = ny - 1 - j;
                    pixels[row * nx..(row + 1) * nx]
                        .iter()
                        .map(move |p| p[channel])
                })
                .collect()
        };
        Ok(WeatherGrid {
            size: [width, height],
            cell_size: cell,
            coverage: layer(0),
            cloud_type: layer(1),
            precipitation: Some(layer(2)),
        })
    }
    #[cfg(not(feature = "png"))]
    {
        let _ = cell;
        Err(format!(
            "reading {} needs render's `png` feature (the image crate's PNG decoder)",
            path.display()
        ))
    }
}

#[cfg(all(test, feature = "png"))]
mod tests {
    use super::*;

    fn write_png(path: &Path, image: image::DynamicImage) {
        image
            .save_with_format(path, image::ImageFormat::Png)
            .unwrap();
    }

    #[test]
    fn an_rgb_png_is_a_grid_with_north_up() {
        let dir = std::env::temp_dir().join(format!("skyscape_weather_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // 3 × 2 pixels, 16-bit: top row (north) coverage 1, bottom row coverage 0.
        let mut img = image::ImageBuffer::<image::Rgb<u16>, _>::new(3, 2);
        for (x, y, p) in img.enumerate_pixels_mut() {
            let coverage = if y == 0 { 65535 } else { 0 };
            *p = image::Rgb([coverage, (x * 30000) as u16, 65535]);
        }
        let path = dir.join("w16.png");
        write_png(&path, image::DynamicImage::ImageRgb16(img));
        let grid = read_weather_png(&path, 500.0).unwrap();
        assert_eq!(grid.size, [3, 2]);
        assert_eq!(grid.coverage, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        assert_eq!(grid.cloud_type[1], 30000.0 / 65535.0);
        assert_eq!(grid.precipitation.as_deref(), Some(&[1.0f32; 6][..]));
        // 8-bit grey is refused, naming the colour type.
        let grey = dir.join("grey.png");
        write_png(
            &grey,
            image::DynamicImage::ImageLuma8(image::ImageBuffer::new(2, 2)),
        );
        let err = read_weather_png(&grey, 500.0).unwrap_err();
        assert!(err.contains("L8"), "{err}");
        let err = read_weather_png(&dir.join("missing.png"), 500.0).unwrap_err();
        assert!(err.starts_with("cannot read"), "{err}");
        std::fs::remove_dir_all(&dir).ok();
    }
}
