//! GPU == CPU, bit for bit (skipped without an adapter, see skyscape-harness).
#![cfg(feature = "gpu")]

use cloudsim::gpu::{GpuSimulation, decode_state};
use cloudsim::{Boundary, Config, Ellipsoid, GridSize, Model, PackedState, Probabilities, packed};

fn config(size: GridSize, boundary: Boundary, wind: bool) -> Config {
    let mut c = Config::new(size);
    c.boundary = boundary;
    c.seed = 0x5eed_2000;
    c.probabilities = Probabilities {
        extinction: 0.15,
        humidity: 0.3,
        activation: 0.02,
    };
    let (nx, ny, nz) = (size.nx as f32, size.ny as f32, size.nz as f32);
    c.ellipsoids = vec![
        Ellipsoid {
            center: [nx * 0.35, ny * 0.5, nz * 0.45],
            radii: [nx * 0.3, ny * 0.4, nz * 0.45],
        },
        Ellipsoid {
            center: [nx * 0.75, ny * 0.4, nz * 0.6],
            radii: [nx * 0.2, ny * 0.3, nz * 0.3],
        },
    ];
    if wind {
        c.wind = (0..size.nz)
            .map(|z| [0.15 * z as f32 - 0.6, 0.4 - 0.05 * z as f32])
            .collect();
    }
    c
}

fn cpu_steps(model: &Model, start: &PackedState, first: u32, steps: u32) -> PackedState {
    let mut state = start.clone();
    let mut scratch = PackedState::empty(model.size()).unwrap();
    for k in 0..steps {
        packed::step(model, &mut state, &mut scratch, first + k, 2).unwrap();
    }
    state
}

fn gpu_steps(
    gpu: &skyscape_harness::GpuContext,
    model: &Model,
    start: &PackedState,
    first: u32,
    batches: &[u32],
) -> (PackedState, u32) {
    let device = &gpu.device;
    let mut sim = GpuSimulation::new(device, &gpu.queue, model, start, first).unwrap();
    // Several encode calls into one encoder, then a single submit.
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("cloudsim test"),
    });
    for &steps in batches {
        sim.encode_steps(&mut encoder, steps);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "cloudsim state",
        sim.state_buffer(),
        0,
        sim.state_size(),
    )
    .unwrap();
    let decoded = sim.decode_state(&bytes).unwrap();
    assert_eq!(decoded.1, sim.step_index());
    decoded
}

#[test]
fn gpu_matches_cpu_bit_for_bit() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("cloudsim::gpu_matches_cpu_bit_for_bit") else {
        return;
    };
    for (size, boundary, wind, batches) in [
        (
            GridSize::new(64, 32, 16),
            Boundary::Empty,
            false,
            vec![20, 0, 20],
        ),
        (
            GridSize::new(64, 32, 16),
            Boundary::Periodic,
            true,
            vec![1, 29],
        ),
        (GridSize::new(45, 17, 9), Boundary::Empty, true, vec![30]),
    ] {
        let model = Model::new(config(size, boundary, wind)).unwrap();
        let start = PackedState::random(size, 77, 0.4, 0.05, 0.3).unwrap();
        let first = 1000;
        let steps: u32 = batches.iter().sum();
        let (gpu_state, counter) = gpu_steps(gpu, &model, &start, first, &batches);
        assert_eq!(counter, first + steps);
        let cpu_state = cpu_steps(&model, &start, first, steps);
        assert!(
            cpu_state.cloud_count() > 0,
            "the test grid must grow clouds"
        );
        assert_eq!(
            gpu_state, cpu_state,
            "{size:?} {boundary:?} wind={wind}: GPU and CPU differ after {steps} steps"
        );
        // and the state actually changed, so equality is not trivial
        assert_ne!(gpu_state, start);
    }
}

#[test]
fn readback_through_encode_readback() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("cloudsim::readback_through_encode_readback")
    else {
        return;
    };
    let size = GridSize::new(40, 8, 4);
    let model = Model::new(config(size, Boundary::Empty, false)).unwrap();
    let start = PackedState::random(size, 3, 0.5, 0.1, 0.2).unwrap();
    let device = &gpu.device;
    let mut encoder = device.create_command_encoder(&Default::default());
    let sim =
        cloudsim::gpu::run_steps(device, &gpu.queue, &mut encoder, &model, &start, 5, 3).unwrap();
    let staging = sim.encode_readback(device, &mut encoder);
    gpu.queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |r| {
        let _ = sender.send(r);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).unwrap();
    receiver.recv().unwrap().unwrap();
    let bytes = staging.get_mapped_range(..).unwrap().to_vec();
    let (state, counter) = decode_state(&model, &bytes).unwrap();
    assert_eq!(counter, 8);
    assert_eq!(state, cpu_steps(&model, &start, 5, 3));
    assert!(matches!(
        decode_state(&model, &bytes[4..]),
        Err(cloudsim::gpu::GpuError::ReadbackSize { .. })
    ));
}

#[test]
fn gpu_density_matches_cpu_density() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("cloudsim::gpu_density_matches_cpu_density")
    else {
        return;
    };
    for (size, boundary, radius_cells, radius_steps, steps) in [
        (GridSize::new(48, 20, 12), Boundary::Empty, 1, 2, 25),
        (GridSize::new(64, 16, 10), Boundary::Periodic, 2, 3, 2), // history not yet full
        (GridSize::new(33, 9, 7), Boundary::Empty, 0, 0, 12),
    ] {
        let mut c = config(size, boundary, true);
        c.smoothing = cloudsim::Smoothing {
            radius_cells,
            radius_steps,
        };
        c.slice_density = (0..size.nz).map(|z| 1.0 - 0.05 * z as f32).collect();
        let model = Model::new(c).unwrap();
        let start = PackedState::random(size, 9, 0.4, 0.05, 0.3).unwrap();
        let mut cpu = cloudsim::Simulation::with_state(model.clone(), start.clone(), 0).unwrap();
        cpu.advance(steps).unwrap();
        let expected = cpu.density().unwrap();

        let device = &gpu.device;
        let mut sim = GpuSimulation::new(device, &gpu.queue, &model, &start, 0).unwrap();
        let mut density = cloudsim::gpu::GpuDensity::new(device, &gpu.queue, &model).unwrap();
        let mut encoder = device.create_command_encoder(&Default::default());
        assert!(
            density.encode_density(&mut encoder).is_err(),
            "empty history"
        );
        density.encode_capture(&mut encoder, &sim).unwrap(); // the start, as the CPU keeps it
        density
            .encode_steps_with_history(&mut encoder, &mut sim, steps)
            .unwrap();
        assert_eq!(density.history_len(), (steps + 1).min(radius_steps + 1));
        density.encode_density(&mut encoder).unwrap();
        gpu.queue.submit([encoder.finish()]);
        let bytes = skyscape_harness::read_buffer(
            gpu,
            "cloudsim density",
            density.density_buffer(),
            0,
            density.density_size(),
        )
        .unwrap();
        let got = density.decode_density(&bytes).unwrap();
        assert!(
            expected.iter().any(|&d| d > 0.0),
            "the test must grow clouds"
        );
        // integer sums on both sides; f32 division (<= 2.5 ULP in WGSL) and scale
        for (i, (&g, &e)) in got.iter().zip(&expected).enumerate() {
            assert!(
                (g - e).abs() <= 1e-6,
                "{size:?} cell {i}: GPU {g} vs CPU {e}"
            );
        }
    }
}
