//! [`ShadowMapPass`]: the ground's cloud shadow map of a [`CloudVolume`] on a GPU
//! (`shaders/cloudlight/shadow_map_pass.wgsl`: `field_march.wgsl`'s `shadow_texel` over
//! the volume's grid, `density_grid.wgsl`), bring your own device.
//!
//! [`ShadowMapPass::new`] builds the pipeline; [`ShadowMapPass::prepare`] uploads the
//! volume's density and the plan and creates the output texture and the bind group;
//! [`ShadowMapPass::encode`] only records one dispatch (8×8 texels per workgroup).
//!
//! The output is an **R32Float** 2-D texture, `resolution[0] × resolution[1]`, texel
//! `(i, j)` the transmittance at the ground point of [`ShadowGrid::texel_centre`]
//! (`STORAGE_BINDING | TEXTURE_BINDING | COPY_SRC`). Why R32Float: it is a core WebGPU
//! storage format (R16Float is not writable as a storage texture without an extension),
//! and it holds the f32 twin's value exactly, so the GPU test compares like with like. It
//! is not filterable without `FLOAT32_FILTERABLE`: sample it with `textureLoad` (and
//! interpolate yourself) or a non-filtering sampler, or copy it into an R16Float texture
//! if you want hardware filtering (half floats keep 3 decimal digits of a value in [0, 1],
//! 5e-4 at most near 1).
//!
//! The f32 CPU twin is [`shadow_map::<f32>`](crate::shadow_map::shadow_map).
//!
//! [`ShadowGrid::texel_centre`]: crate::shadow_map::ShadowGrid::texel_centre

use super::density_source::SourceBuffers;
use super::field_shadow::{shadow_bind_group, shadow_params, shadow_pipeline, shadow_workgroups};
use crate::CloudVolume;
use crate::shadow_map::ShadowMapPlan;

/// The output texture's format (see the module documentation).
pub const SHADOW_MAP_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Float;

/// Errors of the shadow-map pass, naming the field and value.
#[derive(Debug, thiserror::Error)]
pub enum ShadowMapGpuError {
    /// Composing the WGSL failed (a packaging bug).
    #[error(transparent)]
    Compose(#[from] skyscape_wgsl::ComposeError),
    /// The density buffer is larger than the device lets a shader bind.
    #[error(
        "density needs {bytes} bytes but the device's max_storage_buffer_binding_size is {limit}"
    )]
    BufferTooLarge {
        /// The buffer's size.
        bytes: u64,
        /// The device limit.
        limit: u64,
    },
    /// The map is wider or taller than the device's 2-D textures.
    #[error("{field} = {value} texels, the device's max_texture_dimension_2d is {limit}")]
    TextureTooLarge {
        /// `resolution.x` or `resolution.y`.
        field: &'static str,
        /// Texels along it.
        value: u32,
        /// The device limit.
        limit: u32,
    },
    /// The map needs more workgroups along one axis than the device can dispatch.
    #[error("{field} = {value} texels needs {groups} workgroups, the device allows {limit}")]
    TooManyWorkgroups {
        /// `resolution.x` or `resolution.y`.
        field: &'static str,
        /// Texels along it.
        value: u32,
        /// Workgroups needed.
        groups: u32,
        /// `max_compute_workgroups_per_dimension`.
        limit: u32,
    },
    /// `encode` was called before `prepare`.
    #[error("encode before prepare: no shadow map to compute")]
    EncodeBeforePrepare,
    /// Bytes handed to [`ShadowMapPass::decode`] have the wrong length.
    #[error("readback has {got} bytes, expected {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}

/// The composed WGSL of the shadow-map pass (entry point `shadow_map_main`).
pub fn compose_shadow_map_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    super::density_source::compose_over::<CloudVolume>("cloudlight::shadow_map_pass")
}

#[derive(Debug)]
struct Prepared {
    bind_group: wgpu::BindGroup,
    workgroups: [u32; 2],
    resolution: [u32; 2],
    texture: wgpu::Texture,
    view: wgpu::TextureView,
    _params: wgpu::Buffer,
    _source: SourceBuffers,
}

/// The cloud shadow map on a GPU (see the module documentation).
#[derive(Debug)]
pub struct ShadowMapPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

impl ShadowMapPass {
    /// Builds the pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShadowMapGpuError> {
        let (pipeline, layout) = shadow_pipeline::<CloudVolume>(
            device,
            "cloudlight::shadow_map_pass",
            "shadow_map_main",
            "cloudlight shadow map",
            wgpu::BindingType::StorageTexture {
                access: wgpu::StorageTextureAccess::WriteOnly,
                format: SHADOW_MAP_FORMAT,
                view_dimension: wgpu::TextureViewDimension::D2,
            },
        )?;
        Ok(Self {
            pipeline,
            layout,
            prepared: None,
        })
    }

    /// Uploads `volume`'s density and `plan`, creates the output texture and the bind
    /// group [`ShadowMapPass::encode`] records with. Takes effect at the next submit.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        volume: &CloudVolume,
        plan: &ShadowMapPlan,
    ) -> Result<(), ShadowMapGpuError> {
        let limits = device.limits();
        let bytes = volume.density().len() as u64 * 4;
        let limit = limits.max_storage_buffer_binding_size;
        if bytes > limit {
            return Err(ShadowMapGpuError::BufferTooLarge { bytes, limit });
        }
        let resolution = plan.grid.resolution();
        for (field, value) in ["resolution.x", "resolution.y"].into_iter().zip(resolution) {
            let limit = limits.max_texture_dimension_2d;
            if value > limit {
                return Err(ShadowMapGpuError::TextureTooLarge {
                    field,
                    value,
                    limit,
                });
            }
        }
        let workgroups =
            shadow_workgroups(device, resolution).map_err(|(field, value, groups, limit)| {
                ShadowMapGpuError::TooManyWorkgroups {
                    field,
                    value,
                    groups,
                    limit,
                }
            })?;
        let params = shadow_params(device, queue, plan, "cloudlight shadow map params");
        let source = SourceBuffers::upload(device, queue, volume, "cloudlight shadow map", limit)
            .map_err(|bytes| ShadowMapGpuError::BufferTooLarge { bytes, limit })?;
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some("cloudlight shadow map"),
            size: wgpu::Extent3d {
                width: resolution[0],
                height: resolution[1],
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: SHADOW_MAP_FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor::default());
        let bind_group = shadow_bind_group(
            device,
            &self.layout,
            "cloudlight shadow map",
            &params,
            wgpu::BindingResource::TextureView(&view),
            &source,
        );
        self.prepared = Some(Prepared {
            bind_group,
            workgroups,
            resolution,
            texture,
            view,
            _params: params,
            _source: source,
        });
        Ok(())
    }

    /// Records the map's dispatch into `encoder`.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), ShadowMapGpuError> {
        self.encode_timed(encoder, None)
    }

    /// [`ShadowMapPass::encode`] with timestamp writes on its compute pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), ShadowMapGpuError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(ShadowMapGpuError::EncodeBeforePrepare)?;
        super::dispatch_2d(
            encoder,
            "cloudlight shadow map",
            timestamp_writes,
            &self.pipeline,
            &prepared.bind_group,
            prepared.workgroups,
        );
        Ok(())
    }

    /// The shadow map (R32Float, see the module documentation); `None` before `prepare`.
    pub fn texture(&self) -> Option<&wgpu::Texture> {
        self.prepared.as_ref().map(|p| &p.texture)
    }

    /// A view of the whole shadow map; `None` before `prepare`.
    pub fn view(&self) -> Option<&wgpu::TextureView> {
        self.prepared.as_ref().map(|p| &p.view)
    }

    /// Turns the texture's tightly packed bytes (rows without padding, as
    /// `skyscape_harness::read_texture` returns them) into one f32 per texel, `i` fastest.
    pub fn decode(&self, bytes: &[u8]) -> Result<Vec<f32>, ShadowMapGpuError> {
        let expected = self.prepared.as_ref().map_or(0, |p| {
            p.resolution[0] as usize * p.resolution[1] as usize * 4
        });
        if bytes.len() != expected || expected == 0 {
            return Err(ShadowMapGpuError::ReadbackSize {
                got: bytes.len(),
                expected,
            });
        }
        Ok(bytes
            .chunks_exact(4)
            .map(|b| f32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
            .collect())
    }
}
