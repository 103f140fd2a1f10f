//! Fast (bit-packed) vs naive step at 256×256×64 with ellipsoids and all three
//! stochastic terms. Throughput is reported in cell updates per second.
//!
//! `cargo bench -p cloudsim --no-default-features --bench step -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use cloudsim::{
    Config, Ellipsoid, GridSize, Model, PackedState, Probabilities, Simulation, naive, packed,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

/// A 256×256×64 grid with three cumulus ellipsoids, grown for 60 steps so that the
/// state has clouds, humidity and activation in realistic proportions.
fn grown() -> (Model, PackedState) {
    let size = GridSize::new(256, 256, 64);
    let mut c = Config::new(size);
    c.seed = 2000;
    c.probabilities = Probabilities {
        extinction: 0.1,
        humidity: 0.1,
        activation: 0.001,
    };
    c.ellipsoids = vec![
        Ellipsoid {
            center: [90.0, 100.0, 30.0],
            radii: [70.0, 60.0, 24.0],
        },
        Ellipsoid {
            center: [180.0, 160.0, 34.0],
            radii: [60.0, 70.0, 22.0],
        },
        Ellipsoid {
            center: [150.0, 60.0, 28.0],
            radii: [40.0, 40.0, 16.0],
        },
    ];
    let model = Model::new(c).expect("valid bench config");
    let mut sim = Simulation::new(model.clone()).expect("valid size");
    sim.advance(60).expect("valid state");
    (model, sim.state().clone())
}

fn bench(c: &mut Criterion) {
    let (model, state) = grown();
    let cells = model.size().cells() as u64;
    let mut group = c.benchmark_group("step_256x256x64");
    group.throughput(Throughput::Elements(cells));
    group.sample_size(10);

    group.bench_function("naive", |b| {
        let reference = state.to_naive();
        let mut step = 60u32;
        b.iter(|| {
            step += 1;
            black_box(naive::step(&model, &reference, step).expect("valid"))
        });
    });
    for t in [1usize, 2] {
        group.bench_function(format!("packed_{t}_threads"), |b| {
            let mut current = state.clone();
            let mut scratch = PackedState::empty(model.size()).expect("valid");
            let mut step = 60u32;
            b.iter(|| {
                packed::step(&model, &mut current, &mut scratch, step, t).expect("valid");
                step += 1;
                black_box(&current);
            });
        });
    }
    // The deterministic rules alone (no draws, no regions): the ceiling of the packed path.
    let mut rules_only = model.config().clone();
    rules_only.ellipsoids.clear();
    rules_only.probabilities = Probabilities {
        extinction: 0.0,
        humidity: 0.0,
        activation: 0.0,
    };
    let rules_only = Model::new(rules_only).expect("valid");
    group.bench_function("packed_rules_only_1_threads", |b| {
        let mut current = state.clone();
        let mut scratch = PackedState::empty(model.size()).expect("valid");
        let mut step = 60u32;
        b.iter(|| {
            packed::step(&rules_only, &mut current, &mut scratch, step, 1).expect("valid");
            step += 1;
            black_box(&current);
        });
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
