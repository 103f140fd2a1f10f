//! [`ShellShadowMapPass`]: the ground's cloud shadow map of a procedural cloud shell on a
//! GPU (`shaders/cloudlight/shell_shadow_map_pass.wgsl`: `field_march.wgsl`'s
//! `shadow_texel` over the shell, `density_shell.wgsl`), bring your own device. The
//! weather is procedural or a user grid (its cells uploaded in `prepare` to the source's
//! storage buffer, binding 5).
//!
//! [`ShellShadowMapPass::new`] builds the pipeline; [`ShellShadowMapPass::prepare`]
//! uploads the shell's parameters ([`ShellField`]) and the plan and creates the output
//! buffer and the bind group; [`ShellShadowMapPass::encode`] only records one dispatch
//! (8×8 texels per workgroup). The noise is evaluated per sample, as the GPU shell march
//! ([`crate::gpu::MarchShellPass`]) evaluates it: no noise bake.
//!
//! The output is a storage buffer of `resolution[0] × resolution[1]` f32 (`i` fastest,
//! `STORAGE | COPY_SRC`), texel `(i, j)` the transmittance at the ground point of
//! [`ShadowGrid::texel_centre`] in the shell's planet-centred frame: a buffer, not a
//! texture, so a renderer can copy it into a larger buffer of maps at any offset
//! (`copy_buffer_to_buffer` has no 256-byte row alignment).
//!
//! The f32 CPU twin is [`shell_shadow_map::<f32>`](crate::shell_shadow::shell_shadow_map),
//! equal bit for bit to [`shadow_map::<f32>`](crate::shadow_map::shadow_map) on the
//! [`crate::CloudShell`].
//!
//! [`ShadowGrid::texel_centre`]: crate::shadow_map::ShadowGrid::texel_centre

use super::density_source::{SourceBuffers, compose_over};
use super::field_shadow::{shadow_bind_group, shadow_params, shadow_pipeline, shadow_workgroups};
use crate::shadow_map::ShadowMapPlan;
use crate::shell_shadow::ShellField;

/// Errors of the shell's shadow-map pass, naming the field and value.
#[derive(Debug, thiserror::Error)]
pub enum ShellShadowMapGpuError {
    /// Composing the WGSL failed (a packaging bug).
    #[error(transparent)]
    Compose(#[from] skyscape_wgsl::ComposeError),
    /// The output buffer is larger than the device lets a shader bind.
    #[error(
        "the map needs {bytes} bytes but the device's max_storage_buffer_binding_size is {limit}"
    )]
    BufferTooLarge {
        /// The buffer's size.
        bytes: u64,
        /// The device limit.
        limit: u64,
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
    #[error("encode before prepare: no shell shadow map to compute")]
    EncodeBeforePrepare,
    /// Bytes handed to [`ShellShadowMapPass::decode`] have the wrong length.
    #[error("readback has {got} bytes, expected {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}

/// The composed WGSL of the pass (entry point `shell_shadow_map_main`).
pub fn compose_shell_shadow_map_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    compose_over::<ShellField<f32>>("cloudlight::shell_shadow_map_pass")
}

#[derive(Debug)]
struct Prepared {
    bind_group: wgpu::BindGroup,
    workgroups: [u32; 2],
    resolution: [u32; 2],
    output: wgpu::Buffer,
    _params: wgpu::Buffer,
    _source: SourceBuffers,
}

/// The shell's cloud shadow map on a GPU (see the module documentation).
#[derive(Debug)]
pub struct ShellShadowMapPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

impl ShellShadowMapPass {
    /// Builds the pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, ShellShadowMapGpuError> {
        let (pipeline, layout) = shadow_pipeline::<ShellField<f32>>(
            device,
            "cloudlight::shell_shadow_map_pass",
            "shell_shadow_map_main",
            "cloudlight shell shadow map",
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: false },
                has_dynamic_offset: false,
                min_binding_size: None,
            },
        )?;
        Ok(Self {
            pipeline,
            layout,
            prepared: None,
        })
    }

    /// Uploads `field` (the shell, [`ShellField::of`]) and `plan` (its grid in the shell's
    /// planet-centred frame), creates the output buffer and the bind group
    /// [`ShellShadowMapPass::encode`] records with. Takes effect at the next submit.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        field: &ShellField<f32>,
        plan: &ShadowMapPlan,
    ) -> Result<(), ShellShadowMapGpuError> {
        let resolution = plan.grid.resolution();
        let bytes = plan.grid.texels() as u64 * 4;
        let limit = device.limits().max_storage_buffer_binding_size;
        if bytes > limit {
            return Err(ShellShadowMapGpuError::BufferTooLarge { bytes, limit });
        }
        let workgroups =
            shadow_workgroups(device, resolution).map_err(|(field, value, groups, limit)| {
                ShellShadowMapGpuError::TooManyWorkgroups {
                    field,
                    value,
                    groups,
                    limit,
                }
            })?;
        let params = shadow_params(device, queue, plan, "cloudlight shell shadow map params");
        let output = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight shell shadow map"),
            size: bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let source =
            SourceBuffers::upload(device, queue, field, "cloudlight shell shadow map", limit)
                .map_err(|bytes| ShellShadowMapGpuError::BufferTooLarge { bytes, limit })?;
        let bind_group = shadow_bind_group(
            device,
            &self.layout,
            "cloudlight shell shadow map",
            &params,
            output.as_entire_binding(),
            &source,
        );
        self.prepared = Some(Prepared {
            bind_group,
            workgroups,
            resolution,
            output,
            _params: params,
            _source: source,
        });
        Ok(())
    }

    /// Records the map's dispatch into `encoder`.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), ShellShadowMapGpuError> {
        self.encode_timed(encoder, None)
    }

    /// [`ShellShadowMapPass::encode`] with timestamp writes on its compute pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), ShellShadowMapGpuError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(ShellShadowMapGpuError::EncodeBeforePrepare)?;
        super::dispatch_2d(
            encoder,
            "cloudlight shell shadow map",
            timestamp_writes,
            &self.pipeline,
            &prepared.bind_group,
            prepared.workgroups,
        );
        Ok(())
    }

    /// The map (f32 per texel, `i` fastest); `None` before `prepare`.
    pub fn buffer(&self) -> Option<&wgpu::Buffer> {
        self.prepared.as_ref().map(|p| &p.output)
    }

    /// `[nx, ny]` texels of the prepared map; `None` before `prepare`.
    pub fn resolution(&self) -> Option<[u32; 2]> {
        self.prepared.as_ref().map(|p| p.resolution)
    }

    /// Turns the buffer's bytes (as `skyscape_harness::read_buffer` returns them) into
    /// one f32 per texel, `i` fastest.
    pub fn decode(&self, bytes: &[u8]) -> Result<Vec<f32>, ShellShadowMapGpuError> {
        let expected = self.prepared.as_ref().map_or(0, |p| {
            p.resolution[0] as usize * p.resolution[1] as usize * 4
        });
        if bytes.len() != expected || expected == 0 {
            return Err(ShellShadowMapGpuError::ReadbackSize {
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
