//! The WGSL implementation (feature `gpu`): bring your own device.
//!
//! [`GpuSimulation::new`] prepares everything (pipelines, buffers, uploads through
//! `queue.write_buffer`); [`GpuSimulation::encode_steps`] records steps into the
//! caller's encoder; [`GpuSimulation::encode_readback`] records a copy into a mappable
//! buffer whose bytes [`GpuSimulation::decode_state`] turns back into a
//! [`PackedState`]. Nothing here creates a device or submits.
//!
//! The state lives in two ping-pong storage buffers laid out as in
//! `shaders/cloudsim/step.wgsl`: a 4-word header whose word 0 is the step counter, then
//! the `hum`, `act` and `cld` words of [`PackedState`]. The counter travels with the
//! state, so any number of `encode_steps` calls may be recorded before one submit.

use crate::{Error, Model, PackedState};

pub mod density;
pub use density::GpuDensity;

/// Words before the fields in a GPU state buffer (word 0: the step counter).
pub const HEADER_WORDS: usize = 4;
/// Workgroup size of all kernels (one invocation per packed word, or per cell for the
/// density).
pub const WORKGROUP_SIZE: u32 = 64;

/// Errors of the GPU path.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    /// The model or state was rejected.
    #[error(transparent)]
    Model(#[from] Error),
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
    /// The grid needs more workgroups than the device can dispatch.
    #[error(transparent)]
    Dispatch(#[from] skyscape_wgsl::dispatch::DispatchError),
    /// Bytes handed to [`GpuSimulation::decode_state`] have the wrong length.
    #[error("readback has {got} bytes, the state needs {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}

/// The composed WGSL of the automaton (entry points `step_main`, `wind_main`).
pub fn compose_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer.add_modules(crate::WGSL_MODULES)?;
    composer.compose_module("cloudsim::step")
}

/// Workgroup counts for `n` invocations of a `WORKGROUP_SIZE` kernel on `device`,
/// folded into y past its `max_compute_workgroups_per_dimension` (the kernels recover
/// `gid.x + gid.y * num_workgroups.x * 64`).
fn workgroups(device: &wgpu::Device, n: u32) -> Result<[u32; 3], GpuError> {
    let limit = device.limits().max_compute_workgroups_per_dimension;
    Ok(skyscape_wgsl::dispatch::workgroups_1d(
        n,
        WORKGROUP_SIZE,
        limit,
    )?)
}

/// The automaton on a GPU, in two ping-pong buffers.
#[derive(Debug)]
pub struct GpuSimulation {
    model: Model,
    step_pipeline: wgpu::ComputePipeline,
    wind_pipeline: wgpu::ComputePipeline,
    /// `[0]`: buffer 0 → 1, `[1]`: buffer 1 → 0.
    bind_groups: [wgpu::BindGroup; 2],
    buffers: [wgpu::Buffer; 2],
    /// Which buffer holds the state after the recorded steps.
    current: usize,
    step: u32,
    wind: bool,
    /// Workgroup counts of one step or wind dispatch (one invocation per packed word).
    workgroups: [u32; 3],
    _params: wgpu::Buffer,
    _region_index: wgpu::Buffer,
    _region_entries: wgpu::Buffer,
    _wind: wgpu::Buffer,
}

fn storage_entry(binding: u32, read_only: bool) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn state_bytes_of(model: &Model) -> u64 {
    ((HEADER_WORDS + 3 * model.size().words()) * 4) as u64
}

impl GpuSimulation {
    /// Prepares pipelines and buffers for `model` and uploads `state` as the state
    /// before step `step`.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        model: &Model,
        state: &PackedState,
        step: u32,
    ) -> Result<Self, GpuError> {
        let size = model.size();
        check_state(model, state)?;
        let limit = device.limits().max_storage_buffer_binding_size;
        let state_bytes = state_bytes_of(model);
        // With ellipsoids the region table's GPU layout; without, one unused word each.
        let (region_index, region_entries) = match model.regions() {
            Some(table) => table.gpu_layout(size.words()),
            None => (vec![0], vec![0]),
        };
        let index_bytes = (region_index.len() * 4) as u64;
        let entries_bytes = (region_entries.len() * 4) as u64;
        for (what, bytes) in [
            ("state", state_bytes),
            ("region_index", index_bytes),
            ("region_entries", entries_bytes),
        ] {
            if bytes > limit {
                return Err(GpuError::BufferTooLarge { what, bytes, limit });
            }
        }
        let source = compose_shader()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cloudsim::step"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cloudsim"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
                storage_entry(1, true),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, false),
                storage_entry(5, true),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cloudsim"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        };
        let step_pipeline = pipeline("step_main");
        let wind_pipeline = pipeline("wind_main");

        let buffer = |label: &str, bytes: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let [t_ext, t_hum, t_act] = model.thresholds();
        let params_data: [u32; 12] = [
            size.nx,
            size.ny,
            size.nz,
            size.words_per_row() as u32,
            size.words() as u32,
            u32::from(model.boundary() == crate::Boundary::Periodic),
            model.seed(),
            size.last_word_mask(),
            t_ext,
            t_hum,
            t_act,
            u32::from(model.has_regions()),
        ];
        let params = buffer(
            "cloudsim params",
            48,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&params_data));

        let index = buffer("cloudsim region index", index_bytes, storage);
        queue.write_buffer(&index, 0, bytemuck::cast_slice(&region_index));
        let entries = buffer("cloudsim region entries", entries_bytes, storage);
        queue.write_buffer(&entries, 0, bytemuck::cast_slice(&region_entries));

        let mut wind_data: Vec<i32> = model.wind_fixed().iter().flatten().copied().collect();
        if wind_data.is_empty() {
            wind_data = vec![0; 2 * size.nz as usize];
        }
        let wind = buffer("cloudsim wind", (wind_data.len() * 4) as u64, storage);
        queue.write_buffer(&wind, 0, bytemuck::cast_slice(&wind_data));

        let state_usage = storage | wgpu::BufferUsages::COPY_SRC;
        let buffers = [
            buffer("cloudsim state 0", state_bytes, state_usage),
            buffer("cloudsim state 1", state_bytes, state_usage),
        ];
        let bind_group = |from: usize| {
            let resources = [
                params.as_entire_binding(),
                index.as_entire_binding(),
                wind.as_entire_binding(),
                buffers[from].as_entire_binding(),
                buffers[1 - from].as_entire_binding(),
                entries.as_entire_binding(),
            ];
            let resources: Vec<wgpu::BindGroupEntry> = resources
                .into_iter()
                .enumerate()
                .map(|(binding, resource)| wgpu::BindGroupEntry {
                    binding: binding as u32,
                    resource,
                })
                .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("cloudsim"),
                layout: &layout,
                entries: &resources,
            })
        };
        let bind_groups = [bind_group(0), bind_group(1)];
        let mut sim = Self {
            model: model.clone(),
            step_pipeline,
            wind_pipeline,
            bind_groups,
            buffers,
            current: 0,
            step,
            wind: model.has_wind(),
            workgroups: workgroups(device, size.words() as u32)?,
            _params: params,
            _region_index: index,
            _region_entries: entries,
            _wind: wind,
        };
        sim.upload(queue, state, step)?;
        Ok(sim)
    }

    /// Replaces the state (as the state before step `step`) through `queue.write_buffer`.
    /// Takes effect at the next submit, before the work recorded after this call.
    pub fn upload(
        &mut self,
        queue: &wgpu::Queue,
        state: &PackedState,
        step: u32,
    ) -> Result<(), GpuError> {
        check_state(&self.model, state)?;
        let mut data = Vec::with_capacity(HEADER_WORDS + 3 * state.hum.len());
        data.extend_from_slice(&[step, 0, 0, 0]);
        data.extend_from_slice(&state.hum);
        data.extend_from_slice(&state.act);
        data.extend_from_slice(&state.cld);
        queue.write_buffer(&self.buffers[self.current], 0, bytemuck::cast_slice(&data));
        self.step = step;
        Ok(())
    }

    /// Records `steps` automaton steps into `encoder` (one compute pass; two
    /// dispatches per step when the model has wind).
    pub fn encode_steps(&mut self, encoder: &mut wgpu::CommandEncoder, steps: u32) {
        self.encode_steps_timed(encoder, steps, None);
    }

    /// [`GpuSimulation::encode_steps`] with timestamp writes on its single compute pass
    /// (e.g. from `skyscape_harness::PassTimer`), for GPU timings.
    pub fn encode_steps_timed(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        steps: u32,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        if steps == 0 {
            return;
        }
        let [x, y, z] = self.workgroups;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("cloudsim steps"),
            timestamp_writes,
        });
        for _ in 0..steps {
            pass.set_pipeline(&self.step_pipeline);
            pass.set_bind_group(0, &self.bind_groups[self.current], &[]);
            pass.dispatch_workgroups(x, y, z);
            self.current ^= 1;
            if self.wind {
                pass.set_pipeline(&self.wind_pipeline);
                pass.set_bind_group(0, &self.bind_groups[self.current], &[]);
                pass.dispatch_workgroups(x, y, z);
                self.current ^= 1;
            }
            self.step = self.step.wrapping_add(1);
        }
    }

    /// The counter of the next step after everything recorded so far.
    pub fn step_index(&self) -> u32 {
        self.step
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The buffer that holds the state after everything recorded so far (`STORAGE |
    /// COPY_SRC | COPY_DST`, [`GpuSimulation::state_size`] bytes).
    pub fn state_buffer(&self) -> &wgpu::Buffer {
        &self.buffers[self.current]
    }

    /// Bytes of a state buffer: `4 * (HEADER_WORDS + 3 * words)`.
    pub fn state_size(&self) -> u64 {
        state_bytes_of(&self.model)
    }

    /// Records a copy of the current state into a new `MAP_READ | COPY_DST` buffer and
    /// returns it. After the caller submits and maps it, pass its bytes to
    /// [`GpuSimulation::decode_state`].
    pub fn encode_readback(
        &self,
        device: &wgpu::Device,
        encoder: &mut wgpu::CommandEncoder,
    ) -> wgpu::Buffer {
        let staging = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudsim readback"),
            size: self.state_size(),
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        encoder.copy_buffer_to_buffer(self.state_buffer(), 0, &staging, 0, self.state_size());
        staging
    }

    /// Turns the bytes of a state buffer back into `(state, step counter)`.
    pub fn decode_state(&self, bytes: &[u8]) -> Result<(PackedState, u32), GpuError> {
        decode_state(&self.model, bytes)
    }
}

fn check_state(model: &Model, state: &PackedState) -> Result<(), Error> {
    state.check()?;
    if state.size() != model.size() {
        return Err(Error::SizeMismatch {
            what: "state",
            got: state.size().cells(),
            expected: model.size().cells(),
        });
    }
    Ok(())
}

/// Turns the bytes of a GPU state buffer for `model` into `(state, step counter)`.
pub fn decode_state(model: &Model, bytes: &[u8]) -> Result<(PackedState, u32), GpuError> {
    let expected = state_bytes_of(model) as usize;
    if bytes.len() != expected {
        return Err(GpuError::ReadbackSize {
            got: bytes.len(),
            expected,
        });
    }
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|b| u32::from_ne_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    let n = model.size().words();
    let mut state = PackedState::empty(model.size())?;
    let fields = &words[HEADER_WORDS..];
    state.hum.copy_from_slice(&fields[..n]);
    state.act.copy_from_slice(&fields[n..2 * n]);
    state.cld.copy_from_slice(&fields[2 * n..]);
    Ok((state, words[0]))
}

/// Prepares a [`GpuSimulation`] for `model` starting from `state` before step `step`,
/// and records `steps` steps into `encoder`. Submit the encoder, then read back with
/// [`GpuSimulation::encode_readback`] (or copy [`GpuSimulation::state_buffer`]).
pub fn run_steps(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    encoder: &mut wgpu::CommandEncoder,
    model: &Model,
    state: &PackedState,
    step: u32,
    steps: u32,
) -> Result<GpuSimulation, GpuError> {
    let mut sim = GpuSimulation::new(device, queue, model, state, step)?;
    sim.encode_steps(encoder, steps);
    Ok(sim)
}
