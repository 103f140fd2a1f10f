//! The sky pass on the GPU, bring-your-own-device: the caller owns the device, the
//! queue and the command encoder; this type never creates a device or submits.
//!
//! ```no_run
//! # fn demo(device: &wgpu::Device, queue: &wgpu::Queue) -> Result<(), render::RenderError> {
//! let mut sky = render::gpu::SkyRenderer::new(device)?;
//! sky.prepare(device, queue, &render::SkyScene::default())?; // per frame: validate + upload
//! let mut encoder = device.create_command_encoder(&Default::default());
//! sky.encode(&mut encoder)?;                                  // record the dispatch
//! queue.submit([encoder.finish()]);                           // your submit
//! // sky.pixel_buffer(): RGBA8 pixels, one u32 each, COPY_SRC.
//! # Ok(()) }
//! ```

use crate::error::RenderError;

pub mod present;
use crate::sky::{SkyScene, SkyUniforms};
pub use present::Presenter;

/// Compute pass writing the tone-mapped, dithered sky into a storage buffer.
#[derive(Debug)]
pub struct SkyRenderer {
    pipeline: wgpu::ComputePipeline,
    bind_group_layout: wgpu::BindGroupLayout,
    uniform_buffer: wgpu::Buffer,
    target: Option<Target>,
}

#[derive(Debug)]
struct Target {
    width: u32,
    height: u32,
    pixels: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
}

/// The composed WGSL of the sky pass (entry point `sky_main`).
pub fn sky_shader_source() -> Result<String, RenderError> {
    let composer = crate::composer();
    Ok(composer.compose_module("render::sky_closed_form")?)
}

impl SkyRenderer {
    /// Compiles the pass on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        let source = sky_shader_source()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("skyscape sky_closed_form"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let bind_group_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("skyscape sky"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(
                            std::mem::size_of::<SkyUniforms>() as u64
                        ),
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(4),
                    },
                    count: None,
                },
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("skyscape sky"),
            bind_group_layouts: &[Some(&bind_group_layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("skyscape sky"),
            layout: Some(&layout),
            module: &module,
            entry_point: Some("sky_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let uniform_buffer = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("skyscape sky uniforms"),
            size: std::mem::size_of::<SkyUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Self {
            pipeline,
            bind_group_layout,
            uniform_buffer,
            target: None,
        })
    }

    /// Validates the scene, uploads its constants and (re)allocates the pixel
    /// buffer when the size changed. Call once per frame before [`Self::encode`].
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &SkyScene,
    ) -> Result<(), RenderError> {
        let uniforms = SkyUniforms::from_scene(scene)?;
        queue.write_buffer(&self.uniform_buffer, 0, bytemuck::bytes_of(&uniforms));
        let resized = self
            .target
            .as_ref()
            .is_none_or(|t| (t.width, t.height) != (scene.width, scene.height));
        if resized {
            let pixels = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("skyscape sky pixels"),
                size: u64::from(scene.width) * u64::from(scene.height) * 4,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("skyscape sky"),
                layout: &self.bind_group_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: self.uniform_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: pixels.as_entire_binding(),
                    },
                ],
            });
            self.target = Some(Target {
                width: scene.width,
                height: scene.height,
                pixels,
                bind_group,
            });
        }
        Ok(())
    }

    /// Records the pass into the caller's encoder.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), RenderError> {
        let target = self.target.as_ref().ok_or(RenderError::NotPrepared)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("skyscape sky"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &target.bind_group, &[]);
        pass.dispatch_workgroups(target.width.div_ceil(8), target.height.div_ceil(8), 1);
        Ok(())
    }

    /// The RGBA8 pixels (one `u32` each, row-major, R in the low byte), once prepared.
    pub fn pixel_buffer(&self) -> Option<&wgpu::Buffer> {
        self.target.as_ref().map(|t| &t.pixels)
    }
}
