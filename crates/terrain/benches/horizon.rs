//! East/west horizon bakes: hull sweep vs brute force, thread scaling, the 4096²
//! sweep on its own, and a 16-azimuth bake (general digital lines).
//!
//! `CARGO_TARGET_DIR=/tmp/target-terrain cargo bench -p terrain --no-default-features
//!  --bench horizon -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;
use std::num::NonZeroUsize;

use criterion::{Criterion, criterion_group, criterion_main};
use terrain::generate::{GeneratorParams, generate};
use terrain::{Algorithm, Heightfield, HorizonOptions, bake_azimuths, bake_east_west};

fn terrain(n: usize) -> Heightfield {
    // 30 m spacing, 2 km relief: a mountainous DEM-like map.
    let params = GeneratorParams {
        amplitude: 2000.0,
        ..GeneratorParams::new(n, n, 30.0, 2010)
    };
    generate(&params).expect("valid generator parameters")
}

fn sweep_vs_brute(c: &mut Criterion) {
    let options = HorizonOptions::default();
    let mut group = c.benchmark_group("east_west");
    group.sample_size(10);
    for n in [256usize, 512, 1024] {
        let hf = terrain(n);
        // Same output (the tests check this on many terrains; checked here once more).
        let a = bake_east_west(&hf, &options, Algorithm::HullSweep).unwrap();
        let b = bake_east_west(&hf, &options, Algorithm::BruteForce).unwrap();
        let diff = a
            .east
            .angles()
            .iter()
            .chain(a.west.angles())
            .zip(b.east.angles().iter().chain(b.west.angles()))
            .map(|(x, y)| (x - y).abs())
            .fold(0.0f32, f32::max);
        assert!(diff <= 1e-6, "{n}: sweep and brute force differ by {diff}");
        group.bench_function(format!("sweep/{n}"), |bench| {
            bench.iter(|| bake_east_west(black_box(&hf), &options, Algorithm::HullSweep).unwrap())
        });
        group.bench_function(format!("brute/{n}"), |bench| {
            bench.iter(|| bake_east_west(black_box(&hf), &options, Algorithm::BruteForce).unwrap())
        });
    }
    group.finish();
}

fn sweep_large(c: &mut Criterion) {
    let mut group = c.benchmark_group("east_west_sweep_large");
    group.sample_size(10);
    let hf = terrain(4096);
    for threads in [1usize, 2] {
        let options = HorizonOptions {
            threads: NonZeroUsize::new(threads),
            ..HorizonOptions::default()
        };
        group.bench_function(format!("4096/threads{threads}"), |bench| {
            bench.iter(|| bake_east_west(black_box(&hf), &options, Algorithm::HullSweep).unwrap())
        });
    }
    let limited = HorizonOptions {
        max_distance: Some(10_000.0),
        ..HorizonOptions::default()
    };
    group.bench_function("4096/max_distance_10km", |bench| {
        bench.iter(|| bake_east_west(black_box(&hf), &limited, Algorithm::HullSweep).unwrap())
    });
    group.finish();
}

fn azimuths(c: &mut Criterion) {
    let mut group = c.benchmark_group("azimuths");
    group.sample_size(10);
    let hf = terrain(1024);
    let options = HorizonOptions::default();
    group.bench_function("16/sweep/1024", |bench| {
        bench.iter(|| bake_azimuths(black_box(&hf), 16, &options, Algorithm::HullSweep).unwrap())
    });
    group.finish();
}

criterion_group!(benches, sweep_vs_brute, sweep_large, azimuths);
criterion_main!(benches);
