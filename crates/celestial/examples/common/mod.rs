//! Shared by the examples: a viewing transform and PNG output. The display mapping is
//! for looking at the examples only (skyscape's tone map is `render::tonemap`, which
//! composes these crates; `celestial` does not depend on it).

#![allow(dead_code)]

use std::path::PathBuf;

/// `target/celestial-examples/<name>` under the workspace, created.
pub fn output(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../target/celestial-examples");
    std::fs::create_dir_all(&dir).expect("create target/celestial-examples");
    dir.join(name)
}

/// Relative luminance of a linear sRGB triple.
pub fn luminance(c: [f32; 3]) -> f32 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// An exposure that maps the `quantile` luminance of `radiance` to 0.5 after the
/// `1 − e^{−x}` curve.
pub fn exposure_for(radiance: &[[f32; 3]], quantile: f64) -> f32 {
    let mut l: Vec<f32> = radiance
        .iter()
        .map(|&c| luminance(c))
        .filter(|v| *v > 0.0)
        .collect();
    if l.is_empty() {
        return 1.0;
    }
    l.sort_by(f32::total_cmp);
    let v = l[((l.len() - 1) as f64 * quantile) as usize];
    std::f32::consts::LN_2 / v
}

/// `1 − e^{−x·exposure}` then the sRGB transfer curve, 8 bits.
pub fn to_srgb8(c: [f32; 3], exposure: f32) -> [u8; 3] {
    c.map(|v| {
        let x = 1.0 - (-v.max(0.0) * exposure).exp();
        let s = if x <= 0.003_130_8 {
            12.92 * x
        } else {
            1.055 * x.powf(1.0 / 2.4) - 0.055
        };
        (s * 255.0).round().clamp(0.0, 255.0) as u8
    })
}

/// Writes `radiance` (row-major) as an sRGB PNG.
pub fn write_png(path: &PathBuf, width: u32, height: u32, radiance: &[[f32; 3]], exposure: f32) {
    let mut image = image::RgbImage::new(width, height);
    for (i, c) in radiance.iter().enumerate() {
        image.put_pixel(
            i as u32 % width,
            i as u32 / width,
            image::Rgb(to_srgb8(*c, exposure)),
        );
    }
    image
        .save(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    println!("wrote {}", path.display());
}

/// Per-pixel sky radiance (no objects) of `model` for `camera` (east/north/up, sun
/// in `camera.sun`), the moonlit sky added when `moon` is given.
pub fn per_pixel_sky(
    model: &(dyn atmos::SkyModel + Sync),
    atmosphere: &atmos::Atmosphere,
    camera: &atmos::frame::FrameCamera,
    moon: Option<&celestial::MoonLight>,
) -> Vec<[f32; 3]> {
    use glam::DVec3;
    let position = DVec3::from_array(camera.position.map(f64::from));
    let sun = DVec3::from_array(camera.sun.map(f64::from)).normalize();
    let mut out = vec![[0.0f32; 3]; camera.pixel_count()];
    let scale = moon.map(|m| m.sky_scale(atmosphere));
    std::thread::scope(|scope| {
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let rows = (camera.height as usize).div_ceil(threads);
        for (chunk_index, chunk) in out.chunks_mut(rows * camera.width as usize).enumerate() {
            let scale = &scale;
            scope.spawn(move || {
                for (i, px) in chunk.iter_mut().enumerate() {
                    let index = chunk_index * rows * camera.width as usize + i;
                    let pixel = [
                        (index % camera.width as usize) as u32,
                        (index / camera.width as usize) as u32,
                    ];
                    let view = DVec3::from_array(
                        atmos::frame::frame_view_direction(pixel, camera).map(f64::from),
                    )
                    .normalize();
                    let q = atmos::SkyQuery::new(atmosphere.planet_radius, position, view, sun)
                        .expect("valid query");
                    let mut l = model.evaluate(&q).radiance;
                    if let (Some(m), Some(s)) = (moon, scale) {
                        let q = atmos::SkyQuery::new(
                            atmosphere.planet_radius,
                            position,
                            view,
                            DVec3::from_array(m.direction),
                        )
                        .expect("valid query");
                        let lm = model.evaluate(&q).radiance;
                        for c in 0..3 {
                            l[c] += lm[c] * s[c];
                        }
                    }
                    *px = l.map(|v| v as f32);
                }
            });
        }
    });
    out
}
