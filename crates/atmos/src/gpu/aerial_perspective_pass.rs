//! Aerial perspective applied to a caller's colour target from its depth buffer: the
//! haze over everything an engine drew, without touching its shaders. Two full-screen
//! draws in the caller's render pass (multiply by the transmittance, then add the
//! in-scatter: no dual-source blending needed); each pixel's ray and distance come from
//! the view's matrices ([`crate::view::ViewCamera`]) and the depth value. CPU twin:
//! [`crate::lut::drop_in::depth_aerial_perspective`].
//!
//! The render pass it draws in has the colour target as its one colour attachment and
//! **no depth attachment** (the depth texture is read as a texture: it needs
//! `TEXTURE_BINDING` usage, one sample). The view matrix must be rigid and in metres
//! (the distance is measured in view space).

use crate::gpu::luts::{AtmosphereView, LutLayouts};
use crate::gpu::resources::{READ_STAGES, uniform_buffer};
use crate::view::Viewport;
use crate::{AtmosError, GpuError};

/// Which way round the caller's depth buffer runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthConvention {
    /// Near plane at depth 0, far plane (and cleared, empty pixels) at 1.
    Standard,
    /// Reversed z: near plane at 1, far plane (and empty pixels) at 0.
    Reversed,
}

impl DepthConvention {
    /// The depth of a pixel where nothing was drawn (the sky).
    pub fn sky_depth(self) -> f32 {
        match self {
            Self::Standard => 1.0,
            Self::Reversed => 0.0,
        }
    }
}

/// The pass's uniform (layout identical to WGSL `AerialPerspectivePassParameters`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
struct Parameters {
    sky_depth: f32,
    radiance_scale: f32,
    padding: [f32; 2],
}

/// The depth-buffer aerial-perspective pass.
#[derive(Debug)]
pub struct AerialPerspectivePass {
    device: wgpu::Device,
    transmittance: wgpu::RenderPipeline,
    inscatter: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    parameters: wgpu::Buffer,
    convention: DepthConvention,
    bind_group: Option<wgpu::BindGroup>,
}

impl AerialPerspectivePass {
    /// Creates the two pipelines for the LUT layouts of `luts` and a single-sample
    /// colour target of `color_format` (a float format: the pass adds radiance).
    pub fn new(
        device: &wgpu::Device,
        luts: &(impl AsRef<LutLayouts> + ?Sized),
        color_format: wgpu::TextureFormat,
        convention: DepthConvention,
    ) -> Result<Self, AtmosError> {
        let layouts = luts.as_ref();
        let source = crate::composer().compose_module("atmos::aerial_perspective_pass")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("atmos aerial-perspective pass"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos aerial-perspective pass"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: READ_STAGES,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("atmos aerial-perspective pass"),
            bind_group_layouts: &[
                Some(&layouts.uniforms),
                Some(&layouts.tables),
                Some(&layout),
            ],
            immediate_size: 0,
        });
        // Alpha is left as the target holds it.
        let keep_alpha = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let pipeline = |entry: &str, color: wgpu::BlendComponent| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some("aerial_perspective_pass_vertex"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: None,
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: color_format,
                        blend: Some(wgpu::BlendState {
                            color,
                            alpha: keep_alpha,
                        }),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let transmittance = pipeline(
            "aerial_perspective_pass_transmittance",
            wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::Src,
                operation: wgpu::BlendOperation::Add,
            },
        );
        let inscatter = pipeline(
            "aerial_perspective_pass_inscatter",
            wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        );
        Ok(Self {
            device: device.clone(),
            transmittance,
            inscatter,
            parameters: uniform_buffer(
                device,
                "atmos aerial-perspective pass parameters",
                std::mem::size_of::<Parameters>() as u64,
            ),
            layout,
            convention,
            bind_group: None,
        })
    }

    /// Writes the parameters (`radiance_scale`: finite, ≥ 0, as the sky pass's) and
    /// binds the caller's depth texture (`TEXTURE_BINDING`, single-sample, a depth
    /// format).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        depth: &wgpu::TextureView,
        radiance_scale: f32,
    ) -> Result<(), AtmosError> {
        if !(radiance_scale.is_finite() && radiance_scale >= 0.0) {
            return Err(AtmosError::InvalidSetting {
                setting: "aerial-perspective pass",
                field: "radiance_scale".to_owned(),
                value: f64::from(radiance_scale),
                reason: "must be finite and ≥ 0",
            });
        }
        let parameters = Parameters {
            sky_depth: self.convention.sky_depth(),
            radiance_scale,
            padding: [0.0; 2],
        };
        queue.write_buffer(&self.parameters, 0, bytemuck::bytes_of(&parameters));
        self.bind_group = Some(self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("atmos aerial-perspective pass"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.parameters.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(depth),
                },
            ],
        }));
        Ok(())
    }

    /// Records the two draws for `view` into the caller's render pass (sets this
    /// pass's pipelines and bind groups 0–2). Draws where the render pass's viewport
    /// and scissor let it: set them to the view's. The view's tables must have been
    /// baked for its camera by then.
    pub fn draw(
        &self,
        pass: &mut wgpu::RenderPass<'_>,
        view: &AtmosphereView,
    ) -> Result<(), AtmosError> {
        let bind_group = self.bind_group.as_ref().ok_or(GpuError::NotPrepared {
            pass: "AerialPerspectivePass",
        })?;
        pass.set_bind_group(0, view.uniform_bind_group(), &[]);
        pass.set_bind_group(1, view.table_bind_group(), &[]);
        pass.set_bind_group(2, bind_group, &[]);
        pass.set_pipeline(&self.transmittance);
        pass.draw(0..3, 0..1);
        pass.set_pipeline(&self.inscatter);
        pass.draw(0..3, 0..1);
        Ok(())
    }

    /// Records a render pass of its own over `color` (loaded and stored, no depth
    /// attachment) drawing each view in its viewport: the whole pass for a caller that
    /// does not draw the haze inside a pass of its own ([`Self::draw`]).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        color: &wgpu::TextureView,
        views: &[(&AtmosphereView, Viewport)],
    ) -> Result<(), AtmosError> {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("atmos aerial-perspective pass"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: color,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            ..Default::default()
        });
        for (view, v) in views {
            pass.set_viewport(v.x, v.y, v.width, v.height, 0.0, 1.0);
            self.draw(&mut pass, view)?;
        }
        Ok(())
    }
}
