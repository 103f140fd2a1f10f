//! The default scene's cloud layers are shaded, not flat: a layer's column is thin at
//! its edges and thick at its cores, and celestial's `cloud_layer_radiance` lights each
//! column by its own optical thickness and the angle to the sun, so the layer's pixels
//! span a range of luminance.

mod common;

/// The default scene's size here (a quarter of its 960×540 in each axis).
const WIDTH: u32 = 480;
const HEIGHT: u32 = 270;
/// Rows that show only sky and cloud layers (the highest ridge reaches row 205 of 540).
const SKY_ROWS: usize = 100;

/// The luminances of the first `SKY_ROWS` rows' pixels that the layers change by more
/// than 10 % of the sky behind them (a layer pixel, not an almost clear edge), sorted.
fn layer_pixels(name: &str) -> Vec<f64> {
    let (_, with_layers, sky) = common::luminance_with_and_without_clouds(name, WIDTH, HEIGHT);
    let mut pixels: Vec<f64> = (0..SKY_ROWS * WIDTH as usize)
        .filter(|&i| (with_layers[i] - sky[i]).abs() > 0.1 * sky[i])
        .map(|i| with_layers[i])
        .collect();
    pixels.sort_by(f64::total_cmp);
    pixels
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[test]
fn the_default_scenes_cloud_layer_spans_a_range_of_luminance() {
    let pixels = layer_pixels("default");
    let (p5, p95) = (percentile(&pixels, 0.05), percentile(&pixels, 0.95));
    eprintln!(
        "default: {} layer pixels, luminance p5 {p5:.4e}, p95 {p95:.4e}, p95/p5 {:.3}",
        pixels.len(),
        p95 / p5
    );
    // The layer covers a tenth of the sky rows or more (coverage 0.3 seen from below).
    assert!(
        pixels.len() > SKY_ROWS * WIDTH as usize / 10,
        "{}",
        pixels.len()
    );
    // A layer lit as one value per layer (every column at the kind's τ, one radiance)
    // varies only by its view angle and the fog: about 1.4 on this scene. Thick cores
    // with darker bases, edges of partial cover and the forward glow toward the sun
    // spread it past 2.
    assert!(p95 / p5 > 2.0, "p95/p5 {}", p95 / p5);
}
