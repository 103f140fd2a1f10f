//! Headless GPU harness shared by skyscape's tests and `cargo xtask`.
//!
//! Policy (the same for every GPU test and every xtask command):
//! * an adapter is found → the GPU work runs;
//! * no adapter and `SKYSCAPE_REQUIRE_GPU=1` → the run **fails**, saying why;
//! * no adapter otherwise → the GPU work is reported as skipped, on a line written
//!   straight to stderr (not through the test harness's capture, so it is visible).
//!
//! The adapter honours `WGPU_BACKEND` (`vulkan`, `gl`, …) and `WGPU_ADAPTER_NAME`, and
//! is printed once per process (name, backend, device type, driver).
//!
//! This crate creates devices and submits work on purpose: it is the *test* side.
//! Library crates never do either; they take `&wgpu::Device` / `&wgpu::Queue` and
//! record into the caller's encoder.

use std::io::Write as _;
use std::sync::OnceLock;

mod timer;
pub use timer::{PassTimer, median_pass_seconds};

/// Environment variable that turns "no adapter" from a skip into a failure.
pub const REQUIRE_GPU_ENV: &str = "SKYSCAPE_REQUIRE_GPU";

/// A device, its queue and a description of the adapter behind them.
#[derive(Debug)]
pub struct GpuContext {
    /// The adapter (kept for capability queries).
    pub adapter: wgpu::Adapter,
    /// The device every skyscape GPU test uses.
    pub device: wgpu::Device,
    /// Its queue.
    pub queue: wgpu::Queue,
    /// What the adapter reported about itself.
    pub info: wgpu::AdapterInfo,
}

/// Why GPU work could not run, or failed.
#[derive(Debug, thiserror::Error)]
pub enum HarnessError {
    /// No adapter matched the requested backends.
    #[error("no GPU adapter (WGPU_BACKEND={backend}): {reason}")]
    NoAdapter {
        /// The value of `WGPU_BACKEND`, or `unset`.
        backend: String,
        /// wgpu's reason.
        reason: String,
    },
    /// The process-wide context could not be created earlier (the reason is kept).
    #[error("{reason}")]
    Unavailable {
        /// Why the context could not be created.
        reason: String,
    },
    /// The adapter refused to create a device.
    #[error("adapter `{adapter}` refused a device: {reason}")]
    NoDevice {
        /// Adapter name.
        adapter: String,
        /// wgpu's reason.
        reason: String,
    },
    /// A feature this work needs is missing on the adapter.
    #[error("adapter `{adapter}` lacks required feature(s) {missing:?}")]
    MissingFeature {
        /// Adapter name.
        adapter: String,
        /// The features not supported.
        missing: wgpu::Features,
    },
    /// A texture format capability this work needs is missing.
    #[error("adapter `{adapter}` cannot use {format:?} for {needed:?}")]
    MissingFormatCapability {
        /// Adapter name.
        adapter: String,
        /// The format.
        format: wgpu::TextureFormat,
        /// The usages that are not supported.
        needed: wgpu::TextureUsages,
    },
    /// A limit is below what this work needs.
    #[error("adapter `{adapter}` limit `{limit}` is {have}, {need} needed")]
    LimitTooLow {
        /// Adapter name.
        adapter: String,
        /// Limit name.
        limit: &'static str,
        /// The adapter's value.
        have: u64,
        /// The required value.
        need: u64,
    },
    /// A dispatch does not fit the device's workgroup-count limit.
    #[error(transparent)]
    Dispatch(#[from] skyscape_wgsl::dispatch::DispatchError),
    /// The composed WGSL did not validate (reported by naga before wgpu sees it).
    #[error(transparent)]
    Shader(#[from] skyscape_wgsl::ValidateError),
    /// wgpu reported a validation or out-of-memory error.
    #[error("wgpu error in `{label}`: {message}")]
    Wgpu {
        /// What was being done.
        label: String,
        /// wgpu's message.
        message: String,
    },
    /// Buffer mapping or polling failed.
    #[error("reading back `{label}` failed: {message}")]
    Readback {
        /// What was being read.
        label: String,
        /// Why.
        message: String,
    },
}

/// True when `SKYSCAPE_REQUIRE_GPU` is set to `1` (or `true`).
pub fn gpu_required() -> bool {
    std::env::var(REQUIRE_GPU_ENV)
        .map(|v| v == "1" || v.eq_ignore_ascii_case("true"))
        .unwrap_or(false)
}

fn backend_env() -> String {
    std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "unset".into())
}

static BACKENDS: OnceLock<wgpu::Backends> = OnceLock::new();

/// Chooses the backends instead of `WGPU_BACKEND` (e.g. from a `--backend` flag).
/// Must be called before the first [`context`].
pub fn select_backends(backends: wgpu::Backends) -> Result<(), HarnessError> {
    if CONTEXT.get().is_some() || BACKENDS.set(backends).is_err() {
        return Err(HarnessError::NoAdapter {
            backend: format!("{backends:?}"),
            reason: "backends must be selected before the GPU context is created".into(),
        });
    }
    Ok(())
}

fn create_context() -> Result<GpuContext, HarnessError> {
    let mut descriptor = wgpu::InstanceDescriptor::new_without_display_handle_from_env();
    if let Some(backends) = BACKENDS.get() {
        descriptor.backends = *backends;
    }
    let instance = wgpu::Instance::new(descriptor);
    let adapter = pollster::block_on(wgpu::util::initialize_adapter_from_env_or_default(
        &instance, None,
    ))
    .map_err(|e| HarnessError::NoAdapter {
        backend: backend_env(),
        reason: e.to_string(),
    })?;
    let info = adapter.get_info();
    // Ask only for what skyscape can use; timestamps are optional (used for timing).
    let wanted = wgpu::Features::TIMESTAMP_QUERY | wgpu::Features::FLOAT32_FILTERABLE;
    let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
        label: Some("skyscape-harness"),
        required_features: adapter.features() & wanted,
        required_limits: adapter.limits(),
        ..Default::default()
    }))
    .map_err(|e| HarnessError::NoDevice {
        adapter: info.name.clone(),
        reason: e.to_string(),
    })?;
    Ok(GpuContext {
        adapter,
        device,
        queue,
        info,
    })
}

static CONTEXT: OnceLock<Result<GpuContext, String>> = OnceLock::new();

/// The process-wide GPU context, created on first use. Prints the adapter once.
pub fn context() -> Result<&'static GpuContext, HarnessError> {
    let result = CONTEXT.get_or_init(|| {
        let created = create_context();
        let mut err = std::io::stderr().lock();
        match &created {
            Ok(ctx) => {
                let _ = writeln!(err, "skyscape GPU: {}", describe_adapter(&ctx.info));
            }
            Err(e) => {
                let _ = writeln!(err, "skyscape GPU: none ({e})");
            }
        }
        created.map_err(|e| e.to_string())
    });
    result.as_ref().map_err(|reason| HarnessError::Unavailable {
        reason: reason.clone(),
    })
}

/// One line describing an adapter: name, backend, type, driver.
pub fn describe_adapter(info: &wgpu::AdapterInfo) -> String {
    format!(
        "{} ({:?}, {}, driver {} {})",
        info.name,
        info.backend,
        device_type_label(info.device_type),
        info.driver,
        info.driver_info
    )
}

/// A label that never lets a CPU adapter pass for a GPU.
pub fn device_type_label(kind: wgpu::DeviceType) -> &'static str {
    match kind {
        wgpu::DeviceType::Cpu => "CPU adapter (software rasteriser)",
        wgpu::DeviceType::DiscreteGpu => "discrete GPU",
        wgpu::DeviceType::IntegratedGpu => "integrated GPU",
        wgpu::DeviceType::VirtualGpu => "virtual GPU",
        wgpu::DeviceType::Other => "other adapter",
    }
}

/// The policy in one call, for tests:
/// `let Some(gpu) = skyscape_harness::gpu_or_skip("name") else { return };`
///
/// # Panics
/// When no adapter exists and `SKYSCAPE_REQUIRE_GPU=1` — that is the failure the
/// policy asks for.
pub fn gpu_or_skip(test_name: &str) -> Option<&'static GpuContext> {
    match context() {
        Ok(ctx) => Some(ctx),
        Err(e) if gpu_required() => {
            panic!("{test_name}: {REQUIRE_GPU_ENV}=1 but no GPU is usable: {e}")
        }
        Err(e) => {
            let _ = writeln!(
                std::io::stderr().lock(),
                "SKIPPED {test_name}: {e} (set {REQUIRE_GPU_ENV}=1 to make this a failure)"
            );
            None
        }
    }
}

impl GpuContext {
    /// Workgroup counts for `n` invocations of a 1-D kernel, folded into `y` past this
    /// device's `max_compute_workgroups_per_dimension`
    /// ([`skyscape_wgsl::dispatch::workgroups_1d`]).
    pub fn workgroups_1d(&self, n: u32, workgroup_size: u32) -> Result<[u32; 3], HarnessError> {
        let limit = self.device.limits().max_compute_workgroups_per_dimension;
        Ok(skyscape_wgsl::dispatch::workgroups_1d(
            n,
            workgroup_size,
            limit,
        )?)
    }

    /// Errors unless every feature in `features` is enabled on this device.
    pub fn require_features(&self, features: wgpu::Features) -> Result<(), HarnessError> {
        let missing = features - self.device.features();
        if missing.is_empty() {
            Ok(())
        } else {
            Err(HarnessError::MissingFeature {
                adapter: self.info.name.clone(),
                missing,
            })
        }
    }

    /// Errors unless `format` supports `usages` on this adapter.
    pub fn require_format(
        &self,
        format: wgpu::TextureFormat,
        usages: wgpu::TextureUsages,
    ) -> Result<(), HarnessError> {
        let have = self
            .adapter
            .get_texture_format_features(format)
            .allowed_usages;
        let missing = usages - have;
        if missing.is_empty() {
            Ok(())
        } else {
            Err(HarnessError::MissingFormatCapability {
                adapter: self.info.name.clone(),
                format,
                needed: missing,
            })
        }
    }

    /// Errors unless storage buffers of `bytes` can be bound.
    pub fn require_storage_binding(&self, bytes: u64) -> Result<(), HarnessError> {
        let have = self.device.limits().max_storage_buffer_binding_size;
        if have >= bytes {
            Ok(())
        } else {
            Err(HarnessError::LimitTooLow {
                adapter: self.info.name.clone(),
                limit: "max_storage_buffer_binding_size",
                have,
                need: bytes,
            })
        }
    }

    /// True for software adapters (lavapipe, llvmpipe, WARP): timings taken on them are
    /// CPU timings and must be labelled so.
    pub fn is_cpu_adapter(&self) -> bool {
        self.info.device_type == wgpu::DeviceType::Cpu
    }
}

/// Workgroup counts for `n` invocations of a 1-D kernel with `workgroup_size`, folded
/// into `y` past WebGPU's guaranteed `max_compute_workgroups_per_dimension`
/// (`wgpu::Limits::downlevel_defaults()`, 65,535), so they are valid on every device
/// without asking it; [`GpuContext::workgroups_1d`] uses the device's own limit.
/// Kernels recover the linear index as `gid.x + gid.y * num_workgroups.x * workgroup_size`.
///
/// # Panics
///
/// When `workgroup_size` is 0 (a caller's constant, never user input). Any `u32`
/// count fits for `workgroup_size >= 2`.
pub fn workgroups_1d(n: u32, workgroup_size: u32) -> [u32; 3] {
    let limit = wgpu::Limits::downlevel_defaults().max_compute_workgroups_per_dimension;
    match skyscape_wgsl::dispatch::workgroups_1d(n, workgroup_size, limit) {
        Ok(groups) => groups,
        Err(error) => panic!("workgroups_1d({n}, {workgroup_size}): {error}"),
    }
}

/// One compute dispatch over storage buffers, for [`run_compute`].
///
/// Bindings: `@group(0) @binding(i)` is `inputs[i]` (read-only storage) for
/// `i < inputs.len()`, and `@binding(inputs.len())` is the read-write output of
/// `output_bytes` bytes. `constants` set WGSL `override` values.
#[derive(Debug, Clone, Copy)]
pub struct ComputeJob<'a> {
    /// Label for wgpu objects and errors.
    pub label: &'a str,
    /// Composed WGSL (no `#import` left).
    pub source: &'a str,
    /// Entry point.
    pub entry: &'a str,
    /// `override` constants.
    pub constants: &'a [(&'a str, f64)],
    /// Read-only storage inputs, in binding order.
    pub inputs: &'a [&'a [u8]],
    /// Size of the output buffer in bytes.
    pub output_bytes: u64,
    /// Workgroup counts (see [`workgroups_1d`]).
    pub workgroups: [u32; 3],
}

/// Validates the job's WGSL with naga, runs it once and reads back the output.
pub fn run_compute(ctx: &GpuContext, job: &ComputeJob<'_>) -> Result<Vec<u8>, HarnessError> {
    let ComputeJob {
        label,
        source,
        entry,
        constants,
        inputs,
        output_bytes,
        workgroups,
    } = *job;
    use wgpu::util::DeviceExt as _;
    skyscape_wgsl::validate(label, source)?;
    let device = &ctx.device;
    let scope = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(label),
        layout: None,
        module: &module,
        entry_point: Some(entry),
        compilation_options: wgpu::PipelineCompilationOptions {
            constants,
            ..Default::default()
        },
        cache: None,
    });
    let input_buffers: Vec<wgpu::Buffer> = inputs
        .iter()
        .map(|bytes| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: wgpu::BufferUsages::STORAGE,
            })
        })
        .collect();
    let output = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: output_bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    });
    let mut entries: Vec<wgpu::BindGroupEntry> = input_buffers
        .iter()
        .enumerate()
        .map(|(i, b)| wgpu::BindGroupEntry {
            binding: i as u32,
            resource: b.as_entire_binding(),
        })
        .collect();
    entries.push(wgpu::BindGroupEntry {
        binding: inputs.len() as u32,
        resource: output.as_entire_binding(),
    });
    let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    });
    let mut encoder =
        device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some(label) });
    {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes: None,
        });
        pass.set_pipeline(&pipeline);
        pass.set_bind_group(0, &bind_group, &[]);
        pass.dispatch_workgroups(workgroups[0], workgroups[1], workgroups[2]);
    }
    ctx.queue.submit([encoder.finish()]);
    if let Some(error) = pollster::block_on(scope.pop()) {
        return Err(HarnessError::Wgpu {
            label: label.to_owned(),
            message: error.to_string(),
        });
    }
    read_buffer(ctx, label, &output, 0, output_bytes)
}

/// Copies `size` bytes at `offset` of a `COPY_SRC` buffer back to the CPU.
pub fn read_buffer(
    ctx: &GpuContext,
    label: &str,
    buffer: &wgpu::Buffer,
    offset: u64,
    size: u64,
) -> Result<Vec<u8>, HarnessError> {
    let device = &ctx.device;
    let staging = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape-harness readback"),
        size,
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor {
        label: Some("skyscape-harness readback"),
    });
    encoder.copy_buffer_to_buffer(buffer, offset, &staging, 0, size);
    ctx.queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    let readback_error = |message: String| HarnessError::Readback {
        label: label.to_owned(),
        message,
    };
    device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| readback_error(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| readback_error(e.to_string()))?
        .map_err(|e| readback_error(e.to_string()))?;
    let bytes = staging
        .get_mapped_range(..)
        .map_err(|e| readback_error(e.to_string()))?
        .to_vec();
    staging.unmap();
    Ok(bytes)
}

/// Copies every texel of a `COPY_SRC` texture (all array layers or depth slices, mip 0)
/// back to the CPU, tightly packed: layer-major, then rows, then texels (the rows'
/// 256-byte copy alignment removed). Formats with a block size of one texel only.
pub fn read_texture(
    ctx: &GpuContext,
    label: &str,
    texture: &wgpu::Texture,
) -> Result<Vec<u8>, HarnessError> {
    let readback_error = |message: String| HarnessError::Readback {
        label: label.to_owned(),
        message,
    };
    let size = texture.size();
    let texel_bytes = texture
        .format()
        .block_copy_size(None)
        .ok_or_else(|| readback_error(format!("{:?} has no single copy size", texture.format())))?;
    let row_bytes = size.width * texel_bytes;
    let padded_row =
        row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let layers = size.depth_or_array_layers;
    let staging = ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("skyscape-harness texture readback"),
        size: u64::from(padded_row) * u64::from(size.height) * u64::from(layers),
        usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let mut encoder = ctx
        .device
        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
            label: Some("skyscape-harness texture readback"),
        });
    encoder.copy_texture_to_buffer(
        wgpu::TexelCopyTextureInfo {
            texture,
            mip_level: 0,
            origin: wgpu::Origin3d::ZERO,
            aspect: wgpu::TextureAspect::All,
        },
        wgpu::TexelCopyBufferInfo {
            buffer: &staging,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row),
                rows_per_image: Some(size.height),
            },
        },
        size,
    );
    ctx.queue.submit([encoder.finish()]);
    let (sender, receiver) = std::sync::mpsc::channel();
    staging.map_async(wgpu::MapMode::Read, .., move |result| {
        let _ = sender.send(result);
    });
    ctx.device
        .poll(wgpu::PollType::wait_indefinitely())
        .map_err(|e| readback_error(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| readback_error(e.to_string()))?
        .map_err(|e| readback_error(e.to_string()))?;
    let padded = staging
        .get_mapped_range(..)
        .map_err(|e| readback_error(e.to_string()))?
        .to_vec();
    staging.unmap();
    Ok(padded
        .chunks(padded_row as usize)
        .flat_map(|row| &row[..row_bytes as usize])
        .copied()
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The folding itself is tested in `skyscape_wgsl::dispatch`; here, that the
    /// harness uses WebGPU's guaranteed limit and the device's own.
    #[test]
    fn workgroup_folding_uses_the_guaranteed_and_the_device_limit() {
        assert_eq!(workgroups_1d(65_535 * 64, 64), [65_535, 1, 1]);
        assert_eq!(workgroups_1d(65_535 * 64 + 1, 64), [32_768, 2, 1]);
        let Some(gpu) = gpu_or_skip("harness::workgroup_folding") else {
            return;
        };
        let limit = gpu.device.limits().max_compute_workgroups_per_dimension;
        assert!(
            limit >= 65_535,
            "WebGPU guarantees 65,535, the device says {limit}"
        );
        let [x, y, _] = gpu.workgroups_1d(u32::MAX, 64).unwrap();
        assert!(x <= limit && y <= limit);
        let row = limit.min(u32::MAX / 64);
        assert_eq!(gpu.workgroups_1d(row * 64, 64).unwrap(), [row, 1, 1]);
    }

    #[test]
    fn compute_round_trip_or_visible_skip() {
        let Some(gpu) = gpu_or_skip("harness::compute_round_trip") else {
            return;
        };
        let src = "@group(0) @binding(0) var<storage, read> a: array<f32>;\n\
                   @group(0) @binding(1) var<storage, read_write> out: array<f32>;\n\
                   override scale: f32 = 1.0;\n\
                   @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) gid: vec3<u32>) {\n\
                     if gid.x < arrayLength(&a) { out[gid.x] = a[gid.x] * scale; }\n\
                   }\n";
        let input: Vec<f32> = (0..100).map(|i| i as f32).collect();
        let out = run_compute(
            gpu,
            &ComputeJob {
                label: "round_trip",
                source: src,
                entry: "main",
                constants: &[("scale", 2.0)],
                inputs: &[bytemuck::cast_slice(&input)],
                output_bytes: 400,
                workgroups: workgroups_1d(100, 64),
            },
        )
        .unwrap();
        let out: &[f32] = bytemuck::cast_slice(&out);
        assert_eq!(out[99], 198.0);
    }

    #[test]
    fn invalid_shader_is_a_typed_error() {
        let Some(gpu) = gpu_or_skip("harness::invalid_shader") else {
            return;
        };
        let err = run_compute(
            gpu,
            &ComputeJob {
                label: "bad",
                source: "fn oops( {",
                entry: "main",
                constants: &[],
                inputs: &[],
                output_bytes: 4,
                workgroups: [1, 1, 1],
            },
        );
        assert!(matches!(err, Err(HarnessError::Shader(_))), "{err:?}");
    }

    #[test]
    fn pass_timer_measures_a_dispatch_that_does_work() {
        let Some(gpu) = gpu_or_skip("harness::pass_timer") else {
            return;
        };
        if gpu
            .device
            .features()
            .contains(wgpu::Features::TIMESTAMP_QUERY)
        {
            let module = gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("busy"),
                source: wgpu::ShaderSource::Wgsl(
                    "@group(0) @binding(0) var<storage, read_write> out: array<f32>;\n\
                     @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) gid: vec3<u32>) {\n\
                       var x = f32(gid.x);\n\
                       for (var i = 0u; i < 4096u; i++) { x = sin(x) + 1.0; }\n\
                       out[gid.x] = x;\n\
                     }\n"
                        .into(),
                ),
            });
            let pipeline = gpu
                .device
                .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some("busy"),
                    layout: None,
                    module: &module,
                    entry_point: Some("main"),
                    compilation_options: Default::default(),
                    cache: None,
                });
            let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("busy out"),
                size: 4 * 64 * 64,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            });
            let bind_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("busy"),
                layout: &pipeline.get_bind_group_layout(0),
                entries: &[wgpu::BindGroupEntry {
                    binding: 0,
                    resource: buffer.as_entire_binding(),
                }],
            });
            let seconds = median_pass_seconds(gpu, 3, |encoder, timer, span| {
                let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                    label: Some("busy"),
                    timestamp_writes: Some(timer.compute_writes(span)),
                });
                pass.set_pipeline(&pipeline);
                pass.set_bind_group(0, &bind_group, &[]);
                pass.dispatch_workgroups(64, 1, 1);
            })
            .unwrap();
            // 4096 × 4096 sines: microseconds on any real GPU, milliseconds on a CPU
            // adapter; never zero, never more than a few seconds.
            assert!(seconds > 0.0 && seconds < 5.0, "{seconds} s");
            eprintln!("pass timer: busy dispatch took {:.3} ms", seconds * 1e3);
        } else {
            let err = PassTimer::new(gpu, 1).unwrap_err();
            assert!(matches!(err, HarnessError::MissingFeature { .. }), "{err}");
        }
    }
}
