//! CPU cost of rung 1 of the ladder (criterion): the closed form per pixel, and per
//! vertex of a dome — the vertex pass (once per viewer and sun) and the per-pixel
//! interpolation. `cargo bench -p atmos --bench ladder_closed_form`

use atmos::Atmosphere;
use atmos::closed_form_sky::ClosedFormSky;
use atmos::dome::{DomeInterpolated, DomeResolution};
use atmos::ladder::{SkyModel, SkyQuery};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;

/// 256 view directions over the sphere, from a viewer 1 km up, sun at 30°.
fn queries(earth: &Atmosphere, sun: DVec3) -> Vec<SkyQuery> {
    let position = DVec3::new(0.0, 0.0, earth.planet_radius + 1_000.0);
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..256)
        .map(|i| {
            let z = 1.0 - 2.0 * (f64::from(i) + 0.5) / 256.0;
            let radius = (1.0 - z * z).sqrt();
            let phi = golden * f64::from(i);
            let view = DVec3::new(radius * phi.cos(), radius * phi.sin(), z);
            SkyQuery::new(earth.planet_radius, position, view, sun).expect("valid query")
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let earth = Atmosphere::earth();
    let sun = DVec3::new(30f64.to_radians().cos(), 0.0, 30f64.to_radians().sin());
    let set = queries(&earth, sun);
    let mut group = c.benchmark_group("ladder rung 1 (256 queries)");
    let per_pixel = ClosedFormSky::new(&earth).expect("Earth is valid");
    group.bench_function("closed form per pixel", |b| {
        b.iter(|| {
            set.iter()
                .map(|q| per_pixel.evaluate(black_box(q)).radiance[2])
                .sum::<f64>()
        })
    });
    for (rings, segments) in [(8, 16), (16, 32), (32, 64)] {
        let dome = DomeInterpolated::new(
            ClosedFormSky::new(&earth).expect("Earth is valid"),
            DomeResolution { rings, segments },
            &earth,
        )
        .expect("valid dome");
        // The dome is built on the first query of a viewer and sun; later queries only
        // interpolate: this measures the interpolation (the per-pixel cost).
        dome.evaluate(&set[0]);
        group.bench_function(
            format!("closed form per vertex {rings}x{segments}: interpolation"),
            |b| {
                b.iter(|| {
                    set.iter()
                        .map(|q| dome.evaluate(black_box(q)).radiance[2])
                        .sum::<f64>()
                })
            },
        );
    }
    group.finish();
    let mut group = c.benchmark_group("ladder rung 1 dome vertices (once per viewer and sun)");
    for (rings, segments) in [(8, 16), (16, 32), (32, 64)] {
        group.bench_function(format!("{rings}x{segments}"), |b| {
            b.iter(|| {
                // A fresh dome each time so every iteration evaluates all vertices.
                let dome = DomeInterpolated::new(
                    ClosedFormSky::new(&earth).expect("Earth is valid"),
                    DomeResolution { rings, segments },
                    &earth,
                )
                .expect("valid dome");
                dome.evaluate(black_box(&set[0])).radiance[2]
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
