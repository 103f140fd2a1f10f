//! Small constructors every atmos pass (and `render`'s present pass) shares: compute
//! bind-group layout entries for buffers, per-frame uniform buffers, and the one
//! binding layout of the per-pixel frame renderers (rungs 1 and 2).

use crate::frame::FrameCamera;
use crate::gpu::FrameOutput;
use crate::{AtmosError, GpuError};

/// A compute-stage buffer binding of type `ty` (uniform or storage), unsized.
pub fn compute_buffer_entry(
    binding: u32,
    ty: wgpu::BufferBindingType,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// A compute-stage storage-buffer binding.
pub fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    compute_buffer_entry(binding, wgpu::BufferBindingType::Storage { read_only })
}

/// A compute-stage uniform-buffer binding.
pub fn uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    compute_buffer_entry(binding, wgpu::BufferBindingType::Uniform)
}

/// A `UNIFORM | COPY_DST` buffer of `size` bytes, written by a pass's `prepare`.
pub fn uniform_buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// Bindings of a frame renderer's pass (group 0): the camera uniform (0), the model's
/// parameter uniform (1), the [`FrameOutput`] radiance and transmittance (2, 3), then
/// the renderer's own storage buffers (4, …).
#[derive(Debug)]
pub(crate) struct FramePassLayout {
    pub(crate) bind_group: wgpu::BindGroupLayout,
    pub(crate) pipeline: wgpu::PipelineLayout,
    label: &'static str,
}

impl FramePassLayout {
    pub(crate) fn new(device: &wgpu::Device, label: &'static str, own_storage: u32) -> Self {
        let storage = wgpu::BufferBindingType::Storage { read_only: false };
        let entries: Vec<_> = [
            compute_buffer_entry(0, wgpu::BufferBindingType::Uniform),
            compute_buffer_entry(1, wgpu::BufferBindingType::Uniform),
        ]
        .into_iter()
        .chain((2..4 + own_storage).map(|binding| compute_buffer_entry(binding, storage)))
        .collect();
        let bind_group = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &entries,
        });
        let pipeline = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some(label),
            bind_group_layouts: &[Some(&bind_group)],
            immediate_size: 0,
        });
        Self {
            bind_group,
            pipeline,
            label,
        }
    }

    /// The camera `prepare` uploaded, checked against `output`'s size, and the bind
    /// group of this frame's buffers.
    pub(crate) fn bind(
        &self,
        device: &wgpu::Device,
        prepared: Option<FrameCamera>,
        camera: &wgpu::Buffer,
        parameters: &wgpu::Buffer,
        output: &FrameOutput,
        own_storage: &[&wgpu::Buffer],
    ) -> Result<(FrameCamera, wgpu::BindGroup), AtmosError> {
        let prepared = prepared.ok_or(GpuError::NotPrepared { pass: self.label })?;
        output.check_camera(&prepared)?;
        let [radiance, transmittance] = output.bind_group_entries(2);
        let entries: Vec<_> = [
            wgpu::BindGroupEntry {
                binding: 0,
                resource: camera.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: parameters.as_entire_binding(),
            },
            radiance,
            transmittance,
        ]
        .into_iter()
        .chain(
            own_storage
                .iter()
                .zip(4..)
                .map(|(buffer, binding)| wgpu::BindGroupEntry {
                    binding,
                    resource: buffer.as_entire_binding(),
                }),
        )
        .collect();
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(self.label),
            layout: &self.bind_group,
            entries: &entries,
        });
        Ok((prepared, bind_group))
    }
}
