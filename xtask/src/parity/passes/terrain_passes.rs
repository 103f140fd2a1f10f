//! Parity passes of `terrain`: the horizon-map bakes.

use super::*;

/// The pass cases of this crate, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![PassCase {
        name: "terrain::horizon_bake (east+west, 96x96)",
        cpu: horizon_cpu,
        gpu: horizon_gpu,
        tolerance: Tolerance {
            abs: 1e-5,
            rel: 0.0,
            ulp: 0.0,
            bound: None,
            why: "reference: the exact hull sweep; cpu: the brute force on the same sampling \
                      (equal to ~0 rad); gpu: the same maxima in f32 (heights of km rounded to \
                      ~1e-4 m, the curvature drop, atan): 1e-5 rad (3.2e-6 measured on lavapipe)",
        },
    }]
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
