//! CPU cost of the default scene (`scenes/default.toml`) at 960×540 on the CPU
//! reference renderer (criterion): terrain ray casts, shading, aerial perspective,
//! sky, tone map and dither on all cores; the scene's preparation (LUT bake, terrain
//! generation, horizon maps) is done once outside the measurement.
//! `cargo bench -p render --bench scene`

use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/default.toml");
    let mut scene = render::scene::Scene::open(path).unwrap();
    scene.file.output.width = 960;
    scene.file.output.height = 540;
    let prepared = scene.prepare().unwrap();
    let mut group = c.benchmark_group("render");
    group.sample_size(10);
    group.measurement_time(std::time::Duration::from_secs(40));
    group.bench_function("default scene 960x540 (cpu_renderer)", |b| {
        b.iter(|| render::cpu_renderer::render_cpu(black_box(&prepared)).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
