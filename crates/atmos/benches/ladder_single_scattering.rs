//! CPU cost per evaluation of rung 2 (single scattering, f32 twin) at several sample
//! counts, and of the Reference (rung 4) per query after its precomputation, whose
//! wall-clock time is printed. `cargo bench -p atmos --bench ladder_single_scattering`

use atmos::reference::{ReferenceSettings, ReferenceSky};
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{Atmosphere, SkyModel, SkyQuery};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;

/// 64 queries from the ground and from 10 km: directions over the sphere, sun at 30°.
fn queries(planet_radius: f64) -> Vec<SkyQuery> {
    let sun = DVec3::new(0.866, 0.0, 0.5);
    let mut out = Vec::new();
    for altitude in [1.0, 10_000.0] {
        for i in 0..32 {
            let mu = -1.0 + 2.0 * (i as f64 + 0.5) / 32.0;
            let phi = 2.399_963 * i as f64; // golden angle
            let s = (1.0 - mu * mu).sqrt();
            let view = DVec3::new(s * phi.cos(), s * phi.sin(), mu);
            out.push(
                SkyQuery::new(
                    planet_radius,
                    DVec3::new(0.0, 0.0, planet_radius + altitude),
                    view,
                    sun,
                )
                .unwrap(),
            );
        }
    }
    out
}

fn bench(c: &mut Criterion) {
    let earth = Atmosphere::earth();
    let qs = queries(earth.planet_radius);
    let mut group = c.benchmark_group("ladder single scattering (per evaluation, 64 queries)");
    for (view, light) in [(32, 8), (16, 4), (64, 16)] {
        let sky = SingleScatteringSky::new(
            &earth,
            SingleScatteringSettings {
                view_samples: view,
                light_samples: light,
            },
        )
        .unwrap();
        group.bench_function(format!("rung 2 {view}/{light}"), |b| {
            b.iter(|| {
                qs.iter()
                    .map(|q| sky.evaluate(black_box(q)).radiance[0])
                    .sum::<f64>()
            })
        });
    }
    group.finish();

    let start = std::time::Instant::now();
    let reference = ReferenceSky::new(&earth, ReferenceSettings::default()).unwrap();
    eprintln!(
        "reference precomputation ({}): {:.2} s wall clock",
        reference.label(),
        start.elapsed().as_secs_f64()
    );
    let mut group = c.benchmark_group("ladder reference (per evaluation, 64 queries)");
    group.sample_size(10);
    group.bench_function("reference query (default)", |b| {
        b.iter(|| {
            qs.iter()
                .map(|q| reference.evaluate(black_box(q)).radiance[0])
                .sum::<f64>()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
