//! CPU cost of the closed-form sky frame (criterion): the whole CPU twin path
//! (shade, tone map, dither) on all cores. `cargo bench -p render --bench sky`

use criterion::{Criterion, criterion_group, criterion_main};
use render::SkyScene;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let scene = SkyScene {
        width: 320,
        height: 180,
        ..SkyScene::default()
    };
    let mut group = c.benchmark_group("render");
    group.sample_size(20);
    group.bench_function("render_sky_cpu 320x180", |b| {
        b.iter(|| render::sky::render_sky_cpu(black_box(&scene)).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
