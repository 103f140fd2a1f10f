//! Times GPU steps with timestamp queries (`skyscape_harness::PassTimer`, the median of
//! 5 passes of 40 steps after a warm-up) on the harness adapter, and checks the result
//! against the CPU. The adapter type is printed with the timing: on a CPU adapter
//! (lavapipe/llvmpipe) it is a CPU timing, not GPU speed.
//!
//! `WGPU_BACKEND=vulkan cargo run --release -p cloudsim --example gpu_step_time`

use cloudsim::gpu::GpuSimulation;
use cloudsim::{Config, Ellipsoid, GridSize, Model, PackedState, Simulation};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let gpu = skyscape_harness::context()?;
    let size = GridSize::new(128, 128, 32);
    let mut config = Config::new(size);
    config.seed = 2000;
    config.ellipsoids = vec![Ellipsoid {
        center: [64.0, 64.0, 14.0],
        radii: [50.0, 44.0, 12.0],
    }];
    let model = Model::new(config)?;
    let start = PackedState::empty(size)?;
    let mut sim = GpuSimulation::new(&gpu.device, &gpu.queue, &model, &start, 0)?;
    // Warm-up (pipelines, first touch) and let clouds grow, untimed.
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    sim.encode_steps(&mut encoder, 50);
    gpu.queue.submit([encoder.finish()]);
    const STEPS_PER_PASS: u32 = 40;
    let seconds_per_pass =
        skyscape_harness::median_pass_seconds(gpu, 5, |encoder, timer, span| {
            sim.encode_steps_timed(encoder, STEPS_PER_PASS, Some(timer.compute_writes(span)));
        })?;
    let steps = STEPS_PER_PASS;
    let seconds = seconds_per_pass;
    let bytes =
        skyscape_harness::read_buffer(gpu, "state", sim.state_buffer(), 0, sim.state_size())?;
    let (state, counter) = sim.decode_state(&bytes)?;
    let mut cpu = Simulation::new(model)?;
    cpu.advance(counter)?;
    println!(
        "adapter: {}{}\n{}x{}x{}: {steps} steps in {:.3} s (timestamp queries) = {:.3} ms/step = {:.2} G cell-updates/s; bit-identical to CPU: {}",
        skyscape_harness::describe_adapter(&gpu.info),
        if gpu.is_cpu_adapter() {
            " — a CPU adapter: CPU time, not GPU speed"
        } else {
            ""
        },
        size.nx,
        size.ny,
        size.nz,
        seconds,
        seconds * 1e3 / f64::from(steps),
        size.cells() as f64 * f64::from(steps) / seconds / 1e9,
        &state == cpu.state()
    );
    Ok(())
}
