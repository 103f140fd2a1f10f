//! The density volume on the GPU (feature `gpu`): Dobashi's space–time smoothing of
//! `cld` in WGSL (`shaders/cloudsim/density.wgsl`), the twin of [`crate::density()`].
//!
//! [`GpuDensity::new`] prepares the pipeline, a ring of `radius_steps + 1` packed `cld`
//! fields and the `f32` output buffer. [`GpuDensity::encode_capture`] records a copy of a
//! [`GpuSimulation`]'s current `cld` field into the ring (newest first), and
//! [`GpuDensity::encode_density`] records the smoothing pass. The ring position is
//! tracked on the CPU at encode time and handed to the shader by a buffer copy, so any
//! number of captures and passes can be recorded before one submit. Nothing here creates
//! a device or submits; `cloudlight`/`render` bind [`GpuDensity::density_buffer`]
//! directly (one `f32` per cell, index `x + nx * (y + ny * z)`).

use super::{GpuError, GpuSimulation, HEADER_WORDS, WORKGROUP_SIZE, storage_entry, workgroups};
use crate::{Boundary, Error, Model};

/// The composed WGSL of the density pass (entry point `density_main`).
pub fn compose_density_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer.add_modules(crate::WGSL_MODULES)?;
    composer.compose_module("cloudsim::density")
}

/// Bytes of one ring-table entry (`Ring` in WGSL: newest, len, 2 × unused).
const RING_ENTRY_BYTES: u64 = 16;

/// The smoothed density of a GPU simulation's recent `cld` history.
#[derive(Debug)]
pub struct GpuDensity {
    model: Model,
    pipeline: wgpu::ComputePipeline,
    bind_group: wgpu::BindGroup,
    history: wgpu::Buffer,
    ring: wgpu::Buffer,
    ring_table: wgpu::Buffer,
    output: wgpu::Buffer,
    /// Ring slots (`radius_steps + 1`).
    keep: u32,
    /// Slot of the newest captured field.
    newest: u32,
    /// Filled slots.
    len: u32,
    /// Workgroup counts of the density dispatch (one invocation per cell).
    workgroups: [u32; 3],
    _params: wgpu::Buffer,
    _scale: wgpu::Buffer,
}

impl GpuDensity {
    /// Prepares the density pass for `model` (pipeline, ring, output); the ring starts
    /// empty.
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        model: &Model,
    ) -> Result<Self, GpuError> {
        let size = model.size();
        let smoothing = model.smoothing();
        let keep = smoothing.radius_steps + 1;
        let words = size.words() as u64;
        let history_bytes = words * 4 * u64::from(keep);
        let output_bytes = size.cells() as u64 * 4;
        let limit = device.limits().max_storage_buffer_binding_size;
        for (what, bytes) in [("cld_history", history_bytes), ("density", output_bytes)] {
            if bytes > limit {
                return Err(GpuError::BufferTooLarge { what, bytes, limit });
            }
        }
        let source = compose_density_shader()?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("cloudsim::density"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let uniform_entry = |binding| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("cloudsim density"),
            entries: &[
                uniform_entry(0),
                uniform_entry(1),
                storage_entry(2, true),
                storage_entry(3, true),
                storage_entry(4, false),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("cloudsim density"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("density_main"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("density_main"),
            compilation_options: wgpu::PipelineCompilationOptions::default(),
            cache: None,
        });
        let buffer = |label: &str, bytes: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage,
                mapped_at_creation: false,
            })
        };
        let params_data: [u32; 8] = [
            size.nx,
            size.ny,
            size.nz,
            size.words_per_row() as u32,
            size.words() as u32,
            u32::from(model.boundary() == Boundary::Periodic),
            smoothing.radius_cells,
            smoothing.radius_steps,
        ];
        let params = buffer(
            "cloudsim density params",
            32,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&params_data));
        let ring = buffer(
            "cloudsim density ring",
            RING_ENTRY_BYTES,
            wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        );
        // Every (newest, len) the ring can be in; encode_density copies one entry.
        let table: Vec<u32> = (0..keep)
            .flat_map(|newest| (0..=keep).flat_map(move |len| [newest, len, 0, 0]))
            .collect();
        let ring_table = buffer(
            "cloudsim density ring table",
            (table.len() * 4) as u64,
            wgpu::BufferUsages::COPY_SRC | wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&ring_table, 0, bytemuck::cast_slice(&table));
        let storage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST;
        let history = buffer("cloudsim cld history", history_bytes, storage);
        let scale = buffer("cloudsim slice scale", u64::from(size.nz) * 4, storage);
        queue.write_buffer(&scale, 0, bytemuck::cast_slice(model.slice_density()));
        let output = buffer(
            "cloudsim density",
            output_bytes,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        );
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("cloudsim density"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: ring.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: history.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: scale.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: output.as_entire_binding(),
                },
            ],
        });
        Ok(Self {
            model: model.clone(),
            pipeline,
            bind_group,
            history,
            ring,
            ring_table,
            output,
            keep,
            newest: keep - 1,
            len: 0,
            workgroups: workgroups(device, size.cells() as u32)?,
            _params: params,
            _scale: scale,
        })
    }

    /// Records a copy of `sim`'s current `cld` field (after everything recorded into
    /// `sim` so far) as the newest entry of the history ring; the oldest entry beyond
    /// `radius_steps + 1` is dropped.
    pub fn encode_capture(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        sim: &GpuSimulation,
    ) -> Result<(), GpuError> {
        if sim.model().size() != self.model.size() {
            return Err(Error::SizeMismatch {
                what: "simulation",
                got: sim.model().size().cells(),
                expected: self.model.size().cells(),
            }
            .into());
        }
        let words = self.model.size().words() as u64;
        self.newest = (self.newest + 1) % self.keep;
        self.len = (self.len + 1).min(self.keep);
        let cld_offset = (HEADER_WORDS as u64 + 2 * words) * 4;
        encoder.copy_buffer_to_buffer(
            sim.state_buffer(),
            cld_offset,
            &self.history,
            u64::from(self.newest) * words * 4,
            words * 4,
        );
        Ok(())
    }

    /// Records `steps` steps of `sim`, capturing the `cld` field after each of the last
    /// `radius_steps + 1` of them (the fields the smoothing reads).
    pub fn encode_steps_with_history(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        sim: &mut GpuSimulation,
        steps: u32,
    ) -> Result<(), GpuError> {
        let tail = steps.min(self.keep);
        sim.encode_steps(encoder, steps - tail);
        for _ in 0..tail {
            sim.encode_steps(encoder, 1);
            self.encode_capture(encoder, sim)?;
        }
        Ok(())
    }

    /// Records the smoothing pass over the captured history into
    /// [`GpuDensity::density_buffer`]. Errors if nothing has been captured yet.
    pub fn encode_density(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), GpuError> {
        if self.len == 0 {
            return Err(Error::SizeMismatch {
                what: "cld_history",
                got: 0,
                expected: 1,
            }
            .into());
        }
        let entry = u64::from(self.newest * (self.keep + 1) + self.len);
        encoder.copy_buffer_to_buffer(
            &self.ring_table,
            entry * RING_ENTRY_BYTES,
            &self.ring,
            0,
            RING_ENTRY_BYTES,
        );
        let [x, y, z] = self.workgroups;
        debug_assert_eq!(WORKGROUP_SIZE, 64);
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("cloudsim density"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.bind_group, &[]);
        pass.dispatch_workgroups(x, y, z);
        Ok(())
    }

    /// How many history fields the next [`GpuDensity::encode_density`] reads.
    pub fn history_len(&self) -> u32 {
        self.len
    }

    /// The density volume (`STORAGE | COPY_SRC`, one `f32` per cell).
    pub fn density_buffer(&self) -> &wgpu::Buffer {
        &self.output
    }

    /// Bytes of [`GpuDensity::density_buffer`].
    pub fn density_size(&self) -> u64 {
        self.model.size().cells() as u64 * 4
    }

    /// Turns the bytes of the density buffer into one `f32` per cell.
    pub fn decode_density(&self, bytes: &[u8]) -> Result<Vec<f32>, GpuError> {
        let expected = self.density_size() as usize;
        if bytes.len() != expected {
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
