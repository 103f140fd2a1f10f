//! criterion benches of the procedural shell's per-sample density path (f32, one thread):
//!
//! * `worley_noise` at 4096 points (period 16): the F1 search the shape and detail noise
//!   call nine times per density sample;
//! * `perlin_fbm` at the same points (the weather and the Perlin–Worley channel);
//! * `cloud_shape_noise` and `cloud_detail_noise` at 4096 tile coordinates;
//! * the density of `ShellSettings::stratocumulus_deck` (render's `stratocumulus` scene's
//!   deck) at 4096 points spread through the shell, weather included.
//!
//! ```sh
//! cargo bench -p cloudlight --bench shell_noise -- --warm-up-time 1 --measurement-time 3
//! ```

use std::hint::black_box;

use cloudlight::noise::{cloud_detail_noise, cloud_shape_noise, perlin_fbm, worley_noise};
use cloudlight::{CloudShell, DensityField, ShellSettings};
use criterion::{Criterion, criterion_group, criterion_main};
use skyscape_wgsl::common::hash_u32;

/// A deterministic value in [0, 1) for point `i` and channel `salt`.
fn unit(i: u32, salt: u32) -> f64 {
    f64::from(hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt) >> 8) / 16_777_216.0
}

/// 4096 points in [−span, span]³.
fn points(span: f64) -> Vec<[f32; 3]> {
    (0..4096u32)
        .map(|i| [1, 2, 3].map(|s| (span * (2.0 * unit(i, s) - 1.0)) as f32))
        .collect()
}

fn noise(c: &mut Criterion) {
    let lattice = points(16.0);
    let tiles = points(1.0);
    let mut group = c.benchmark_group("noise_f32_4096_points");
    group.bench_function("worley_noise", |b| {
        b.iter(|| {
            let sum: f32 = lattice
                .iter()
                .map(|&p| worley_noise(black_box(p), 16, 7))
                .sum();
            black_box(sum)
        })
    });
    group.bench_function("perlin_fbm", |b| {
        b.iter(|| {
            let sum: f32 = lattice
                .iter()
                .map(|&p| perlin_fbm(black_box(p), 16, 7))
                .sum();
            black_box(sum)
        })
    });
    group.bench_function("cloud_shape_noise", |b| {
        b.iter(|| {
            let sum: f32 = tiles
                .iter()
                .map(|&u| cloud_shape_noise(black_box(u), 3).iter().sum::<f32>())
                .sum();
            black_box(sum)
        })
    });
    group.bench_function("cloud_detail_noise", |b| {
        b.iter(|| {
            let sum: f32 = tiles
                .iter()
                .map(|&u| cloud_detail_noise(black_box(u), 3).iter().sum::<f32>())
                .sum();
            black_box(sum)
        })
    });
    group.finish();
}

fn shell_density(c: &mut Criterion) {
    let earth = atmos::Atmosphere::earth();
    let settings = ShellSettings::stratocumulus_deck(earth.planet_radius);
    let (inner, outer) = (settings.inner_radius, settings.outer_radius);
    let shell = CloudShell::new(&earth, settings).expect("valid deck");
    // Planet-centred points over ±20 km horizontally at every height of the deck.
    let samples: Vec<[f32; 3]> = (0..4096u32)
        .map(|i| {
            let x = 20_000.0 * (2.0 * unit(i, 1) - 1.0);
            let y = 20_000.0 * (2.0 * unit(i, 2) - 1.0);
            let r = inner + (outer - inner) * unit(i, 3);
            let z = (r * r - x * x - y * y).sqrt();
            [x as f32, y as f32, z as f32]
        })
        .collect();
    let mut group = c.benchmark_group("shell_density_f32_4096_points");
    group.bench_function("stratocumulus_deck", |b| {
        b.iter(|| {
            let sum: f32 = samples
                .iter()
                .map(|&p| DensityField::<f32>::density(&shell, black_box(p)))
                .sum();
            black_box(sum)
        })
    });
    group.finish();
}

criterion_group!(benches, noise, shell_density);
criterion_main!(benches);
