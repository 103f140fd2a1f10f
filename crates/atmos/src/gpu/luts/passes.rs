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
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
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
pub(super) const SKY_VIEW: usize = 2;
pub(super) const AERIAL_PERSPECTIVE: usize = 3;

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
