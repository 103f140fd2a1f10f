//! Grows a cloud with the bit-packed CPU automaton and writes its smoothed density as
//! PNG slices (one horizontal slice per 4 cells of height, plus a vertical section)
//! into `target/cloudsim-grow/`.
//!
//! `cargo run --release -p cloudsim --no-default-features --example grow`

use cloudsim::{Config, Ellipsoid, GridSize, Model, Probabilities, Simulation, Smoothing};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let size = GridSize::new(128, 128, 48);
    let mut config = Config::new(size);
    config.seed = 2000;
    config.probabilities = Probabilities {
        extinction: 0.1,
        humidity: 0.1,
        activation: 0.001,
    };
    config.ellipsoids = vec![
        Ellipsoid {
            center: [56.0, 64.0, 20.0],
            radii: [40.0, 34.0, 14.0],
        },
        Ellipsoid {
            center: [88.0, 56.0, 26.0],
            radii: [28.0, 26.0, 14.0],
        },
    ];
    // Denser towards the cloud base, fading at the top (the per-slice density table of Dobashi et al. 2000).
    config.slice_density = (0..size.nz)
        .map(|z| 1.0 - 0.6 * z as f32 / size.nz as f32)
        .collect();
    // A gentle shear: upper slices drift faster.
    config.wind = (0..size.nz).map(|z| [0.01 * z as f32, 0.0]).collect();
    config.smoothing = Smoothing {
        radius_cells: 2,
        radius_steps: 3,
    };
    let model = Model::new(config)?;
    let mut sim = Simulation::new(model)?;
    let started = std::time::Instant::now();
    sim.advance(150)?;
    let elapsed = started.elapsed();
    let density = sim.density()?;
    println!(
        "150 steps of {}x{}x{} in {:.3} s on {} threads; {} cloud cells",
        size.nx,
        size.ny,
        size.nz,
        elapsed.as_secs_f64(),
        sim.threads(),
        sim.state().cloud_count()
    );

    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/cloudsim-grow");
    std::fs::create_dir_all(&dir)?;
    let to_byte = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    for z in (0..size.nz).step_by(4) {
        let image = image::GrayImage::from_fn(size.nx, size.ny, |x, y| {
            image::Luma([to_byte(density[size.index(x, y, z).unwrap()])])
        });
        image.save(dir.join(format!("slice_z{z:02}.png")))?;
    }
    // Vertical section through y = ny / 2, z up.
    let y = size.ny / 2;
    let section = image::GrayImage::from_fn(size.nx, size.nz, |x, row| {
        image::Luma([to_byte(
            density[size.index(x, y, size.nz - 1 - row).unwrap()],
        )])
    });
    section.save(dir.join("section_y.png"))?;
    println!("wrote {}", dir.canonicalize()?.display());
    Ok(())
}
