//! CPU cost of rung 3 of the ladder (criterion), split the way a frame pays it:
//! the static bakes (transmittance, multiple scattering; once per atmosphere), the
//! per-frame bakes (sky view for a viewer altitude and sun; aerial-perspective volume
//! for a frame camera), and per-pixel lookups (256 queries through
//! `PrecomputedSky::evaluate_prepared`, and `shade_pixel` of a frame), each
//! [`ViewTransmittance`] source where it changes the cost.
//! Bakes are threaded over all cores (`std::thread::scope`).
//! `cargo bench -p atmos --bench ladder_precomputed`

use atmos::Atmosphere;
use atmos::frame::FrameCamera;
use atmos::ladder::SkyQuery;
use atmos::lut::aerial_perspective::bake_aerial_perspective;
use atmos::lut::multiple_scattering_lut::bake_multiple_scattering_lut;
use atmos::lut::precomputed_sky::shade_pixel;
use atmos::lut::sky_view_lut::bake_sky_view_lut;
use atmos::lut::transmittance_lut::bake_transmittance_lut;
use atmos::lut::{FrameLuts, LutSettings, PrecomputedSky, ViewTransmittance};
use criterion::{Criterion, criterion_group, criterion_main};
use glam::DVec3;
use std::hint::black_box;
use std::time::Duration;

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
    let settings = LutSettings::default();
    let sun = DVec3::new(30f64.to_radians().cos(), 0.0, 30f64.to_radians().sin());
    let sky = PrecomputedSky::new(&earth, &settings).expect("Earth is valid");
    let luts = sky.static_luts();
    let bindings = luts.bindings();
    let camera = FrameCamera::look_at(
        DVec3::new(0.0, 0.0, earth.planet_radius + 1_000.0),
        DVec3::new(1.0, 0.0, 0.1),
        DVec3::Z,
        1.0,
        1280,
        720,
        sun,
        Some(10_000.0),
    )
    .expect("valid camera");

    let mut bakes = c.benchmark_group("ladder rung 3 bakes (default sizes)");
    bakes
        .sample_size(10)
        .measurement_time(Duration::from_secs(5));
    bakes.bench_function("transmittance 256x64 (static)", |b| {
        b.iter(|| bake_transmittance_lut(black_box(&luts.atmosphere), &luts.settings))
    });
    let orders = LutSettings::default().multiple_scattering_orders;
    bakes.bench_function("multiple scattering 32x32, orders 2-5 (static)", |b| {
        b.iter(|| bake_multiple_scattering_lut(black_box(&bindings), orders))
    });
    let r = (earth.planet_radius + 1_000.0) as f32;
    let mu_s = 30f32.to_radians().sin();
    bakes.bench_function("sky view 192x108/30 (per frame)", |b| {
        b.iter(|| bake_sky_view_lut(black_box(&bindings), r, mu_s))
    });
    let radiance_only = PrecomputedSky::new(
        &earth,
        &LutSettings {
            view_transmittance: ViewTransmittance::TransmittanceLut,
            ..settings
        },
    )
    .expect("Earth is valid");
    let radiance_only_bindings = radiance_only.static_luts().bindings();
    bakes.bench_function("sky view 192x108/30, radiance only (per frame)", |b| {
        b.iter(|| bake_sky_view_lut(black_box(&radiance_only_bindings), r, mu_s))
    });
    bakes.bench_function("aerial perspective 32x32x32 (per frame)", |b| {
        b.iter(|| bake_aerial_perspective(black_box(&bindings), &camera))
    });
    bakes.finish();

    let set = queries(&earth, sun);
    let sky_view = sky.prepare(set[0].position(), sun);
    let frame = FrameLuts::bake(
        luts,
        &FrameCamera {
            max_distance: atmos::frame::UNLIMITED_DISTANCE,
            ..camera
        },
    );
    let mut pixels = c.benchmark_group("ladder rung 3 per pixel (256 lookups)");
    pixels.bench_function("evaluate_prepared (sky view with its transmittance)", |b| {
        b.iter(|| {
            set.iter()
                .map(|q| sky.evaluate_prepared(&sky_view, black_box(q)).radiance[2])
                .sum::<f64>()
        })
    });
    let radiance_only_sky_view = radiance_only.prepare(set[0].position(), sun);
    pixels.bench_function(
        "evaluate_prepared (sky view, transmittance LUT per pixel)",
        |b| {
            b.iter(|| {
                set.iter()
                    .map(|q| {
                        radiance_only
                            .evaluate_prepared(&radiance_only_sky_view, black_box(q))
                            .radiance[2]
                    })
                    .sum::<f64>()
            })
        },
    );
    pixels.bench_function("shade_pixel (GPU twin, sky)", |b| {
        b.iter(|| {
            (0..256u32)
                .map(|i| shade_pixel(luts, &frame, black_box([i * 5, (i * 37) % 720])).radiance[2])
                .sum::<f32>()
        })
    });
    pixels.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
