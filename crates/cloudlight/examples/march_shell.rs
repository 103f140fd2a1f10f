//! Schneider's (Nubis) procedural cloud shell, ray-marched from the ground at two sun elevations
//! (60° top, 10° bottom), lit by `atmos`: the sun's irradiance and the ambient sky at the
//! layer's middle height from `march::atmos_light`, the sky behind from the same model,
//! the clouds seen through the air by `march::apply_aerial_perspective`. Writes
//! `target/cloudlight/march_shell.png` (linear radiance × exposure, Reinhard, sRGB; the
//! ground below the horizon is left black) and prints the time per image (240×100 at 48
//! view steps, partitioned 6 + 1 cone, 3 octaves: 12.8 s and 16.1 s on the shared 2 cores):
//!
//! ```sh
//! cargo run --release -p cloudlight --example march_shell
//! ```

use std::time::Instant;

use atmos::SkyModel;
use atmos::ground_irradiance::HemisphereQuadrature;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use cloudlight::cone::ConeWeights;
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchSettings, Octaves, PinholeCamera,
    apply_aerial_perspective, atmos_light, march_view_at_pixel, pixel_direction,
};
use cloudlight::{CloudShell, ShellSettings};
use glam::DVec3;
use rayon::prelude::*;

const WIDTH: u32 = 240;
const HEIGHT: u32 = 100;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let earth = atmos::Atmosphere::earth();
    let r = earth.planet_radius;
    let shell = CloudShell::new(&earth, ShellSettings::cumulus_over(r))?;
    let sky = SingleScatteringSky::new(&earth, SingleScatteringSettings::default())?;
    let settings = MarchSettings::new(MarchConfig {
        view_steps: 48,
        jitter: Jitter::InterleavedGradient,
        light: LightMarch::Cone {
            step: 1e9,
            spread: 0.0,
            weights: ConeWeights::Partitioned,
        },
        octaves: Octaves {
            count: 3,
            a: 0.5,
            b: 0.5,
            c: 0.5,
        },
        ambient_steps: 0,
        ..MarchConfig::default()
    })?;
    // The camera on the ground at the north pole, looking north-east 12° above the
    // horizon; 100° across.
    let origin = [0.0, 0.0, r + 2.0];
    let look = DVec3::new(1.0, 0.3, 0.25).normalize();
    let target = [look.x * 1e4, look.y * 1e4, r + 2.0 + look.z * 1e4];
    let camera = PinholeCamera::look_at(origin, target, [0.0, 0.0, 1.0], 100f64.to_radians())?;
    let size = [WIDTH, HEIGHT];
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half(size);
    let mut rows = Vec::new();
    for elevation in [60.0f64, 10.0] {
        let start = Instant::now();
        let (e, a) = (elevation.to_radians(), 40f64.to_radians());
        let sun = DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        // The light at the layer's middle height above the camera (the frame's axes are
        // the planet-centred ones: the field is written in them).
        let middle = DVec3::new(0.0, 0.0, r + 2750.0);
        let light = atmos_light(&sky, &earth, middle, sun, HemisphereQuadrature::default())?;
        let lighting = Lighting::<f64>::new(
            sun.to_array(),
            light.sun_irradiance,
            light.ambient_radiance,
            [0.0, 0.0, 1.0],
        )?;
        let pixels: Vec<[f64; 3]> = (0..HEIGHT)
            .into_par_iter()
            .flat_map_iter(|y| (0..WIDTH).map(move |x| [x, y]))
            .map(|pixel| {
                let d = pixel_direction(pixel, size, forward, right, up, tan_half);
                let view = DVec3::from_array(d);
                let query = atmos::SkyQuery::new(r, DVec3::from_array(origin), view, sun)
                    .expect("a unit view from the ground");
                let behind = sky.evaluate(&query).radiance;
                let cloud = march_view_at_pixel(&shell, origin, d, &settings, &lighting, pixel);
                if cloud.transmittance >= 1.0 {
                    return behind;
                }
                let front = apply_aerial_perspective(
                    &sky,
                    &earth,
                    DVec3::from_array(origin),
                    view,
                    sun,
                    &cloud,
                )
                .expect("the camera is above the ground");
                std::array::from_fn(|k| front[k] + cloud.transmittance * behind[k])
            })
            .collect();
        println!(
            "sun {elevation}°: {WIDTH}x{HEIGHT} in {:.1} s (f64, {} threads); sun irradiance at \
             2.75 km {:.3?}, ambient radiance {:.4?}",
            start.elapsed().as_secs_f64(),
            rayon::current_num_threads(),
            light.sun_irradiance,
            light.ambient_radiance
        );
        rows.push(pixels);
    }
    let mut image = image::RgbImage::new(WIDTH, HEIGHT * 2);
    for (k, pixels) in rows.iter().enumerate() {
        // Exposure from each image's median luminance, so both elevations are visible.
        let mut lum: Vec<f64> = pixels
            .iter()
            .map(|p| atmos::ladder::luminance(*p))
            .collect();
        lum.sort_by(f64::total_cmp);
        let exposure = 0.25 / lum[lum.len() / 2].max(1e-12);
        for (i, p) in pixels.iter().enumerate() {
            let (x, y) = (i as u32 % WIDTH, i as u32 / WIDTH + k as u32 * HEIGHT);
            let rgb = p.map(|c| {
                let v = c * exposure;
                let v = v / (1.0 + v);
                let s = if v <= 0.003_130_8 {
                    12.92 * v
                } else {
                    1.055 * v.powf(1.0 / 2.4) - 0.055
                };
                (s * 255.0).round().clamp(0.0, 255.0) as u8
            });
            image.put_pixel(x, y, image::Rgb(rgb));
        }
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/cloudlight");
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("march_shell.png");
    image.save(&path)?;
    println!("wrote {}", path.display());
    Ok(())
}
