//! Small constructors every atmos pass (and `render`'s passes) shares: bind-group layout
//! entries for buffers and textures, per-frame uniform buffers, and the one binding
//! layout of the per-pixel frame renderers (rungs 1 and 2).

use crate::frame::FrameCamera;
use crate::gpu::FrameOutput;
use crate::{AtmosError, GpuError};

/// The stages a table or uniform of atmos may be read from: compute bakes and a user's
/// render pipelines alike.
pub const READ_STAGES: wgpu::ShaderStages = wgpu::ShaderStages::COMPUTE
    .union(wgpu::ShaderStages::VERTEX)
    .union(wgpu::ShaderStages::FRAGMENT);

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

/// A uniform-buffer binding readable from [`READ_STAGES`].
pub fn shared_uniform_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        visibility: READ_STAGES,
        ..uniform_entry(binding)
    }
}

/// An unfilterable-float sampled texture of `dimension`, readable from
/// [`READ_STAGES`] (read with `textureLoad`).
pub fn float_texture_entry(
    binding: u32,
    dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: READ_STAGES,
        ty: wgpu::BindingType::Texture {
            sample_type: wgpu::TextureSampleType::Float { filterable: false },
            view_dimension: dimension,
            multisampled: false,
        },
        count: None,
    }
}

/// A compute-stage write-only `rgba32float` storage texture of `dimension`.
pub fn storage_texture_entry(
    binding: u32,
    dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::StorageTexture {
            access: wgpu::StorageTextureAccess::WriteOnly,
            format: FrameOutput::FORMAT,
            view_dimension: dimension,
        },
        count: None,
    }
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

/// Errors unless the device can write `rgba32float` storage textures from compute
/// passes and read them unfiltered (every WebGPU adapter can; a downlevel GL adapter
/// may not), and on wgpu's GL backend, whose 3-D storage writes reach only the first
/// slice ([`GpuError::UnsupportedBackend`]): there the bake would run and give wrong
/// tables.
pub fn check_texture_support(device: &wgpu::Device) -> Result<(), AtmosError> {
    let backend = device.adapter_info().backend;
    if backend == wgpu::Backend::Gl {
        return Err(GpuError::UnsupportedBackend {
            backend: backend.to_string(),
            reason: "wgpu's GL backend writes only the first slice of a 3-D storage texture \
                     (the aerial-perspective volume would be zero beyond it); use Vulkan, \
                     Metal or DX12, or bake the tables on the CPU",
        }
        .into());
    }
    if device.limits().max_storage_textures_per_shader_stage < 2 {
        return Err(GpuError::UnsupportedFormat {
            format: "rgba32float",
            need: "write-only storage textures (max_storage_textures_per_shader_stage < 2)",
        }
        .into());
    }
    Ok(())
}

/// Bindings of a frame renderer's pass (group 0): the camera uniform (0), the model's
/// parameter uniform (1), the [`FrameOutput`] radiance and transmittance storage
/// textures (2, 3), then the renderer's own storage buffers (4, …).
#[derive(Debug)]
pub(crate) struct FramePassLayout {
    pub(crate) bind_group: wgpu::BindGroupLayout,
    pub(crate) pipeline: wgpu::PipelineLayout,
    label: &'static str,
}

/// What a frame renderer's `prepare` made for its `encode`: the camera and the bind
/// group of the frame's resources.
#[derive(Debug)]
pub(crate) struct PreparedFrame {
    pub(crate) camera: FrameCamera,
    pub(crate) bind_group: wgpu::BindGroup,
}

impl FramePassLayout {
    pub(crate) fn new(device: &wgpu::Device, label: &'static str, own_storage: u32) -> Self {
        let storage = wgpu::BufferBindingType::Storage { read_only: false };
        let entries: Vec<_> = [
            compute_buffer_entry(0, wgpu::BufferBindingType::Uniform),
            compute_buffer_entry(1, wgpu::BufferBindingType::Uniform),
            storage_texture_entry(2, wgpu::TextureViewDimension::D2),
            storage_texture_entry(3, wgpu::TextureViewDimension::D2),
        ]
        .into_iter()
        .chain((4..4 + own_storage).map(|binding| compute_buffer_entry(binding, storage)))
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

    /// The bind group of this frame's resources, for `prepare`: `camera` checked
    /// against `output`'s size.
    pub(crate) fn prepare(
        &self,
        device: &wgpu::Device,
        camera: &FrameCamera,
        camera_buffer: &wgpu::Buffer,
        parameters: &wgpu::Buffer,
        output: &FrameOutput,
        own_storage: &[&wgpu::Buffer],
    ) -> Result<PreparedFrame, AtmosError> {
        output.check_camera(camera)?;
        let [radiance, transmittance] = output.bind_group_entries(2);
        let entries: Vec<_> = [
            wgpu::BindGroupEntry {
                binding: 0,
                resource: camera_buffer.as_entire_binding(),
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
        Ok(PreparedFrame {
            camera: *camera,
            bind_group,
        })
    }

    /// What `prepare` made, or the typed error of an `encode` before `prepare`.
    pub(crate) fn prepared<'a>(
        &self,
        prepared: &'a Option<PreparedFrame>,
    ) -> Result<&'a PreparedFrame, AtmosError> {
        prepared
            .as_ref()
            .ok_or_else(|| GpuError::NotPrepared { pass: self.label }.into())
    }
}
