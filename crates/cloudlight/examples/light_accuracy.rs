//! Every light-transmittance method of `cloudlight` against the exact reference
//! (`cloudlight::reference`), on two volumes and two sun elevations: RMSE and max error of
//! the transmittance toward the sun at every cell centre with density > 0, and the CPU cost
//! of lighting the whole volume (f64 instantiations, one thread, this machine).
//!
//! `cargo run --release -p cloudlight --example light_accuracy` (add `-- --accuracy-only`
//! to skip the 128³ cost table).

use std::time::Instant;

use cloudlight::CloudVolume;
use cloudlight::cone::{ConeWeights, box_exit_distance, cone_optical_depth, march_optical_depth};
use cloudlight::propagate::{Resampling, SliceMode, SlicePlan, propagate};
use cloudlight::reference::transmittance;

/// A paraboloid blob, 32³ cells of 40 m, σ_t 0.01 /m (τ up to 6.4 through the centre).
fn blob() -> CloudVolume {
    let n = 32u32;
    let c = (f64::from(n) - 1.0) / 2.0;
    let mut density = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let r2: f64 = [x, y, z].iter().map(|&v| (f64::from(v) - c).powi(2)).sum();
                density.push((1.0 - r2 / (c * c)).max(0.0) as f32);
            }
        }
    }
    CloudVolume::new([n; 3], [0.0, 0.0, 1000.0], 40.0, 0.01, density).unwrap()
}

/// A cumulus grown by cloudsim (seed 2026, 64×64×24, 600 steps, two ellipsoids), smoothed
/// density, cells of 50 m, σ_t 0.01 /m per unit density.
fn cumulus() -> CloudVolume {
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
    let model = cloudsim::Model::new(config).unwrap();
    let mut sim = cloudsim::Simulation::new(model).unwrap();
    sim.advance(600).unwrap();
    let density = sim.density().unwrap();
    CloudVolume::new([64, 64, 24], [0.0, 0.0, 1500.0], 50.0, 0.01, density).unwrap()
}

fn sun(elevation_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), 30f64.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

struct Row {
    method: String,
    samples: String,
    rmse: f64,
    max: f64,
    ms: f64,
}

fn errors(light: &[f64], exact: &[f64], inside: &[usize]) -> (f64, f64) {
    let (mut sum, mut max) = (0.0, 0.0f64);
    for &c in inside {
        let e = light[c] - exact[c];
        sum += e * e;
        max = max.max(e.abs());
    }
    ((sum / inside.len() as f64).sqrt(), max)
}

/// CPU cost of lighting every cell of a 128³ blob (no reference: cost only).
fn cost_at_128() {
    let n = 128u32;
    let c = (f64::from(n) - 1.0) / 2.0;
    let mut density = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let r2: f64 = [x, y, z].iter().map(|&v| (f64::from(v) - c).powi(2)).sum();
                density.push((1.0 - r2 / (c * c)).max(0.0) as f32);
            }
        }
    }
    let volume = CloudVolume::new([n; 3], [0.0; 3], 10.0, 0.01, density).unwrap();
    let l = sun(60.0);
    let hi = [f64::from(n) * 10.0; 3];
    let time = |f: &dyn Fn() -> f64| {
        let start = Instant::now();
        let checksum = f();
        (start.elapsed().as_secs_f64() * 1e3, checksum)
    };
    println!("\nCPU cost at 128³ (sun 60°, f64, one thread):");
    println!("| method | ms | per cell |");
    println!("|---|---|---|");
    let plan = SlicePlan::new(&volume, l, SliceMode::Physical).unwrap();
    let slices = time(&|| {
        propagate::<f64>(&volume, &plan)
            .expect("the plan was made for this volume")
            .iter()
            .sum()
    });
    let bilinear = plan.clone().with_resampling(Resampling::Bilinear);
    let slices_bilinear = time(&|| {
        propagate::<f64>(&volume, &bilinear)
            .expect("the plan was made for this volume")
            .iter()
            .sum()
    });
    let density = |q: [f64; 3]| volume.density_at(q);
    let cells = (n * n * n) as usize;
    let point = |cell: usize| {
        let (x, y, z) = (cell % 128, (cell / 128) % 128, cell / (128 * 128));
        [x, y, z].map(|v| (v as f64 + 0.5) * 10.0)
    };
    let cone = time(&|| {
        (0..cells)
            .map(|cell| {
                let p = point(cell);
                let exit = box_exit_distance(p, l, [0.0; 3], hi);
                cone_optical_depth(
                    density,
                    0.01,
                    p,
                    l,
                    10.0,
                    exit,
                    0.0,
                    ConeWeights::Partitioned,
                )
            })
            .sum()
    });
    let mut rows = vec![
        ("slices, physical, Catmull-Rom".to_string(), slices.0),
        ("slices, physical, bilinear".to_string(), slices_bilinear.0),
        ("cone 6+1, partitioned".to_string(), cone.0),
    ];
    for steps in [32u32, 128] {
        let march = time(&|| {
            (0..cells)
                .map(|cell| {
                    let p = point(cell);
                    let exit = box_exit_distance(p, l, [0.0; 3], hi);
                    march_optical_depth(density, 0.01, p, l, exit, steps.try_into().unwrap())
                })
                .sum()
        });
        rows.push((format!("per-voxel light march, {steps} steps"), march.0));
    }
    for (method, ms) in rows {
        println!("| {method} | {ms:.0} | {:.0} ns |", ms * 1e6 / cells as f64);
    }
}

fn main() {
    // `-- --accuracy-only` skips the 128³ cost table (slow in the dev profile).
    if !std::env::args().any(|a| a == "--accuracy-only") {
        cost_at_128();
    }
    for (name, volume) in [
        ("blob 32³", blob()),
        ("cloudsim cumulus 64×64×24", cumulus()),
    ] {
        let [nx, ny, nz] = volume.dims();
        let h = volume.voxel_size();
        let o = volume.origin();
        let hi = [0, 1, 2].map(|a| o[a] + f64::from(volume.dims()[a]) * h);
        let centre = |c: usize| {
            let (x, y, z) = (
                c % nx as usize,
                (c / nx as usize) % ny as usize,
                c / (nx * ny) as usize,
            );
            [x, y, z].map(|v| v as f64 + 0.5).map(|v| v * h)
        };
        let point = |c: usize| {
            let p = centre(c);
            [p[0] + o[0], p[1] + o[1], p[2] + o[2]]
        };
        let cells = (nx * ny * nz) as usize;
        let inside: Vec<usize> = (0..cells).filter(|&c| volume.density()[c] > 0.0).collect();
        for elevation in [60.0, 10.0] {
            let l = sun(elevation);
            let exact: Vec<f64> = (0..cells)
                .map(|c| transmittance(&volume, point(c), l, f64::INFINITY).unwrap())
                .collect();
            let mut rows = Vec::new();
            for (label, resampling) in [
                ("slices, physical, Catmull-Rom", Resampling::CatmullRom),
                ("slices, physical, bilinear", Resampling::Bilinear),
            ] {
                let plan = SlicePlan::new(&volume, l, SliceMode::Physical)
                    .unwrap()
                    .with_resampling(resampling);
                let start = Instant::now();
                let light =
                    propagate::<f64>(&volume, &plan).expect("the plan was made for this volume");
                let ms = start.elapsed().as_secs_f64() * 1e3;
                let (rmse, max) = errors(&light, &exact, &inside);
                rows.push(Row {
                    method: label.into(),
                    samples: "1 sweep".into(),
                    rmse,
                    max,
                    ms,
                });
            }
            let density = |q: [f64; 3]| volume.density_at(q);
            let sigma = volume.extinction_per_density();
            // Cone step Δ: one cell (Schneider: dense near the point), or unbounded so the
            // partitioned layout becomes 7 equal steps over the path (Δ = L/7).
            for (label, weights, spread, step) in [
                (
                    "cone 6+1, raw (Schneider), Δ = 1 cell",
                    ConeWeights::Raw,
                    0.2,
                    h,
                ),
                (
                    "cone 6+1, raw, no spread, Δ = 1 cell",
                    ConeWeights::Raw,
                    0.0,
                    h,
                ),
                ("cone 6+1, raw, Δ = 2 cells", ConeWeights::Raw, 0.2, 2.0 * h),
                (
                    "cone 6+1, partitioned, Δ = 1 cell",
                    ConeWeights::Partitioned,
                    0.0,
                    h,
                ),
                (
                    "cone 6+1, partitioned, spread 0.2, Δ = 1 cell",
                    ConeWeights::Partitioned,
                    0.2,
                    h,
                ),
                (
                    "cone 6+1, partitioned, Δ = L/7",
                    ConeWeights::Partitioned,
                    0.0,
                    f64::MAX,
                ),
            ] {
                let start = Instant::now();
                let light: Vec<f64> = (0..cells)
                    .map(|c| {
                        let p = point(c);
                        let exit = box_exit_distance(p, l, o, hi);
                        let tau =
                            cone_optical_depth(density, sigma, p, l, step, exit, spread, weights);
                        (-tau).exp()
                    })
                    .collect();
                let ms = start.elapsed().as_secs_f64() * 1e3;
                let (rmse, max) = errors(&light, &exact, &inside);
                rows.push(Row {
                    method: label.into(),
                    samples: "7 / cell".into(),
                    rmse,
                    max,
                    ms,
                });
            }
            for steps in [8u32, 16, 32, 64, 128] {
                let start = Instant::now();
                let light: Vec<f64> = (0..cells)
                    .map(|c| {
                        let p = point(c);
                        let exit = box_exit_distance(p, l, o, hi);
                        (-march_optical_depth(
                            density,
                            sigma,
                            p,
                            l,
                            exit,
                            steps.try_into().unwrap(),
                        ))
                        .exp()
                    })
                    .collect();
                let ms = start.elapsed().as_secs_f64() * 1e3;
                let (rmse, max) = errors(&light, &exact, &inside);
                rows.push(Row {
                    method: format!("full light march, {steps} steps"),
                    samples: format!("{steps} / cell"),
                    rmse,
                    max,
                    ms,
                });
            }
            println!(
                "\n{name}, sun {elevation}° (azimuth 30°), {} cells with density > 0 of {cells}",
                inside.len()
            );
            println!("| method | density samples | RMSE | max error | CPU ms (whole volume) |");
            println!("|---|---|---|---|---|");
            for r in rows {
                println!(
                    "| {} | {} | {:.4} | {:.3} | {:.1} |",
                    r.method, r.samples, r.rmse, r.max, r.ms
                );
            }
        }
    }
}
