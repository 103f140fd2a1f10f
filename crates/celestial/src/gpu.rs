//! The sky objects on the GPU, bring-your-own-device: [`SkyObjectsPass`] draws the sun,
//! the moon, planets and stars of a [`SkyObjectsFrame`] into the caller's colour target
//! (added to what is there — the sky — as radiance; depth writes off, an optional depth
//! test against the caller's depth buffer so terrain hides them). The pass never creates
//! a device or submits.
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue, target: &wgpu::TextureView,
//! #         frame: &celestial::objects::SkyObjectsFrame) -> celestial::Result<()> {
//! use celestial::gpu::{SkyObjectsPass, SkyObjectsSettings};
//! let mut pass = SkyObjectsPass::new(device, &SkyObjectsSettings::new(wgpu::TextureFormat::Rgba16Float))?;
//! pass.prepare(queue, frame)?; // per frame: validate + upload
//! let mut encoder = device.create_command_encoder(&Default::default());
//! pass.encode(&mut encoder, target, None, None)?; // record the draws
//! queue.submit([encoder.finish()]);                // your submit
//! # Ok(()) }
//! ```
//!
//! The pixel-for-pixel CPU twin is [`crate::objects::render_sky_objects_cpu`].

mod sky_dome;

pub use sky_dome::{SkyDomeRenderer, sky_dome_shader_source};

use crate::draw::{DiscObject, PointSource};
use crate::error::{CelestialError, Result};
use crate::objects::{SkyObjectsFrame, SkyObjectsUniforms};

/// Why the pass cannot run.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum GpuError {
    /// The colour format cannot be blended (radiance is added to the target).
    #[error("colour_format = {format:?} is not blendable on this device (use e.g. Rgba16Float)")]
    NotBlendable {
        /// The format asked for.
        format: wgpu::TextureFormat,
    },
    /// More point sources than the pass was created for.
    #[error("points = {count} exceeds max_points = {capacity} given to SkyObjectsPass::new")]
    TooManyPoints {
        /// Points in the frame.
        count: usize,
        /// The capacity.
        capacity: u32,
    },
    /// A zero capacity or one above the device's storage binding limit.
    #[error("max_points = {value} must be in 1..={limit} on this device")]
    Capacity {
        /// The capacity asked for.
        value: u32,
        /// The largest this device binds.
        limit: u64,
    },
    /// `encode` before `prepare`.
    #[error("{pass}: encode called before prepare")]
    NotPrepared {
        /// The pass.
        pass: &'static str,
    },
    /// A depth view passed without depth settings, or settings without a view.
    #[error("depth: the pass was created {created} a depth test but encode got {given} view")]
    DepthMismatch {
        /// "with" or "without".
        created: &'static str,
        /// "a" or "no".
        given: &'static str,
    },
}

impl From<GpuError> for CelestialError {
    fn from(error: GpuError) -> Self {
        CelestialError::Gpu(error)
    }
}

/// A depth test against the caller's depth buffer (no writes).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DepthTest {
    /// The depth buffer's format.
    pub format: wgpu::TextureFormat,
    /// How the objects' depth (`SkyObjectsUniforms::far_depth`) compares with it:
    /// `LessEqual` with far = 1 for the usual convention, `GreaterEqual` with far = 0
    /// for reversed Z.
    pub compare: wgpu::CompareFunction,
}

/// How the pass is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SkyObjectsSettings {
    /// The colour target's format (blendable: radiance is added).
    pub colour_format: wgpu::TextureFormat,
    /// An optional depth test.
    pub depth: Option<DepthTest>,
    /// Most point sources per frame.
    pub max_points: u32,
}

impl SkyObjectsSettings {
    /// `colour_format`, no depth test, room for 16,384 points (the catalogue to the
    /// naked-eye limit has ~8,500 stars).
    pub fn new(colour_format: wgpu::TextureFormat) -> Self {
        Self {
            colour_format,
            depth: None,
            max_points: 16_384,
        }
    }
}

/// The composed WGSL of the pass (`celestial::sky_objects`).
pub fn sky_objects_shader_source() -> Result<String> {
    Ok(crate::composer().compose_module("celestial::sky_objects")?)
}

/// The render pass drawing a [`SkyObjectsFrame`].
#[derive(Debug)]
pub struct SkyObjectsPass {
    disc_pipeline: wgpu::RenderPipeline,
    point_pipeline: wgpu::RenderPipeline,
    uniforms: wgpu::Buffer,
    discs: wgpu::Buffer,
    points: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    settings: SkyObjectsSettings,
    prepared_points: Option<u32>,
}

impl SkyObjectsPass {
    /// Compiles the pipelines and creates the buffers on `device`.
    pub fn new(device: &wgpu::Device, settings: &SkyObjectsSettings) -> Result<Self> {
        let features = settings
            .colour_format
            .guaranteed_format_features(device.features());
        if !features
            .flags
            .contains(wgpu::TextureFormatFeatureFlags::BLENDABLE)
        {
            return Err(GpuError::NotBlendable {
                format: settings.colour_format,
            }
            .into());
        }
        let point_size = std::mem::size_of::<PointSource>() as u64;
        let limit = device.limits().max_storage_buffer_binding_size / point_size;
        if settings.max_points == 0 || u64::from(settings.max_points) > limit {
            return Err(GpuError::Capacity {
                value: settings.max_points,
                limit,
            }
            .into());
        }
        let source = sky_objects_shader_source()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("celestial sky_objects"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let storage = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("celestial sky_objects"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(std::mem::size_of::<
                            SkyObjectsUniforms,
                        >() as u64),
                    },
                    count: None,
                },
                storage(1),
                storage(2),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("celestial sky_objects"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let additive = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::Zero,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            },
        };
        let depth_stencil = settings.depth.map(|d| wgpu::DepthStencilState {
            format: d.format,
            depth_write_enabled: Some(false),
            depth_compare: Some(d.compare),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        });
        let pipeline = |vertex: &str, fragment: &str| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some("celestial sky_objects"),
                layout: Some(&pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &module,
                    entry_point: Some(vertex),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: depth_stencil.clone(),
                multisample: wgpu::MultisampleState::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &module,
                    entry_point: Some(fragment),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        format: settings.colour_format,
                        blend: Some(additive),
                        write_mask: wgpu::ColorWrites::ALL,
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let disc_pipeline = pipeline("disc_vertex", "disc_fragment");
        let point_pipeline = pipeline("point_vertex", "point_fragment");
        let buffer = |label, size: u64, usage| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: usage | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        let uniforms = buffer(
            "celestial sky_objects uniforms",
            std::mem::size_of::<SkyObjectsUniforms>() as u64,
            wgpu::BufferUsages::UNIFORM,
        );
        let discs = buffer(
            "celestial sky_objects discs",
            2 * std::mem::size_of::<DiscObject>() as u64,
            wgpu::BufferUsages::STORAGE,
        );
        let points = buffer(
            "celestial sky_objects points",
            u64::from(settings.max_points) * point_size,
            wgpu::BufferUsages::STORAGE,
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("celestial sky_objects"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniforms.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: discs.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: points.as_entire_binding(),
                },
            ],
        });
        Ok(Self {
            disc_pipeline,
            point_pipeline,
            uniforms,
            discs,
            points,
            bind_group,
            settings: *settings,
            prepared_points: None,
        })
    }

    /// Uploads `frame` (checked against the capacity).
    pub fn prepare(&mut self, queue: &wgpu::Queue, frame: &SkyObjectsFrame) -> Result<()> {
        if frame.points.len() > self.settings.max_points as usize {
            return Err(GpuError::TooManyPoints {
                count: frame.points.len(),
                capacity: self.settings.max_points,
            }
            .into());
        }
        queue.write_buffer(&self.uniforms, 0, bytemuck::bytes_of(&frame.uniforms));
        queue.write_buffer(&self.discs, 0, bytemuck::cast_slice(&frame.discs));
        if !frame.points.is_empty() {
            queue.write_buffer(&self.points, 0, bytemuck::cast_slice(&frame.points));
        }
        self.prepared_points = Some(frame.points.len() as u32);
        Ok(())
    }

    /// Records the draws into `encoder`: one render pass loading `target` (and testing
    /// against `depth` when the pass was built with a [`DepthTest`]).
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        depth: Option<&wgpu::TextureView>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<()> {
        let points = self.prepared_points.ok_or(GpuError::NotPrepared {
            pass: "SkyObjectsPass",
        })?;
        let depth_attachment = match (self.settings.depth, depth) {
            (Some(_), Some(view)) => Some(wgpu::RenderPassDepthStencilAttachment {
                view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            (None, None) => None,
            (Some(_), None) => {
                return Err(GpuError::DepthMismatch {
                    created: "with",
                    given: "no",
                }
                .into());
            }
            (None, Some(_)) => {
                return Err(GpuError::DepthMismatch {
                    created: "without",
                    given: "a",
                }
                .into());
            }
        };
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("celestial sky_objects"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: target,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: depth_attachment,
            timestamp_writes,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.set_pipeline(&self.disc_pipeline);
        pass.draw(0..6, 0..2);
        if points > 0 {
            pass.set_pipeline(&self.point_pipeline);
            pass.draw(0..6, 0..points);
        }
        Ok(())
    }
}
