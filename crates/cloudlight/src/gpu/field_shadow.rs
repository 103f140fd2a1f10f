//! What the two shadow-map passes ([`super::ShadowMapPass`], [`super::ShellShadowMapPass`])
//! share: one march, `field_march.wgsl`'s `shadow_texel` over the field's
//! [`GpuDensitySource`], its uniform (`ShadowMapParams`), pipeline, bind group and
//! dispatch size. They differ only in their source and their output (a texture, a buffer).

use super::density_source::{GpuDensitySource, SourceBuffers, compose_over, source_layout_entries};
use crate::shadow_map::ShadowMapPlan;

/// Texels per workgroup along each axis of the map.
pub const SHADOW_WORKGROUP_SIZE: u32 = 8;

/// Bytes of `field_march.wgsl`'s `ShadowMapParams`.
const PARAMS_BYTES: u64 = 48;

/// A shadow-map pass's pipeline and its one bind group's layout: the uniform (binding
/// 0), `output` (binding 1) and the source's bindings 4 and 5.
pub(super) fn shadow_pipeline<S: GpuDensitySource + ?Sized>(
    device: &wgpu::Device,
    entry: &str,
    entry_point: &str,
    label: &str,
    output: wgpu::BindingType,
) -> Result<(wgpu::ComputePipeline, wgpu::BindGroupLayout), skyscape_wgsl::ComposeError> {
    let source = compose_over::<S>(entry)?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(entry),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let entry = |binding: u32, ty: wgpu::BindingType| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty,
        count: None,
    };
    let mut entries = vec![
        entry(
            0,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(PARAMS_BYTES),
            },
        ),
        entry(1, output),
    ];
    entries.extend(source_layout_entries::<S>(wgpu::ShaderStages::COMPUTE));
    let (pipeline, layout) =
        super::one_group_pipeline(device, label, &entries, &module, entry_point);
    Ok((pipeline, layout))
}

/// The workgroups of a map of `resolution` texels, or the first axis that needs more
/// than the device allows: `(field, value, groups, limit)`.
pub(super) fn shadow_workgroups(
    device: &wgpu::Device,
    resolution: [u32; 2],
) -> Result<[u32; 2], (&'static str, u32, u32, u32)> {
    let limit = device.limits().max_compute_workgroups_per_dimension;
    let mut workgroups = [0u32; 2];
    for (k, (field, value)) in ["resolution.x", "resolution.y"]
        .into_iter()
        .zip(resolution)
        .enumerate()
    {
        let groups = value.div_ceil(SHADOW_WORKGROUP_SIZE);
        if groups > limit {
            return Err((field, value, groups, limit));
        }
        workgroups[k] = groups;
    }
    Ok(workgroups)
}

/// `plan`'s `ShadowMapParams`, uploaded.
pub(super) fn shadow_params(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    plan: &ShadowMapPlan,
    label: &str,
) -> wgpu::Buffer {
    let grid = &plan.grid;
    let f = |x: f64| (x as f32).to_bits();
    let l = plan.to_sun();
    let resolution = grid.resolution();
    let words: [u32; 12] = [
        f(grid.origin()[0]),
        f(grid.origin()[1]),
        f(grid.cell_size()),
        f(grid.ground_height()),
        f(l[0]),
        f(l[1]),
        f(l[2]),
        0,
        resolution[0],
        resolution[1],
        plan.steps(),
        0,
    ];
    let params = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: PARAMS_BYTES,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
    params
}

/// A shadow-map pass's bind group: the uniform, `output` and the source's buffers.
pub(super) fn shadow_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    params: &wgpu::Buffer,
    output: wgpu::BindingResource<'_>,
    source: &SourceBuffers,
) -> wgpu::BindGroup {
    let mut entries = vec![
        wgpu::BindGroupEntry {
            binding: 0,
            resource: params.as_entire_binding(),
        },
        wgpu::BindGroupEntry {
            binding: 1,
            resource: output,
        },
    ];
    entries.extend(source.entries());
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}
