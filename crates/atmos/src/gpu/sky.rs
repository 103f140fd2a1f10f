//! The sky drawn into a caller's colour target: a render pipeline (one full-screen
//! triangle) that reads the precomputed rung's tables, for a render pass the caller
//! owns. Normally drawn first, with depth writes off (the sky hemisphere of Hoffman & Preetham 2002), then
//! the caller's geometry over it; or drawn last at the far plane with a `LessEqual`
//! depth test so covered pixels cost nothing. CPU twin:
//! [`crate::lut::drop_in::sky_pass_radiance`].
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue, target: &wgpu::TextureView) -> Result<(), atmos::AtmosError> {
//! use atmos::gpu::{AtmosphereLuts, sky::{SkyPass, SkyPassDescriptor}};
//! use atmos::lut::drop_in::SkyPassParameters;
//! let earth = atmos::Atmosphere::earth();
//! let luts = AtmosphereLuts::new(device, &earth, &Default::default())?;
//! let mut sky = SkyPass::new(device, &luts, &SkyPassDescriptor::new(wgpu::TextureFormat::Rgba16Float))?;
//! let camera = atmos::frame::FrameCamera::look_at(
//!     glam::DVec3::new(0.0, 0.0, 6_360_002.0), glam::DVec3::X, glam::DVec3::Z,
//!     1.2, 1280, 720, glam::DVec3::new(0.5, 0.0, 0.866), None)?;
//! luts.prepare(queue, &camera);
//! sky.prepare(queue, &SkyPassParameters::new(&earth, true, 1.0, 1.0)?);
//! let mut encoder = device.create_command_encoder(&Default::default());
//! luts.encode_static_luts(&mut encoder, None); // once per atmosphere
//! luts.encode_frame_luts(&mut encoder, None); // once per frame
//! {
//!     let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
//!         color_attachments: &[Some(wgpu::RenderPassColorAttachment {
//!             view: target,
//!             depth_slice: None,
//!             resolve_target: None,
//!             ops: wgpu::Operations { load: wgpu::LoadOp::Clear(wgpu::Color::BLACK), store: wgpu::StoreOp::Store },
//!         })],
//!         ..Default::default()
//!     });
//!     sky.draw(&mut pass, &luts)?;
//!     // … then your geometry, its shaders applying atmos::aerial_perspective.
//! }
//! queue.submit([encoder.finish()]);
//! # Ok(()) }
//! ```

use crate::gpu::luts::{AtmosphereLuts, AtmosphereView, LutLayouts};
use crate::gpu::resources::{READ_STAGES, uniform_buffer};
use crate::lut::drop_in::SkyPassParameters;
use crate::{AtmosError, GpuError};

/// How the sky pass's pipeline fits the caller's render pass.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyPassDescriptor {
    /// The colour attachment's format (a float format keeps the radiance: HDR).
    pub color_format: wgpu::TextureFormat,
    /// The depth attachment's format, if the render pass has one.
    pub depth_format: Option<wgpu::TextureFormat>,
    /// The depth test against the attachment (`Always` when drawn first; `LessEqual` at
    /// depth 1, or `GreaterEqual` at 0 with reverse z, when drawn after the geometry).
    /// Depth is never written.
    pub depth_compare: wgpu::CompareFunction,
    /// The render pass's sample count.
    pub sample_count: u32,
    /// How the sky meets what the target holds: `None` replaces it (the sky drawn
    /// first); additive blending adds a second light's sky (a moonlit sky over the
    /// sunlit one: radiance is linear in the source).
    pub blend: Option<wgpu::BlendState>,
}

impl SkyPassDescriptor {
    /// A pass with only a colour attachment of `color_format`, one sample.
    pub fn new(color_format: wgpu::TextureFormat) -> Self {
        Self {
            color_format,
            depth_format: None,
            depth_compare: wgpu::CompareFunction::Always,
            sample_count: 1,
            blend: None,
        }
    }
}

/// The sky as a full-screen draw in the caller's render pass.
#[derive(Debug)]
pub struct SkyPass {
    pipeline: wgpu::RenderPipeline,
    parameters: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    prepared: bool,
}

/// The composed WGSL of the sky pass.
pub fn sky_pass_source() -> Result<String, AtmosError> {
    Ok(crate::composer().compose_module("atmos::sky_pass")?)
}

impl SkyPass {
    /// Creates the pipeline for the LUT bind-group layouts (of an [`AtmosphereLuts`],
    /// an [`AtmosphereTables`](crate::gpu::AtmosphereTables) or [`LutLayouts`]) and the
    /// caller's attachments. One pass draws any number of views of those tables.
    pub fn new(
        device: &wgpu::Device,
        luts: &(impl AsRef<LutLayouts> + ?Sized),
        descriptor: &SkyPassDescriptor,
    ) -> Result<Self, AtmosError> {
        let layouts = luts.as_ref();
        if descriptor.sample_count == 0 {
            return Err(AtmosError::InvalidSetting {
                setting: "sky pass",
                field: "sample_count".to_owned(),
                value: 0.0,
                reason: "must be ≥ 1",
            });
        }
        let source = sky_pass_source()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("atmos sky pass"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let parameter_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos sky pass parameters"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: READ_STAGES,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("atmos sky pass"),
            bind_group_layouts: &[
                Some(&layouts.uniforms),
                Some(&layouts.tables),
                Some(&parameter_layout),
            ],
            immediate_size: 0,
        });
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("atmos sky pass"),
            layout: Some(&layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some("sky_pass_vertex"),
                compilation_options: Default::default(),
                buffers: &[],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: descriptor
                .depth_format
                .map(|format| wgpu::DepthStencilState {
                    format,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(descriptor.depth_compare),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
            multisample: wgpu::MultisampleState {
                count: descriptor.sample_count,
                ..Default::default()
            },
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some("sky_pass_fragment"),
                compilation_options: Default::default(),
                targets: &[Some(wgpu::ColorTargetState {
                    format: descriptor.color_format,
                    blend: descriptor.blend,
                    write_mask: wgpu::ColorWrites::ALL,
                })],
            }),
            multiview_mask: None,
            cache: None,
        });
        let parameters = uniform_buffer(
            device,
            "atmos sky pass parameters",
            std::mem::size_of::<SkyPassParameters>() as u64,
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("atmos sky pass parameters"),
            layout: &parameter_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: parameters.as_entire_binding(),
            }],
        });
        Ok(Self {
            pipeline,
            parameters,
            bind_group,
            prepared: false,
        })
    }

    /// Writes the pass's parameters (the sun's disc, the radiance scale, the depth),
    /// shared by every view it draws. The camera is the view's
    /// ([`AtmosphereView::prepare`], [`AtmosphereLuts::prepare`]).
    pub fn prepare(&mut self, queue: &wgpu::Queue, parameters: &SkyPassParameters) {
        queue.write_buffer(&self.parameters, 0, bytemuck::bytes_of(parameters));
        self.prepared = true;
    }

    /// Records the draw of `luts`' one view into the caller's render pass (see
    /// [`Self::draw_view`]).
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        luts: &AtmosphereLuts,
    ) -> Result<(), AtmosError> {
        self.draw_view(pass, luts.view())
    }

    /// Records the draw of `view` into the caller's render pass (sets this pass's
    /// pipeline and bind groups 0–2; set your own again afterwards). Each fragment
    /// takes its ray from its own target position through the view's matrices and
    /// viewport, so the sky is right wherever the view sits in the target; set the
    /// render pass's viewport (or scissor) to the view's to draw only there. The
    /// view's tables must have been baked for its camera by then.
    pub fn draw_view(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        view: &AtmosphereView,
    ) -> Result<(), AtmosError> {
        if !self.prepared {
            return Err(GpuError::NotPrepared { pass: "SkyPass" }.into());
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, view.uniform_bind_group(), &[]);
        pass.set_bind_group(1, view.table_bind_group(), &[]);
        pass.set_bind_group(2, &self.bind_group, &[]);
        pass.draw(0..3, 0..1);
        Ok(())
    }
}
