//! The ground's cloud shadow map of a cloudsim cumulus at two sun elevations, written as
//! one PNG (sun 60° left, 15° right; white = no shadow) to `target/cloudlight/shadow_map.png`,
//! with the f32 twin's (the GPU pass's march) error against the exact f64 map at several
//! step counts:
//!
//! ```sh
//! cargo run --release -p cloudlight --example shadow_map
//! ```

use std::time::Instant;

use cloudlight::CloudVolume;
use cloudlight::shadow_map::{
    DEFAULT_STEPS, ShadowGrid, ShadowMapPlan, map_error, shadow_map, shadow_map_reference,
};

/// The cumulus of `examples/light_accuracy.rs`: cloudsim seed 2026, 64×64×24 cells of
/// 50 m from 1500 m up, 600 steps, two ellipsoids, σ_t 0.01 /m per unit density.
fn cumulus() -> Result<CloudVolume, Box<dyn std::error::Error>> {
    let size = cloudsim::GridSize::new(64, 64, 24);
    let mut config = cloudsim::Config::new(size);
    config.seed = 2026;
    config.ellipsoids = vec![
        cloudsim::Ellipsoid {
            center: [28.0, 32.0, 9.0],
            radii: [20.0, 18.0, 8.0],
        },
        cloudsim::Ellipsoid {
            center: [40.0, 30.0, 13.0],
            radii: [16.0, 20.0, 9.0],
        },
    ];
    let model = cloudsim::Model::new(config)?;
    let mut sim = cloudsim::Simulation::new(model)?;
    sim.advance(600)?;
    let density = sim.density()?;
    Ok(CloudVolume::new(
        [64, 64, 24],
        [0.0, 0.0, 1500.0],
        50.0,
        0.01,
        density,
    )?)
}

fn sun(elevation_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), 30f64.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

const SIZE: u32 = 256;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cloud = cumulus()?;
    let mut image = vec![0u8; (2 * SIZE * SIZE) as usize];
    for (panel, elevation) in [60.0, 15.0].into_iter().enumerate() {
        let l = sun(elevation);
        // 256² texels of 25 m (6.4 km) centred on the shadow of the cloud's centre
        // (1600, 1600, 2100) on flat ground at 0 m.
        let lift = 2100.0 / l[2];
        let centre = [1600.0 - lift * l[0], 1600.0 - lift * l[1]];
        let half = 0.5 * 25.0 * f64::from(SIZE);
        let grid = ShadowGrid::new(
            [centre[0] - half, centre[1] - half],
            25.0,
            [SIZE, SIZE],
            0.0,
        )?;
        let plan = ShadowMapPlan::new(grid, l, DEFAULT_STEPS)?;
        let start = Instant::now();
        let exact = shadow_map_reference(&cloud, &plan)?;
        let exact_ms = start.elapsed().as_secs_f64() * 1e3;
        let shaded = exact.iter().filter(|&&t| t < 0.99).count();
        println!(
            "sun {elevation}°: {shaded} of {} texels shaded (exact T < 0.99), exact map {exact_ms:.0} ms",
            exact.len()
        );
        for steps in [8, 16, 32, DEFAULT_STEPS, 128] {
            let plan = ShadowMapPlan::new(grid, l, steps)?;
            let start = Instant::now();
            let map = shadow_map::<f32, _>(&cloud, &plan);
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let (rmse, max) = map_error(&map, &exact).ok_or("map sizes differ")?;
            println!(
                "  f32 twin, {steps:>3} steps: RMSE {rmse:.2e}, max {max:.2e} against the exact map ({ms:.0} ms)"
            );
            if steps == DEFAULT_STEPS {
                for j in 0..SIZE {
                    for i in 0..SIZE {
                        let t = map[(i + SIZE * j) as usize].clamp(0.0, 1.0);
                        // Image rows from the top: north (+y) up.
                        let row = SIZE - 1 - j;
                        let at = (row * 2 * SIZE + panel as u32 * SIZE + i) as usize;
                        image[at] = (t * 255.0).round() as u8;
                    }
                }
            }
        }
    }
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/cloudlight");
    std::fs::create_dir_all(&dir)?;
    let path = dir.join("shadow_map.png");
    image::GrayImage::from_raw(2 * SIZE, SIZE, image)
        .ok_or("image buffer size")?
        .save(&path)?;
    println!("wrote {}", path.canonicalize()?.display());
    Ok(())
}
