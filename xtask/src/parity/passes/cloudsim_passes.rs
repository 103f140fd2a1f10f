//! Parity passes of `cloudsim`: the automaton step and the density volume.

use super::*;

/// The pass cases of this crate, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "cloudsim::step (1000 steps, 128x128x32)",
            cpu: cloudsim_cpu,
            gpu: cloudsim_gpu,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer rules and counter-based draws (shared hash, integer thresholds): \
                  the naive reference, the bit-packed CPU and the WGSL must agree bit for bit",
            },
        },
        PassCase {
            name: "cloudsim::density (after 1000 steps, 128x128x32, R=1, T=2)",
            cpu: density_cpu,
            gpu: density_gpu,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-6,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "the weighted space-time sums are exact integers on both sides (< 2^24 here: \
                  norm 6 * 2^6 = 384); only sum / norm (WGSL f32 division, <= 2.5 ULP) and \
                  the slice scale (0.5 ULP) round, so |GPU - f64| <= ~3.5 ULP of values \
                  <= 1, i.e. < 2.1e-7; 1e-6 is the issue's bound",
            },
        },
    ]
}

const CLOUDSIM_STEPS: u32 = 1000;

/// The grid: 128×128×32 with two ellipsoids and a height-dependent wind.
fn cloudsim_model() -> Result<cloudsim::Model, String> {
    let size = cloudsim::GridSize::new(128, 128, 32);
    let mut config = cloudsim::Config::new(size);
    config.seed = 2026;
    config.ellipsoids = vec![
        cloudsim::Ellipsoid {
            center: [44.0, 64.0, 12.0],
            radii: [36.0, 30.0, 10.0],
        },
        cloudsim::Ellipsoid {
            center: [92.0, 58.0, 16.0],
            radii: [26.0, 34.0, 12.0],
        },
    ];
    config.wind = (0..32)
        .map(|z| [0.02 * z as f32, 0.1 - 0.01 * z as f32])
        .collect();
    // a slice table like Dobashi et al. 2000's: denser at the base
    config.slice_density = (0..32).map(|z| 1.0 - 0.015 * z as f32).collect();
    cloudsim::Model::new(config).map_err(|e| e.to_string())
}

fn packed_words(state: &cloudsim::PackedState) -> Vec<u32> {
    [&state.hum[..], &state.act[..], &state.cld[..]].concat()
}

fn cloudsim_cpu() -> Result<PassCpu, String> {
    let model = cloudsim_model()?;
    let size = model.size();
    let mut naive = cloudsim::NaiveState::empty(size).map_err(|e| e.to_string())?;
    let mut fast = cloudsim::PackedState::empty(size).map_err(|e| e.to_string())?;
    let mut scratch = fast.clone();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    for step in 0..CLOUDSIM_STEPS {
        naive = cloudsim::naive::step(&model, &naive, step).map_err(|e| e.to_string())?;
        cloudsim::packed::step(&model, &mut fast, &mut scratch, step, threads)
            .map_err(|e| e.to_string())?;
    }
    let reference = cloudsim::PackedState::from_naive(&naive).map_err(|e| e.to_string())?;
    if reference.cloud_count() == 0 {
        return Err("cloudsim parity grid grew no cloud: the case would prove nothing".into());
    }
    Ok(PassCpu {
        inputs: size.cells(),
        reference: words_as_exact_floats(&packed_words(&reference))
            .into_iter()
            .map(f64::from)
            .collect(),
        bounds: None,
        cpu: words_as_exact_floats(&packed_words(&fast)),
    })
}

fn cloudsim_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let model = cloudsim_model()?;
    let start = cloudsim::PackedState::empty(model.size()).map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let sim = cloudsim::gpu::run_steps(
        &gpu.device,
        &gpu.queue,
        &mut encoder,
        &model,
        &start,
        0,
        CLOUDSIM_STEPS,
    )
    .map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "cloudsim state",
        sim.state_buffer(),
        0,
        sim.state_size(),
    )
    .map_err(|e| e.to_string())?;
    let (state, step) = sim.decode_state(&bytes).map_err(|e| e.to_string())?;
    if step != CLOUDSIM_STEPS {
        return Err(format!(
            "GPU step counter is {step}, expected {CLOUDSIM_STEPS}"
        ));
    }
    Ok(words_as_exact_floats(&packed_words(&state)))
}

fn density_cpu() -> Result<PassCpu, String> {
    let model = cloudsim_model()?;
    let mut sim = cloudsim::Simulation::new(model).map_err(|e| e.to_string())?;
    sim.advance(CLOUDSIM_STEPS).map_err(|e| e.to_string())?;
    let reference = sim.density_f64().map_err(|e| e.to_string())?;
    if !reference.iter().any(|&d| d > 0.0) {
        return Err(
            "cloudsim density parity grid has no cloud: the case would prove nothing".into(),
        );
    }
    Ok(PassCpu {
        inputs: reference.len(),
        reference,
        bounds: None,
        cpu: sim.density().map_err(|e| e.to_string())?,
    })
}

fn density_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let model = cloudsim_model()?;
    let start = cloudsim::PackedState::empty(model.size()).map_err(|e| e.to_string())?;
    let mut sim = cloudsim::gpu::GpuSimulation::new(&gpu.device, &gpu.queue, &model, &start, 0)
        .map_err(|e| e.to_string())?;
    let mut density = cloudsim::gpu::GpuDensity::new(&gpu.device, &gpu.queue, &model)
        .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    density
        .encode_steps_with_history(&mut encoder, &mut sim, CLOUDSIM_STEPS)
        .map_err(|e| e.to_string())?;
    density
        .encode_density(&mut encoder)
        .map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "cloudsim density",
        density.density_buffer(),
        0,
        density.density_size(),
    )
    .map_err(|e| e.to_string())?;
    density.decode_density(&bytes).map_err(|e| e.to_string())
}
