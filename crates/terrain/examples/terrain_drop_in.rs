//! terrain in someone else's wgpu program, through the public API alone: the program
//! owns the device, its mesh (the heightfield as a triangle grid in a +y-up world,
//! metres), its camera (a glam view-projection matrix) and its shader. terrain bakes 16
//! horizon maps on the program's device (`GpuHorizonBaker::record_azimuth`, one storage
//! buffer of angles each), the program copies them into its own buffer, and its
//! fragment shader shadows the terrain with terrain's WGSL (`#import terrain::shadow`:
//! `azimuth_layers`, `sun_elevation`, `sun_azimuth`, `soft_shadow`) at the bind group
//! and binding it chose. Headless; writes `target/terrain-examples/drop_in.png` and
//! checks the GPU's shadowed fraction against terrain's CPU twin.
//!
//! ```sh
//! cargo run --release -p terrain --example terrain_drop_in
//! ```

use glam::{Mat4, Vec3, Vec4};
use terrain::generate::{GeneratorParams, generate};
use terrain::gpu::GpuHorizonBaker;
use terrain::{Algorithm, HorizonOptions, bake_azimuths};
use wgpu::util::DeviceExt as _;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;
const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8Unorm;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// Heightfield side (texels), spacing (m), relief (m) and horizon azimuths.
const SIDE: usize = 192;
const SPACING: f64 = 30.0;
const RELIEF: f64 = 1_500.0;
const AZIMUTHS: usize = 16;
/// The sun: azimuth 110° (clockwise from north, off the grid axes), elevation 9°.
const SUN_AZIMUTH_DEG: f32 = 110.0;
const SUN_ELEVATION_DEG: f32 = 9.0;

/// The program's own shader: its view uniform in group 0, binding 0, and the horizon
/// stack (layer k at k · 2π / N, row-major texels) in group 0, binding 1.
const SHADER: &str = r"
#import terrain::shadow

struct View {
    view_projection: mat4x4<f32>,
    // Towards the sun in the program's world (+y up, x east, z south).
    to_sun_world: vec3<f32>,
    width: u32,
    // Towards the sun in terrain's east-north-up frame.
    to_sun_enu: vec3<f32>,
    height: u32,
    layers: u32,
    padding0: u32,
    padding1: u32,
    padding2: u32,
}
@group(0) @binding(0) var<uniform> view: View;
@group(0) @binding(1) var<storage, read> horizon: array<f32>;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) normal: vec3<f32>,
    @location(1) texel: vec2<f32>,
    @location(2) elevation: f32,
}

@vertex
fn vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) texel: vec2<f32>) -> Varyings {
    return Varyings(view.view_projection * vec4<f32>(position, 1.0), normal, texel, position.y);
}

// The horizon stack's angle at a texel for the sun's azimuth (terrain's interpolation
// between the two neighbouring layers).
fn horizon_angle(texel: vec2<u32>) -> f32 {
    let i = texel.y * view.width + texel.x;
    let layer = view.width * view.height;
    let l = azimuth_layers(sun_azimuth(view.to_sun_enu), view.layers);
    let a = horizon[l.lower * layer + i];
    let b = horizon[l.upper * layer + i];
    return a + (b - a) * l.weight;
}

@fragment
fn fragment(in: Varyings) -> @location(0) vec4<f32> {
    let texel = vec2<u32>(round(in.texel));
    let lit = soft_shadow(sun_elevation(view.to_sun_enu), horizon_angle(texel), SUN_ANGULAR_RADIUS);
    let lambert = max(dot(normalize(in.normal), view.to_sun_world), 0.0);
    let rock = vec3<f32>(0.45, 0.42, 0.38);
    let grass = vec3<f32>(0.20, 0.30, 0.12);
    let albedo = mix(grass, rock, smoothstep(300.0, 900.0, in.elevation));
    let sky = vec3<f32>(0.10, 0.13, 0.20);
    let c = albedo * (3.0 * lambert * lit + sky);
    return vec4<f32>(pow(c / (1.0 + c), vec3<f32>(1.0 / 2.2)), 1.0);
}
";

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ViewUniform {
    view_projection: [[f32; 4]; 4],
    to_sun_world: [f32; 3],
    width: u32,
    to_sun_enu: [f32; 3],
    height: u32,
    layers: u32,
    padding: [u32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    texel: [f32; 2],
}

/// A right-handed view matrix looking from `eye` at `target`, +y up.
fn look_at(eye: Vec3, target: Vec3) -> Mat4 {
    let f = (target - eye).normalize();
    let s = f.cross(Vec3::Y).normalize();
    let u = s.cross(f);
    Mat4::from_cols(
        Vec4::new(s.x, u.x, -f.x, 0.0),
        Vec4::new(s.y, u.y, -f.y, 0.0),
        Vec4::new(s.z, u.z, -f.z, 0.0),
        Vec4::new(-s.dot(eye), -u.dot(eye), f.dot(eye), 1.0),
    )
}

/// A right-handed perspective projection to wgpu's depth range [0, 1].
fn perspective(fov_y: f32, aspect: f32, near: f32, far: f32) -> Mat4 {
    let h = 1.0 / (0.5 * fov_y).tan();
    let r = far / (near - far);
    Mat4::from_cols(
        Vec4::new(h / aspect, 0.0, 0.0, 0.0),
        Vec4::new(0.0, h, 0.0, 0.0),
        Vec4::new(0.0, 0.0, r, -1.0),
        Vec4::new(0.0, 0.0, r * near, 0.0),
    )
}

/// Runs a future that wgpu's native backends complete without waiting on anything
/// else (adapter and device requests), so this example needs no executor crate.
fn block_on<F: std::future::Future>(future: F) -> F::Output {
    let mut future = std::pin::pin!(future);
    let mut cx = std::task::Context::from_waker(std::task::Waker::noop());
    loop {
        if let std::task::Poll::Ready(value) = future.as_mut().poll(&mut cx) {
            return value;
        }
        std::thread::yield_now();
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The program's device (terrain never creates one).
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = block_on(wgpu::util::initialize_adapter_from_env_or_default(
        &instance, None,
    ))?;
    let (device, queue) = block_on(adapter.request_device(&Default::default()))?;
    println!("adapter: {}", adapter.get_info().name);

    // The terrain, and its mesh in the program's world: x east, y up, z south, metres,
    // centred on the map.
    let hf = generate(&GeneratorParams {
        amplitude: RELIEF,
        ..GeneratorParams::new(SIDE, SIDE, SPACING, 7)
    })?;
    let half = (SIDE - 1) as f32 * SPACING as f32 / 2.0;
    let h = |x: usize, y: usize| hf.elevation(x, y).map(|e| e as f32);
    let mut vertices = Vec::with_capacity(SIDE * SIDE);
    for y in 0..SIDE {
        for x in 0..SIDE {
            let (x0, x1) = (x.saturating_sub(1), (x + 1).min(SIDE - 1));
            let (y0, y1) = (y.saturating_sub(1), (y + 1).min(SIDE - 1));
            let dx = (h(x1, y)? - h(x0, y)?) / ((x1 - x0) as f32 * SPACING as f32);
            let dz = (h(x, y1)? - h(x, y0)?) / ((y1 - y0) as f32 * SPACING as f32);
            vertices.push(Vertex {
                position: [
                    x as f32 * SPACING as f32 - half,
                    h(x, y)?,
                    y as f32 * SPACING as f32 - half,
                ],
                normal: Vec3::new(-dx, 1.0, -dz).normalize().to_array(),
                texel: [x as f32, y as f32],
            });
        }
    }
    let mut indices: Vec<u32> = Vec::with_capacity((SIDE - 1) * (SIDE - 1) * 6);
    for y in 0..SIDE as u32 - 1 {
        for x in 0..SIDE as u32 - 1 {
            let i = y * SIDE as u32 + x;
            let s = SIDE as u32;
            indices.extend_from_slice(&[i, i + s, i + 1, i + 1, i + s, i + s + 1]);
        }
    }

    // The sun, in terrain's east-north-up frame and in the program's world.
    let (az, el) = (SUN_AZIMUTH_DEG.to_radians(), SUN_ELEVATION_DEG.to_radians());
    let enu = Vec3::new(az.sin() * el.cos(), az.cos() * el.cos(), el.sin());
    let world = Vec3::from_array(terrain::skyscape_wgsl::common::enu_to_world(enu.to_array()));

    // terrain bakes on the program's device and queue, into the program's encoder.
    let options = HorizonOptions::default();
    let baker = GpuHorizonBaker::new(&device);
    let layer_bytes = (SIDE * SIDE * 4) as u64;
    let stack = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("drop_in horizon stack"),
        size: layer_bytes * AZIMUTHS as u64,
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&Default::default());
    let mut maps = Vec::with_capacity(AZIMUTHS);
    for k in 0..AZIMUTHS {
        let azimuth = k as f64 * std::f64::consts::TAU / AZIMUTHS as f64;
        let map = baker.record_azimuth(&device, &queue, &mut encoder, &hf, azimuth, &options)?;
        encoder.copy_buffer_to_buffer(&map.angles, 0, &stack, k as u64 * layer_bytes, layer_bytes);
        maps.push(map); // kept alive until the submit
    }
    queue.submit([encoder.finish()]);

    // The program's pipeline, its shader composed with terrain's modules.
    let source = terrain::composer().compose("drop_in", SHADER)?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("drop_in"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("drop_in"),
        layout: None,
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2],
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: Default::default(),
            bias: Default::default(),
        }),
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module: &module,
            entry_point: Some("fragment"),
            compilation_options: Default::default(),
            targets: &[Some(COLOR.into())],
        }),
        multiview_mask: None,
        cache: None,
    });

    // The camera: south-east of the map, 2.5 km up, looking at its centre.
    let eye = Vec3::new(0.9 * half, 2_500.0, 1.6 * half);
    let view = look_at(eye, Vec3::new(0.0, 300.0, 0.0));
    let projection = perspective(
        50f32.to_radians(),
        WIDTH as f32 / HEIGHT as f32,
        10.0,
        50_000.0,
    );
    let uniform = ViewUniform {
        view_projection: (projection * view).to_cols_array_2d(),
        to_sun_world: world.to_array(),
        width: SIDE as u32,
        to_sun_enu: enu.to_array(),
        height: SIDE as u32,
        layers: AZIMUTHS as u32,
        padding: [0; 3],
    };
    let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("drop_in view"),
        contents: bytemuck::bytes_of(&uniform),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("drop_in"),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform_buffer.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: stack.as_entire_binding(),
            },
        ],
    });
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("drop_in mesh"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let index_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("drop_in indices"),
        contents: bytemuck::cast_slice(&indices),
        usage: wgpu::BufferUsages::INDEX,
    });
    let target = |format, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some("drop_in target"),
            size: wgpu::Extent3d {
                width: WIDTH,
                height: HEIGHT,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats: &[],
        })
    };
    let color = target(
        COLOR,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
    );
    let depth = target(DEPTH, wgpu::TextureUsages::RENDER_ATTACHMENT);
    let color_view = color.create_view(&Default::default());
    let depth_view = depth.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("drop_in"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color {
                        r: 0.35,
                        g: 0.5,
                        b: 0.75,
                        a: 1.0,
                    }),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Discard,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &group, &[]);
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.set_index_buffer(index_buffer.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(0..indices.len() as u32, 0, 0..1);
    }
    let row = WIDTH * 4;
    let padded =
        row.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("drop_in readback"),
        size: u64::from(padded * HEIGHT),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        color.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded),
                rows_per_image: None,
            },
        },
        color.size(),
    );
    let stack_readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("drop_in stack readback"),
        size: stack.size(),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_buffer_to_buffer(&stack, 0, &stack_readback, 0, stack.size());
    queue.submit([encoder.finish()]);
    stack_readback.map_async(wgpu::MapMode::Read, .., |result| {
        result.expect("stack readback maps")
    });
    readback.map_async(wgpu::MapMode::Read, .., |result| {
        result.expect("readback maps")
    });
    device.poll(wgpu::PollType::wait_indefinitely())?;
    let bytes = readback.get_mapped_range(..)?.to_vec();
    let mut pixels = Vec::with_capacity((WIDTH * HEIGHT * 4) as usize);
    for line in bytes.chunks(padded as usize) {
        pixels.extend_from_slice(&line[..row as usize]);
    }
    let out =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/terrain-examples");
    std::fs::create_dir_all(&out)?;
    let path = out.join("drop_in.png");
    image::save_buffer(
        &path,
        &pixels,
        WIDTH,
        HEIGHT,
        image::ExtendedColorType::Rgba8,
    )?;

    // A check the example can fail (CI runs it): the stack the shader read gives the
    // same hard shadows as terrain's CPU bake (within 0.1 % of the texels: f32 on the
    // GPU), and the sun shadows a plausible part of the map.
    let gpu_angles: Vec<f32> = bytemuck::cast_slice(&stack_readback.get_mapped_range(..)?).to_vec();
    let cpu = bake_azimuths(&hf, AZIMUTHS, &options, Algorithm::HullSweep)?;
    let (sun_azimuth, sun_elevation) =
        (SUN_AZIMUTH_DEG.to_radians(), SUN_ELEVATION_DEG.to_radians());
    let layers = terrain::shadow::azimuth_layers(sun_azimuth, AZIMUTHS as u32)?;
    let (mut shadowed, mut differ) = (0usize, 0usize);
    for y in 0..SIDE {
        for x in 0..SIDE {
            let i = y * SIDE + x;
            let a = gpu_angles[layers.lower as usize * SIDE * SIDE + i];
            let b = gpu_angles[layers.upper as usize * SIDE * SIDE + i];
            let gpu_shadow = a + (b - a) * layers.weight >= sun_elevation;
            let cpu_shadow = cpu.horizon_angle(x, y, sun_azimuth)? >= sun_elevation;
            shadowed += usize::from(cpu_shadow);
            differ += usize::from(gpu_shadow != cpu_shadow);
        }
    }
    let n = (SIDE * SIDE) as f64;
    let (fraction, disagree) = (shadowed as f64 / n, differ as f64 / n);
    println!(
        "{:.1} % of the texels in hard shadow at {SUN_AZIMUTH_DEG}° / {SUN_ELEVATION_DEG}°; GPU and CPU stacks disagree on {differ}",
        100.0 * fraction
    );
    if !(0.01..0.9).contains(&fraction) || disagree > 1e-3 {
        return Err(format!("shadowed {fraction}, GPU/CPU disagreement {disagree}").into());
    }
    println!("wrote {}", path.display());
    Ok(())
}
