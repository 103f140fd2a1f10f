//! GPU passes (feature `gpu`): bring your own device.
//!
//! [`SlicePropagation`] runs Dobashi et al. 2000's slice propagation
//! (`shaders/cloudlight/slice_propagation_pass.wgsl`): [`SlicePropagation::new`] builds
//! the pipeline; [`SlicePropagation::prepare`] uploads a volume and a
//! [`SlicePlan`] and creates the buffers and bind groups;
//! [`SlicePropagation::encode`] only records one compute pass of one dispatch per slice
//! into the caller's encoder. Nothing here creates a device or submits.
//!
//! The light of every cell lands in [`SlicePropagation::light_buffer`] (f32, x fastest,
//! like the density); the f32 CPU twin is [`propagate::<f32>`](crate::propagate::propagate).

use crate::CloudVolume;
use crate::propagate::{Resampling, SliceMode, SlicePlan};

pub mod billboard;

mod density_source;
pub use density_source::GpuDensitySource;

mod field_shadow;
pub use field_shadow::SHADOW_WORKGROUP_SIZE;

mod march;
pub use march::{
    FieldMarchPass, MARCH_WORKGROUP_SIZE, MarchGpuError, MarchPass, MarchShellPass, MarchStage,
    MarchedField, OutsideShadow, SKY_DISTANCE_M, TemporalMarch, compose_march_shader,
    compose_march_shell_shader,
};

mod noise_bake;
pub use noise_bake::{
    NOISE_BAKE_WORKGROUP_SIZE, NOISE_TEXTURE_FORMAT, NoiseBake, NoiseBakeError, NoiseBakeSettings,
    compose_noise_bake_shader,
};

mod shadow_map;
pub use shadow_map::{ShadowMapGpuError, ShadowMapPass, compose_shadow_map_shader};

mod shell_shadow_map;
pub use shell_shadow_map::{
    ShellShadowMapGpuError, ShellShadowMapPass, compose_shell_shadow_map_shader,
};

/// Workgroup size of the slice kernel along each in-slice axis.
pub const WORKGROUP_SIZE: u32 = 8;

/// Errors of the GPU passes, naming the field and value.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// Composing the WGSL failed (a packaging bug).
    #[error(transparent)]
    Compose(#[from] skyscape_wgsl::ComposeError),
    /// A buffer is larger than the device lets a shader bind.
    #[error(
        "`{what}` needs {bytes} bytes but the device's max_storage_buffer_binding_size is {limit}"
    )]
    BufferTooLarge {
        /// Which buffer.
        what: &'static str,
        /// Its size.
        bytes: u64,
        /// The device limit.
        limit: u64,
    },
    /// A slice needs more workgroups along one axis than the device can dispatch.
    #[error("{field} = {value} texels needs {groups} workgroups, the device allows {limit}")]
    TooManyWorkgroups {
        /// `nb` or `nc` (the in-slice axes).
        field: &'static str,
        /// Texels along it.
        value: u32,
        /// Workgroups needed.
        groups: u32,
        /// `max_compute_workgroups_per_dimension`.
        limit: u32,
    },
    /// The plan was made for a volume of other dimensions.
    #[error("plan is for a {plan:?} volume, the volume is {volume:?}")]
    PlanMismatch {
        /// The plan's `[nx, ny, nz]`.
        plan: [u32; 3],
        /// The volume's.
        volume: [u32; 3],
    },
    /// `encode` was called before `prepare`.
    #[error("encode before prepare: nothing to propagate")]
    EncodeBeforePrepare,
    /// Bytes handed to a decode have the wrong length.
    #[error("readback has {got} bytes, expected {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}

/// The composed WGSL of the slice pass (entry point `propagate_slice`).
pub fn compose_slice_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer.add_modules(crate::WGSL_MODULES)?;
    composer.compose_module("cloudlight::slice_propagation_pass")
}

/// Buffers and bind groups of one prepared volume.
#[derive(Debug)]
struct Prepared {
    plan: SlicePlan,
    bind_groups: [wgpu::BindGroup; 2],
    step_stride: u32,
    workgroups: [u32; 2],
    light: wgpu::Buffer,
    light_bytes: u64,
    _sweep: wgpu::Buffer,
    _steps: wgpu::Buffer,
    _density: wgpu::Buffer,
    _ping: [wgpu::Buffer; 2],
}

/// Dobashi et al. 2000's slice propagation on a GPU (see the module documentation).
#[derive(Debug)]
pub struct SlicePropagation {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

/// A compute pipeline whose one bind group has `entries`: the group's layout and
/// `entry_point` of `module`.
fn one_group_pipeline(
    device: &wgpu::Device,
    label: &str,
    entries: &[wgpu::BindGroupLayoutEntry],
    module: &wgpu::ShaderModule,
    entry_point: &str,
) -> (wgpu::ComputePipeline, wgpu::BindGroupLayout) {
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry_point),
        layout: Some(&pipeline_layout),
        module,
        entry_point: Some(entry_point),
        compilation_options: wgpu::PipelineCompilationOptions::default(),
        cache: None,
    });
    (pipeline, layout)
}

fn entry(binding: u32, ty: wgpu::BindingType) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty,
        count: None,
    }
}

fn storage(read_only: bool) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Storage { read_only },
        has_dynamic_offset: false,
        min_binding_size: None,
    }
}

/// Records one compute pass labelled `label` that dispatches `pipeline` over
/// `workgroups` (x, y) with `bind_group` as group 0: the whole of a single-dispatch
/// pass's `encode`.
fn dispatch_2d(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    pipeline: &wgpu::ComputePipeline,
    bind_group: &wgpu::BindGroup,
    workgroups: [u32; 2],
) {
    let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
        label: Some(label),
        timestamp_writes,
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    pass.dispatch_workgroups(workgroups[0], workgroups[1], 1);
}

fn uniform(dynamic: bool, size: u64) -> wgpu::BindingType {
    wgpu::BindingType::Buffer {
        ty: wgpu::BufferBindingType::Uniform,
        has_dynamic_offset: dynamic,
        min_binding_size: wgpu::BufferSize::new(size),
    }
}

const SWEEP_BYTES: u64 = 48;
const STEP_BYTES: u64 = 32;

impl SlicePropagation {
    /// Builds the pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, GpuError> {
        let source = compose_slice_shader()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cloudlight::slice_propagation_pass"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let (pipeline, layout) = one_group_pipeline(
            device,
            "cloudlight slices",
            &[
                entry(0, uniform(false, SWEEP_BYTES)),
                entry(1, uniform(true, STEP_BYTES)),
                entry(2, storage(true)),
                entry(3, storage(true)),
                entry(4, storage(false)),
                entry(5, storage(false)),
            ],
            &module,
            "propagate_slice",
        );
        Ok(Self {
            pipeline,
            layout,
            prepared: None,
        })
    }

    /// Uploads `volume`'s density and `plan`'s sweep, and creates the buffers and bind
    /// groups [`SlicePropagation::encode`] records with. Takes effect at the next submit.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        volume: &CloudVolume,
        plan: &SlicePlan,
    ) -> Result<(), GpuError> {
        if plan.volume_dims() != volume.dims() {
            return Err(GpuError::PlanMismatch {
                plan: plan.volume_dims(),
                volume: volume.dims(),
            });
        }
        let limits = device.limits();
        let [na, nb, nc] = plan.dims_abc;
        let cells = volume.density().len() as u64;
        let texels = u64::from(nb) * u64::from(nc);
        let limit = limits.max_storage_buffer_binding_size;
        for (what, bytes) in [("density", cells * 4), ("slice", texels * 4)] {
            if bytes > limit {
                return Err(GpuError::BufferTooLarge { what, bytes, limit });
            }
        }
        let mut workgroups = [0u32; 2];
        for (k, (field, value)) in [("nb", nb), ("nc", nc)].into_iter().enumerate() {
            let groups = value.div_ceil(WORKGROUP_SIZE);
            let limit = limits.max_compute_workgroups_per_dimension;
            if groups > limit {
                return Err(GpuError::TooManyWorkgroups {
                    field,
                    value,
                    groups,
                    limit,
                });
            }
            workgroups[k] = groups;
        }
        let buffer = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage,
                mapped_at_creation: false,
            })
        };
        let dims = volume.dims();
        let (mode, ratio) = match plan.mode {
            SliceMode::Physical => (0u32, 0f32),
            SliceMode::Faithful { attenuation_ratio } => (1, attenuation_ratio as f32),
        };
        let mut sweep = [0u32; 12];
        let resampling = u32::from(plan.resampling == Resampling::CatmullRom);
        sweep[..8].copy_from_slice(&[
            dims[0],
            dims[1],
            dims[2],
            plan.axis as u32,
            nb,
            nc,
            mode,
            resampling,
        ]);
        for (slot, value) in [
            plan.shift[0] as f32,
            plan.shift[1] as f32,
            plan.sigma_ds as f32,
            ratio,
        ]
        .into_iter()
        .enumerate()
        {
            sweep[8 + slot] = value.to_bits();
        }
        let sweep_buffer = buffer(
            "cloudlight sweep",
            SWEEP_BYTES,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&sweep_buffer, 0, bytemuck::cast_slice(&sweep));

        let stride = limits
            .min_uniform_buffer_offset_alignment
            .max(STEP_BYTES as u32);
        let words = (stride / 4) as usize;
        let mut steps = vec![0u32; words * na as usize];
        for k in 0..na {
            let slice = plan.slice_at(k);
            let prev = if k == 0 { slice } else { plan.slice_at(k - 1) };
            let [ob, oc] = plan.offsets[k as usize];
            let at = words * k as usize;
            steps[at..at + 8].copy_from_slice(&[k, slice, prev, 0, ob as u32, oc as u32, 0, 0]);
        }
        let steps_buffer = buffer(
            "cloudlight slice steps",
            (steps.len() * 4) as u64,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&steps_buffer, 0, bytemuck::cast_slice(&steps));

        let read = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let density = buffer("cloudlight density", cells * 4, read);
        queue.write_buffer(&density, 0, bytemuck::cast_slice(volume.density()));
        let ping = [
            buffer("cloudlight slice 0", texels * 4, read),
            buffer("cloudlight slice 1", texels * 4, read),
        ];
        let light = buffer(
            "cloudlight light",
            cells * 4,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        let bind_group = |from: usize| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("cloudlight slices"),
                layout: &self.layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: sweep_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                            buffer: &steps_buffer,
                            offset: 0,
                            size: wgpu::BufferSize::new(STEP_BYTES),
                        }),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: density.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: ping[from].as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: ping[1 - from].as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 5,
                        resource: light.as_entire_binding(),
                    },
                ],
            })
        };
        let bind_groups = [bind_group(0), bind_group(1)];
        self.prepared = Some(Prepared {
            plan: plan.clone(),
            bind_groups,
            step_stride: stride,
            workgroups,
            light,
            light_bytes: cells * 4,
            _sweep: sweep_buffer,
            _steps: steps_buffer,
            _density: density,
            _ping: ping,
        });
        Ok(())
    }

    /// Records the sweep (one compute pass, one dispatch per slice) into `encoder`.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), GpuError> {
        self.encode_timed(encoder, None)
    }

    /// [`SlicePropagation::encode`] with timestamp writes on its compute pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), GpuError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(GpuError::EncodeBeforePrepare)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("cloudlight slices"),
            timestamp_writes,
        });
        pass.set_pipeline(&self.pipeline);
        let [gx, gy] = prepared.workgroups;
        for k in 0..prepared.plan.dims_abc[0] {
            // Slice k reads the buffer slice k − 1 wrote: bind group k mod 2.
            let offset = k * prepared.step_stride;
            pass.set_bind_group(0, &prepared.bind_groups[(k % 2) as usize], &[offset]);
            pass.dispatch_workgroups(gx, gy, 1);
        }
        Ok(())
    }

    /// The light of every cell after the recorded sweep (f32, x fastest; `STORAGE |
    /// COPY_SRC`, [`SlicePropagation::light_size`] bytes); `None` before `prepare`.
    pub fn light_buffer(&self) -> Option<&wgpu::Buffer> {
        self.prepared.as_ref().map(|p| &p.light)
    }

    /// Bytes of the light buffer (0 before `prepare`).
    pub fn light_size(&self) -> u64 {
        self.prepared.as_ref().map_or(0, |p| p.light_bytes)
    }

    /// The prepared plan.
    pub fn plan(&self) -> Option<&SlicePlan> {
        self.prepared.as_ref().map(|p| &p.plan)
    }

    /// Turns the light buffer's bytes into one f32 per cell.
    pub fn decode_light(&self, bytes: &[u8]) -> Result<Vec<f32>, GpuError> {
        let expected = self.light_size() as usize;
        if bytes.len() != expected || expected == 0 {
            return Err(GpuError::ReadbackSize {
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
