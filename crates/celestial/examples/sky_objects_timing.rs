//! The sky-objects pass's cost (GPU timestamp queries, median of 20): the star field of the
//! `star_field` example's night (the catalogue to the naked-eye limit, the moon, the
//! sun below the horizon) in a 960 × 540 frame, 60° high. A measurement command:
//! `cargo run --release -p celestial --example sky_objects_timing`.

use atmos::Atmosphere;
use atmos::closed_form_sky::ClosedFormSky;
use celestial::Angle;
use celestial::gpu::{SkyObjectsPass, SkyObjectsSettings};
use celestial::objects::render_sky_objects_cpu;

const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

fn dir(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()]
}

fn main() -> std::process::ExitCode {
    let gpu = match skyscape_harness::context() {
        Ok(gpu) => gpu,
        Err(e) => {
            eprintln!("sky_objects_timing: no usable GPU adapter: {e}");
            return std::process::ExitCode::FAILURE;
        }
    };
    let atmosphere = Atmosphere::earth();
    let model = ClosedFormSky::new(&atmosphere).unwrap();
    let mut sky = celestial::Sky::build(atmosphere, celestial::SkyOptions::default()).unwrap();
    let observer =
        celestial::Observer::new(Angle::from_degrees(52.0), Angle::from_degrees(5.0), 10.0)
            .unwrap();
    sky.reposition(
        &observer,
        &celestial::Instant::parse("2024-08-20T02:30:00Z").unwrap(),
    )
    .unwrap();
    sky.repaint(&model).unwrap();
    let camera = sky
        .camera(
            dir(32.0, 95.0),
            [0.0, 0.0, 1.0],
            Angle::from_degrees(60.0),
            960,
            540,
        )
        .unwrap();
    let frame = sky.sky_objects_frame(&camera).unwrap();
    let mut pass = SkyObjectsPass::new(&gpu.device, &SkyObjectsSettings::new(FORMAT)).unwrap();
    pass.prepare(&gpu.queue, &frame).unwrap();
    let texture = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("timing target"),
        size: wgpu::Extent3d {
            width: 960,
            height: 540,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let seconds = skyscape_harness::median_pass_seconds(gpu, 20, |encoder, timer, span| {
        pass.encode(encoder, &view, None, Some(timer.render_writes(span)))
            .unwrap();
    })
    .unwrap();
    let start = std::time::Instant::now();
    let mut radiance = vec![[0.0f32; 3]; 960 * 540];
    render_sky_objects_cpu(&frame, &mut radiance).unwrap();
    println!(
        "sky objects, 960×540, {} point sources: GPU pass median {:.3} ms on {} ({}); CPU twin {:.1} ms (one thread)",
        frame.points.len(),
        1e3 * seconds,
        gpu.info.name,
        if gpu.is_cpu_adapter() {
            "CPU adapter"
        } else {
            "GPU"
        },
        1e3 * start.elapsed().as_secs_f64()
    );
    std::process::ExitCode::SUCCESS
}
