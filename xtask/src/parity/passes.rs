//! Parity cases for whole passes (a simulation step, a bake): the case supplies its
//! own CPU evaluation (reference and f32 twin) and GPU evaluation; comparison and
//! reporting are shared with the function cases.

use super::compare::Tolerance;

/// The CPU side of a pass case.
#[derive(Debug, Default)]
pub struct PassCpu {
    /// Number of inputs (cells, texels, …) the pass covered.
    pub inputs: usize,
    /// The reference outputs (f64; exact integers for bit-exact passes).
    pub reference: Vec<f64>,
    /// Optional forward-error allowance per output.
    pub bounds: Option<Vec<f64>>,
    /// The fast CPU implementation's outputs.
    pub cpu: Vec<f32>,
}

/// A pass checked GPU vs CPU vs reference.
pub struct PassCase {
    /// `crate::pass`.
    pub name: &'static str,
    /// Runs the reference and the CPU implementation.
    pub cpu: fn() -> Result<PassCpu, String>,
    /// Runs the pass on the GPU; outputs in the same order as `PassCpu::reference`.
    pub gpu: fn(&skyscape_harness::GpuContext) -> Result<Vec<f32>, String>,
    /// Tolerance with its justification.
    pub tolerance: Tolerance,
}

/// Splits 32-bit words into exact f32 halves (16 bits each), so bit-exact state
/// comparisons go through the same comparator (exact tolerance).
pub fn words_as_exact_floats(words: &[u32]) -> Vec<f32> {
    words
        .iter()
        .flat_map(|w| [(w & 0xffff) as f32, (w >> 16) as f32])
        .collect()
}

/// All pass cases, in report order.
pub fn all() -> Vec<PassCase> {
    vec![
        PassCase {
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
        },
        PassCase {
            name: "cloudsim::step (1000 steps, 128x128x32)",
            cpu: cloudsim_cpu,
            gpu: cloudsim_gpu,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer rules and counter-based draws (shared hash, integer thresholds): \
                  the naive reference, the bit-packed CPU and the WGSL must agree bit for bit",
            },
        },
    ]
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

#[cfg(test)]
mod tests {
    #[test]
    fn word_split_is_exact_and_ordered() {
        assert_eq!(
            super::words_as_exact_floats(&[0xdead_beef]),
            vec![0xbeef as f32, 0xdead as f32]
        );
    }
}
