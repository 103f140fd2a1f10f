//! Parity passes of atmos' drop-in path: the sky pass (a render pipeline) drawn into a
//! colour target, and aerial perspective and sunlight evaluated by a caller's own
//! compute shader that binds the LUTs at groups 2 and 3
//! (`atmos::gpu::composer_with_lut_groups`). Each against its CPU twin in
//! `atmos::lut::drop_in` on tables baked by the CPU (the GPU reads its own bakes).
//!
//! The reference is the CPU f32 twin (there is no f64 version of the table lookups):
//! `Audit::CPU_IS_REFERENCE`, the CPU rows are "reference = this side". Tolerances as
//! the precomputed frame's (5e-4 relative: the bakes' drift plus the lookups' weights).

use super::*;
use atmos::Atmosphere;
use atmos::frame::{FrameCamera, LocalFrame};
use atmos::gpu::sky::{SkyPass, SkyPassDescriptor};
use atmos::gpu::{AtmosphereLuts, composer_with_lut_groups};
use atmos::lut::drop_in::{SkyPassParameters, aerial_perspective, sky_pass_radiance, sunlight_at};
use atmos::lut::{FrameLuts, LutSettings, StaticLuts};
use glam::DVec3;
use wgpu::util::DeviceExt as _;

const WIDTH: u32 = 24;
const HEIGHT: u32 = 16;

/// A camera 2 m above a local origin 300 m up, looking north-east and a little down,
/// the sun low in the west.
fn camera() -> Result<FrameCamera, String> {
    let frame = LocalFrame::new(&Atmosphere::earth(), 300.0).map_err(|e| e.to_string())?;
    frame
        .frame_camera(
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, -0.05, -1.0),
            DVec3::Y,
            1.1,
            WIDTH,
            HEIGHT,
            DVec3::new(-1.0, 0.35, 0.2),
            None,
        )
        .map_err(|e| e.to_string())
}

fn sky_parameters() -> Result<SkyPassParameters, String> {
    SkyPassParameters::new(&Atmosphere::earth(), true, 1.0, 1.0).map_err(|e| e.to_string())
}

fn cpu_tables() -> Result<(StaticLuts, FrameLuts, FrameCamera), String> {
    let camera = camera()?;
    let luts =
        StaticLuts::bake(&Atmosphere::earth(), &LutSettings::small()).map_err(|e| e.to_string())?;
    let frame = FrameLuts::bake(&luts, &camera);
    Ok((luts, frame, camera))
}

fn gpu_tables(gpu: &skyscape_harness::GpuContext) -> Result<AtmosphereLuts, String> {
    let luts = AtmosphereLuts::new(&gpu.device, &Atmosphere::earth(), &LutSettings::small())
        .map_err(|e| e.to_string())?;
    luts.prepare(&gpu.queue, &camera()?);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    luts.encode_static_luts(&mut encoder, None);
    luts.encode_frame_luts(&mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    Ok(luts)
}

fn reference_pass(values: Vec<f32>, inputs: usize) -> PassCpu {
    PassCpu {
        inputs,
        reference: values.iter().map(|&v| f64::from(v)).collect(),
        bounds: None,
        cpu: values,
    }
}

fn sky_pass_cpu() -> Result<PassCpu, String> {
    let (luts, frame, _) = cpu_tables()?;
    let parameters = sky_parameters()?;
    let mut values = Vec::new();
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let [r, g, b] = sky_pass_radiance(&luts, &frame, [x, y], &parameters);
            values.extend([r, g, b, 1.0]);
        }
    }
    Ok(reference_pass(values, (WIDTH * HEIGHT) as usize))
}

fn sky_pass_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let luts = gpu_tables(gpu)?;
    let format = wgpu::TextureFormat::Rgba32Float;
    let mut sky = SkyPass::new(&gpu.device, &luts, &SkyPassDescriptor::new(format))
        .map_err(|e| e.to_string())?;
    sky.prepare(&gpu.queue, &sky_parameters()?);
    let target = gpu.device.create_texture(&wgpu::TextureDescriptor {
        label: Some("sky pass target"),
        size: wgpu::Extent3d {
            width: WIDTH,
            height: HEIGHT,
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
        sky.draw(&mut pass, &luts).map_err(|e| e.to_string())?;
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes =
        skyscape_harness::read_texture(gpu, "sky pass", &target).map_err(|e| e.to_string())?;
    Ok(bytemuck::cast_slice::<u8, f32>(&bytes).to_vec())
}

/// Points in view inside the volume's range, beyond it, behind the camera and below
/// its horizon: local-frame offsets from the camera (m).
fn offsets() -> Vec<[f32; 4]> {
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
    offsets
}

fn caller_cpu() -> Result<PassCpu, String> {
    let (luts, frame, camera) = cpu_tables()?;
    let mut values = Vec::new();
    for offset in offsets() {
        let planet = atmos::frame::local_to_planet_direction([offset[0], offset[1], offset[2]]);
        let segment = aerial_perspective(&luts, &frame, planet);
        let sun = sunlight_at(&luts, &camera, planet);
        for rgb in [segment.radiance, segment.transmittance, sun] {
            values.extend(rgb);
        }
    }
    Ok(reference_pass(values, offsets().len()))
}

/// A caller's own compute shader: its buffers in group 0, nothing in group 1, the LUTs
/// at groups 2 (uniforms) and 3 (tables).
const CALLER_KERNEL: &str = r"
#import atmos::aerial_perspective

@group(0) @binding(0) var<storage, read> offsets: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> results: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= arrayLength(&offsets) {
        return;
    }
    let offset = local_to_planet_direction(offsets[id.x].xyz);
    let segment = aerial_perspective(offset);
    let sun = sunlight_at(offset);
    let values = array<vec3<f32>, 3>(segment.radiance, segment.transmittance, sun);
    for (var k = 0u; k < 3u; k++) {
        for (var c = 0u; c < 3u; c++) {
            results[9u * id.x + 3u * k + c] = values[k][c];
        }
    }
}
";

fn caller_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let luts = gpu_tables(gpu)?;
    let offsets = offsets();
    run_lut_caller(
        gpu,
        &luts,
        CALLER_KERNEL,
        bytemuck::cast_slice(&offsets),
        offsets.len(),
        (offsets.len() * 9 * 4) as u64,
    )
}

/// Runs `kernel` (a caller's compute shader: its input in group 0 binding 0, its
/// results in binding 1, atmos' tables in groups 2 and 3) over `invocations` threads
/// with `luts` bound, and reads back `output_bytes` of f32 results: what a user's own
/// shader calling atmos' WGSL sees.
pub(super) fn run_lut_caller(
    gpu: &skyscape_harness::GpuContext,
    luts: &AtmosphereLuts,
    kernel: &str,
    input: &[u8],
    invocations: usize,
    output_bytes: u64,
) -> Result<Vec<f32>, String> {
    let source = composer_with_lut_groups(2, 3)
        .map_err(|e| e.to_string())?
        .compose("caller", kernel)
        .map_err(|e| e.to_string())?;
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
    let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("caller input"),
        contents: input,
        usage: wgpu::BufferUsages::STORAGE,
    });
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("results"),
        size: output_bytes,
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
        pass.dispatch_workgroups((invocations as u32).div_ceil(64), 1, 1);
    }
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(gpu, "results", &output, 0, output.size())
        .map_err(|e| e.to_string())?;
    Ok(bytemuck::cast_slice::<u8, f32>(&bytes).to_vec())
}

/// The drop-in pass cases, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "atmos::sky_pass (render pipeline, 24x16)",
            cpu: sky_pass_cpu,
            gpu: sky_pass_gpu,
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "sky_pass_radiance = the precomputed frame's unlimited segment (its 5e-4 \
                      budget: the sky-view bake's drift and the lookup weights) plus the sun's \
                      disc through the transmittance where the pixel sees it; the fragment's \
                      ray is its position through the view's pixel-to-ray matrix, as the twin's",
            },
        },
        PassCase {
            name: "atmos::aerial_perspective + sunlight_at (caller's shader, groups 2/3)",
            cpu: caller_cpu,
            gpu: caller_gpu,
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "in range: the aerial-perspective bake's 5e-4 and a trilinear lookup; \
                      beyond it, behind the camera: a LUT march (the sky-view bake's budget); \
                      sunlight: one transmittance lookup (the transmittance bake's 2e-5)",
            },
        },
    ]
}
