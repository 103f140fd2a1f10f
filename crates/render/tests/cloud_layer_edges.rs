//! The default scene's cloud layers have no dark specks along their edges: where a
//! layer thins out over the sky its pixels are never darker than the sky behind them
//! (celestial's `cloud_layer_radiance` sees the column's light through its opacity, and
//! a thin column scatters more than it hides). A thick core's base may be darker than a
//! bright sky (its diffuse transmission falls with its optical thickness); the edge is
//! where the layer meets clear sky. Within a few degrees of the horizon the layer is
//! seen edge-on against the brightest haze, where a distant cloud is greyer than the
//! sky behind it; the check starts 5° up.

mod common;

/// Rows of the default scene at 960×540 that show only sky and cloud layers (the
/// highest ridge reaches row 205).
const SKY_ROWS: usize = 200;

/// Relative luminance (Rec. 709) of display-linear values decoded from sRGB codes.
fn displayed_luminance(pixel: u32) -> f64 {
    let decode = |channel: usize| {
        let c = f64::from(common::code(pixel, channel)) / 255.0;
        if c <= 0.040_45 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * decode(0) + 0.7152 * decode(1) + 0.0722 * decode(2)
}

/// Whether pixel `i` looks at least 5° above the horizon.
fn high_enough(scene: &render::scene::PreparedScene, i: usize) -> bool {
    let width = scene.camera.width as usize;
    let view =
        atmos::frame::frame_view_direction([(i % width) as u32, (i / width) as u32], &scene.camera);
    let up = scene.camera_position.normalize();
    let sine = f64::from(view[0]) * up.x + f64::from(view[1]) * up.y + f64::from(view[2]) * up.z;
    sine >= 5f64.to_radians().sin()
}

/// The edge pixels of the first `SKY_ROWS` rows looking 5° up or more (a pixel the
/// layers change, beside one of its 8 neighbours that they leave within 1 % of the
/// sky: clear) whose luminance is below `factor` × the luminance of the same pixel
/// without the layers (`sky`).
fn darker_than_the_sky(
    scene: &render::scene::PreparedScene,
    image: &[f64],
    sky: &[f64],
    factor: f64,
) -> Vec<usize> {
    let width = scene.camera.width as usize;
    let clear = |i: usize| (image[i] - sky[i]).abs() <= 0.01 * sky[i];
    (0..SKY_ROWS * width)
        .filter(|&i| high_enough(scene, i))
        .filter(|&i| {
            let (x, y) = ((i % width) as i64, (i / width) as i64);
            let beside_clear = (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    nx >= 0
                        && ny >= 0
                        && nx < width as i64
                        && ny < SKY_ROWS as i64
                        && clear((ny as usize) * width + nx as usize)
                })
            });
            !clear(i) && beside_clear && image[i] < factor * sky[i]
        })
        .collect()
}

#[test]
fn the_default_scenes_cloud_layer_edges_are_not_darker_than_the_sky() {
    let (scene, with_layers, sky) = common::luminance_with_and_without_clouds("default", 960, 540);
    let mut cloudless = common::shipped("default", 960, 540);
    cloudless.file.clouds = None;
    let cloudless = cloudless.prepare().unwrap();
    let width = scene.camera.width as usize;
    // The default's cumulus are lit from the south-west at 33°: their bases, seen from
    // below, are over three times the sky's luminance, so no pixel of a layer should be
    // darker than the sky behind it; 1 % allows for f32 rounding.
    let interior = (0..SKY_ROWS * width)
        .map(|i| with_layers[i] / sky[i])
        .fold(0.0f64, f64::max);
    assert!(
        interior > 3.0,
        "the brightest cloud is {interior} × the sky"
    );
    let dark = darker_than_the_sky(&scene, &with_layers, &sky, 0.99);
    let darkest = dark
        .iter()
        .map(|&i| with_layers[i] / sky[i])
        .fold(1.0f64, f64::min);
    eprintln!(
        "CPU: {} edge pixels of the layers darker than the sky behind them (darkest \
         {darkest:.3} × the sky)",
        dark.len()
    );
    assert!(
        dark.is_empty(),
        "CPU: {} pixels, darkest {darkest}",
        dark.len()
    );

    let Some(gpu) = common::gpu_or_skip("render::cloud_layer_edges") else {
        return;
    };
    let shown = |scene: &render::scene::PreparedScene| -> Vec<f64> {
        common::gpu_pixels(gpu, scene)
            .iter()
            .map(|&p| displayed_luminance(p))
            .collect()
    };
    let (with_layers, sky) = (shown(&scene), shown(&cloudless));
    // Displayed: 8-bit codes with a ±1 code dither each (up to 4 % of a dark sky's
    // linear value between two images).
    let dark = darker_than_the_sky(&scene, &with_layers, &sky, 0.95);
    eprintln!(
        "GPU: {} displayed edge pixels of the layers 5 % darker than the sky behind them",
        dark.len()
    );
    assert!(dark.is_empty(), "GPU: {} pixels", dark.len());
}
