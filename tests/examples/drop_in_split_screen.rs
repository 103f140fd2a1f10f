//! An engine's own wgpu frame (its device, Rgba16Float colour and reversed-z Depth32Float
//! targets, terrain mesh and shader, two cameras side by side in one encoder) with atmos'
//! sky, sunlight, GPU sky irradiance and depth-buffer haze, and terrain's GPU horizon
//! stack for self-shadows. Headless: `cargo run -p skyscape-tests --example
//! drop_in_split_screen` writes `target/skyscape-examples/split_screen.png`.

use atmos::frame::LocalFrame;
use atmos::gpu::{sky::SkyPass, sky::SkyPassDescriptor, *};
use atmos::lut::{LutSettings, drop_in::SkyPassParameters};
use atmos::view::{ViewCamera, Viewport};
use glam::DVec3;
use glam::dcamera::rh::{proj::directx as proj, view::look_to_mat4};
use skyscape_wgsl::common::enu_to_world;
use terrain::generate::{GeneratorParams, generate};
use terrain::horizon_stack::HorizonStack;
use terrain::horizon_texture::{GpuHorizonStack, horizon_stack_bindings_wgsl};
use wgpu::util::DeviceExt as _;

const W: u32 = 320; // each view; the target is 2W × H
const H: u32 = 240;
const SIDE: usize = 129; // heightfield texels per side
const SPACING: f64 = 60.0; // metres
const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The engine's terrain shader: its camera in group 0, the horizon stack in group 1,
/// atmos' tables in groups 2 and 3. World: +y up, −z north, metres (atmos' LocalFrame).
const SHADER: &str = r"
#import atmos::aerial_perspective
#import terrain::horizon_stack
struct Camera { view_projection: mat4x4<f32>, sun_world: vec3<f32>, planet_radius: f32 }
@group(0) @binding(0) var<uniform> camera: Camera;
struct Out { @builtin(position) clip: vec4<f32>, @location(0) world: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) texel: vec2<f32> }
@vertex
fn vertex(@location(0) world: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) texel: vec2<f32>) -> Out {
    return Out(camera.view_projection * vec4<f32>(world, 1.0), world, normal, texel);
}
@fragment
fn fragment(in: Out) -> @location(0) vec4<f32> {
    // World → east-north-up: terrain's axes and atmos' planet frame's (moved by R).
    let position = world_to_enu(in.world) + vec3<f32>(0.0, 0.0, camera.planet_radius);
    let normal = world_to_enu(normalize(in.normal));
    let sun = world_to_enu(camera.sun_world);
    let shadow = self_shadow(horizon_stack, horizon_stack_params, in.texel, sun, SUN_ANGULAR_RADIUS);
    let direct = lut_atmosphere.sun_irradiance * sun_transmittance_at(position) * max(dot(normal, sun), 0.0) * shadow;
    let albedo = vec3<f32>(0.16, 0.14, 0.10);
    return vec4<f32>(albedo / PI * (direct + sky_irradiance(position, normal)), 1.0);
}
";

/// The two cameras: eye (x, height above the highest peak, z) and forward, world axes.
const CAMERAS: [[f64; 6]; 2] = [
    [-1500.0, 150.0, 2500.0, 0.5, -0.12, -1.0],
    [3000.0, 3000.0, -3000.0, -0.8, -0.55, 0.9],
];

const ATTRIBUTES: [wgpu::VertexAttribute; 3] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x2];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let instance =
        wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
    let adapter = wgpu::util::initialize_adapter_from_env_or_default(&instance, None);
    let adapter = pollster::block_on(adapter)?;
    let (device, queue) = pollster::block_on(adapter.request_device(&Default::default()))?;

    // The engine's terrain: a generated heightfield, its normals and 16 horizon azimuths.
    let start = std::time::Instant::now();
    let hf = generate(&GeneratorParams::new(SIDE, SIDE, SPACING, 7))?;
    let normals = terrain::NormalMap::from_heightfield(&hf);
    let maps = terrain::bake_azimuths(&hf, 16, &Default::default(), terrain::Algorithm::HullSweep)?;
    println!("CPU terrain bakes: {:.2} s", start.elapsed().as_secs_f64());
    let encoded = HorizonStack::new(&maps, terrain::HorizonEncoding::Unorm16)?;
    let stack = GpuHorizonStack::upload(&device, &queue, &encoded)?;
    // Texel (x, y) sits at world (x, height, y) × spacing, centred: rows run south = +z.
    let half = (SIDE as f64 - 1.0) * SPACING / 2.0;
    let mut vertices: Vec<[f32; 8]> = Vec::with_capacity(SIDE * SIDE);
    for y in 0..SIDE {
        for x in 0..SIDE {
            let [e, u, s] = enu_to_world(normals.normal(x, y)?); // east, up, south
            let (px, pz) = (x as f64 * SPACING - half, y as f64 * SPACING - half);
            let h = hf.elevation(x, y)? as f32;
            vertices.push([px as f32, h, pz as f32, e, u, s, x as f32, y as f32]);
        }
    }
    let side = SIDE as u32;
    let indices: Vec<u32> = (0..side - 1)
        .flat_map(|y| (0..side - 1).map(move |x| y * side + x))
        .flat_map(|i| [i, i + side, i + 1, i + 1, i + side, i + side + 1])
        .collect();
    let buffer = |contents: &[u8], usage| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: None,
            contents,
            usage,
        })
    };
    let vertex_buffer = buffer(bytemuck::cast_slice(&vertices), wgpu::BufferUsages::VERTEX);
    let index_buffer = buffer(bytemuck::cast_slice(&indices), wgpu::BufferUsages::INDEX);
    // atmos: the shared tables (with the sky irradiance), one view per camera.
    let earth = atmos::Atmosphere::earth();
    let frame = LocalFrame::new(&earth, 0.0)?;
    let tables = AtmosphereTables::new(&device, &earth, &LutSettings::default())?;
    let views = [AtmosphereView::new(&tables), AtmosphereView::new(&tables)];
    let mut targets = SkyPassDescriptor::new(COLOR);
    targets.depth_format = Some(DEPTH);
    let mut sky = SkyPass::new(&device, &tables, &targets)?;
    sky.prepare(&queue, &SkyPassParameters::new(&earth, true, 1.0, 0.0)?);
    let mut haze = AerialPerspectivePass::new(&device, &tables, COLOR, DepthConvention::Reversed)?;

    // The engine's pipeline: its shader composed with atmos' and terrain's modules.
    let mut composer = composer_with_lut_groups(2, 3)?;
    composer.add_modules(terrain::WGSL_MODULES)?;
    let shader = format!("{}{SHADER}", horizon_stack_bindings_wgsl(1));
    let source = composer.compose("terrain_shader", &shader)?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: None,
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let camera_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: None,
        entries: &[atmos::gpu::resources::shared_uniform_entry(0)],
    });
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: None,
        bind_group_layouts: &[
            Some(&camera_layout),
            Some(stack.layout()),
            Some(&tables.layouts().uniforms),
            Some(&tables.layouts().tables),
        ],
        immediate_size: 0,
    });
    let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("terrain"),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module: &module,
            entry_point: Some("vertex"),
            compilation_options: Default::default(),
            buffers: &[Some(wgpu::VertexBufferLayout {
                array_stride: 32,
                step_mode: wgpu::VertexStepMode::Vertex,
                attributes: &ATTRIBUTES,
            })],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH,
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Greater), // reversed z
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

    // Two cameras: just above the peaks looking north-east, high above looking south-west.
    let top = hf.elevations().into_iter().fold(f64::MIN, f64::max);
    let sun_world = DVec3::new(-0.5, 0.22, 0.6).normalize(); // low in the south-west
    let projection = proj::perspective_infinite_reverse(1.0, f64::from(W) / f64::from(H), 1.0);
    let (mut hazed, mut camera_groups) = (Vec::new(), Vec::new());
    for (i, ([x, y, z, fx, fy, fz], view)) in CAMERAS.into_iter().zip(&views).enumerate() {
        let eye = DVec3::new(x, top + y, z);
        let view_matrix = look_to_mat4(eye, DVec3::new(fx, fy, fz).normalize(), DVec3::Y);
        let mut viewport = Viewport::full(W, H);
        viewport.x = (i as u32 * W) as f32; // side by side in one target
        let camera =
            ViewCamera::from_matrices(&frame, view_matrix, projection, viewport, sun_world, None)?;
        view.prepare(&queue, &camera);
        // The engine's camera uniform: view-projection, the sun (world), the planet's radius.
        let mut uniform = [0.0f32; 20];
        uniform[..16].copy_from_slice(&(projection * view_matrix).as_mat4().to_cols_array());
        let sun_and_radius = sun_world.as_vec3().extend(earth.planet_radius as f32);
        uniform[16..].copy_from_slice(&sun_and_radius.to_array());
        let uniform = buffer(bytemuck::cast_slice(&uniform), wgpu::BufferUsages::UNIFORM);
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &camera_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: uniform.as_entire_binding(),
            }],
        });
        hazed.push((view, viewport));
        camera_groups.push(group);
    }

    // The engine's targets, and the frame: one encoder, one submit.
    let target = |format, usage| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: None,
            size: wgpu::Extent3d {
                width: 2 * W,
                height: H,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | usage,
            view_formats: &[],
        })
    };
    let color = target(COLOR, wgpu::TextureUsages::COPY_SRC);
    let depth = target(DEPTH, wgpu::TextureUsages::TEXTURE_BINDING);
    let color_view = color.create_view(&Default::default());
    let depth_view = depth.create_view(&Default::default());
    haze.prepare(&queue, &depth_view, 1.0)?;
    let mut encoder = device.create_command_encoder(&Default::default());
    tables.encode_static_luts(&mut encoder, None);
    tables.encode_sky_irradiance(&mut encoder, None);
    for view in &views {
        view.encode(&mut encoder, None)?;
    }
    {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &color_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations::default(), // clear to black, store
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &depth_view,
                depth_ops: Some(wgpu::Operations::default()), // clear to 0 (reversed z's far)
                stencil_ops: None,
            }),
            ..Default::default()
        });
        for ((view, v), group) in hazed.iter().zip(&camera_groups) {
            pass.set_viewport(v.x, v.y, v.width, v.height, 0.0, 1.0);
            sky.draw_view(&mut pass, view)?;
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, group, &[]);
            pass.set_bind_group(1, stack.bind_group(), &[]);
            pass.set_bind_group(2, view.uniform_bind_group(), &[]);
            pass.set_bind_group(3, view.table_bind_group(), &[]);
            pass.set_vertex_buffer(0, vertex_buffer.slice(..));
            pass.set_index_buffer(index_buffer.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..indices.len() as u32, 0, 0..1);
        }
    }
    // atmos' haze over everything the depth buffer holds, each view in its viewport.
    haze.encode(&mut encoder, &color_view, &hazed)?;
    let row = 2 * W * 8; // Rgba16Float; 5120 bytes, a multiple of 256
    let readback = device.create_buffer(&wgpu::BufferDescriptor {
        label: None,
        size: u64::from(row * H),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        color.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &readback,
            layout: wgpu::TexelCopyBufferLayout {
                bytes_per_row: Some(row),
                ..Default::default()
            },
        },
        color.size(),
    );
    queue.submit([encoder.finish()]);
    readback.map_async(wgpu::MapMode::Read, .., |mapped| mapped.expect("maps"));
    device.poll(wgpu::PollType::wait_indefinitely())?;
    let bytes = readback.get_mapped_range(..)?.to_vec();
    // Tone map (exposure, 1 − e^−x, gamma 2.2) and write the PNG.
    let radiance: Vec<f32> = bytes
        .chunks_exact(2)
        .map(|b| half::f16::from_le_bytes([b[0], b[1]]).to_f32())
        .collect();
    let tone = |c: f32| ((1.0 - (-12.0 * c.max(0.0)).exp()).powf(1.0 / 2.2) * 255.0 + 0.5) as u8;
    let rgb = |t: &[f32]| [tone(t[0]), tone(t[1]), tone(t[2])];
    let pixels: Vec<u8> = radiance.chunks_exact(4).flat_map(rgb).collect();
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/skyscape-examples");
    std::fs::create_dir_all(&out)?;
    let path = out.join("split_screen.png");
    image::save_buffer(&path, &pixels, 2 * W, H, image::ExtendedColorType::Rgb8)?;
    // Checks it can fail: all finite, a blue sky atop each view, the two views different.
    let at = |x: u32, y: u32| &radiance[4 * (y * 2 * W + x) as usize..][..3];
    if radiance.iter().any(|v| !v.is_finite())
        || (0..2).any(|v| at(v * W + W / 2, 2)[2] <= at(v * W + W / 2, 2)[0])
        || at(W / 2, H / 2) == at(W + W / 2, H / 2)
    {
        return Err("the image fails its checks (NaN, no blue sky, or equal views)".into());
    }
    println!("wrote {}", path.display());
    Ok(())
}
