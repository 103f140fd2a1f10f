//! atmos in someone else's wgpu program, through the public API alone: the program owns
//! the device, its mesh (a ground plane and a row of blocks in a +y-up world, metres),
//! its camera (a glam view-projection matrix) and its shader. atmos bakes its tables
//! into textures, draws the sky into the program's colour target, and the program's
//! own fragment shader lights its geometry with `sunlight_at` and hazes it with
//! `apply_aerial_perspective`, reading the tables from bind groups 2 and 3 — the
//! groups this program chose. Headless; writes `target/atmos-examples/drop_in.png`.
//!
//! ```sh
//! cargo run --release -p atmos --example atmos_drop_in
//! ```

use atmos::Atmosphere;
use atmos::frame::LocalFrame;
use atmos::gpu::sky::{SkyPass, SkyPassDescriptor};
use atmos::gpu::{AtmosphereLuts, composer_with_lut_groups};
use atmos::ground_irradiance::{HemisphereQuadrature, ground_irradiance};
use atmos::lut::drop_in::SkyPassParameters;
use atmos::lut::{LutSettings, PrecomputedSky};
use glam::{DVec3, Vec3};
use wgpu::util::DeviceExt as _;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;
const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The program's own shader: its view uniform and lighting in group 0, atmos' LUT
/// uniforms in group 2 and tables in group 3 (`composer_with_lut_groups(2, 3)`).
const SHADER: &str = r"
#import atmos::aerial_perspective

struct View {
    view_projection: mat4x4<f32>,
    eye: vec3<f32>,
    exposure: f32,
    to_sun: vec3<f32>,
    padding: f32,
    sky_irradiance: vec3<f32>,
    padding2: f32,
}
@group(0) @binding(0) var<uniform> view: View;

struct Varyings {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) albedo: vec3<f32>,
}

@vertex
fn vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) albedo: vec3<f32>) -> Varyings {
    return Varyings(view.view_projection * vec4<f32>(position, 1.0), position, normal, albedo);
}

@fragment
fn fragment(in: Varyings) -> @location(0) vec4<f32> {
    // This program's world is a local frame (+y up); atmos wants planet-frame axes.
    let offset = local_to_planet_direction(in.world - view.eye);
    let lambert = max(dot(normalize(in.normal), view.to_sun), 0.0);
    // Lambertian: albedo/π × (sun irradiance × cos + sky irradiance on the horizontal).
    let irradiance = sunlight_at(offset) * lambert + view.sky_irradiance * (0.5 + 0.5 * in.normal.y);
    let surface = in.albedo / 3.14159265 * irradiance;
    return vec4<f32>(apply_aerial_perspective(surface, offset) * view.exposure, 1.0);
}
";

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ViewUniform {
    view_projection: [[f32; 4]; 4],
    eye: [f32; 3],
    exposure: f32,
    to_sun: [f32; 3],
    padding: f32,
    sky_irradiance: [f32; 3],
    padding2: f32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Vertex {
    position: [f32; 3],
    normal: [f32; 3],
    albedo: [f32; 3],
}

/// A 40 km ground square and blocks stepping away along the view: 2, 5, 10 and 20 km.
fn mesh() -> Vec<Vertex> {
    let mut vertices = Vec::new();
    let mut quad = |corners: [Vec3; 4], normal: Vec3, albedo: [f32; 3]| {
        for i in [0, 1, 2, 0, 2, 3] {
            vertices.push(Vertex {
                position: corners[i].to_array(),
                normal: normal.to_array(),
                albedo,
            });
        }
    };
    let s = 20_000.0;
    quad(
        [
            Vec3::new(-s, 0.0, s),
            Vec3::new(s, 0.0, s),
            Vec3::new(s, 0.0, -s),
            Vec3::new(-s, 0.0, -s),
        ],
        Vec3::Y,
        [0.12, 0.16, 0.08],
    );
    for (i, distance) in [2_000.0f32, 5_000.0, 10_000.0, 20_000.0]
        .into_iter()
        .enumerate()
    {
        let centre = Vec3::new(-600.0 + 400.0 * i as f32, 0.0, -distance);
        let (w, h) = (60.0 + 40.0 * i as f32, 300.0 + 200.0 * i as f32);
        let c = |x: f32, y: f32, z: f32| centre + Vec3::new(x * w, y * h, z * w);
        let albedo = [0.5, 0.45, 0.4];
        quad(
            [
                c(-1.0, 0.0, 1.0),
                c(1.0, 0.0, 1.0),
                c(1.0, 1.0, 1.0),
                c(-1.0, 1.0, 1.0),
            ],
            Vec3::Z,
            albedo,
        );
        quad(
            [
                c(1.0, 0.0, 1.0),
                c(1.0, 0.0, -1.0),
                c(1.0, 1.0, -1.0),
                c(1.0, 1.0, 1.0),
            ],
            Vec3::X,
            albedo,
        );
        quad(
            [
                c(-1.0, 0.0, -1.0),
                c(-1.0, 0.0, 1.0),
                c(-1.0, 1.0, 1.0),
                c(-1.0, 1.0, -1.0),
            ],
            Vec3::NEG_X,
            albedo,
        );
        quad(
            [
                c(-1.0, 1.0, 1.0),
                c(1.0, 1.0, 1.0),
                c(1.0, 1.0, -1.0),
                c(-1.0, 1.0, -1.0),
            ],
            Vec3::Y,
            albedo,
        );
    }
    vertices
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // The program's device (atmos never creates one).
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
        &instance, None,
    ))?;
    let (device, queue) = pollster::block_on(adapter.request_device(&Default::default()))?;
    println!("adapter: {}", adapter.get_info().name);

    // The world and the camera: 30 m above a local origin at sea level, looking north,
    // a late-afternoon sun in the south-west.
    let earth = Atmosphere::earth();
    let frame = LocalFrame::new(&earth, 0.0)?;
    let eye = DVec3::new(0.0, 30.0, 0.0);
    let forward = DVec3::new(0.0, -0.02, -1.0).normalize();
    let to_sun = DVec3::new(-0.6, 0.28, 0.75).normalize();
    let fov_y = 0.9;
    let camera = frame.frame_camera(eye, forward, DVec3::Y, fov_y, WIDTH, HEIGHT, to_sun, None)?;
    let view = glam::camera::rh::view::look_to_mat4(eye.as_vec3(), forward.as_vec3(), Vec3::Y);
    // wgpu's clip space: z in [0, 1], y up (DirectX's convention).
    let projection = glam::camera::rh::proj::directx::perspective(
        fov_y as f32,
        WIDTH as f32 / HEIGHT as f32,
        1.0,
        1e5,
    );

    // atmos: the tables, the sky pass, and the sky's irradiance on the ground for the
    // program's ambient term (the CPU side of the same rung).
    let settings = LutSettings::default();
    let luts = AtmosphereLuts::new(&device, &earth, &settings)?;
    let descriptor = SkyPassDescriptor {
        depth_format: Some(DEPTH),
        ..SkyPassDescriptor::new(COLOR)
    };
    let mut sky = SkyPass::new(&device, &luts, &descriptor)?;
    let exposure = 12.0;
    luts.prepare(&queue, &camera);
    sky.prepare(
        &queue,
        &SkyPassParameters::new(&earth, true, exposure, 1.0)?,
    );
    let ground = ground_irradiance(
        &PrecomputedSky::new(&earth, &settings)?,
        &earth,
        frame.to_planet_position(eye),
        frame.to_planet_direction(to_sun),
        HemisphereQuadrature::default(),
    )?;

    // The program's pipeline, its shader composed with atmos' modules at groups 2, 3.
    let source = composer_with_lut_groups(2, 3)?.compose("drop_in", SHADER)?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("drop_in"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let view_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("drop_in view"),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        }],
    });
    let unused = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("drop_in group 1 (unused)"),
        entries: &[],
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("drop_in"),
        bind_group_layouts: &[
            Some(&view_layout),
            Some(&unused),
            Some(&luts.layouts().uniforms),
            Some(&luts.layouts().tables),
        ],
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("drop_in"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: std::mem::size_of::<Vertex>() as u64,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3],
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
    let vertices = mesh();
    let vertex_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("drop_in mesh"),
        contents: bytemuck::cast_slice(&vertices),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let uniform = ViewUniform {
        view_projection: (projection * view).to_cols_array_2d(),
        eye: eye.as_vec3().to_array(),
        exposure,
        to_sun: to_sun.as_vec3().to_array(),
        padding: 0.0,
        sky_irradiance: ground.sky.map(|e| e as f32),
        padding2: 0.0,
    };
    let uniform_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("drop_in view"),
        contents: bytemuck::bytes_of(&uniform),
        usage: wgpu::BufferUsages::UNIFORM,
    });
    let view_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("drop_in view"),
        layout: &view_layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: uniform_buffer.as_entire_binding(),
        }],
    });
    let unused_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("drop_in group 1 (unused)"),
        layout: &unused,
        entries: &[],
    });

    // The program's targets.
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

    // One frame: atmos' bakes, then one render pass: the sky first, the mesh over it.
    let mut encoder = device.create_command_encoder(&Default::default());
    luts.encode_static_luts(&mut encoder, None);
    luts.encode_frame_luts(&mut encoder, None);
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("drop_in frame"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(1.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            ..Default::default()
        });
        sky.draw(&mut pass, &luts)?;
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &view_group, &[]);
        pass.set_bind_group(1, &unused_group, &[]);
        pass.set_bind_group(2, luts.uniform_bind_group(), &[]);
        pass.set_bind_group(3, luts.table_bind_group(), &[]);
        pass.set_vertex_buffer(0, vertex_buffer.slice(..));
        pass.draw(0..vertices.len() as u32, 0..1);
    }
    // Read the HDR frame back and tone-map it on the CPU (the program's choice).
    let row = WIDTH * 16;
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
    queue.submit([encoder.finish()]);
    readback.map_async(wgpu::MapMode::Read, .., |result| {
        result.expect("readback maps")
    });
    device.poll(wgpu::PollType::wait_indefinitely())?;
    let bytes = readback.get_mapped_range(..)?.to_vec();
    let mut pixels = Vec::with_capacity((WIDTH * HEIGHT * 4) as usize);
    for line in bytes.chunks(padded as usize) {
        let floats: &[f32] = bytemuck::cast_slice(&line[..row as usize]);
        for texel in floats.chunks(4) {
            for &c in &texel[..3] {
                let display = 1.0 - (-c.max(0.0)).exp();
                let srgb = if display <= 0.003_130_8 {
                    12.92 * display
                } else {
                    1.055 * display.powf(1.0 / 2.4) - 0.055
                };
                pixels.push((srgb * 255.0 + 0.5).clamp(0.0, 255.0) as u8);
            }
            pixels.push(255);
        }
    }
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../target/atmos-examples");
    std::fs::create_dir_all(&out)?;
    let path = out.join("drop_in.png");
    image::save_buffer(
        &path,
        &pixels,
        WIDTH,
        HEIGHT,
        image::ExtendedColorType::Rgba8,
    )?;
    // A check the example can fail (CI runs it): the sky's top row is blue.
    let at = |x: u32, y: u32| {
        let i = 4 * (x + WIDTH * y) as usize;
        [pixels[i], pixels[i + 1], pixels[i + 2]]
    };
    let top = at(WIDTH / 2, 2);
    if top[2] <= top[0] {
        return Err(format!("the sky's top row is not blue: {top:?}").into());
    }
    println!("wrote {}", path.display());
    Ok(())
}
