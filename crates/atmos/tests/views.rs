//! Views of one atmosphere on the GPU, each against the image the same camera gives
//! alone in its own target: two views recorded into one submit, a view in a viewport
//! offset into a wider target, and a jittered projection. The scene is a caller's own:
//! an Rgba16Float colour target, a reversed-z Depth32Float depth target, its own ground
//! and wall pipeline; atmos draws the sky (`SkyPass`) and the haze
//! (`AerialPerspectivePass`) over it.

use atmos::Atmosphere;
use atmos::frame::LocalFrame;
use atmos::gpu::{
    AerialPerspectivePass, AtmosphereLuts, AtmosphereTables, AtmosphereView, DepthConvention,
    SkyPass, SkyPassDescriptor,
};
use atmos::lut::drop_in::{SkyPassParameters, depth_aerial_perspective, sky_pass_radiance_at};
use atmos::lut::{FrameLuts, LutSettings, StaticLuts};
use atmos::view::{ViewCamera, Viewport};
use glam::dcamera::rh::{proj::directx as proj, view as look};
use glam::{DMat4, DVec3};
use skyscape_harness::GpuContext;
use wgpu::util::DeviceExt as _;

const WIDTH: u32 = 96;
const HEIGHT: u32 = 64;
const COLOR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The caller's geometry: a 60 km ground square and a wall 3 km north, one colour.
const GROUND: &str = r"
@group(0) @binding(0) var<uniform> view_projection: mat4x4<f32>;
@vertex
fn vertex(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return view_projection * vec4<f32>(position, 1.0);
}
@fragment
fn fragment() -> @location(0) vec4<f32> {
    return vec4<f32>(0.05, 0.08, 0.03, 1.0);
}
";

fn mesh() -> Vec<[f32; 3]> {
    let quad = |c: [[f32; 3]; 4]| [c[0], c[1], c[2], c[0], c[2], c[3]];
    let s = 30_000.0;
    let mut vertices = quad([[-s, 0.0, s], [s, 0.0, s], [s, 0.0, -s], [-s, 0.0, -s]]).to_vec();
    vertices.extend(quad([
        [-1500.0, 0.0, -3000.0],
        [1500.0, 0.0, -3000.0],
        [1500.0, 900.0, -3000.0],
        [-1500.0, 900.0, -3000.0],
    ]));
    vertices
}

/// One camera: where it is, where it looks, its projection and its viewport.
#[derive(Clone, Copy)]
struct Camera {
    eye: DVec3,
    forward: DVec3,
    projection: DMat4,
    viewport: Viewport,
}

impl Camera {
    fn view(&self) -> DMat4 {
        look::look_to_mat4(self.eye, self.forward.normalize(), DVec3::Y)
    }

    fn atmos(&self, frame: &LocalFrame) -> ViewCamera {
        let sun = DVec3::new(0.4, 0.35, 0.6);
        ViewCamera::from_matrices(
            frame,
            self.view(),
            self.projection,
            self.viewport,
            sun,
            None,
        )
        .unwrap()
    }
}

fn perspective(fov: f64, width: f64, height: f64) -> DMat4 {
    proj::perspective_infinite_reverse(fov, width / height, 0.5)
}

/// Camera A: 300 m up, looking north at the wall. Camera B: 3 km up, looking
/// south-west and down, a wider field of view.
fn camera_a(viewport: Viewport) -> Camera {
    Camera {
        eye: DVec3::new(0.0, 300.0, 0.0),
        forward: DVec3::new(0.2, -0.05, -1.0),
        projection: perspective(1.0, f64::from(WIDTH), f64::from(HEIGHT)),
        viewport,
    }
}

fn camera_b(viewport: Viewport) -> Camera {
    Camera {
        eye: DVec3::new(2000.0, 3000.0, 1000.0),
        forward: DVec3::new(-0.5, -0.3, 1.0),
        projection: perspective(1.3, f64::from(WIDTH), f64::from(HEIGHT)),
        viewport,
    }
}

/// What the caller owns and atmos' passes, made once.
struct Renderer {
    frame: LocalFrame,
    tables: AtmosphereTables,
    sky: SkyPass,
    haze: AerialPerspectivePass,
    ground: wgpu::RenderPipeline,
    ground_layout: wgpu::BindGroupLayout,
    vertices: wgpu::Buffer,
    vertex_count: u32,
    convention: DepthConvention,
}

impl Renderer {
    fn new(gpu: &GpuContext) -> Self {
        Self::with_depth(gpu, DepthConvention::Reversed)
    }

    /// The caller's pipeline and atmos' haze for a depth buffer of `convention`.
    fn with_depth(gpu: &GpuContext, convention: DepthConvention) -> Self {
        let device = &gpu.device;
        let earth = Atmosphere::earth();
        let tables = AtmosphereTables::new(device, &earth, &LutSettings::small()).unwrap();
        let mut sky = SkyPass::new(
            device,
            &tables,
            &SkyPassDescriptor {
                depth_format: Some(DEPTH),
                ..SkyPassDescriptor::new(COLOR)
            },
        )
        .unwrap();
        sky.prepare(
            &gpu.queue,
            &SkyPassParameters::new(&earth, true, 1.0, 0.0).unwrap(),
        );
        let haze = AerialPerspectivePass::new(device, &tables, COLOR, convention).unwrap();
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("caller's ground"),
            source: wgpu::ShaderSource::Wgsl(GROUND.into()),
        });
        let ground_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: None,
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: None,
            bind_group_layouts: &[Some(&ground_layout)],
            immediate_size: 0,
        });
        let ground = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("caller's ground"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("vertex"),
                compilation_options: Default::default(),
                buffers: &[Some(wgpu::VertexBufferLayout {
                    array_stride: 12,
                    step_mode: wgpu::VertexStepMode::Vertex,
                    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
                })],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(true),
                depth_compare: Some(match convention {
                    DepthConvention::Reversed => wgpu::CompareFunction::Greater,
                    DepthConvention::Standard => wgpu::CompareFunction::Less,
                }),
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
        let mesh = mesh();
        let vertices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("caller's mesh"),
            contents: bytemuck::cast_slice(&mesh),
            usage: wgpu::BufferUsages::VERTEX,
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        tables.encode_static_luts(&mut encoder, None);
        gpu.queue.submit([encoder.finish()]);
        Self {
            frame: LocalFrame::new(&earth, 100.0).unwrap(),
            tables,
            sky,
            haze,
            ground,
            ground_layout,
            vertices,
            vertex_count: mesh.len() as u32,
            convention,
        }
    }

    /// Draws each (camera, view) into one target of `width × height` in one encoder
    /// and one submit — every view prepared first, then every view recorded — and
    /// reads the target back (RGB per pixel, row-major).
    fn draw(
        &mut self,
        gpu: &GpuContext,
        width: u32,
        views: &[(Camera, &AtmosphereView)],
    ) -> Vec<[f32; 3]> {
        self.draw_with_depth(gpu, width, views).0
    }

    /// [`Self::draw`], and the depth buffer it drew with.
    fn draw_with_depth(
        &mut self,
        gpu: &GpuContext,
        width: u32,
        views: &[(Camera, &AtmosphereView)],
    ) -> (Vec<[f32; 3]>, Vec<f32>) {
        let device = &gpu.device;
        let target = |format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: None,
                size: wgpu::Extent3d {
                    width,
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
        let attachment = wgpu::TextureUsages::RENDER_ATTACHMENT;
        let color = target(COLOR, attachment | wgpu::TextureUsages::COPY_SRC);
        let depth = target(
            DEPTH,
            attachment | wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_SRC,
        );
        let color_view = color.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        self.haze.prepare(&gpu.queue, &depth_view, 1.0).unwrap();
        let ground_groups: Vec<wgpu::BindGroup> = views
            .iter()
            .map(|(camera, view)| {
                view.prepare(&gpu.queue, &camera.atmos(&self.frame));
                let view_projection = (camera.projection * camera.view()).as_mat4();
                let buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: None,
                    contents: bytemuck::bytes_of(&view_projection.to_cols_array()),
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: None,
                    layout: &self.ground_layout,
                    entries: &[wgpu::BindGroupEntry {
                        binding: 0,
                        resource: buffer.as_entire_binding(),
                    }],
                })
            })
            .collect();
        let mut encoder = device.create_command_encoder(&Default::default());
        for (_, view) in views {
            view.encode(&mut encoder, None).unwrap();
        }
        let set_viewport = |pass: &mut wgpu::RenderPass<'_>, v: Viewport| {
            pass.set_viewport(v.x, v.y, v.width, v.height, 0.0, 1.0);
        };
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("caller's scene"),
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
                        load: wgpu::LoadOp::Clear(f64::from(self.convention.sky_depth()) as f32),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            for ((camera, view), ground) in views.iter().zip(&ground_groups) {
                set_viewport(&mut pass, camera.viewport);
                self.sky.draw_view(&mut pass, view).unwrap();
                pass.set_pipeline(&self.ground);
                pass.set_bind_group(0, ground, &[]);
                pass.set_vertex_buffer(0, self.vertices.slice(..));
                pass.draw(0..self.vertex_count, 0..1);
            }
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("atmos haze"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &color_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            for (camera, view) in views {
                set_viewport(&mut pass, camera.viewport);
                self.haze.draw(&mut pass, view).unwrap();
            }
        }
        gpu.queue.submit([encoder.finish()]);
        let bytes = skyscape_harness::read_texture(gpu, "colour", &color).unwrap();
        let color = bytes
            .chunks_exact(8)
            .map(|texel| {
                std::array::from_fn(|c| {
                    half_to_f32(u16::from_le_bytes([texel[2 * c], texel[2 * c + 1]]))
                })
            })
            .collect();
        let bytes = skyscape_harness::read_texture(gpu, "depth", &depth).unwrap();
        (color, bytemuck::pod_collect_to_vec(&bytes))
    }
}

/// IEEE 754 binary16 to f32.
fn half_to_f32(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let exponent = i32::from((bits >> 10) & 0x1f);
    let mantissa = f32::from(bits & 0x3ff);
    match exponent {
        0 => sign * mantissa * 2f32.powi(-24),
        31 => f32::NAN,
        e => sign * (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

/// The pixels `[x0, x0 + w) × [y0, y0 + h)` of a row-major image `width` wide.
fn crop(image: &[[f32; 3]], width: u32, x0: u32, y0: u32, w: u32, h: u32) -> Vec<[f32; 3]> {
    (y0..y0 + h)
        .flat_map(|y| (x0..x0 + w).map(move |x| image[(y * width + x) as usize]))
        .collect()
}

/// Largest per-channel difference relative to the larger of the two values (floored
/// at 1e-3 of the image's brightest value, so dark pixels are compared absolutely).
fn max_relative_difference(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
    assert_eq!(a.len(), b.len());
    let peak = a.iter().flatten().fold(0.0f32, |m, v| m.max(v.abs()));
    a.iter()
        .zip(b)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c], q[c])))
        .map(|(x, y)| {
            assert!(x.is_finite() && y.is_finite(), "{x} {y}");
            (x - y).abs() / x.abs().max(y.abs()).max(1e-3 * peak)
        })
        .fold(0.0, f32::max)
}

fn full() -> Viewport {
    Viewport::full(WIDTH, HEIGHT)
}

/// Two views of one atmosphere prepared one after the other and recorded into one
/// encoder each get their own sky and haze. The control: one `AtmosphereLuts` (one
/// camera buffer) prepared for both gives A the image of B's camera, the failure the
/// per-view split removes.
#[test]
fn two_views_in_one_submit_each_match_their_single_view_image() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("two_views_in_one_submit") else {
        return;
    };
    let mut renderer = Renderer::new(gpu);
    let view_a = AtmosphereView::new(&renderer.tables);
    let view_b = AtmosphereView::new(&renderer.tables);
    let (a, b) = (camera_a(full()), camera_b(full()));
    let single_a = renderer.draw(gpu, WIDTH, &[(a, &view_a)]);
    let single_b = renderer.draw(gpu, WIDTH, &[(b, &view_b)]);
    let apart = max_relative_difference(&single_a, &single_b);
    assert!(
        apart > 0.3,
        "the two cameras must see different skies: {apart}"
    );

    // Split screen: A in the left half, B in the right half of one target, one submit.
    let left = Viewport { x: 0.0, ..full() };
    let right = Viewport {
        x: WIDTH as f32,
        ..full()
    };
    let both = renderer.draw(
        gpu,
        2 * WIDTH,
        &[(camera_a(left), &view_a), (camera_b(right), &view_b)],
    );
    let got_a = crop(&both, 2 * WIDTH, 0, 0, WIDTH, HEIGHT);
    let got_b = crop(&both, 2 * WIDTH, WIDTH, 0, WIDTH, HEIGHT);
    let error_a = max_relative_difference(&got_a, &single_a);
    let error_b = max_relative_difference(&got_b, &single_b);
    eprintln!("two views in one submit: max relative difference A {error_a:e}, B {error_b:e}");
    // The same uniforms and shaders as the single-view draws except the viewport's
    // offset in B's pixel-to-ray matrix (f32 rounding of the ray, ≈ 1e-7): the
    // target's half floats (2^-11 relative) absorb it but for a rounding step.
    assert!(
        error_a <= 2e-3 && error_b <= 2e-3,
        "A {error_a}, B {error_b}"
    );

    // Control: one camera buffer for both views (AtmosphereLuts), the old hazard.
    let luts =
        AtmosphereLuts::new(&gpu.device, &Atmosphere::earth(), &LutSettings::small()).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    luts.encode_static_luts(&mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    let shared = renderer.draw(
        gpu,
        2 * WIDTH,
        &[
            (camera_a(left), luts.view()),
            (camera_b(right), luts.view()),
        ],
    );
    let hazard = max_relative_difference(&crop(&shared, 2 * WIDTH, 0, 0, WIDTH, HEIGHT), &single_a);
    eprintln!("one camera buffer for both views: A's max relative difference {hazard:e}");
    assert!(
        hazard > 0.1,
        "the control must show the shared buffer's error: {hazard}"
    );
}

/// A camera drawn in the right half of a target twice as wide sees what it sees
/// alone in its own target.
#[test]
fn a_view_in_an_offset_viewport_matches_its_single_view_image() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("view_in_an_offset_viewport") else {
        return;
    };
    let mut renderer = Renderer::new(gpu);
    let view = AtmosphereView::new(&renderer.tables);
    let single = renderer.draw(gpu, WIDTH, &[(camera_a(full()), &view)]);
    let offset = Viewport {
        x: WIDTH as f32,
        ..full()
    };
    let wide = renderer.draw(gpu, 2 * WIDTH, &[(camera_a(offset), &view)]);
    let error = max_relative_difference(&crop(&wide, 2 * WIDTH, WIDTH, 0, WIDTH, HEIGHT), &single);
    eprintln!("viewport offset by {WIDTH} px: max relative difference {error:e}");
    // Only the f32 rounding of the viewport's offset in the pixel-to-ray matrix differs.
    assert!(error <= 2e-3, "{error}");
}

/// A projection jittered by whole pixels (as TAA jitters by fractions of one) draws
/// the single-view image shifted by the jitter.
#[test]
fn a_jittered_projection_matches_the_single_view_image_shifted() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("jittered_projection") else {
        return;
    };
    let mut renderer = Renderer::new(gpu);
    let view = AtmosphereView::new(&renderer.tables);
    let camera = camera_a(full());
    let single = renderer.draw(gpu, WIDTH, &[(camera, &view)]);
    let (jitter_x, jitter_y) = (4u32, 3u32);
    // Clip-space translation by (2 jx / W, −2 jy / H) × w: the image moves right by jx
    // and down by jy pixels.
    let jitter = DMat4::from_translation(DVec3::new(
        2.0 * f64::from(jitter_x) / f64::from(WIDTH),
        -2.0 * f64::from(jitter_y) / f64::from(HEIGHT),
        0.0,
    ));
    let jittered = Camera {
        projection: jitter * camera.projection,
        ..camera
    };
    let image = renderer.draw(gpu, WIDTH, &[(jittered, &view)]);
    let (w, h) = (WIDTH - jitter_x, HEIGHT - jitter_y);
    let error = max_relative_difference(
        &crop(&image, WIDTH, jitter_x, jitter_y, w, h),
        &crop(&single, WIDTH, 0, 0, w, h),
    );
    let unshifted = max_relative_difference(
        &crop(&image, WIDTH, 0, 0, w, h),
        &crop(&single, WIDTH, 0, 0, w, h),
    );
    eprintln!(
        "projection jittered by ({jitter_x}, {jitter_y}) px: max relative difference {error:e} \
         (not shifted back: {unshifted:e})"
    );
    // The sky and each pixel's ray are exact for the jittered projection; the
    // aerial-perspective volume is laid over the covering frustum, which moves with
    // the jitter, so a hazed point is interpolated between other froxels: the
    // difference is the volume's trilinear interpolation error over a shift of a
    // fraction of a froxel (a 32-froxel-wide volume over 96 pixels: 4 px = 1.3 froxels).
    assert!(error <= 1e-2, "{error}");
    // The comparison sees a wrong shift: the same images compared without it differ.
    assert!(unshifted > 10.0 * error, "{unshifted}");
}

/// The sky pass and the depth-buffer aerial perspective against their CPU twins on
/// every pixel of a view: the sky where the depth buffer is empty, the caller's surface
/// colour through the transmittance plus the in-scatter elsewhere.
#[test]
fn the_sky_and_the_depth_haze_match_their_cpu_twins() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("sky_and_depth_haze_twins") else {
        return;
    };
    let mut renderer = Renderer::new(gpu);
    let view = AtmosphereView::new(&renderer.tables);
    let camera = camera_a(full());
    let (image, depth) = renderer.draw_with_depth(gpu, WIDTH, &[(camera, &view)]);
    let earth = Atmosphere::earth();
    let luts = StaticLuts::bake(&earth, &LutSettings::small()).unwrap();
    let view_camera = camera.atmos(&renderer.frame);
    let frame = FrameLuts::bake(&luts, &view_camera.camera);
    let parameters = SkyPassParameters::new(&earth, true, 1.0, 0.0).unwrap();
    // The caller's surface colour as the Rgba16Float target holds it.
    let surface = [0.05f32, 0.08, 0.03].map(|v| half_to_f32(f32_to_half(v)));
    let mut expected = Vec::new();
    let mut hazed = 0;
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let position = [x as f32 + 0.5, y as f32 + 0.5];
            let d = depth[(y * WIDTH + x) as usize];
            expected.push(if d == DepthConvention::Reversed.sky_depth() {
                sky_pass_radiance_at(&luts, &frame, &view_camera.view, position, &parameters)
            } else {
                hazed += 1;
                let segment =
                    depth_aerial_perspective(&luts, &frame, &view_camera.view, position, d);
                std::array::from_fn(|c| surface[c] * segment.transmittance[c] + segment.radiance[c])
            });
        }
    }
    let split = |sky: bool| {
        let pick = |image: &[[f32; 3]]| -> Vec<[f32; 3]> {
            image
                .iter()
                .zip(&depth)
                .filter(|&(_, &d)| (d == DepthConvention::Reversed.sky_depth()) == sky)
                .map(|(p, _)| *p)
                .collect()
        };
        max_relative_difference(&pick(&image), &pick(&expected))
    };
    let (sky_error, haze_error) = (split(true), split(false));
    eprintln!(
        "GPU against the CPU twins: sky {sky_error:e}, depth haze ({hazed} of {} pixels) \
         {haze_error:e} max relative difference",
        WIDTH * HEIGHT
    );
    assert!(hazed > (WIDTH * HEIGHT / 4) as usize && hazed < (WIDTH * HEIGHT) as usize);
    // The tables' GPU-vs-CPU drift (5e-4 relative: the sky-view and
    // aerial-perspective bakes' parity budget) and the Rgba16Float target's rounding
    // (2^-11 relative): once for the sky; for the haze three times (the surface, its
    // product with the transmittance, the sum with the in-scatter).
    assert!(sky_error <= 1.5e-3, "{sky_error}");
    assert!(haze_error <= 3e-3, "{haze_error}");
}

/// f32 to IEEE 754 binary16, rounding to nearest (normal range only: the test's
/// colours).
fn f32_to_half(value: f32) -> u16 {
    let bits = value.to_bits();
    let sign = ((bits >> 16) & 0x8000) as u16;
    let exponent = ((bits >> 23) & 0xff) as i32 - 127 + 15;
    let mantissa = bits & 0x7f_ffff;
    assert!(
        (1..31).contains(&exponent),
        "{value} is outside the normal half range"
    );
    let half = (exponent as u32) << 10 | (mantissa >> 13);
    let round = (mantissa >> 12) & 1 != 0 && ((mantissa & 0x1fff) != 0x1000 || half & 1 != 0);
    sign | (half + u32::from(round)) as u16
}

/// A standard depth buffer (near 0, far 1) with its projection and
/// `DepthConvention::Standard` hazes the scene as the reversed-z one does.
#[test]
fn a_standard_depth_buffer_gives_the_reversed_z_image() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("standard_depth_buffer") else {
        return;
    };
    let mut reversed = Renderer::new(gpu);
    let view = AtmosphereView::new(&reversed.tables);
    let camera = camera_a(full());
    let expected = reversed.draw(gpu, WIDTH, &[(camera, &view)]);
    let mut standard = Renderer::with_depth(gpu, DepthConvention::Standard);
    let view = AtmosphereView::new(&standard.tables);
    let projection = proj::perspective(1.0, f64::from(WIDTH) / f64::from(HEIGHT), 0.5, 1e5);
    let image = standard.draw(
        gpu,
        WIDTH,
        &[(
            Camera {
                projection,
                ..camera
            },
            &view,
        )],
    );
    let error = max_relative_difference(&image, &expected);
    eprintln!("standard against reversed depth: max relative difference {error:e}");
    // Depth32Float near 1 resolves 2^-24: a standard buffer's distance at 30 km (near
    // plane 0.5 m) is good to 2^-24 · 30 km / 0.5 m ≈ 4e-3 relative, which moves the
    // haze far less than the half-float target rounds.
    assert!(error <= 2e-3, "{error}");
}
