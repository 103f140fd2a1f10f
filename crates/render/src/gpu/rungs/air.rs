//! A rung's aerial perspective of the terrain per pixel: a compute pass over the frame
//! reading the depth, its result copied back into the HDR target.

use wgpu::util::DeviceExt as _;

use super::uniforms::RungAirUniform;
use crate::RenderError;
use crate::gpu::layout::{fragment_texture, fragment_uniform};
use crate::gpu::rung_kind::{compose_rung_entry, rung_parameters};
use crate::scene::prepare::PreparedScene;

impl AirPass {
    pub(super) fn new(
        device: &wgpu::Device,
        scene: &PreparedScene,
        hdr: wgpu::TextureFormat,
        constants: &[(&'static str, f64)],
    ) -> Result<Self, RenderError> {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render::rung_air"),
            source: wgpu::ShaderSource::Wgsl(
                compose_rung_entry(scene.rung, "render::rung_air")?.into(),
            ),
        });
        let compute = wgpu::ShaderStages::COMPUTE;
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render terrain air (rung)"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    visibility: compute,
                    ..fragment_uniform(0)
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: compute,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    visibility: compute,
                    ..fragment_texture(2)
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 3,
                    visibility: compute,
                    ty: wgpu::BindingType::StorageTexture {
                        access: wgpu::StorageTextureAccess::WriteOnly,
                        format: hdr,
                        view_dimension: wgpu::TextureViewDimension::D2,
                    },
                    count: None,
                },
            ],
        });
        let parameters_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render terrain air parameters (rung)"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    visibility: compute,
                    ..fragment_uniform(0)
                },
                wgpu::BindGroupLayoutEntry {
                    visibility: compute,
                    ..fragment_uniform(1)
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render terrain air (rung)"),
            bind_group_layouts: &[Some(&layout), Some(&parameters_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("render terrain air (rung)"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("rung_air"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants,
                ..Default::default()
            },
            cache: None,
        });
        // The rung's parameters for the sun's atmosphere and the added light's (the
        // sun's twice without one: the shader then reads only the first). The shader
        // adds one light's in-scatter to the sun's (`crate::gpu::frame::MAX_LIGHTS`).
        let sun = rung_parameters(scene.rung, &scene.atmosphere)?;
        let moon = match scene.other_lights.first() {
            Some(added) => rung_parameters(scene.rung, &added.atmosphere)?,
            None => sun.clone(),
        };
        let buffer = |label: &str, contents: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage: wgpu::BufferUsages::UNIFORM,
            })
        };
        let sun = buffer("render terrain air sun parameters", &sun);
        let moon = buffer("render terrain air moon parameters", &moon);
        let parameters = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render terrain air parameters (rung)"),
            layout: &parameters_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: sun.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: moon.as_entire_binding(),
                },
            ],
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render terrain air (rung)"),
            size: std::mem::size_of::<RungAirUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let scratch = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("render terrain air (rung) target"),
            size: wgpu::Extent3d {
                width: scene.camera.width,
                height: scene.camera.height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: hdr,
            usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        Ok(Self {
            pipeline,
            layout,
            uniform,
            parameters,
            scratch_view: scratch.create_view(&Default::default()),
            scratch,
            targets: None,
        })
    }

    /// Binds the scene's targets (once: the same every frame) and writes the frame's
    /// camera and lights.
    pub(super) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        hdr_view: &wgpu::TextureView,
        depth_view: &wgpu::TextureView,
    ) {
        if self.targets.is_none() {
            self.targets = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("render terrain air (rung)"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.uniform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::TextureView(depth_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(hdr_view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: wgpu::BindingResource::TextureView(&self.scratch_view),
                    },
                ],
            }));
        }
        let air = RungAirUniform {
            camera: scene.camera,
            moon_direction: scene
                .other_lights
                .first()
                .map_or([0.0; 3], |added| added.direction.as_vec3().to_array()),
            moon: u32::from(!scene.other_lights.is_empty()),
            near: scene.near.max(0.01) as f32,
            radiance_scale: scene.present.exposure,
            padding: [0.0; 2],
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&air));
    }
}

/// The terrain's aerial perspective: a compute pass reading the drawn surface and the
/// depth, writing `scratch`, copied back into the scene's HDR target.
#[derive(Debug)]
pub(super) struct AirPass {
    pub(super) pipeline: wgpu::ComputePipeline,
    pub(super) layout: wgpu::BindGroupLayout,
    pub(super) uniform: wgpu::Buffer,
    pub(super) parameters: wgpu::BindGroup,
    pub(super) scratch: wgpu::Texture,
    pub(super) scratch_view: wgpu::TextureView,
    pub(super) targets: Option<wgpu::BindGroup>,
}
