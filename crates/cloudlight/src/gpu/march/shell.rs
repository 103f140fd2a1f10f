//! [`MarchShellPass`]: the march over a procedural [`CloudShell`].

use super::shared::*;
use super::*;
use crate::CloudShell;
use crate::march::{Lighting, MarchResult, MarchSettings, PinholeCamera};
use crate::shell_shadow::ShellField;

/// The composed WGSL of the shell march pass (entry point `march_shell_main`).
pub fn compose_march_shell_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    crate::composer().compose_module("cloudlight::march_shell_pass")
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
        let weather_grid = crate::gpu::weather_grid_buffer(
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
        crate::gpu::dispatch_2d(
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
