//! The sky-objects pass on the GPU against its CPU twin, pixel for pixel (harness GPU
//! policy: an adapter runs it, none skips it visibly, none with SKYSCAPE_REQUIRE_GPU=1
//! fails).

use atmos::Atmosphere;
use atmos::closed_form_sky::ClosedFormSky;
use atmos::frame::FrameCamera;
use celestial::draw::{DISC_MOON, PointSource};
use celestial::gpu::{GpuError, SkyObjectsPass, SkyObjectsSettings};
use celestial::objects::{
    BackgroundSampling, SkyObjectsBuilder, SkyObjectsFrame, render_sky_objects_cpu,
};
use celestial::{Angle, CelestialError, LuminanceScale};
use glam::DVec3;

const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;

fn dir(elevation_deg: f64, azimuth_deg: f64) -> [f64; 3] {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()]
}

/// A low sun, a half-lit moon 0.9° beside it, and a dozen point sources (bright and
/// faint, dark and bright backgrounds) in a 64 × 48 view 3° high.
fn scene() -> SkyObjectsFrame {
    let atmosphere = Atmosphere::earth();
    let model = ClosedFormSky::new(&atmosphere).unwrap();
    let au = celestial::sun::ASTRONOMICAL_UNIT_M;
    let sun = dir(3.0, 250.0);
    let builder = SkyObjectsBuilder::new(
        &atmosphere,
        &model,
        5.0,
        sun,
        au,
        None,
        BackgroundSampling::PerObject,
    )
    .unwrap();
    let sun_disc = builder.sun_disc().unwrap();
    // A moon disc built like the builder's, lit from the side.
    let mut moon = builder.sun_disc_towards(dir(3.4, 250.9)).unwrap();
    moon.kind = DISC_MOON;
    moon.sin_radius = 0.0045;
    moon.radiance = [3.0e3, 2.5e3, 2.0e3];
    let m = DVec3::from_array(moon.direction.map(f64::from));
    let side = m.cross(DVec3::Z).normalize();
    moon.shading = (side * 0.9 - m * 0.436).normalize().as_vec3().to_array();
    let scale = LuminanceScale::new(&atmosphere, au).unwrap();
    let mut points = Vec::new();
    for k in 0..12 {
        let d = dir(2.2 + 0.2 * f64::from(k % 4), 248.5 + 0.25 * f64::from(k));
        let mut p = builder
            .point_source(
                d,
                celestial::illuminance_from_magnitude(f64::from(k) * 0.5 - 1.0),
                [1.0, 0.9, 0.8],
            )
            .unwrap();
        p.background_luminance = if k % 5 == 4 { 5000.0 } else { 1e-4 };
        points.push(p);
    }
    // One behind the camera.
    points.push(PointSource {
        direction: [0.0, 0.0, -1.0],
        ..points[0]
    });
    let camera = FrameCamera::look_at(
        DVec3::new(0.0, 0.0, atmosphere.planet_radius + 5.0),
        DVec3::from_array(dir(3.0, 250.0)),
        DVec3::Z,
        3f64.to_radians(),
        64,
        48,
        DVec3::from_array(sun),
        None,
    )
    .unwrap();
    let mut frame = SkyObjectsFrame::new(
        camera,
        atmosphere.planet_radius,
        &scale,
        1.0,
        [sun_disc, moon],
        points,
    )
    .unwrap();
    // Stars bright enough for half floats (the pass draws whatever lux scale it gets).
    frame.uniforms.lux_per_unit = 1e-2;
    frame
}

fn f16_to_f32(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = i32::from((bits >> 10) & 0x1f);
    let mantissa = f32::from(bits & 0x3ff);
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        31 => f32::INFINITY,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

#[test]
fn sky_objects_pass_matches_the_cpu_twin() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("sky_objects_pass_matches_the_cpu_twin") else {
        return;
    };
    let frame = scene();
    let (width, height) = (frame.uniforms.camera.width, frame.uniforms.camera.height);
    let base = [0.01f32, 0.02, 0.04];
    let mut cpu = vec![base; (width * height) as usize];
    render_sky_objects_cpu(&frame, &mut cpu).unwrap();

    let device = &gpu.device;
    let mut pass = SkyObjectsPass::new(device, &SkyObjectsSettings::new(FORMAT)).unwrap();
    // encode before prepare is a typed error.
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("sky objects test target"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    assert!(matches!(
        pass.encode(&mut encoder, &view, None, None),
        Err(CelestialError::Gpu(GpuError::NotPrepared { .. }))
    ));
    pass.prepare(&gpu.queue, &frame).unwrap();
    {
        // Clear to the base colour, then draw.
        let _clear = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("clear"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: 0.01,
                        g: 0.02,
                        b: 0.04,
                        a: 1.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
    }
    pass.encode(&mut encoder, &view, None, None).unwrap();
    let row_bytes = width * 8;
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("sky objects readback"),
        size: u64::from(row_bytes * height),
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(row_bytes),
                rows_per_image: Some(height),
            },
        },
        wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
    );
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "sky objects",
        &readback,
        0,
        u64::from(row_bytes * height),
    )
    .unwrap();
    let gpu_pixels: Vec<[f32; 3]> = bytes
        .chunks_exact(8)
        .map(|p| std::array::from_fn(|i| f16_to_f32(u16::from_le_bytes([p[2 * i], p[2 * i + 1]]))))
        .collect();

    // Half floats keep 11 bits (relative 4.9e-4); the f32 twins agree to ~1e-6.
    let (mut bad, mut cpu_sum, mut gpu_sum, mut lit) = (0, [0.0f64; 3], [0.0f64; 3], 0);
    for (c, g) in cpu.iter().zip(&gpu_pixels) {
        for i in 0..3 {
            cpu_sum[i] += f64::from(c[i]);
            gpu_sum[i] += f64::from(g[i]);
            if (c[i] - g[i]).abs() > 2e-3 * c[i].abs() + 1e-4 {
                bad += 1;
            }
        }
        lit += usize::from(c[0] > 2.0 * base[0]);
    }
    println!(
        "sky objects pass: {lit} lit pixels, {bad} channel values outside tolerance; sums cpu {cpu_sum:?} gpu {gpu_sum:?}"
    );
    assert!(lit > 100, "the scene draws discs and sprites: {lit}");
    // Rim pixels can fall inside the disc in one and outside in the other (the view
    // directions are normalised in each): allow a handful.
    assert!(bad <= 6, "{bad}");
    for i in 0..3 {
        assert!(
            (gpu_sum[i] / cpu_sum[i] - 1.0).abs() < 2e-3,
            "{cpu_sum:?} vs {gpu_sum:?}"
        );
    }

    // Typed errors: too many points for the capacity, a depth view it was not built for.
    let mut small = SkyObjectsPass::new(
        device,
        &SkyObjectsSettings {
            max_points: 2,
            ..SkyObjectsSettings::new(FORMAT)
        },
    )
    .unwrap();
    assert!(matches!(
        small.prepare(&gpu.queue, &frame),
        Err(CelestialError::Gpu(GpuError::TooManyPoints {
            count: 13,
            capacity: 2
        }))
    ));
    assert!(matches!(
        SkyObjectsPass::new(
            device,
            &SkyObjectsSettings {
                max_points: 0,
                ..SkyObjectsSettings::new(FORMAT)
            }
        ),
        Err(CelestialError::Gpu(GpuError::Capacity { .. }))
    ));
    let _ = Angle::ZERO;
}
