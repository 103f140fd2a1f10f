//! `[clouds.shell]` with a weather grid from a PNG (`weather_image`, `weather_cell_m`;
//! `render::shell_clouds`): the shipped `stratocumulus` scene with its procedural
//! weather replaced by an 8×6 RGB image of 2 km cells. The image becomes cloudlight's
//! `WeatherGrid` (north up), the keys' errors name the field and value, and the GPU image
//! (cloudlight's `MarchShellPass` and `ShellShadowMapPass` reading the grid) agrees with
//! the CPU's (lavapipe in CI; GPU policy of skyscape-harness). Needs the `png` feature
//! (default, through `cli`): the image crate writes the test images.
#![cfg(feature = "png")]

mod common;

use std::path::{Path, PathBuf};

use cloudlight::shell::WeatherMap;
use render::scene::{Scene, SceneError};

/// The test image's (coverage, cloud type, precipitation) of pixel column `x`, row `y`
/// (row 0 the top), 8-bit.
fn pixel(x: u32, y: u32) -> [u8; 3] {
    let coverage = [51u8, 140, 204, 230][((x + 2 * y) % 4) as usize];
    [coverage, 128, (x * 30) as u8]
}

/// A folder of its own holding `weather.png` (8×6, RGB8).
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "skyscape_shell_weather_{name}_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let image = image::RgbImage::from_fn(8, 6, |x, y| image::Rgb(pixel(x, y)));
    image
        .save_with_format(dir.join("weather.png"), image::ImageFormat::Png)
        .unwrap();
    dir
}

/// The shipped stratocumulus scene with `keys` added to `[clouds.shell]`, its paths
/// relative to `dir`.
fn scene(dir: &Path, keys: &str, width: u32, height: u32) -> Result<Scene, SceneError> {
    let text = std::fs::read_to_string(common::scene_path("stratocumulus")).unwrap();
    assert!(text.contains("[clouds.shell]\n"));
    let text = text.replacen("[clouds.shell]\n", &format!("[clouds.shell]\n{keys}"), 1);
    let mut scene = Scene::parse(&text, dir)?;
    scene.file.output.width = width;
    scene.file.output.height = height;
    Ok(scene)
}

const GRID_KEYS: &str = "weather_image = \"weather.png\"\nweather_cell_m = 2000.0\n";

#[test]
fn a_weather_image_is_the_shells_grid() {
    let dir = folder("grid");
    let prepared = scene(&dir, GRID_KEYS, 8, 8).unwrap().prepare().unwrap();
    let shell = &prepared.shell_cloud.as_ref().unwrap().shell;
    let WeatherMap::Grid(grid) = &shell.settings().weather else {
        panic!("procedural weather: {:?}", shell.settings().weather);
    };
    assert_eq!(grid.size, [8, 6]);
    assert_eq!(grid.cell_size, 2000.0);
    // Cell (i, j) is pixel (i, 5 − j): north up.
    for (i, j) in [(0u32, 0u32), (3, 2), (7, 5)] {
        let k = (i + 8 * j) as usize;
        let [c, t, p] = pixel(i, 5 - j).map(|v| f32::from(v) / 255.0);
        assert_eq!(grid.coverage[k], c);
        assert_eq!(grid.cloud_type[k], t);
        assert_eq!(grid.precipitation.as_ref().unwrap()[k], p);
    }
    // At the centre of cell (3, 2) the lookup is that cell's value.
    let w = shell.weather_at([7000.0f64, 5000.0]);
    assert_eq!(w.coverage, f64::from(f32::from(pixel(3, 3)[0]) / 255.0));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn weather_image_errors_name_the_field_and_value() {
    let dir = folder("errors");
    std::fs::write(dir.join("not.png"), b"not a png").unwrap();
    let grey = image::GrayImage::new(4, 4);
    grey.save_with_format(dir.join("grey.png"), image::ImageFormat::Png)
        .unwrap();
    for (keys, field, shown) in [
        (
            "weather_image = \"missing.png\"\nweather_cell_m = 500.0\n",
            "clouds.shell.weather_image",
            "\"missing.png\"",
        ),
        (
            "weather_image = \"not.png\"\nweather_cell_m = 500.0\n",
            "clouds.shell.weather_image",
            "not a readable PNG",
        ),
        (
            "weather_image = \"grey.png\"\nweather_cell_m = 500.0\n",
            "clouds.shell.weather_image",
            "L8",
        ),
        (
            "weather_image = \"weather.png\"\nweather_cell_m = 0.0\n",
            "clouds.shell.weather_cell_m",
            "0 m",
        ),
        (
            "weather_image = \"weather.png\"\nweather_cell_m = -5.0\n",
            "clouds.shell.weather_cell_m",
            "-5 m",
        ),
        (
            "weather_image = \"weather.png\"\n",
            "clouds.shell.weather_image",
            "needs weather_cell_m",
        ),
        (
            "weather_cell_m = 500.0\n",
            "clouds.shell.weather_cell_m",
            "needs weather_image",
        ),
    ] {
        let err = scene(&dir, keys, 8, 8).unwrap().prepare().unwrap_err();
        let text = err.to_string();
        assert_eq!(err.field(), Some(field), "{keys}: {text}");
        assert!(text.contains(shown), "{keys}: {text}");
        assert!(err.location().is_some(), "{keys}: {text}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The grid-weather scene at 64×36 on the GPU (the march and the shadow map bake read
/// the grid from storage buffers) and on the CPU.
#[test]
fn a_grid_weather_deck_agrees_on_the_gpu_and_the_cpu() {
    let Some(gpu) = common::gpu_or_skip("render::shell_weather_grid") else {
        return;
    };
    let dir = folder("gpu");
    let (width, height) = (64, 36);
    let prepared = scene(&dir, GRID_KEYS, width, height)
        .unwrap()
        .prepare()
        .unwrap();
    let cloud = prepared.shell_cloud.as_ref().unwrap();
    assert!(
        cloud.lights[0].shadow.is_some(),
        "a shadow map over the terrain"
    );
    let (gpu_image, cpu_image, agreement) = common::compare(gpu, &prepared);
    let camera = render::shell_clouds::shell_camera(&prepared.camera).unwrap();
    let mut deck = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let m = render::shell_clouds::march_shell_pixel(
                cloud,
                &camera,
                [width, height],
                [x, y],
                f32::INFINITY,
            );
            if m.transmittance < 1.0 {
                deck.push((y * width + x) as usize);
            }
        }
    }
    let (cloud_pixels, cloud_within, worst) = common::within_two_over(&gpu_image, &cpu_image, deck);
    eprintln!(
        "grid weather stratocumulus {width}×{height} GPU vs CPU: {agreement}; deck pixels \
         {cloud_within} of {cloud_pixels} within 2 LSB, worst {worst} LSB"
    );
    assert!(cloud_pixels > 100, "{cloud_pixels}");
    assert!(agreement.close(), "{}", agreement.fractions());
    assert!(
        cloud_within * 1000 >= cloud_pixels * 995,
        "{cloud_within} of {cloud_pixels}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
