//! [`MarchPass`]: seed 003's view ray-march of a [`CloudVolume`] on a GPU
//! (`shaders/cloudlight/march_pass.wgsl`), bring your own device.
//!
//! [`MarchPass::new`] builds the pipeline; [`MarchPass::prepare`] uploads the volume's
//! density (a storage buffer read with manual trilinear interpolation, as the CPU's
//! [`CloudVolume::density_at`] does), the camera, settings and lighting, and creates the
//! output buffer and the bind group; [`MarchPass::encode`] only records one dispatch
//! (8×8 pixels per workgroup; [`MarchPass::encode_timed`] adds timestamp writes).
//! [`MarchPass::prepare_limited`] also binds a per-pixel distance buffer (`f32` metres
//! along each pixel's ray, x fastest, row 0 at the top) where each march stops: terrain
//! in front of or inside the cloud. A caller with a depth buffer converts depth to
//! distance along the ray itself.
//!
//! The output is a storage buffer of two `vec4<f32>` per pixel (x fastest, row 0 at the
//! top): `(radiance r, g, b, transmittance)` and `(depth, 0, 0, 0)` — the fields of
//! [`MarchResult`]; [`MarchPass::decode`] turns its bytes into them. The f32 CPU twin is
//! [`render_image::<f32>`](crate::march::render_image) on the same volume (whose density
//! lookup is f64 rounded once; the shader's is f32).

use crate::march::{Jitter, LightMarch, Lighting, MarchResult, MarchSettings, PinholeCamera};
use crate::shell_shadow::ShellField;
use crate::{CloudShell, CloudVolume};

/// Pixels per workgroup along each image axis.
pub const MARCH_WORKGROUP_SIZE: u32 = 8;

const PARAMS_BYTES: u64 = 240;

/// Bytes of `outside_shadow.wgsl`'s `OutsideShadowParams`.
const OUTSIDE_PARAMS_BYTES: u64 = 64;

/// Another cloud's shadow map a march reads (`shaders/cloudlight/outside_shadow.wgsl`,
/// bindings 8 and 9 of both passes): at each view sample `p` the light march's optical
/// depth gains that cloud's above `p`, read where `p`'s light ray meets the map's plane
/// ([`crate::shadow_map::shadow_map_texel`], bilinear between texel centres, 1 outside
/// the map, then [`crate::shadow_map::shadow_depth_above`]). The CPU twin is
/// [`crate::march::march_view_lit_through`] with that lookup as its `outside_depth`
/// (`render::mutual_shadow`). Altitudes are the march frame's height minus
/// `frame_height`.
///
/// The fields are [`crate::shadow_map::OutsideShadowMap`]'s, the CPU twin's, with the
/// values in a buffer: usage `STORAGE`, at least `4·resolution[0]·resolution[1]` bytes,
/// east fastest.
pub type OutsideShadow<'a> = crate::shadow_map::OutsideShadowMap<&'a wgpu::Buffer, f32>;

/// The uniform and values bound as bindings 8 and 9: `outside`'s, or a disabled uniform
/// and a 4-byte placeholder.
fn outside_bindings(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    outside: Option<&OutsideShadow<'_>>,
) -> Result<(wgpu::Buffer, wgpu::Buffer), MarchGpuError> {
    let f = |x: f32| x.to_bits();
    let words: [u32; 16] = match outside {
        None => [0; 16],
        Some(o) => {
            let needed = u64::from(o.resolution[0]) * u64::from(o.resolution[1]) * 4;
            let (bytes, usage) = (o.values.size(), o.values.usage());
            if needed == 0 || bytes < needed || !usage.contains(wgpu::BufferUsages::STORAGE) {
                return Err(MarchGpuError::OutsideShadowBuffer {
                    bytes,
                    usage,
                    needed,
                });
            }
            [
                f(o.origin[0]),
                f(o.origin[1]),
                f(o.cell_size),
                f(o.plane),
                f(o.to_light[0]),
                f(o.to_light[1]),
                f(o.to_light[2]),
                f(1.0),
                f(o.extent[0]),
                f(o.extent[1]),
                f(o.frame_height),
                0,
                o.resolution[0],
                o.resolution[1],
                0,
                0,
            ]
        }
    };
    let params = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("cloudlight march outside shadow"),
        size: OUTSIDE_PARAMS_BYTES,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
    let values = match outside {
        Some(o) => o.values.clone(),
        None => device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march no outside shadow"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        }),
    };
    Ok((params, values))
}

/// Errors of the march pass, naming the field and value.
#[derive(Debug, thiserror::Error)]
pub enum MarchGpuError {
    /// Composing the WGSL failed (a packaging bug).
    #[error(transparent)]
    Compose(#[from] skyscape_wgsl::ComposeError),
    /// A buffer is larger than the device lets a shader bind.
    #[error(
        "`{what}` needs {bytes} bytes but the device's max_storage_buffer_binding_size is {limit}"
    )]
    BufferTooLarge {
        /// `density`, `image` or `weather grid`.
        what: &'static str,
        /// Its size.
        bytes: u64,
        /// The device limit.
        limit: u64,
    },
    /// The image is empty or needs more workgroups along one axis than the device allows.
    #[error("{field} = {value} pixels: must be ≥ 1 and need at most {limit} workgroups")]
    ImageSize {
        /// `size.x` or `size.y`.
        field: &'static str,
        /// Pixels along it.
        value: u32,
        /// `max_compute_workgroups_per_dimension`.
        limit: u32,
    },
    /// The per-pixel distance buffer is too small or cannot be bound as storage.
    #[error(
        "max_distance buffer: {bytes} bytes with usage {usage:?}: needs ≥ {needed} bytes (one f32 per pixel) and STORAGE"
    )]
    DistanceBuffer {
        /// Its size.
        bytes: u64,
        /// Its usage.
        usage: wgpu::BufferUsages,
        /// `4·size[0]·size[1]`.
        needed: u64,
    },
    /// Another cloud's shadow map buffer is too small or cannot be bound as storage.
    #[error(
        "outside shadow values: {bytes} bytes with usage {usage:?}: needs ≥ {needed} bytes (one f32 per texel, ≥ 1 texel) and STORAGE"
    )]
    OutsideShadowBuffer {
        /// Its size.
        bytes: u64,
        /// Its usage.
        usage: wgpu::BufferUsages,
        /// `4·resolution[0]·resolution[1]`.
        needed: u64,
    },
    /// `encode` was called before `prepare`.
    #[error("encode before prepare: no image to march")]
    EncodeBeforePrepare,
    /// Bytes handed to [`MarchPass::decode`] have the wrong length.
    #[error("readback has {got} bytes, expected {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}

/// The composed WGSL of the march pass (entry point `march_main`).
pub fn compose_march_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    crate::composer().compose_module("cloudlight::march_pass")
}

/// What either march pass keeps from `prepare`: the bind group, the dispatch and the
/// output image; `_inputs` keeps the bound buffers alive.
#[derive(Debug)]
struct Prepared {
    bind_group: wgpu::BindGroup,
    workgroups: [u32; 2],
    size: [u32; 2],
    image: wgpu::Buffer,
    _inputs: Vec<wgpu::Buffer>,
}

/// The view march on a GPU (see the module documentation).
#[derive(Debug)]
pub struct MarchPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

/// The uniform block of `march_pass.wgsl` (`MarchParams`), as 60 words.
fn params_words(
    volume: &CloudVolume,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    limited: bool,
) -> [u32; 60] {
    let c = settings.config();
    let f = |x: f64| (x as f32).to_bits();
    let g = |x: f32| x.to_bits();
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half(size);
    let origin = camera.origin();
    let (lo, dims, voxel) = (volume.origin(), volume.dims(), volume.voxel_size());
    let hi: [f64; 3] = [0, 1, 2].map(|a| lo[a] + f64::from(dims[a]) * voxel);
    let (sun, irr, amb, amb_up) = (
        lighting.sun_direction(),
        lighting.sun_irradiance(),
        lighting.ambient_radiance(),
        lighting.up(),
    );
    let (mode, cone_step, spread, light_steps, jitter) = light_words(settings);
    [
        f(origin[0]),
        f(origin[1]),
        f(origin[2]),
        0,
        f(forward[0]),
        f(forward[1]),
        f(forward[2]),
        f(tan_half[0]),
        f(right[0]),
        f(right[1]),
        f(right[2]),
        f(tan_half[1]),
        f(up[0]),
        f(up[1]),
        f(up[2]),
        f(volume.extinction_per_density()),
        f(lo[0]),
        f(lo[1]),
        f(lo[2]),
        f(voxel),
        f(hi[0]),
        f(hi[1]),
        f(hi[2]),
        f(c.transmittance_epsilon),
        g(sun[0]),
        g(sun[1]),
        g(sun[2]),
        f(c.albedo),
        g(irr[0]),
        g(irr[1]),
        g(irr[2]),
        f(c.g_forward),
        g(amb[0]),
        g(amb[1]),
        g(amb[2]),
        f(c.g_back),
        g(amb_up[0]),
        g(amb_up[1]),
        g(amb_up[2]),
        f(c.back_weight),
        f(c.octaves.a),
        f(c.octaves.b),
        f(c.octaves.c),
        f(cone_step),
        f(spread),
        g(if limited { 1.0 } else { 0.0 }),
        0,
        0,
        dims[0],
        dims[1],
        dims[2],
        c.view_steps,
        size[0],
        size[1],
        jitter,
        mode,
        light_steps,
        c.octaves.count,
        u32::from(c.powder),
        c.ambient_steps,
    ]
}

/// A march pass's compute pipeline and its one bind group's layout: `bindings[i]` is
/// binding `i`'s buffer type and minimum size (both passes bind buffers only), then
/// bindings 8 and 9, another cloud's shadow ([`OutsideShadow`]).
fn march_pipeline(
    device: &wgpu::Device,
    source: &str,
    label: &str,
    entry_point: &str,
    bindings: &[(wgpu::BufferBindingType, Option<u64>)],
) -> (wgpu::ComputePipeline, wgpu::BindGroupLayout) {
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(label),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let entries: Vec<wgpu::BindGroupLayoutEntry> = bindings
        .iter()
        .enumerate()
        .map(|(binding, &(ty, min))| wgpu::BindGroupLayoutEntry {
            binding: binding as u32,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty,
                has_dynamic_offset: false,
                min_binding_size: min.and_then(wgpu::BufferSize::new),
            },
            count: None,
        })
        .chain(
            [
                // outside_shadow.wgsl's uniform and values (both passes import it).
                (
                    8,
                    wgpu::BufferBindingType::Uniform,
                    Some(OUTSIDE_PARAMS_BYTES),
                ),
                (
                    9,
                    wgpu::BufferBindingType::Storage { read_only: true },
                    None,
                ),
            ]
            .map(|(binding, ty, min)| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty,
                    has_dynamic_offset: false,
                    min_binding_size: min.and_then(wgpu::BufferSize::new),
                },
                count: None,
            }),
        )
        .collect();
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some(label),
        entries: &entries,
    });
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(&layout)],
        immediate_size: 0,
    });
    let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
        label: Some(entry_point),
        layout: Some(&pipeline_layout),
        module: &module,
        entry_point: Some(entry_point),
        compilation_options: wgpu::PipelineCompilationOptions::default(),
        cache: None,
    });
    (pipeline, layout)
}

impl MarchPass {
    /// Builds the pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, MarchGpuError> {
        use wgpu::BufferBindingType::{Storage, Uniform};
        let (pipeline, layout) = march_pipeline(
            device,
            &compose_march_shader()?,
            "cloudlight march",
            "march_main",
            &[
                (Uniform, Some(PARAMS_BYTES)),
                (Storage { read_only: true }, None),
                (Storage { read_only: false }, None),
                (Storage { read_only: true }, None),
            ],
        );
        Ok(Self {
            pipeline,
            layout,
            prepared: None,
        })
    }

    /// Uploads `volume`'s density, the camera, settings and lighting, creates the output
    /// buffer (`size[0] × size[1]` pixels) and the bind group [`MarchPass::encode`]
    /// records with. Takes effect at the next submit. Unlimited rays:
    /// [`MarchPass::prepare_limited`] with no distance buffer.
    #[allow(clippy::too_many_arguments)] // device, queue and the twin's five inputs
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        volume: &CloudVolume,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
    ) -> Result<(), MarchGpuError> {
        self.prepare_limited(
            device, queue, volume, camera, size, settings, lighting, None,
        )
    }

    /// [`MarchPass::prepare`] with each pixel's march stopped at a distance:
    /// `max_distance`, when given, holds one `f32` per pixel (x fastest, row 0 at the
    /// top), the metres along that pixel's ray where the march stops (`+∞`, or any value
    /// ≥ `f32::MAX`: no limit; ≤ 0: nothing marched; see
    /// [`march_view_limited`](crate::march::march_view_limited), whose NaN-as-none only
    /// holds on backends that keep NaN comparisons, so write `+∞`). It is bound
    /// as a read-only storage buffer (usage `STORAGE`, at least `4·size[0]·size[1]`
    /// bytes) and read when the pass runs, so the caller may write it on the GPU before
    /// it. A caller with a depth buffer converts depth to distance along the ray itself
    /// (the pass takes no projection). `None` is unlimited. The f32 CPU twin is
    /// [`render_image_limited::<f32>`](crate::march::render_image_limited).
    #[allow(clippy::too_many_arguments)] // device, queue, the twin's five inputs, the limit
    pub fn prepare_limited(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        volume: &CloudVolume,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
        max_distance: Option<&wgpu::Buffer>,
    ) -> Result<(), MarchGpuError> {
        self.prepare_lit_through(
            device,
            queue,
            volume,
            camera,
            size,
            settings,
            lighting,
            max_distance,
            None,
        )
    }

    /// [`MarchPass::prepare_limited`] with the light crossing another cloud too:
    /// `outside`, when given, is its shadow map toward `lighting`'s light
    /// ([`OutsideShadow`]; `None` is [`MarchPass::prepare_limited`]). The f32 CPU twin is
    /// [`march_view_lit_through::<f32>`](crate::march::march_view_lit_through) with the
    /// map's lookup as `outside_depth`.
    #[allow(clippy::too_many_arguments)] // device, queue, the twin's inputs, limit, map
    pub fn prepare_lit_through(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        volume: &CloudVolume,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
        max_distance: Option<&wgpu::Buffer>,
        outside: Option<&OutsideShadow<'_>>,
    ) -> Result<(), MarchGpuError> {
        let workgroups = march_workgroups(device, size)?;
        let limit = device.limits().max_storage_buffer_binding_size;
        let density_bytes = volume.density().len() as u64 * 4;
        if density_bytes > limit {
            return Err(MarchGpuError::BufferTooLarge {
                what: "density",
                bytes: density_bytes,
                limit,
            });
        }
        let image = march_image(device, "cloudlight march image", size, limit)?;
        let words = params_words(
            volume,
            camera,
            size,
            settings,
            lighting,
            max_distance.is_some(),
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march params"),
            size: PARAMS_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
        let density = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march density"),
            size: density_bytes,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&density, 0, bytemuck::cast_slice(volume.density()));
        let distance = distance_binding(device, max_distance, size)?;
        let (outside_params, outside_values) = outside_bindings(device, queue, outside)?;
        let bind_group = march_bind_group(
            device,
            &self.layout,
            "cloudlight march",
            &[
                (0, &params),
                (1, &density),
                (2, &image),
                (3, &distance),
                (8, &outside_params),
                (9, &outside_values),
            ],
        );
        self.prepared = Some(Prepared {
            bind_group,
            workgroups,
            size,
            image,
            _inputs: vec![params, density, distance, outside_params, outside_values],
        });
        Ok(())
    }

    /// Records the march's dispatch into `encoder` (one compute pass, untimed).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), MarchGpuError> {
        self.encode_timed(encoder, None)
    }

    /// [`MarchPass::encode`] with timestamp writes on its compute pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), MarchGpuError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(MarchGpuError::EncodeBeforePrepare)?;
        super::dispatch_2d(
            encoder,
            "cloudlight march",
            timestamp_writes,
            &self.pipeline,
            &prepared.bind_group,
            prepared.workgroups,
        );
        Ok(())
    }

    /// The output buffer (module documentation); `None` before `prepare`.
    pub fn image_buffer(&self) -> Option<&wgpu::Buffer> {
        self.prepared.as_ref().map(|p| &p.image)
    }

    /// The output buffer's size in bytes (0 before `prepare`).
    pub fn image_size(&self) -> u64 {
        self.prepared.as_ref().map_or(0, |p| p.image.size())
    }

    /// Turns the output buffer's bytes into one [`MarchResult`] per pixel (x fastest).
    pub fn decode(&self, bytes: &[u8]) -> Result<Vec<MarchResult<f32>>, MarchGpuError> {
        decode_pixels(bytes, self.prepared.as_ref())
    }
}

/// The composed WGSL of the shell march pass (entry point `march_shell_main`).
pub fn compose_march_shell_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    crate::composer().compose_module("cloudlight::march_shell_pass")
}

/// The light march's mode word, cone step and spread, light steps; the jitter's word.
fn light_words(settings: &MarchSettings) -> (u32, f64, f64, u32, u32) {
    let c = settings.config();
    let (mode, light_steps, cone_step, spread) = match c.light {
        LightMarch::Full { steps } => (0u32, steps.get(), 0.0, 0.0),
        LightMarch::Cone {
            step,
            spread,
            weights,
        } => (
            match weights {
                crate::cone::ConeWeights::Raw => 1,
                crate::cone::ConeWeights::Partitioned => 2,
            },
            0,
            step,
            spread,
        ),
    };
    let jitter = match c.jitter {
        Jitter::None => 0u32,
        Jitter::Bayer4x4 => 1,
        Jitter::InterleavedGradient => 2,
    };
    (mode, cone_step, spread, light_steps, jitter)
}

/// The uniform block of `march_shell_pass.wgsl` (`ShellMarchParams`), as 68 words; the
/// weather's words from `weather` (the shell's [`ShellField`], procedural or grid).
fn shell_params_words(
    shell: &CloudShell,
    weather: &ShellField<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    limited: bool,
) -> [u32; 68] {
    let c = settings.config();
    let s = shell.settings();
    let f = |x: f64| (x as f32).to_bits();
    let g = |x: f32| x.to_bits();
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half(size);
    let origin = camera.origin();
    let (sun, irr, amb, amb_up) = (
        lighting.sun_direction(),
        lighting.sun_irradiance(),
        lighting.ambient_radiance(),
        lighting.up(),
    );
    let (mode, cone_step, spread, light_steps, jitter) = light_words(settings);
    [
        f(origin[0]),
        f(origin[1]),
        f(origin[2]),
        f(shell.planet_radius()),
        f(forward[0]),
        f(forward[1]),
        f(forward[2]),
        f(tan_half[0]),
        f(right[0]),
        f(right[1]),
        f(right[2]),
        f(tan_half[1]),
        f(up[0]),
        f(up[1]),
        f(up[2]),
        f(s.extinction_per_density),
        f(s.inner_radius),
        f(s.outer_radius),
        f(s.shape_period),
        f(s.detail_period),
        f(s.erosion),
        f(s.horizon_fade_start),
        f(s.horizon_fade_end),
        f(c.transmittance_epsilon),
        g(weather.weather_period),
        g(weather.coverage_mean),
        g(weather.coverage_contrast),
        g(weather.cloud_type_mean),
        g(weather.cloud_type_contrast),
        f(c.albedo),
        f(cone_step),
        f(spread),
        g(sun[0]),
        g(sun[1]),
        g(sun[2]),
        f(c.g_forward),
        g(irr[0]),
        g(irr[1]),
        g(irr[2]),
        f(c.g_back),
        g(amb[0]),
        g(amb[1]),
        g(amb[2]),
        f(c.back_weight),
        g(amb_up[0]),
        g(amb_up[1]),
        g(amb_up[2]),
        g(weather.grid_cell_size),
        f(c.octaves.a),
        f(c.octaves.b),
        f(c.octaves.c),
        g(if limited { 1.0 } else { 0.0 }),
        s.seed,
        weather.weather_seed,
        weather.weather_cells,
        c.view_steps,
        size[0],
        size[1],
        jitter,
        mode,
        light_steps,
        c.octaves.count,
        u32::from(c.powder),
        c.ambient_steps,
        weather.weather_kind,
        weather.grid_size[0],
        weather.grid_size[1],
        0,
    ]
}

const SHELL_PARAMS_BYTES: u64 = 272;

/// The view march of a procedural [`CloudShell`] on a GPU
/// (`shaders/cloudlight/march_shell_pass.wgsl`): the same output layout as
/// [`MarchPass`], each pixel faded toward the horizon at its depth. The f32 CPU twin is
/// [`render_image::<f32>`](crate::march::render_image) on the shell, each pixel then
/// [`faded`](crate::march::faded) by [`CloudShell::horizon_fade`] of its depth. The camera
/// is planet-centred (metres). The weather is procedural or a user grid
/// ([`crate::shell::WeatherMap`]; a grid's coverage and cloud type uploaded in `prepare`
/// to a storage buffer, binding 3, and looked up as [`CloudShell::weather_at`] does).
#[derive(Debug)]
pub struct MarchShellPass {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
}

impl MarchShellPass {
    /// Builds the pipeline on `device`.
    pub fn new(device: &wgpu::Device) -> Result<Self, MarchGpuError> {
        use wgpu::BufferBindingType::{Storage, Uniform};
        let (pipeline, layout) = march_pipeline(
            device,
            &compose_march_shell_shader()?,
            "cloudlight march shell",
            "march_shell_main",
            &[
                (Uniform, Some(SHELL_PARAMS_BYTES)),
                (Storage { read_only: false }, None),
                (Storage { read_only: true }, None),
                // The weather grid's cells (a one-cell placeholder for procedural).
                (Storage { read_only: true }, Some(8)),
            ],
        );
        Ok(Self {
            pipeline,
            layout,
            prepared: None,
        })
    }

    /// Uploads the shell, camera, settings and lighting, creates the output buffer
    /// (`size[0] × size[1]` pixels) and the bind group. Takes effect at the next submit.
    /// Unlimited rays: [`MarchShellPass::prepare_limited`] with no distance buffer.
    #[allow(clippy::too_many_arguments)] // device, queue and the twin's five inputs
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        shell: &CloudShell,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
    ) -> Result<(), MarchGpuError> {
        self.prepare_limited(device, queue, shell, camera, size, settings, lighting, None)
    }

    /// [`MarchShellPass::prepare`] with each pixel's march stopped at a distance: the
    /// per-pixel `max_distance` buffer as [`MarchPass::prepare_limited`]'s (one `f32`
    /// per pixel, metres along the ray, x fastest, row 0 at the top; a caller with a depth
    /// buffer converts depth to distance itself; `None` is unlimited). The spans are
    /// clipped before the march and the horizon fade is applied at the limited march's
    /// depth. The f32 CPU twin is
    /// [`render_image_limited::<f32>`](crate::march::render_image_limited) on the shell,
    /// each pixel then [`faded`](crate::march::faded).
    #[allow(clippy::too_many_arguments)] // device, queue, the twin's five inputs, the limit
    pub fn prepare_limited(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        shell: &CloudShell,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
        max_distance: Option<&wgpu::Buffer>,
    ) -> Result<(), MarchGpuError> {
        self.prepare_lit_through(
            device,
            queue,
            shell,
            camera,
            size,
            settings,
            lighting,
            max_distance,
            None,
        )
    }

    /// [`MarchShellPass::prepare_limited`] with the light crossing another cloud too
    /// (`outside`: its shadow map toward `lighting`'s light, [`OutsideShadow`], its
    /// `frame_height` the planet's radius; `None` is
    /// [`MarchShellPass::prepare_limited`]). The f32 CPU twin is
    /// [`march_view_lit_through::<f32>`](crate::march::march_view_lit_through) with the
    /// map's lookup as `outside_depth`, then [`faded`](crate::march::faded).
    #[allow(clippy::too_many_arguments)] // device, queue, the twin's inputs, limit, map
    pub fn prepare_lit_through(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        shell: &CloudShell,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
        max_distance: Option<&wgpu::Buffer>,
        outside: Option<&OutsideShadow<'_>>,
    ) -> Result<(), MarchGpuError> {
        let weather = ShellField::<f32>::of(shell);
        let workgroups = march_workgroups(device, size)?;
        let limit = device.limits().max_storage_buffer_binding_size;
        let image = march_image(device, "cloudlight march shell image", size, limit)?;
        let weather_grid = super::weather_grid_buffer(
            device,
            queue,
            &weather,
            "cloudlight march shell weather grid",
            limit,
        )
        .map_err(|bytes| MarchGpuError::BufferTooLarge {
            what: "weather grid",
            bytes,
            limit,
        })?;
        let words = shell_params_words(
            shell,
            &weather,
            camera,
            size,
            settings,
            lighting,
            max_distance.is_some(),
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march shell params"),
            size: SHELL_PARAMS_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
        let distance = distance_binding(device, max_distance, size)?;
        let (outside_params, outside_values) = outside_bindings(device, queue, outside)?;
        let bind_group = march_bind_group(
            device,
            &self.layout,
            "cloudlight march shell",
            &[
                (0, &params),
                (1, &image),
                (2, &distance),
                (3, &weather_grid),
                (8, &outside_params),
                (9, &outside_values),
            ],
        );
        self.prepared = Some(Prepared {
            bind_group,
            workgroups,
            size,
            image,
            _inputs: vec![
                params,
                distance,
                weather_grid,
                outside_params,
                outside_values,
            ],
        });
        Ok(())
    }

    /// Records the march's dispatch into `encoder` (one compute pass, untimed).
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), MarchGpuError> {
        self.encode_timed(encoder, None)
    }

    /// [`MarchShellPass::encode`] with timestamp writes on its compute pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), MarchGpuError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(MarchGpuError::EncodeBeforePrepare)?;
        super::dispatch_2d(
            encoder,
            "cloudlight march shell",
            timestamp_writes,
            &self.pipeline,
            &prepared.bind_group,
            prepared.workgroups,
        );
        Ok(())
    }

    /// The output buffer (as [`MarchPass`]'s); `None` before `prepare`.
    pub fn image_buffer(&self) -> Option<&wgpu::Buffer> {
        self.prepared.as_ref().map(|p| &p.image)
    }

    /// The output buffer's size in bytes (0 before `prepare`).
    pub fn image_size(&self) -> u64 {
        self.prepared.as_ref().map_or(0, |p| p.image.size())
    }

    /// Turns the output buffer's bytes into one [`MarchResult`] per pixel (x fastest).
    pub fn decode(&self, bytes: &[u8]) -> Result<Vec<MarchResult<f32>>, MarchGpuError> {
        decode_pixels(bytes, self.prepared.as_ref())
    }
}

/// The buffer bound as `max_distance`: the caller's (checked) or a 4-byte placeholder the
/// shader does not read (its flag word is 0).
fn distance_binding(
    device: &wgpu::Device,
    max_distance: Option<&wgpu::Buffer>,
    size: [u32; 2],
) -> Result<wgpu::Buffer, MarchGpuError> {
    let Some(buffer) = max_distance else {
        return Ok(device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("cloudlight march no max_distance"),
            size: 4,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        }));
    };
    let needed = u64::from(size[0]) * u64::from(size[1]) * 4;
    let (bytes, usage) = (buffer.size(), buffer.usage());
    if bytes < needed || !usage.contains(wgpu::BufferUsages::STORAGE) {
        return Err(MarchGpuError::DistanceBuffer {
            bytes,
            usage,
            needed,
        });
    }
    Ok(buffer.clone())
}

/// The workgroups of a `size` image ([`MARCH_WORKGROUP_SIZE`]² pixels each), within the
/// device's limit per dimension.
fn march_workgroups(device: &wgpu::Device, size: [u32; 2]) -> Result<[u32; 2], MarchGpuError> {
    let limit = device.limits().max_compute_workgroups_per_dimension;
    let mut workgroups = [0u32; 2];
    for (k, (field, value)) in ["size.x", "size.y"].into_iter().zip(size).enumerate() {
        let groups = value.div_ceil(MARCH_WORKGROUP_SIZE);
        if value == 0 || groups > limit {
            return Err(MarchGpuError::ImageSize {
                field,
                value,
                limit,
            });
        }
        workgroups[k] = groups;
    }
    Ok(workgroups)
}

/// The output buffer of a `size` image (two `vec4<f32>` per pixel), within the storage
/// binding `limit`.
fn march_image(
    device: &wgpu::Device,
    label: &str,
    size: [u32; 2],
    limit: u64,
) -> Result<wgpu::Buffer, MarchGpuError> {
    let bytes = u64::from(size[0]) * u64::from(size[1]) * 32;
    if bytes > limit {
        return Err(MarchGpuError::BufferTooLarge {
            what: "image",
            bytes,
            limit,
        });
    }
    Ok(device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: bytes,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    }))
}

/// A march pass's bind group: each buffer whole at its binding.
fn march_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    label: &str,
    buffers: &[(u32, &wgpu::Buffer)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry<'_>> = buffers
        .iter()
        .map(|&(binding, buffer)| wgpu::BindGroupEntry {
            binding,
            resource: buffer.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout,
        entries: &entries,
    })
}

/// The output buffer's bytes as one [`MarchResult`] per pixel of `prepared`'s image
/// (none before `prepare`: a size error).
fn decode_pixels(
    bytes: &[u8],
    prepared: Option<&Prepared>,
) -> Result<Vec<MarchResult<f32>>, MarchGpuError> {
    let expected = prepared.map_or(0, |p| p.size[0] as usize * p.size[1] as usize * 32);
    if bytes.len() != expected || expected == 0 {
        return Err(MarchGpuError::ReadbackSize {
            got: bytes.len(),
            expected,
        });
    }
    Ok(bytes
        .chunks_exact(32)
        .map(|b| {
            let w: [f32; 8] = std::array::from_fn(|k| {
                f32::from_ne_bytes([b[4 * k], b[4 * k + 1], b[4 * k + 2], b[4 * k + 3]])
            });
            MarchResult {
                radiance: [w[0], w[1], w[2]],
                transmittance: w[3],
                depth: w[4],
            }
        })
        .collect())
}
