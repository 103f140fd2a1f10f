//! The bake passes' tables, dispatches and pipelines.

use super::*;
use crate::AtmosError;
use wgpu::TextureViewDimension as Dim;

/// One table: its texture and the view of all its layers.
#[derive(Debug)]
pub(super) struct Table {
    pub(super) texture: wgpu::Texture,
    pub(super) view: wgpu::TextureView,
}

impl Table {
    pub(super) fn new(device: &wgpu::Device, label: &str, size: [u32; 3], dimension: Dim) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: size[2],
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: if dimension == Dim::D3 {
                wgpu::TextureDimension::D3
            } else {
                wgpu::TextureDimension::D2
            },
            format: FORMAT,
            // COPY_DST: the static tables can be written from a CPU bake.
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(label),
            dimension: Some(dimension),
            ..Default::default()
        });
        Self { texture, view }
    }
}

/// One bake dispatch: its pipeline, the tables it reads (group 1), its outputs
/// (group 2) and its workgroup counts.
#[derive(Debug)]
pub(super) struct BakePass {
    pub(super) pipeline: wgpu::ComputePipeline,
    pub(super) tables: wgpu::BindGroup,
    pub(super) outputs: wgpu::BindGroup,
    pub(super) workgroups: [u32; 2],
    pub(super) label: &'static str,
}

pub(super) const TRANSMITTANCE: usize = 0;
pub(super) const MULTIPLE_SCATTERING: usize = 1;
pub(super) const SKY_IRRADIANCE: usize = 2;

/// What the per-view bakes (sky view, aerial perspective) of one atmosphere share: their
/// pipelines, the shared tables they read (group 1), the layouts of their outputs
/// (group 2) and their workgroup counts.
#[derive(Debug)]
pub(super) struct ViewBakes {
    pub(super) sky_view: wgpu::ComputePipeline,
    pub(super) aerial_perspective: wgpu::ComputePipeline,
    pub(super) tables: wgpu::BindGroup,
    pub(super) sky_view_outputs: wgpu::BindGroupLayout,
    pub(super) aerial_perspective_outputs: wgpu::BindGroupLayout,
    pub(super) sky_view_workgroups: [u32; 2],
    pub(super) aerial_perspective_workgroups: [u32; 2],
}

/// Records one bake dispatch (its pipeline and groups 1, 2) after `uniforms` at group 0.
pub(super) fn record_bake(
    pass: &mut wgpu::ComputePass<'_>,
    uniforms: &wgpu::BindGroup,
    bake: &BakePass,
) {
    pass.set_pipeline(&bake.pipeline);
    pass.set_bind_group(0, uniforms, &[]);
    pass.set_bind_group(1, &bake.tables, &[]);
    pass.set_bind_group(2, &bake.outputs, &[]);
    pass.dispatch_workgroups(bake.workgroups[0], bake.workgroups[1], 1);
}

/// Composes a WGSL module of this crate and creates its compute pipeline.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    module: &str,
    entry: &str,
) -> Result<wgpu::ComputePipeline, AtmosError> {
    let source = crate::composer().compose_module(module)?;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(module),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    Ok(
        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(module),
            layout: Some(layout),
            module: &shader,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        }),
    )
}
