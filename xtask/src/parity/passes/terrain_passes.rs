//! Parity passes of `terrain`: the horizon-map bakes.

use super::*;

/// The pass cases of this crate, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "terrain::horizon_bake (east+west, 96x96)",
            cpu: horizon_cpu,
            gpu: horizon_gpu,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-5,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "reference: the exact hull sweep; cpu: the brute force on the same sampling \
                      (equal to ~0 rad); gpu: the same maxima in f32 (heights of km rounded to \
                      ~1e-4 m, the curvature drop, atan): 1e-5 rad (3.2e-6 measured on lavapipe)",
            },
        },
        PassCase {
            name: "terrain::horizon_bake (8 azimuths on digital lines, 80x64)",
            cpu: azimuths_cpu,
            gpu: azimuths_gpu,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-5,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "reference: the exact hull sweep per azimuth (4 unlimited, 4 with a 1 km \
                      maximum distance); cpu: the brute force on the same digital lines; gpu: \
                      the same lines (offsets uploaded from the CPU) in f32: 1e-5 rad, as the \
                      east/west bake (3.2e-6 measured on lavapipe)",
            },
        },
    ]
}

/// Azimuths of the any-azimuth pass (radians) and whether each has a 1 km limit.
fn azimuth_set() -> Vec<(f64, Option<f64>)> {
    (0..8)
        .map(|k| {
            let azimuth = 0.37 + f64::from(k) * std::f64::consts::TAU / 8.0;
            (azimuth, if k % 2 == 1 { Some(1000.0) } else { None })
        })
        .collect()
}

fn azimuth_map() -> Result<terrain::Heightfield, String> {
    terrain::generate::generate(&terrain::generate::GeneratorParams {
        amplitude: 2500.0,
        ..terrain::generate::GeneratorParams::new(80, 64, 30.0, 2027)
    })
    .map_err(|e| e.to_string())
}

fn azimuths_cpu() -> Result<PassCpu, String> {
    let heightfield = azimuth_map()?;
    let (mut reference, mut cpu) = (Vec::new(), Vec::new());
    for (azimuth, max_distance) in azimuth_set() {
        let options = terrain::HorizonOptions {
            max_distance,
            ..terrain::HorizonOptions::default()
        };
        let bake = |algorithm| {
            terrain::bake_horizon(&heightfield, azimuth, &options, algorithm)
                .map_err(|e| e.to_string())
        };
        reference.extend(
            bake(terrain::Algorithm::HullSweep)?
                .angles()
                .iter()
                .map(|&a| f64::from(a)),
        );
        cpu.extend_from_slice(bake(terrain::Algorithm::BruteForce)?.angles());
    }
    Ok(PassCpu {
        inputs: heightfield.width() * heightfield.height() * 8,
        reference,
        bounds: None,
        cpu,
    })
}

fn azimuths_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let heightfield = azimuth_map()?;
    let baker = terrain::gpu::GpuHorizonBaker::new(&gpu.device);
    let n = (heightfield.width() * heightfield.height() * 4) as u64;
    let mut values = Vec::new();
    for (azimuth, max_distance) in azimuth_set() {
        let options = terrain::HorizonOptions {
            max_distance,
            ..terrain::HorizonOptions::default()
        };
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        let out = baker
            .record_azimuth(
                &gpu.device,
                &gpu.queue,
                &mut encoder,
                &heightfield,
                azimuth,
                &options,
            )
            .map_err(|e| e.to_string())?;
        gpu.queue.submit([encoder.finish()]);
        let bytes = skyscape_harness::read_buffer(gpu, "terrain horizon", &out.angles, 0, n)
            .map_err(|e| e.to_string())?;
        values.extend_from_slice(bytemuck::cast_slice::<u8, f32>(&bytes));
    }
    Ok(values)
}

fn horizon_map() -> Result<(terrain::Heightfield, terrain::HorizonOptions), String> {
    let heightfield = terrain::generate::generate(&terrain::generate::GeneratorParams {
        amplitude: 2500.0,
        ..terrain::generate::GeneratorParams::new(96, 96, 30.0, 2026)
    })
    .map_err(|e| e.to_string())?;
    Ok((heightfield, terrain::HorizonOptions::default()))
}

fn horizon_cpu() -> Result<PassCpu, String> {
    let (heightfield, options) = horizon_map()?;
    let exact = terrain::bake_east_west(&heightfield, &options, terrain::Algorithm::HullSweep)
        .map_err(|e| e.to_string())?;
    let brute = terrain::bake_east_west(&heightfield, &options, terrain::Algorithm::BruteForce)
        .map_err(|e| e.to_string())?;
    let join = |maps: &terrain::EastWestHorizon| -> Vec<f32> {
        maps.east
            .angles()
            .iter()
            .chain(maps.west.angles())
            .copied()
            .collect()
    };
    Ok(PassCpu {
        inputs: heightfield.width() * heightfield.height(),
        reference: join(&exact).into_iter().map(f64::from).collect(),
        bounds: None,
        cpu: join(&brute),
    })
}

fn horizon_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let (heightfield, options) = horizon_map()?;
    let baker = terrain::gpu::GpuHorizonBaker::new(&gpu.device);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let out = baker
        .record_east_west(
            &gpu.device,
            &gpu.queue,
            &mut encoder,
            &heightfield,
            &options,
        )
        .map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let n = (heightfield.width() * heightfield.height() * 4) as u64;
    let mut values = Vec::new();
    for buffer in [&out.east, &out.west] {
        let bytes = skyscape_harness::read_buffer(gpu, "terrain horizon", buffer, 0, n)
            .map_err(|e| e.to_string())?;
        values.extend_from_slice(bytemuck::cast_slice::<u8, f32>(&bytes));
    }
    Ok(values)
}
