//! CPU cost per evaluation of the atmos f32 twins (criterion).
//! `cargo bench -p atmos --bench functions`

use atmos::{closed_form, geometry, optical_depth, phase, transmittance};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

const R_GROUND: f32 = 6_360_000.0;
const R_TOP: f32 = 6_460_000.0;
const BETA_R: [f32; 3] = [5.802e-6, 13.558e-6, 33.1e-6];
const BETA_M: [f32; 3] = [3.996e-6; 3];

/// 1,024 cosines so the branch predictor does not learn a single input.
fn cosines() -> Vec<f32> {
    (0..1024).map(|i| -1.0 + 2.0 * i as f32 / 1023.0).collect()
}

fn bench(c: &mut Criterion) {
    let mus = cosines();
    let mut group = c.benchmark_group("atmos (1024 evaluations)");
    group.bench_function("rayleigh_phase", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| phase::rayleigh_phase(black_box(mu)))
                .sum::<f32>()
        })
    });
    group.bench_function("henyey_greenstein_phase", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| phase::henyey_greenstein_phase(black_box(mu), 0.8))
                .sum::<f32>()
        })
    });
    group.bench_function("cornette_shanks_phase", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| phase::cornette_shanks_phase(black_box(mu), 0.8))
                .sum::<f32>()
        })
    });
    group.bench_function("ray_sphere_intersect", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| {
                    geometry::ray_sphere_intersect(black_box(R_GROUND + 100.0), mu, R_TOP)[1]
                })
                .sum::<f32>()
        })
    });
    group.bench_function("optical_length_exponential (16 samples)", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| {
                    optical_depth::optical_length_exponential(
                        black_box(R_GROUND + 100.0),
                        mu,
                        100_000.0,
                        R_GROUND,
                        8000.0,
                        16,
                    )
                })
                .sum::<f32>()
        })
    });
    group.bench_function("one_minus_exp_neg", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| transmittance::one_minus_exp_neg(black_box(mu + 1.0)))
                .sum::<f32>()
        })
    });
    group.bench_function("closed_form_inscatter", |b| {
        b.iter(|| {
            mus.iter()
                .map(|&mu| {
                    closed_form::closed_form_inscatter(BETA_R, BETA_M, black_box(mu), 0.8, 30_000.0)
                        [2]
                })
                .sum::<f32>()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
