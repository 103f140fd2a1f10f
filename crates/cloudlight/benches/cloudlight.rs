//! criterion benches of cloudlight's CPU paths (f32, one thread):
//!
//! * slice propagation at 64³ and 128³ (physical with Catmull–Rom, faithful);
//! * the per-voxel light march (32 and 128 steps) on the 128³ volume, timed on 4096 of its
//!   cells (the cost of lighting all 128³ cells is 512× that: a full-volume march takes
//!   tens of seconds per iteration);
//! * one light estimate per sample: the partitioned 6 + 1 cone against the full march
//!   (8, 32 steps), inside the 128³ volume;
//! * the shadow map: 256² texels at the default 64 steps under a 64³ blob, sun 60°.
//!
//! ```sh
//! cargo bench -p cloudlight --bench cloudlight -- --warm-up-time 1 --measurement-time 3
//! ```

use std::hint::black_box;

use cloudlight::CloudVolume;
use cloudlight::cone::{ConeSettings, FullMarchSettings, LightRay};
use cloudlight::propagate::{SliceMode, SlicePlan, propagate};
use cloudlight::shadow_map::{DEFAULT_STEPS, ShadowGrid, ShadowMapPlan, shadow_map};
use criterion::{Criterion, criterion_group, criterion_main};

/// A paraboloid blob of `n³` cells of 40 m (σ_t 0.01 /m), as in `docs/cloudlight-methods.md`'s measurements.
fn blob(n: u32) -> CloudVolume {
    let c = f64::from(n) / 2.0;
    let mut density = Vec::with_capacity((n * n * n) as usize);
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let r2: f64 = [x, y, z]
                    .iter()
                    .map(|&v| (f64::from(v) + 0.5 - c).powi(2))
                    .sum();
                density.push((1.0 - r2 / (c * c)).max(0.0) as f32);
            }
        }
    }
    CloudVolume::new([n; 3], [0.0, 0.0, 1000.0], 40.0, 0.01, density).expect("valid blob")
}

fn sun(elevation_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), 30f64.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// 4096 cell centres spread through the volume (a 16³ lattice of every n/16-th cell).
fn sample_points(v: &CloudVolume) -> Vec<[f64; 3]> {
    let (stride, size, o) = (v.dims()[0] / 16, v.voxel_size(), v.origin());
    let mut points = Vec::with_capacity(4096);
    for z in 0..16u32 {
        for y in 0..16u32 {
            for x in 0..16u32 {
                let cell = [x, y, z].map(|c| (f64::from(c * stride) + 0.5) * size);
                points.push([0, 1, 2].map(|a| o[a] + cell[a]));
            }
        }
    }
    points
}

fn propagation(c: &mut Criterion) {
    let mut group = c.benchmark_group("propagate_f32");
    group.sample_size(10);
    for n in [64, 128] {
        let v = blob(n);
        for (name, mode) in [
            ("physical", SliceMode::Physical),
            (
                "faithful",
                SliceMode::Faithful {
                    attenuation_ratio: 0.6,
                },
            ),
        ] {
            let plan = SlicePlan::new(&v, sun(60.0), mode).expect("valid plan");
            group.bench_function(format!("{name}_{n}^3"), |b| {
                b.iter(|| {
                    black_box(
                        propagate::<f32>(black_box(&v), &plan)
                            .expect("the plan was made for this volume"),
                    )
                })
            });
        }
    }
    group.finish();
}

fn light_march(c: &mut Criterion) {
    let v = blob(128);
    let points = sample_points(&v);
    let rays: Vec<LightRay> = points
        .iter()
        .map(|&p| LightRay::through(&v, p, sun(60.0)).expect("valid ray"))
        .collect();
    let mut group = c.benchmark_group("per_voxel_march_128^3_on_4096_cells");
    group.sample_size(10);
    for steps in [32, 128] {
        let march = FullMarchSettings::new(steps).expect("valid steps");
        group.bench_function(format!("{steps}_steps"), |b| {
            b.iter(|| {
                let mut sum = 0.0f32;
                for ray in &rays {
                    let tau: f32 = ray.march_optical_depth(&v, &march);
                    sum += (-tau).exp();
                }
                black_box(sum)
            })
        });
    }
    group.finish();

    let mut group = c.benchmark_group("light_estimate_per_sample");
    let cone = ConeSettings::sevenths();
    let ray = rays[rays.len() / 2 + 8 * 16 + 8];
    group.bench_function("cone_6+1_partitioned", |b| {
        b.iter(|| {
            let tau: f32 = black_box(&ray).cone_optical_depth(&v, &cone);
            black_box(tau)
        })
    });
    for steps in [8, 32, 128] {
        let march = FullMarchSettings::new(steps).expect("valid steps");
        group.bench_function(format!("full_march_{steps}"), |b| {
            b.iter(|| {
                let tau: f32 = black_box(&ray).march_optical_depth(&v, &march);
                black_box(tau)
            })
        });
    }
    group.finish();
}

fn shadow(c: &mut Criterion) {
    let v = blob(64);
    let grid = ShadowGrid::new([-1500.0, -1000.0], 20.0, [256, 256], 0.0).expect("valid grid");
    let plan = ShadowMapPlan::new(grid, sun(60.0), DEFAULT_STEPS).expect("valid plan");
    let mut group = c.benchmark_group("shadow_map");
    group.sample_size(10);
    group.bench_function("256^2_64_steps_f32", |b| {
        b.iter(|| black_box(shadow_map::<f32, _>(black_box(&v), &plan)))
    });
    group.finish();
}

criterion_group!(benches, propagation, light_march, shadow);
criterion_main!(benches);
