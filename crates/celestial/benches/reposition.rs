//! What moving the sky to another instant costs (criterion): `Sky::reposition` with
//! the default catalogue (magnitude ≤ 6.6, what the eye can see against the natural
//! night sky) and the whole shipped one (magnitude ≤ 8), on one thread.
//! `cargo bench -p celestial --bench reposition`

use celestial::sky::{Sky, SkyOptions};
use celestial::{Angle, Instant, Observer};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let observer = Observer::new(Angle::from_degrees(46.5), Angle::from_degrees(8.0), 1000.0)
        .expect("a valid observer");
    let instant = Instant::parse("2024-09-20T22:00:00Z").expect("a valid instant");
    let mut group = c.benchmark_group("celestial Sky::reposition");
    for limit in [6.6, 8.0] {
        let options = SkyOptions {
            star_limit_magnitude: Some(limit),
            ..Default::default()
        };
        let mut sky = Sky::build(atmos::Atmosphere::earth(), options).expect("the catalogue");
        let stars = sky.catalogue().stars().len();
        group.bench_function(format!("magnitude ≤ {limit} ({stars} stars)"), |b| {
            b.iter(|| {
                sky.reposition(black_box(&observer), black_box(&instant))
                    .map(|p| p.sun.airless.elevation.radians())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
