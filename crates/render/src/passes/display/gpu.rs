//! The display pass on the GPU: a compute pass from the HDR target to packed RGBA8
//! pixels in a storage buffer (`shaders/render/display.wgsl`).

use super::DisplayParameters;
use crate::RenderError;
use crate::gpu::frame::{GpuPass, GpuShared};
use crate::gpu::layout::uniform_entry;
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// The display pipeline and its output.
#[derive(Debug)]
pub(crate) struct DisplayPass {
    display_pipeline: wgpu::ComputePipeline,
    display_uniform: wgpu::Buffer,
    display_group: wgpu::BindGroup,
    /// The frame's RGBA8 pixels (one `u32` each, R in the low byte; `COPY_SRC`).
    pub(crate) pixels: wgpu::Buffer,
}

/// Builds the display pass over the frame's HDR target.
pub(crate) fn build(
    shared: &GpuShared,
    _scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    let device = &shared.device;
    let (width, height, hdr_view) = (shared.width, shared.height, &shared.hdr_view);
    let source = crate::composer().compose_module("render::display")?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("render display"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("render display"),
        entries: &[
            uniform_entry(0, wgpu::ShaderStages::COMPUTE),
            wgpu::BindGroupLayoutEntry {
                binding: 1,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: false },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
                count: None,
            },
            wgpu::BindGroupLayoutEntry {
                binding: 2,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only: false },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            },
        ],
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("render display"),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let display_pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some("render display"),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some("display_main"),
        compilation_options: Default::default(),
        cache: None,
    });
    let display_uniform = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("render display parameters"),
        size: std::mem::size_of::<DisplayParameters>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let pixels = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("render display pixels"),
        size: 4 * u64::from(width) * u64::from(height),
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let display_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("render display"),
        layout: &layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: display_uniform.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(hdr_view),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: pixels.as_entire_binding(),
            },
        ],
    });
    Ok(Box::new(DisplayPass {
        display_pipeline,
        display_uniform,
        display_group,
        pixels,
    }))
}

impl GpuPass for DisplayPass {
    fn prepare(
        &mut self,
        shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        queue.write_buffer(
            &self.display_uniform,
            0,
            bytemuck::bytes_of(&DisplayParameters {
                width: shared.width,
                height: shared.height,
                // The HDR target already holds radiance × exposure.
                exposure: 1.0,
                dither_seed: scene.present.dither_seed,
                display_transform: scene.present.display_transform,
                padding_a: 0,
                padding_b: 0,
                padding_c: 0,
            }),
        );
        Ok(())
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("render display"),
            timestamp_writes: times.and_then(|t| t.compute_writes("display")),
        });
        pass.set_pipeline(&self.display_pipeline);
        pass.set_bind_group(0, &self.display_group, &[]);
        pass.dispatch_workgroups(shared.width.div_ceil(8), shared.height.div_ceil(8), 1);
        Ok(())
    }
}
