//! The present pass on the GPU: a frame of radiance from any atmos rung's renderer
//! ([`atmos::gpu::FrameOutput`]) to RGBA8 pixels. Bring your own device.

use atmos::frame::FrameCamera;
use atmos::gpu::FrameOutput;

use crate::RenderError;
use crate::present::PresentParameters;
use atmos::gpu::resources::{compute_buffer_entry as entry, float_texture_entry, uniform_buffer};

/// Compute pass turning a [`FrameOutput`] into packed RGBA8 pixels.
#[derive(Debug)]
pub struct Presenter {
    device: wgpu::Device,
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    camera: wgpu::Buffer,
    params: wgpu::Buffer,
    pixels: Option<(u32, u32, wgpu::Buffer)>,
    /// The camera and the frame's bind group, made by [`Self::prepare`].
    prepared: Option<(FrameCamera, wgpu::BindGroup)>,
}

impl Presenter {
    /// Compiles the pass on `device`; a pipeline the device rejects is a
    /// [`RenderError::Device`] (caught by device error scopes).
    pub fn new(device: &wgpu::Device) -> Result<Self, RenderError> {
        super::validation::scoped(device, "Presenter::new", || Self::new_unscoped(device))
    }

    fn new_unscoped(device: &wgpu::Device) -> Result<Self, RenderError> {
        let source = crate::composer().compose_module("render::present")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render present"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let texture = |binding| float_texture_entry(binding, wgpu::TextureViewDimension::D2);
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render present"),
            entries: &[
                entry(0, wgpu::BufferBindingType::Uniform),
                entry(1, wgpu::BufferBindingType::Uniform),
                texture(2),
                texture(3),
                entry(4, wgpu::BufferBindingType::Storage { read_only: false }),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render present"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("render present"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("present_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        Ok(Self {
            device: device.clone(),
            pipeline,
            layout,
            camera: uniform_buffer(
                device,
                "render present camera",
                std::mem::size_of::<FrameCamera>() as u64,
            ),
            params: uniform_buffer(
                device,
                "render present parameters",
                std::mem::size_of::<PresentParameters>() as u64,
            ),
            pixels: None,
            prepared: None,
        })
    }

    /// Uploads the frame's camera and display constants, (re)allocates the pixels and
    /// binds `frame` (checked against the camera's frame size) for [`Self::encode`].
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &FrameCamera,
        params: &PresentParameters,
        frame: &FrameOutput,
    ) -> Result<(), RenderError> {
        self.prepared = None;
        frame
            .check_camera(camera)
            .map_err(RenderError::Atmosphere)?;
        if self
            .pixels
            .as_ref()
            .is_none_or(|(w, h, _)| (*w, *h) != (camera.width, camera.height))
        {
            let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("render present pixels"),
                size: 4 * camera.pixel_count() as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            });
            self.pixels = Some((camera.width, camera.height, buffer));
        }
        let (_, _, pixels) = self.pixels.as_ref().expect("allocated above");
        let [radiance, transmittance] = frame.bind_group_entries(2);
        let bind_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render present"),
            layout: &self.layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: self.camera.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: self.params.as_entire_binding(),
                },
                radiance,
                transmittance,
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: pixels.as_entire_binding(),
                },
            ],
        });
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
        queue.write_buffer(&self.params, 0, bytemuck::bytes_of(params));
        self.prepared = Some((*camera, bind_group));
        Ok(())
    }

    /// Records the pass reading the prepared frame.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), RenderError> {
        let (camera, bind_group) = self.prepared.as_ref().ok_or(RenderError::NotPrepared)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("render present"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, bind_group, &[]);
        pass.dispatch_workgroups(camera.width.div_ceil(8), camera.height.div_ceil(8), 1);
        Ok(())
    }

    /// The RGBA8 pixels (one `u32` each, `COPY_SRC`), after [`Self::prepare`].
    pub fn pixel_buffer(&self) -> Option<&wgpu::Buffer> {
        self.pixels.as_ref().map(|(_, _, b)| b)
    }
}
