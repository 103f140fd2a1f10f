//! Small constructors every atmos pass (and `render`'s present pass) shares: compute
//! bind-group layout entries for buffers, and per-frame uniform buffers.

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
