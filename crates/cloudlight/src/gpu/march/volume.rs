//! [`MarchPass`]: the march over a [`CloudVolume`] grid.

use super::shared::*;
use super::*;
use crate::CloudVolume;
use crate::march::{Lighting, MarchResult, MarchSettings, PinholeCamera};

/// The composed WGSL of the march pass (entry point `march_main`).
pub fn compose_march_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    crate::composer().compose_module("cloudlight::march_pass")
}

const PARAMS_BYTES: u64 = 240;

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
        crate::gpu::dispatch_2d(
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
