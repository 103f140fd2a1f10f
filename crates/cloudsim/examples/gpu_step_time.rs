//! Times GPU steps (wall clock, submit to completion) on the harness adapter and checks
//! the result against the CPU. The adapter type is printed with the timing: on a CPU
//! adapter (lavapipe/llvmpipe) it is a CPU timing.
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
    let run = |sim: &mut GpuSimulation, steps: u32| -> Result<f64, Box<dyn std::error::Error>> {
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        sim.encode_steps(&mut encoder, steps);
        let t = std::time::Instant::now();
        gpu.queue.submit([encoder.finish()]);
        gpu.device.poll(wgpu::PollType::wait_indefinitely())?;
        Ok(t.elapsed().as_secs_f64())
    };
    run(&mut sim, 50)?; // warm-up and let clouds grow
    let steps = 200;
    let seconds = run(&mut sim, steps)?;
    let bytes =
        skyscape_harness::read_buffer(gpu, "state", sim.state_buffer(), 0, sim.state_size())?;
    let (state, counter) = sim.decode_state(&bytes)?;
    let mut cpu = Simulation::new(model)?;
    cpu.advance(counter)?;
    println!(
        "adapter: {}\n{}x{}x{}: {steps} steps in {:.3} s = {:.3} ms/step = {:.2} G cell-updates/s; bit-identical to CPU: {}",
        skyscape_harness::describe_adapter(&gpu.info),
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
