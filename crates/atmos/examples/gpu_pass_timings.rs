//! GPU cost of each pass of the precomputed rung at default sizes for a 1280×720 frame
//! (timestamp queries, median of 5 after a warm-up), printed with the adapter's name.
//! On lavapipe/llvmpipe these are CPU-adapter timings, labelled so. A measurement
//! command, not a test:
//!
//! ```sh
//! WGPU_BACKEND=vulkan cargo run --release -p atmos --example gpu_pass_timings
//! ```

use atmos::Atmosphere;
use atmos::frame::FrameCamera;
use atmos::lut::{LutSettings, ViewTransmittance};
use glam::DVec3;

fn main() -> std::process::ExitCode {
    let gpu = match skyscape_harness::context() {
        Ok(gpu) => gpu,
        Err(e) => {
            eprintln!("gpu_pass_timings: no usable GPU adapter: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let label = skyscape_harness::describe_adapter(&gpu.info);
    let earth = Atmosphere::earth();
    let mut renderer = atmos::gpu::precomputed::PrecomputedRenderer::new(
        &gpu.device,
        &earth,
        LutSettings::default(),
    )
    .unwrap();
    let sun = DVec3::new(30f64.to_radians().cos(), 0.0, 30f64.to_radians().sin());
    // 1 km up, looking just above the horizon, 1280×720
    let camera_for = |max_distance: Option<f64>| {
        FrameCamera::look_at(
            DVec3::new(0.0, 0.0, 6_361_000.0),
            DVec3::new(1.0, 0.0, 0.1),
            DVec3::Z,
            1.0,
            1280,
            720,
            sun,
            max_distance,
        )
        .unwrap()
    };
    for max_distance in [None, Some(10_000.0)] {
        let camera = camera_for(max_distance);
        let output = atmos::gpu::FrameOutput::new(&gpu.device, 1280, 720).unwrap();
        renderer.prepare(&gpu.queue, &camera, &output).unwrap();
        let baker = renderer.luts();
        let time = |name: &str,
                    f: &dyn Fn(
            &mut wgpu::CommandEncoder,
            Option<wgpu::ComputePassTimestampWrites<'_>>,
        )| {
            let seconds = skyscape_harness::median_pass_seconds(gpu, 5, |encoder, timer, span| {
                f(encoder, Some(timer.compute_writes(span)))
            })
            .unwrap();
            eprintln!("{name}: {:.3} ms on {label}", seconds * 1e3);
        };
        time("transmittance 256x64", &|e, t| {
            baker.encode_transmittance(e, t)
        });
        time("multiple scattering 128x32, orders 2-5", &|e, t| {
            baker.encode_multiple_scattering(e, t)
        });
        time("sky view 192x108", &|e, t| baker.encode_sky_view(e, t));
        time("aerial perspective 32x32x32", &|e, t| {
            baker.encode_aerial_perspective(e, t)
        });
        time(
            &format!("per-pixel pass 1280x720 (max_distance {max_distance:?})"),
            &|e, t| renderer.encode_pixels(e, t).unwrap(),
        );
    }
    // The other view-transmittance source: a radiance-only sky view, the transmittance
    // LUT read per pixel (only the unlimited frame reads the sky view).
    let mut renderer = atmos::gpu::precomputed::PrecomputedRenderer::new(
        &gpu.device,
        &earth,
        LutSettings {
            view_transmittance: ViewTransmittance::TransmittanceLut,
            ..LutSettings::default()
        },
    )
    .unwrap();
    let output = atmos::gpu::FrameOutput::new(&gpu.device, 1280, 720).unwrap();
    renderer
        .prepare(&gpu.queue, &camera_for(None), &output)
        .unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    renderer.encode_static_luts(&mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    for (name, pixels) in [
        ("sky view 192x108, radiance only", false),
        (
            "per-pixel pass 1280x720 (None), transmittance LUT per pixel",
            true,
        ),
    ] {
        let seconds = skyscape_harness::median_pass_seconds(gpu, 5, |encoder, timer, span| {
            let writes = Some(timer.compute_writes(span));
            if pixels {
                renderer.encode_pixels(encoder, writes).unwrap();
            } else {
                renderer.luts().encode_sky_view(encoder, writes);
            }
        })
        .unwrap();
        eprintln!("{name}: {:.3} ms on {label}", seconds * 1e3);
    }
    std::process::ExitCode::SUCCESS
}
