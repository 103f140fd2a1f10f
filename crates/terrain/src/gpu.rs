//! GPU east/west horizon bake (WGSL compute, `shaders/terrain/horizon_bake.wgsl`).
//!
//! Bring your own device: [`GpuHorizonBaker::new`] takes a `&wgpu::Device`,
//! [`GpuHorizonBaker::record_east_west`] uploads through the caller's `&wgpu::Queue`
//! (`write_buffer`, executed at the caller's next submit) and records the dispatches
//! into the caller's `&mut wgpu::CommandEncoder`. Nothing here creates a device or
//! submits.
//!
//! Same sampling and formula as the CPU bakes ([`crate::horizon`]), evaluated in
//! `f32`: without a maximum distance each row is one invocation running the hull
//! sweep; with one, each texel is one invocation scanning its window. The angles agree
//! with the CPU within the tolerance measured in the tests (`f32` arithmetic and the
//! GPU's `atan`).

use crate::horizon::{HorizonOptions, max_steps_for};
use crate::{Heightfield, TerrainError};

const WORKGROUP: u32 = 64;

/// Uniform block of `horizon_bake.wgsl` (`HorizonBakeParams`).
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    width: u32,
    height: u32,
    max_steps: u32,
    march_east: u32,
    step: f32,
    inv_two_r: f32,
    _pad: [u32; 2],
}

/// Compiled pipelines for the GPU horizon bake.
#[derive(Debug)]
pub struct GpuHorizonBaker {
    sweep: wgpu::ComputePipeline,
    window: wgpu::ComputePipeline,
}

/// Output of [`GpuHorizonBaker::record_east_west`]: two storage buffers of `f32`
/// angles (radians, row-major, `width * height` each), usable as `COPY_SRC`.
#[derive(Debug)]
pub struct GpuEastWest {
    /// Horizon towards the east.
    pub east: wgpu::Buffer,
    /// Horizon towards the west.
    pub west: wgpu::Buffer,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
}

/// The composed WGSL of the bake (for validation and inspection).
pub fn horizon_bake_source() -> String {
    crate::composer()
        .compose_module("terrain::horizon_bake")
        .expect("terrain::horizon_bake composes")
}

impl GpuHorizonBaker {
    /// Compiles the two entry points on `device`.
    pub fn new(device: &wgpu::Device) -> Self {
        let source = horizon_bake_source();
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("terrain::horizon_bake"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let pipeline = |entry: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: wgpu::PipelineCompilationOptions::default(),
                cache: None,
            })
        };
        Self {
            sweep: pipeline("horizon_sweep_rows"),
            window: pipeline("horizon_window"),
        }
    }

    /// Uploads `hf` and records the east and west bakes into `encoder`.
    ///
    /// Errors when the options are invalid, or when a buffer would exceed the device's
    /// `max_storage_buffer_binding_size` (reported as [`TerrainError::TooLarge`]).
    pub fn record_east_west(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        hf: &Heightfield,
        options: &HorizonOptions,
    ) -> Result<GpuEastWest, TerrainError> {
        options.validate()?;
        let (width, height) = (hf.width(), hf.height());
        let bytes = (width * height * 4) as u64;
        let limit = device.limits().max_storage_buffer_binding_size;
        if bytes > limit {
            return Err(TerrainError::TooLarge {
                field: "heightfield bytes (max_storage_buffer_binding_size)",
                value: bytes,
                limit,
            });
        }
        let max_steps = max_steps_for(hf.spacing(), options.max_distance);
        let windowed = max_steps < width.saturating_sub(1);
        let storage = |label: &str, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let heights = storage("terrain heights", wgpu::BufferUsages::COPY_DST);
        let elevations: Vec<f32> = hf.elevations().iter().map(|&e| e as f32).collect();
        queue.write_buffer(&heights, 0, bytemuck::cast_slice(&elevations));
        let hull = storage("terrain hull scratch", wgpu::BufferUsages::empty());
        let out = GpuEastWest {
            east: storage("terrain horizon east", wgpu::BufferUsages::COPY_SRC),
            west: storage("terrain horizon west", wgpu::BufferUsages::COPY_SRC),
            width,
            height,
        };
        let pipeline = if windowed { &self.window } else { &self.sweep };
        for (march_east, target) in [(true, &out.east), (false, &out.west)] {
            let params = Params {
                width: width as u32,
                height: height as u32,
                max_steps: u32::try_from(max_steps).unwrap_or(u32::MAX),
                march_east: u32::from(march_east),
                step: hf.spacing() as f32,
                inv_two_r: options.inv_two_r() as f32,
                _pad: [0; 2],
            };
            let uniform = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("terrain horizon params"),
                size: std::mem::size_of::<Params>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            queue.write_buffer(&uniform, 0, bytemuck::bytes_of(&params));
            let mut entries = vec![
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: heights.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: target.as_entire_binding(),
                },
            ];
            if !windowed {
                entries.push(wgpu::BindGroupEntry {
                    binding: 2,
                    resource: hull.as_entire_binding(),
                });
            }
            let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("terrain horizon bake"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &entries,
            });
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("terrain horizon bake"),
                timestamp_writes: None,
            });
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind_group, &[]);
            if windowed {
                pass.dispatch_workgroups_1d((width * height) as u32);
            } else {
                pass.dispatch_workgroups((height as u32).div_ceil(WORKGROUP), 1, 1);
            }
        }
        Ok(out)
    }
}

/// Workgroup counts for a 1-D dispatch folded into `y` beyond 65,535 groups (the
/// kernel recovers `gid.x + gid.y * num_workgroups.x * 64`).
trait Dispatch1d {
    fn dispatch_workgroups_1d(&mut self, invocations: u32);
}

impl Dispatch1d for wgpu::ComputePass<'_> {
    fn dispatch_workgroups_1d(&mut self, invocations: u32) {
        let groups = invocations.div_ceil(WORKGROUP).max(1);
        let (x, y) = if groups <= 65_535 {
            (groups, 1)
        } else {
            let y = groups.div_ceil(65_535);
            (groups.div_ceil(y), y)
        };
        self.dispatch_workgroups(x, y, 1);
    }
}
