//! GPU horizon bakes (WGSL compute, `shaders/terrain/horizon_bake.wgsl`): the
//! east/west pair, and any azimuth with the sampling of [`crate::horizon`].
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

use crate::horizon::{HorizonOptions, Lines, NEAR_STEPS, check_azimuth, max_steps_for};
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

/// Uniform block `HorizonLineParams` of `horizon_bake.wgsl`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct LineParams {
    dominant_is_x: u32,
    march_forward: u32,
    n_dominant: u32,
    n_minor: u32,
    first_line: i32,
    line_count: u32,
    foot: f32,
    near_steps: u32,
}

/// Compiled pipelines for the GPU horizon bake.
#[derive(Debug)]
pub struct GpuHorizonBaker {
    sweep: wgpu::ComputePipeline,
    window: wgpu::ComputePipeline,
    sweep_lines: wgpu::ComputePipeline,
    window_lines: wgpu::ComputePipeline,
    off_axis_lines: wgpu::ComputePipeline,
}

/// Output of [`GpuHorizonBaker::record_azimuth`]: a storage buffer of `f32` angles
/// (radians, row-major, `width * height`), usable as `COPY_SRC`.
#[derive(Debug)]
pub struct GpuHorizonMap {
    /// The angles.
    pub angles: wgpu::Buffer,
    /// Azimuth, radians clockwise from north, in `[0, 2π)`.
    pub azimuth: f64,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
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
            sweep_lines: pipeline("horizon_sweep_lines"),
            window_lines: pipeline("horizon_window_lines"),
            off_axis_lines: pipeline("horizon_off_axis_lines"),
        }
    }

    /// Uploads `hf` and records the bake of one azimuth (radians clockwise from north)
    /// into `encoder`: the sampling of [`crate::horizon`] (line offsets and their
    /// fractions computed here in `f64` and uploaded, so the GPU reads exactly the CPU's
    /// samples), one invocation per line. On the axes and diagonals: the hull sweep
    /// (per-texel windows with a maximum distance); off them, every texel scans its
    /// window (near field on its own ray, then the line's samples; O(n²) per line).
    ///
    /// Errors like [`GpuHorizonBaker::record_east_west`], and on a non-finite azimuth.
    pub fn record_azimuth(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        hf: &Heightfield,
        azimuth: f64,
        options: &HorizonOptions,
    ) -> Result<GpuHorizonMap, TerrainError> {
        options.validate()?;
        let azimuth = check_azimuth(azimuth)?;
        let (width, height) = (hf.width(), hf.height());
        let lines = Lines::new(width, height, hf.spacing(), azimuth);
        let ids = lines.ids();
        let line_count = (ids.end() - ids.start() + 1) as usize;
        let map_bytes = (width * height * 4) as u64;
        let hull_bytes = (line_count * lines.n_dominant * 4) as u64;
        let limit = device.limits().max_storage_buffer_binding_size;
        for (field, bytes) in [
            (
                "heightfield bytes (max_storage_buffer_binding_size)",
                map_bytes,
            ),
            (
                "line hull bytes (max_storage_buffer_binding_size)",
                hull_bytes,
            ),
        ] {
            if bytes > limit {
                return Err(TerrainError::TooLarge {
                    field,
                    value: bytes,
                    limit,
                });
            }
        }
        let max_steps = max_steps_for(lines.step, options.max_distance);
        let windowed = max_steps < lines.n_dominant.saturating_sub(1);
        let storage = |label: &str, size: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size,
                usage: wgpu::BufferUsages::STORAGE | usage,
                mapped_at_creation: false,
            })
        };
        let heights = storage("terrain heights", map_bytes, wgpu::BufferUsages::COPY_DST);
        let elevations: Vec<f32> = hf.elevations().iter().map(|&e| e as f32).collect();
        queue.write_buffer(&heights, 0, bytemuck::cast_slice(&elevations));
        let offsets: Vec<i32> = lines.offsets.iter().map(|&o| o as i32).collect();
        let offsets_buffer = storage(
            "terrain line offsets",
            (offsets.len() * 4) as u64,
            wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&offsets_buffer, 0, bytemuck::cast_slice(&offsets));
        let hull = storage(
            "terrain line hull scratch",
            hull_bytes.max(4),
            wgpu::BufferUsages::empty(),
        );
        let angles = storage("terrain horizon", map_bytes, wgpu::BufferUsages::COPY_SRC);
        let uniform = |label: &str, bytes: &[u8]| {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.len() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            queue.write_buffer(&buffer, 0, bytes);
            buffer
        };
        let params = uniform(
            "terrain horizon params",
            bytemuck::bytes_of(&Params {
                width: width as u32,
                height: height as u32,
                max_steps: u32::try_from(max_steps).unwrap_or(u32::MAX),
                march_east: 0,
                step: lines.step as f32,
                inv_two_r: options.inv_two_r() as f32,
                _pad: [0; 2],
            }),
        );
        let line_params = uniform(
            "terrain horizon line params",
            bytemuck::bytes_of(&LineParams {
                dominant_is_x: u32::from(lines.dominant_is_x),
                march_forward: u32::from(lines.march > 0),
                n_dominant: lines.n_dominant as u32,
                n_minor: lines.n_minor as u32,
                first_line: *ids.start() as i32,
                line_count: line_count as u32,
                foot: (lines.march as f64 * lines.slope * lines.step
                    / (1.0 + lines.slope * lines.slope)) as f32,
                near_steps: NEAR_STEPS as u32,
            }),
        );
        // Off the axes and diagonals: u·t − round(u·t) per dominant coordinate.
        let fracs: Vec<f32> = lines
            .offsets
            .iter()
            .enumerate()
            .map(|(u, &o)| (u as f64 * lines.slope - o as f64) as f32)
            .collect();
        let fracs_buffer = storage(
            "terrain line fractions",
            (fracs.len() * 4) as u64,
            wgpu::BufferUsages::COPY_DST,
        );
        queue.write_buffer(&fracs_buffer, 0, bytemuck::cast_slice(&fracs));
        let pipeline = if !lines.exact {
            &self.off_axis_lines
        } else if windowed {
            &self.window_lines
        } else {
            &self.sweep_lines
        };
        let mut entries = vec![
            wgpu::BindGroupEntry {
                binding: 0,
                resource: params.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: heights.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: angles.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 4,
                resource: line_params.as_entire_binding(),
            },
            wgpu::BindGroupEntry {
                binding: 5,
                resource: offsets_buffer.as_entire_binding(),
            },
        ];
        if !lines.exact {
            entries.push(wgpu::BindGroupEntry {
                binding: 6,
                resource: fracs_buffer.as_entire_binding(),
            });
        } else if !windowed {
            entries.push(wgpu::BindGroupEntry {
                binding: 2,
                resource: hull.as_entire_binding(),
            });
        }
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("terrain horizon bake (lines)"),
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        });
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("terrain horizon bake (lines)"),
            timestamp_writes: None,
        });
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups((line_count as u32).div_ceil(WORKGROUP), 1, 1);
        drop(pass);
        Ok(GpuHorizonMap {
            angles,
            azimuth,
            width,
            height,
        })
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
        // One invocation per texel when windowed, folded into y past the device's limit.
        let texel_groups = workgroups_1d(device, width * height)?;
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
                pass.dispatch_workgroups(texel_groups[0], texel_groups[1], texel_groups[2]);
            } else {
                pass.dispatch_workgroups((height as u32).div_ceil(WORKGROUP), 1, 1);
            }
        }
        Ok(out)
    }
}

/// Workgroup counts for `invocations` of a [`WORKGROUP`]-sized 1-D kernel, folded into
/// `y` past the device's `max_compute_workgroups_per_dimension` (the kernel recovers
/// `gid.x + gid.y * num_workgroups.x * 64`).
fn workgroups_1d(device: &wgpu::Device, invocations: usize) -> Result<[u32; 3], TerrainError> {
    let limit = device.limits().max_compute_workgroups_per_dimension;
    let too_large = || TerrainError::TooLarge {
        field: "horizon bake invocations (max_compute_workgroups_per_dimension² × 64)",
        value: invocations as u64,
        limit: u64::from(limit) * u64::from(limit) * u64::from(WORKGROUP),
    };
    let invocations_u32 = u32::try_from(invocations).map_err(|_| too_large())?;
    skyscape_wgsl::dispatch::workgroups_1d(invocations_u32, WORKGROUP, limit)
        .map_err(|_| too_large())
}

#[cfg(test)]
mod tests {
    /// The `#[repr(C)]` uniform twins have the size and field offsets of their WGSL
    /// structs in `horizon_bake.wgsl`.
    #[test]
    fn uniform_twins_match_their_wgsl_layouts() {
        let source = crate::composer()
            .compose_module("terrain::horizon_bake")
            .unwrap();
        let module = skyscape_wgsl::validate("terrain::horizon_bake", &source).unwrap();
        let wgsl = |name| skyscape_wgsl::struct_layout(&module, name).unwrap();
        skyscape_wgsl::rust_layout!(super::Params {
            width,
            height,
            max_steps,
            march_east,
            step,
            inv_two_r,
            _pad,
        })
        .check_twin_of(&wgsl("HorizonBakeParams"))
        .unwrap();
        skyscape_wgsl::rust_layout!(super::LineParams {
            dominant_is_x,
            march_forward,
            n_dominant,
            n_minor,
            first_line,
            line_count,
            foot,
            near_steps,
        })
        .check_twin_of(&wgsl("HorizonLineParams"))
        .unwrap();
    }
}
