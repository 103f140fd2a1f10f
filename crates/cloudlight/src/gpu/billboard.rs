//! [`BillboardPass`]: Dobashi et al. 2000's billboards drawn into the caller's colour target
//! (`shaders/cloudlight/billboard_pass.wgsl`); bring your own device.
//!
//! [`BillboardPass::new`] builds the pipeline for a colour format ([`billboard_pipeline`]:
//! blending "over" on premultiplied colour, `One`, `OneMinusSrcAlpha`);
//! [`BillboardPass::prepare`] uploads the particles (already sorted back to front by
//! [`billboards`](crate::billboard::billboards)) as an instance buffer and the camera as a
//! uniform, and creates the bind group; [`BillboardPass::encode`] only records one render
//! pass that loads the target and draws the instances in order. The splat is evaluated
//! analytically in the fragment shader (`shaders/cloudlight/billboard_quad.wgsl`, which a
//! caller's own pass can import with [`instance_layout`], [`uniform_layout`],
//! [`billboard_pipeline`], [`begin_billboard_pass`] and [`draw_billboards`], as `render`'s
//! billboard clouds do).
//! The CPU twin is [`rasterise::<f32>`](crate::billboard::rasterise).

use crate::billboard::{Billboard, Camera, Opacity, ScreenFrame, SizeRule};

/// Errors of [`BillboardPass`], naming the field and value.
#[derive(Debug, thiserror::Error)]
pub enum BillboardPassError {
    /// Composing the WGSL failed (a packaging bug).
    #[error(transparent)]
    Compose(#[from] skyscape_wgsl::ComposeError),
    /// The instance buffer is larger than the device allows.
    #[error(
        "{billboards} billboards need {bytes} bytes of instances; the device's max_buffer_size is {limit}"
    )]
    TooManyBillboards {
        /// Billboards given.
        billboards: usize,
        /// Bytes needed.
        bytes: u64,
        /// `max_buffer_size`.
        limit: u64,
    },
    /// The target is not the camera's image size.
    #[error("target is {target:?} pixels but the camera's image is {camera:?}")]
    TargetSize {
        /// The target's width and height.
        target: [u32; 2],
        /// The camera's.
        camera: [u32; 2],
    },
    /// `encode` was called before `prepare`.
    #[error("encode before prepare: nothing to draw")]
    EncodeBeforePrepare,
}

/// Bytes of one instance: relative position (3 × f32), density, colour (3 × f32), the
/// splat's weight ([`Billboard::weight`]).
pub const INSTANCE_BYTES: u64 = 32;
const FRAME_BYTES: u64 = 64;

/// The composed WGSL of the pass (entry points `billboard_vertex`, `billboard_fragment`).
pub fn compose_billboard_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer.add_modules(crate::WGSL_MODULES)?;
    composer.compose_module("cloudlight::billboard_pass")
}

/// The uniform bytes of `frame` (the WGSL `BillboardFrame`).
pub fn frame_bytes(frame: &ScreenFrame<f32>) -> [u8; FRAME_BYTES as usize] {
    let mut words = [0u32; 16];
    let bits = |v: [f32; 3], w: f32| [v[0].to_bits(), v[1].to_bits(), v[2].to_bits(), w.to_bits()];
    words[0..4].copy_from_slice(&bits(frame.right, frame.focal));
    words[4..8].copy_from_slice(&bits(frame.up, frame.half_width));
    words[8..12].copy_from_slice(&bits(frame.forward, frame.half_height));
    words[12] = frame.size_mode;
    words[13] = frame.size_scale.to_bits();
    words[14] = frame.opacity_mode;
    bytemuck::cast(words)
}

/// The instance bytes of `billboards`, in their order (each value rounded to f32 once,
/// as [`rasterise::<f32>`](crate::billboard::rasterise) rounds it).
pub fn instance_bytes(billboards: &[Billboard]) -> Vec<u8> {
    let mut floats = Vec::with_capacity(billboards.len() * 8);
    for b in billboards {
        floats.extend(b.relative.map(|v| v as f32));
        floats.push(b.density as f32);
        floats.extend(b.colour.map(|v| v as f32));
        floats.push(b.weight as f32);
    }
    bytemuck::cast_slice(&floats).to_vec()
}

/// The instance attributes: `@location(0)` relative position and density,
/// `@location(1)` colour and the splat's weight (see [`instance_bytes`]).
const INSTANCE_ATTRIBUTES: [wgpu::VertexAttribute; 2] =
    wgpu::vertex_attr_array![0 => Float32x4, 1 => Float32x4];

/// The instance buffer's layout (one instance per billboard, [`INSTANCE_BYTES`] each, as
/// [`instance_bytes`] writes them): what a vertex stage built on
/// `cloudlight::billboard_quad` reads.
pub fn instance_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: INSTANCE_BYTES,
        step_mode: wgpu::VertexStepMode::Instance,
        attributes: &INSTANCE_ATTRIBUTES,
    }
}

/// The bind group layout of a billboard pass's uniform: one buffer at binding 0, read by
/// the vertex stage, of at least `bytes` (the frame's 64, or more for a caller's uniform
/// that begins with the WGSL `BillboardFrame`).
pub fn uniform_layout(device: &wgpu::Device, label: &str, bytes: u64) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &[wgpu::BindGroupLayoutEntry {
            binding: 0,
            visibility: wgpu::ShaderStages::VERTEX,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(bytes),
            },
            count: None,
        }],
    })
}

/// What [`billboard_pipeline`] builds a pipeline from: a module whose entry points draw
/// `cloudlight::billboard_quad`'s quads (this pass's, or a caller's that adds its own
/// bindings and depth).
#[derive(Debug)]
pub struct BillboardPipelineDescriptor<'a> {
    /// Debug label.
    pub label: &'a str,
    /// The pipeline layout (the caller's bind groups).
    pub layout: &'a wgpu::PipelineLayout,
    /// The composed shader module.
    pub module: &'a wgpu::ShaderModule,
    /// Its vertex entry point (reads [`instance_layout`]).
    pub vertex_entry: &'a str,
    /// Its fragment entry point (premultiplied colour).
    pub fragment_entry: &'a str,
    /// The colour target's format (blendable).
    pub target: wgpu::TextureFormat,
    /// The depth attachment's state, if the pass has one.
    pub depth_stencil: Option<wgpu::DepthStencilState>,
}

/// A render pipeline drawing instanced billboard quads (six vertices an instance,
/// [`instance_layout`]) blended "over" premultiplied colour (`One`,
/// `OneMinusSrcAlpha`) into `desc.target`.
pub fn billboard_pipeline(
    device: &wgpu::Device,
    desc: &BillboardPipelineDescriptor<'_>,
) -> wgpu::RenderPipeline {
    let over = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
        operation: wgpu::BlendOperation::Add,
    };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(desc.label),
        layout: Some(desc.layout),
        vertex: wgpu::VertexState {
            module: desc.module,
            entry_point: Some(desc.vertex_entry),
            compilation_options: Default::default(),
            buffers: &[Some(instance_layout())],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: desc.depth_stencil.clone(),
        multisample: wgpu::MultisampleState::default(),
        fragment: Some(wgpu::FragmentState {
            module: desc.module,
            entry_point: Some(desc.fragment_entry),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format: desc.target,
                blend: Some(wgpu::BlendState {
                    color: over,
                    alpha: over,
                }),
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Begins a render pass labelled `label` that loads and stores `target` (billboards
/// draw over what is there), with `depth` as its depth attachment if given.
pub fn begin_billboard_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    depth: Option<wgpu::RenderPassDepthStencilAttachment<'_>>,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
) -> wgpu::RenderPass<'e> {
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: depth,
        timestamp_writes,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}

/// Records the draw of `count` billboards from `instances` (laid out as
/// [`instance_layout`]) with `pipeline`, whose bind groups the caller has set.
pub fn draw_billboards(
    pass: &mut wgpu::RenderPass<'_>,
    pipeline: &wgpu::RenderPipeline,
    instances: &wgpu::Buffer,
    count: u32,
) {
    pass.set_pipeline(pipeline);
    pass.set_vertex_buffer(0, instances.slice(..));
    pass.draw(0..6, 0..count);
}

#[derive(Debug)]
struct Prepared {
    bind_group: wgpu::BindGroup,
    instances: Option<wgpu::Buffer>,
    count: u32,
    size: [u32; 2],
    _frame: wgpu::Buffer,
}

/// Dobashi et al. 2000's billboards on a GPU (see the module documentation).
#[derive(Debug)]
pub struct BillboardPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

impl BillboardPass {
    /// Builds the pipeline on `device` for colour targets of `format` (a blendable
    /// format, e.g. `Rgba16Float`).
    pub fn new(
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
    ) -> Result<Self, BillboardPassError> {
        let source = compose_billboard_shader()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cloudlight::billboard_pass"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = uniform_layout(device, "cloudlight billboards", FRAME_BYTES);
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cloudlight billboards"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = billboard_pipeline(
            device,
            &BillboardPipelineDescriptor {
                label: "cloudlight billboards",
                layout: &pipeline_layout,
                module: &module,
                vertex_entry: "billboard_vertex",
                fragment_entry: "billboard_fragment",
                target: format,
                depth_stencil: None,
            },
        );
        Ok(Self {
            pipeline,
            layout,
            prepared: None,
        })
    }

    /// Uploads `billboards` (drawn in their order: back to front from
    /// [`billboards`](crate::billboard::billboards)) and `camera` with `size` and
    /// `opacity` (the settings the billboards were made with), and creates
    /// the bind group [`BillboardPass::encode`] records with. Takes effect at the next
    /// submit.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        billboards: &[Billboard],
        camera: &Camera,
        size: SizeRule,
        opacity: Opacity,
    ) -> Result<(), BillboardPassError> {
        let bytes = billboards.len() as u64 * INSTANCE_BYTES;
        let limit = device.limits().max_buffer_size;
        let count = u32::try_from(billboards.len())
            .ok()
            .filter(|_| bytes <= limit);
        let Some(count) = count else {
            return Err(BillboardPassError::TooManyBillboards {
                billboards: billboards.len(),
                bytes,
                limit,
            });
        };
        let frame = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight billboard frame"),
            size: FRAME_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(
            &frame,
            0,
            &frame_bytes(&ScreenFrame::<f32>::new(camera, size, opacity)),
        );
        let instances = (count > 0).then(|| {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("cloudlight billboard instances"),
                size: bytes,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            queue.write_buffer(&buffer, 0, &instance_bytes(billboards));
            buffer
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cloudlight billboards"),
            layout: &self.layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: frame.as_entire_binding(),
            }],
        });
        self.prepared = Some(Prepared {
            bind_group,
            instances,
            count,
            size: [camera.width(), camera.height()],
            _frame: frame,
        });
        Ok(())
    }

    /// Records one render pass drawing the prepared billboards over `target` (loaded, not
    /// cleared; its texture must have the camera's image size).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
    ) -> Result<(), BillboardPassError> {
        self.encode_timed(encoder, target, None)
    }

    /// [`BillboardPass::encode`] with timestamp writes on its render pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), BillboardPassError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(BillboardPassError::EncodeBeforePrepare)?;
        let target_size = [target.texture().width(), target.texture().height()];
        if target_size != prepared.size {
            return Err(BillboardPassError::TargetSize {
                target: target_size,
                camera: prepared.size,
            });
        }
        let mut pass = begin_billboard_pass(
            encoder,
            "cloudlight billboards",
            target,
            None,
            timestamp_writes,
        );
        if let Some(instances) = &prepared.instances {
            pass.set_bind_group(0, &prepared.bind_group, &[]);
            draw_billboards(&mut pass, &self.pipeline, instances, prepared.count);
        }
        Ok(())
    }

    /// Billboards prepared (0 before `prepare`).
    pub fn count(&self) -> u32 {
        self.prepared.as_ref().map_or(0, |p| p.count)
    }
}
