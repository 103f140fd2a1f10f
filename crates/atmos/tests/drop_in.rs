//! The drop-in path: a caller's local frame, the LUT bindings at groups of the
//! caller's choosing, the sky pass drawn into a caller's colour target and the aerial
//! perspective and sunlight a caller's shader applies to its geometry — each GPU result
//! against its CPU twin.

use atmos::frame::{FrameCamera, LocalFrame};
use atmos::gpu::sky::{SkyPass, SkyPassDescriptor};
use atmos::gpu::{AtmosphereLuts, composer_with_lut_groups, lut_bindings_wgsl};
use atmos::lut::drop_in::{
    SkyPassParameters, aerial_perspective, frame_screen_position, sky_pass_radiance, sunlight_at,
};
use atmos::lut::{FrameLuts, LutSettings, StaticLuts};
use atmos::{Atmosphere, SUN_ANGULAR_RADIUS};
use glam::DVec3;

fn earth() -> Atmosphere {
    Atmosphere::earth()
}

/// A camera 2 m above a local origin 300 m up, looking north-east and a little down,
/// the sun low in the west (local frame: +y up, −z north, +x east).
fn local_camera(frame: &LocalFrame, width: u32, height: u32) -> FrameCamera {
    frame
        .frame_camera(
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, -0.05, -1.0),
            DVec3::Y,
            1.1,
            width,
            height,
            DVec3::new(-1.0, 0.35, 0.2),
            None,
        )
        .unwrap()
}

#[test]
fn the_local_frame_is_a_rotation_and_keeps_altitudes() {
    let frame = LocalFrame::new(&earth(), 300.0).unwrap();
    // Up is the planet's zenith at the origin, north is +y, east +x.
    assert_eq!(frame.to_planet_direction(DVec3::Y), DVec3::Z);
    assert_eq!(frame.to_planet_direction(DVec3::NEG_Z), DVec3::Y);
    assert_eq!(frame.to_planet_direction(DVec3::X), DVec3::X);
    // Right-handed: east × north = up in both frames.
    let (east, north) = (DVec3::X, DVec3::NEG_Z);
    assert_eq!(
        frame.to_planet_direction(east.cross(north)),
        frame
            .to_planet_direction(east)
            .cross(frame.to_planet_direction(north))
    );
    for p in [
        DVec3::ZERO,
        DVec3::new(1234.5, -20.0, 987.0),
        DVec3::new(-5e4, 3e3, 7e4),
    ] {
        let back = frame.to_local_position(frame.to_planet_position(p));
        assert!((back - p).length() < 1e-6, "{p} -> {back}");
    }
    assert!((frame.altitude(DVec3::new(0.0, 2.0, 0.0)) - 302.0).abs() < 1e-6);
    // Curvature: 100 km away at the origin's height is d²/2R higher above the sphere.
    let far = frame.altitude(DVec3::new(1e5, 0.0, 0.0)) - 300.0;
    assert!(
        (far - 1e10 / (2.0 * frame.planet_radius)).abs() < 0.5,
        "{far}"
    );
    assert!(LocalFrame::new(&earth(), f64::NAN).is_err());
    let error = LocalFrame::new(&earth(), -7e6).unwrap_err().to_string();
    assert!(error.contains("origin_altitude"), "{error}");
}

#[test]
fn screen_positions_invert_the_view_directions() {
    let frame = LocalFrame::new(&earth(), 0.0).unwrap();
    let camera = local_camera(&frame, 40, 30);
    for (x, y) in [(0, 0), (39, 0), (20, 15), (7, 29)] {
        let direction = atmos::frame::frame_view_direction([x, y], &camera);
        let [u, v, depth] = frame_screen_position(&camera, direction);
        assert!(depth > 0.0);
        assert!((u - (x as f32 + 0.5) / 40.0).abs() < 1e-5, "{x}: {u}");
        assert!((v - (y as f32 + 0.5) / 30.0).abs() < 1e-5, "{y}: {v}");
    }
}

#[test]
fn the_sun_disc_is_one_formula_with_the_mean_radius() {
    let earth = earth();
    assert_eq!(earth.sun_angular_radius, SUN_ANGULAR_RADIUS);
    // E / (2π(1 − cos α)), against its small-angle limit E / (πα²).
    let disc = earth.sun_disc_radiance()[0];
    let small_angle = 1.0 / (std::f64::consts::PI * SUN_ANGULAR_RADIUS * SUN_ANGULAR_RADIUS);
    assert!(
        (disc / small_angle - 1.0).abs() < 1e-5,
        "{disc} vs {small_angle}"
    );
    let exact = 1.0 / (2.0 * std::f64::consts::PI * (1.0 - SUN_ANGULAR_RADIUS.cos()));
    assert!((disc / exact - 1.0).abs() < 1e-9);
}

#[test]
fn lut_bindings_move_to_the_groups_asked_for() {
    let source = lut_bindings_wgsl(2, 3);
    let composer = composer_with_lut_groups(2, 3).unwrap();
    let composed = composer
        .compose_module("atmos::aerial_perspective")
        .unwrap();
    // Only the group attributes differ from the file's text.
    assert!(source.contains("@group(2) @binding(0) var<uniform> lut_atmosphere"));
    assert!(source.contains("@group(3) @binding(0) var transmittance_lut"));
    assert_eq!(
        source.lines().count(),
        lut_bindings_wgsl(0, 1).lines().count()
    );
    let module = skyscape_wgsl::validate("aerial_perspective at 2, 3", &composed).unwrap();
    let mut groups: Vec<(String, u32)> = module
        .global_variables
        .iter()
        .filter_map(|(_, variable)| {
            variable
                .binding
                .as_ref()
                .map(|b| (variable.name.clone().unwrap_or_default(), b.group))
        })
        .collect();
    groups.sort();
    assert!(groups.contains(&("lut_atmosphere".into(), 2)), "{groups:?}");
    assert!(
        groups.contains(&("transmittance_lut".into(), 3)),
        "{groups:?}"
    );
    assert!(groups.iter().all(|(_, g)| *g == 2 || *g == 3), "{groups:?}");
    let error = composer_with_lut_groups(1, 1).unwrap_err().to_string();
    assert!(error.contains("table_group"), "{error}");
}

fn max_relative_difference(gpu: &[f32], cpu: &[f32], floor: f32) -> f32 {
    assert_eq!(gpu.len(), cpu.len());
    gpu.iter()
        .zip(cpu)
        .map(|(g, c)| {
            assert!(g.is_finite(), "GPU value {g}");
            (g - c).abs() / (c.abs() + floor)
        })
        .fold(0.0, f32::max)
}

fn baked(
    gpu: &skyscape_harness::GpuContext,
    camera: &FrameCamera,
) -> (AtmosphereLuts, StaticLuts, FrameLuts) {
    let settings = LutSettings::small();
    let luts = AtmosphereLuts::new(&gpu.device, &earth(), &settings).unwrap();
    luts.prepare(&gpu.queue, camera);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    luts.encode_static_luts(&mut encoder, None);
    luts.encode_frame_luts(&mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    let cpu = StaticLuts::bake(&earth(), &settings).unwrap();
    let frame = FrameLuts::bake(&cpu, camera);
    (luts, cpu, frame)
}

#[test]
fn the_sky_pass_draws_its_cpu_twin_into_a_colour_target() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("atmos::drop_in sky pass") else {
        return;
    };
    let (width, height) = (24, 16);
    let frame = LocalFrame::new(&earth(), 300.0).unwrap();
    let camera = local_camera(&frame, width, height);
    let (luts, cpu, frame_luts) = baked(gpu, &camera);
    let format = wgpu::TextureFormat::Rgba32Float;
    let mut sky = SkyPass::new(&gpu.device, &luts, &SkyPassDescriptor::new(format)).unwrap();
    let parameters = SkyPassParameters::new(&earth(), true, 1.0, 1.0).unwrap();
    let target = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("sky pass target"),
        size: wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = target.create_view(&Default::default());
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        let error = sky.draw(&mut pass, &luts).unwrap_err().to_string();
        assert!(error.contains("before prepare"), "{error}");
        sky.prepare(&gpu.queue, &parameters);
        sky.draw(&mut pass, &luts).unwrap();
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_texture(gpu, "sky pass", &target).unwrap();
    let got: &[f32] = bytemuck::cast_slice(&bytes);
    let mut want = Vec::new();
    for y in 0..height {
        for x in 0..width {
            let [r, g, b] = sky_pass_radiance(&cpu, &frame_luts, [x, y], &parameters);
            want.extend([r, g, b, 1.0]);
        }
    }
    let difference = max_relative_difference(got, &want, 1e-5);
    eprintln!("sky pass vs CPU twin: max relative difference {difference:.2e}");
    assert!(difference < 5e-3, "{difference}");
    // A sky, not a blank: the top row is blue.
    let top = &want[4 * (width as usize / 2)..][..3];
    assert!(top[2] > top[0], "{top:?}");
}

/// A caller's own compute shader, its own buffers in group 0 and the LUTs at groups 2
/// (uniforms) and 3 (tables): aerial perspective and sunlight at local-frame offsets.
const CALLER_KERNEL: &str = r"
#import atmos::aerial_perspective

@group(0) @binding(0) var<storage, read> offsets: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> results: array<vec4<f32>>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&offsets) {
        return;
    }
    let offset = local_to_planet_direction(offsets[id.x].xyz);
    let segment = aerial_perspective(offset);
    results[3u * id.x] = vec4<f32>(segment.radiance, 0.0);
    results[3u * id.x + 1u] = vec4<f32>(segment.transmittance, 0.0);
    results[3u * id.x + 2u] = vec4<f32>(sunlight_at(offset), 0.0);
}
";

#[test]
fn aerial_perspective_and_sunlight_in_a_callers_shader_match_the_cpu() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("atmos::drop_in aerial perspective") else {
        return;
    };
    let frame = LocalFrame::new(&earth(), 300.0).unwrap();
    let camera = local_camera(&frame, 32, 20);
    let (luts, cpu, frame_luts) = baked(gpu, &camera);
    // Points in view inside the volume's range, beyond it, behind the camera, below.
    let mut offsets = Vec::new();
    for distance in [5.0, 900.0, 4_000.0, 15_000.0, 31_000.0, 60_000.0] {
        for (dx, dy, dz) in [
            (1.0, -0.05, -1.0),
            (0.8, -0.2, -1.1),
            (1.2, 0.1, -0.7),
            (-1.0, -0.1, 1.0),
        ] {
            let d = DVec3::new(dx, dy, dz).normalize() * distance;
            offsets.push([d.x as f32, d.y as f32, d.z as f32, 0.0]);
        }
    }
    let composer = composer_with_lut_groups(2, 3).unwrap();
    let source = composer.compose("caller", CALLER_KERNEL).unwrap();
    let device = &gpu.device;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("caller kernel"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let own = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("caller buffers"),
        entries: &[storage(0, true), storage(1, false)],
    });
    let empty = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("caller's unused group 1"),
        entries: &[],
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("caller"),
        bind_group_layouts: &[
            Some(&own),
            Some(&empty),
            Some(&luts.layouts().uniforms),
            Some(&luts.layouts().tables),
        ],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("caller"),
        layout: Some(&layout),
        module: &module,
        entry_point: Some("main"),
        compilation_options: Default::default(),
        cache: None,
    });
    use wgpu::util::DeviceExt as _;
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("offsets"),
        contents: bytemuck::cast_slice(&offsets),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("results"),
        size: (offsets.len() * 3 * 16) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let own_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("caller buffers"),
        layout: &own,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: input.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: output.as_entire_binding(),
            },
        ],
    });
    let empty_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("empty"),
        layout: &empty,
        entries: &[],
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_compute_pass(&Default::default());
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &own_group, &[]);
        pass.set_bind_group(1, &empty_group, &[]);
        pass.set_bind_group(2, luts.uniform_bind_group(), &[]);
        pass.set_bind_group(3, luts.table_bind_group(), &[]);
        pass.dispatch_workgroups((offsets.len() as u32).div_ceil(64), 1, 1);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(gpu, "results", &output, 0, output.size()).unwrap();
    let got: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    let mut worst = [0.0f32; 3];
    for (i, offset) in offsets.iter().enumerate() {
        let planet = atmos::frame::local_to_planet_direction([offset[0], offset[1], offset[2]]);
        let segment = aerial_perspective(&cpu, &frame_luts, planet);
        let sun = sunlight_at(&cpu, &camera, planet);
        for (k, want) in [segment.radiance, segment.transmittance, sun]
            .into_iter()
            .enumerate()
        {
            let have = &got[3 * i + k][..3];
            worst[k] = worst[k].max(max_relative_difference(have, &want, 1e-6));
        }
    }
    eprintln!(
        "caller's shader vs CPU twin: radiance {:.2e}, transmittance {:.2e}, sunlight {:.2e}",
        worst[0], worst[1], worst[2]
    );
    assert!(worst.iter().all(|&w| w < 5e-3), "{worst:?}");
    // Distant points take more in-scatter and less transmittance.
    let near = aerial_perspective(&cpu, &frame_luts, [900.0, 0.0, -10.0]);
    let far = aerial_perspective(&cpu, &frame_luts, [30_000.0, 0.0, -300.0]);
    assert!(far.radiance[2] > near.radiance[2] && far.transmittance[2] < near.transmittance[2]);
}
