//! [`FieldMarchPass`]: the view march over any [`MarchedField`], one pass whose fields
//! differ only in their density source's bindings and their entry.

use std::marker::PhantomData;

use super::shared::*;
use super::stage::StagePass;
use super::*;
use crate::gpu::density_source::{GpuDensitySource, SourceBuffers, compose_over};
use crate::march::{Lighting, MarchResult, MarchSettings, PinholeCamera};
use crate::{CloudShell, CloudVolume};

/// A field the view march runs over: its density source and the pass's entry (a thin
/// WGSL file around `field_march.wgsl`'s `march_pixel`, one per-pixel function called
/// from a fragment and a compute entry point).
pub trait MarchedField: GpuDensitySource {
    /// The entry's module.
    const ENTRY: &'static str;
    /// The fragment entry point ([`MarchStage::Fragment`]).
    const FRAGMENT_ENTRY_POINT: &'static str;
    /// The compute entry point ([`MarchStage::Compute`]).
    const COMPUTE_ENTRY_POINT: &'static str;
    /// The pass's label.
    const LABEL: &'static str;

    /// The start and end (m) of the fade toward the horizon the entry applies at each
    /// pixel's depth (`[0, 0]` for an entry that applies none).
    fn horizon_fade(&self) -> [f64; 2];
}

/// `march_pass.wgsl`: the volume's image as marched.
impl MarchedField for CloudVolume {
    const ENTRY: &'static str = "cloudlight::march_pass";
    const FRAGMENT_ENTRY_POINT: &'static str = "march_fragment";
    const COMPUTE_ENTRY_POINT: &'static str = "march_main";
    const LABEL: &'static str = "cloudlight march";

    fn horizon_fade(&self) -> [f64; 2] {
        [0.0, 0.0]
    }
}

/// `march_shell_pass.wgsl`: each pixel faded by [`CloudShell::horizon_fade`] of its depth.
impl MarchedField for CloudShell {
    const ENTRY: &'static str = "cloudlight::march_shell_pass";
    const FRAGMENT_ENTRY_POINT: &'static str = "march_shell_fragment";
    const COMPUTE_ENTRY_POINT: &'static str = "march_shell_main";
    const LABEL: &'static str = "cloudlight march shell";

    fn horizon_fade(&self) -> [f64; 2] {
        let s = self.settings();
        [s.horizon_fade_start, s.horizon_fade_end]
    }
}

/// The composed WGSL of the march pass over a [`CloudVolume`] (entry points
/// `march_fragment` and `march_main`).
pub fn compose_march_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    compose_over::<CloudVolume>(CloudVolume::ENTRY)
}

/// The composed WGSL of the shell march pass (entry points `march_shell_fragment` and
/// `march_shell_main`).
pub fn compose_march_shell_shader() -> Result<String, skyscape_wgsl::ComposeError> {
    compose_over::<CloudShell>(CloudShell::ENTRY)
}

/// Bytes of `field_march.wgsl`'s `MarchParams`.
const PARAMS_BYTES: u64 = 208;

/// `field_march.wgsl`'s `MarchParams`, as 52 words.
fn params_words(
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    horizon_fade: [f64; 2],
    limited: bool,
    phase: Option<u32>,
) -> [u32; 52] {
    let c = settings.config();
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
        f(c.albedo),
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
        f(c.transmittance_epsilon),
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
        f(cone_step),
        f(c.octaves.a),
        f(c.octaves.b),
        f(c.octaves.c),
        f(spread),
        f(horizon_fade[0]),
        f(horizon_fade[1]),
        0,
        0,
        size[0],
        size[1],
        jitter,
        mode,
        light_steps,
        c.octaves.count,
        u32::from(c.powder),
        c.ambient_steps,
        c.view_steps,
        u32::from(limited),
        u32::from(phase.is_some()),
        phase.unwrap_or(0),
    ]
}

/// The view march of a field `F` on a GPU (see the module documentation):
/// [`MarchPass`] for a [`CloudVolume`], [`MarchShellPass`] for a [`CloudShell`].
#[derive(Debug)]
pub struct FieldMarchPass<F> {
    /// The pipeline on its stage (and the fragment stage's attachment).
    stage: StagePass,
    layout: wgpu::BindGroupLayout,
    prepared: Option<Prepared>,
    /// The temporal amortisation's phase for the next `prepare` (`None`: every pixel).
    phase: Option<u32>,
    field: PhantomData<fn(&F)>,
}

/// The view march of a [`CloudVolume`] (`shaders/cloudlight/march_pass.wgsl`). The f32
/// CPU twin is [`render_image::<f32>`](crate::march::render_image) on the same volume
/// (whose density lookup is f64 rounded once; the shader's is f32).
pub type MarchPass = FieldMarchPass<CloudVolume>;

/// The view march of a procedural [`CloudShell`]
/// (`shaders/cloudlight/march_shell_pass.wgsl`): the same output layout as
/// [`MarchPass`], each pixel faded toward the horizon at its depth. The f32 CPU twin is
/// [`render_image::<f32>`](crate::march::render_image) on the shell, each pixel then
/// [`faded`](crate::march::faded) by [`CloudShell::horizon_fade`] of its depth. The camera
/// is planet-centred (metres). The weather is procedural or a user grid
/// ([`crate::shell::WeatherMap`]; a grid's coverage and cloud type uploaded in `prepare`
/// to the source's storage buffer and looked up as [`CloudShell::weather_at`] does).
pub type MarchShellPass = FieldMarchPass<CloudShell>;

impl<F: MarchedField> FieldMarchPass<F> {
    /// Builds the pipeline on `device`: on the fragment stage where the device accepts
    /// it (fragment shaders that write storage buffers, what
    /// [`MarchStage::supported`] reads from an adapter's downlevel flags), otherwise on
    /// the compute stage. [`FieldMarchPass::stage`] says which.
    pub fn new(device: &wgpu::Device) -> Result<Self, MarchGpuError> {
        match Self::with_stage(device, MarchStage::Fragment) {
            Err(MarchGpuError::Pipeline { .. }) => Self::with_stage(device, MarchStage::Compute),
            built => built,
        }
    }

    /// Builds the pipeline on `stage` (a caller that knows its adapter's
    /// [`MarchStage::supported`], or a comparison of the two stages); a stage the device
    /// refuses is [`MarchGpuError::Pipeline`].
    pub fn with_stage(device: &wgpu::Device, stage: MarchStage) -> Result<Self, MarchGpuError> {
        use wgpu::BufferBindingType::{Storage, Uniform};
        let entries = march_layout_entries::<F>(
            stage.visibility(),
            &[
                (Uniform, Some(PARAMS_BYTES)),
                (Storage { read_only: false }, None),
                (Storage { read_only: true }, None),
            ],
        );
        let entry_point = match stage {
            MarchStage::Fragment => F::FRAGMENT_ENTRY_POINT,
            MarchStage::Compute => F::COMPUTE_ENTRY_POINT,
        };
        let (stage, layout) = StagePass::new(
            device,
            stage,
            &compose_over::<F>(F::ENTRY)?,
            F::LABEL,
            entry_point,
            &entries,
        )?;
        Ok(Self {
            stage,
            layout,
            prepared: None,
            phase: None,
            field: PhantomData,
        })
    }

    /// The stage the per-pixel march runs on.
    pub fn stage(&self) -> MarchStage {
        self.stage.stage()
    }

    /// Marches, from the next `prepare` on, only the pixels a
    /// [`TemporalMarch`](crate::gpu::TemporalMarch)'s reprojection leaves to it in frame
    /// `phase` (0..3); `None` (the default) marches every pixel. Set by
    /// [`TemporalMarch::phase`](crate::gpu::TemporalMarch::phase).
    pub fn set_phase(&mut self, phase: Option<u32>) {
        self.phase = phase.map(|p| p % 4);
    }

    /// The prepared parameters' buffer and words, and the image's size.
    pub(crate) fn prepared_params(&self) -> Option<(&wgpu::Buffer, &[u32; 52], [u32; 2])> {
        self.prepared
            .as_ref()
            .map(|p| (&p._inputs[0], &p.params, p.size))
    }

    /// Uploads the field (its density source), the camera, settings and lighting,
    /// creates the output buffer (`size[0] × size[1]` pixels), the bind group
    /// [`FieldMarchPass::encode`] records with and, on the fragment stage, the
    /// attachment when the size changed. Takes effect at the next submit.
    /// Unlimited rays: [`FieldMarchPass::prepare_limited`] with no distance buffer.
    #[allow(clippy::too_many_arguments)] // device, queue and the twin's five inputs
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        field: &F,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
    ) -> Result<(), MarchGpuError> {
        self.prepare_limited(device, queue, field, camera, size, settings, lighting, None)
    }

    /// [`FieldMarchPass::prepare`] with each pixel's march stopped at a distance:
    /// `max_distance`, when given, holds one `f32` per pixel (x fastest, row 0 at the
    /// top), the metres along that pixel's ray where the march stops (`+∞`, or any value
    /// ≥ `f32::MAX`: no limit; ≤ 0: nothing marched; see
    /// [`march_view_limited`](crate::march::march_view_limited), whose NaN-as-none only
    /// holds on backends that keep NaN comparisons, so write `+∞`). It is bound
    /// as a read-only storage buffer (usage `STORAGE`, at least `4·size[0]·size[1]`
    /// bytes) and read when the pass runs, so the caller may write it on the GPU before
    /// it. A caller with a depth buffer converts depth to distance along the ray itself
    /// (the pass takes no projection). `None` is unlimited. The field's spans are clipped
    /// before the march (a shell's horizon fade is applied at the limited march's depth).
    /// The f32 CPU twin is
    /// [`render_image_limited::<f32>`](crate::march::render_image_limited) (for a shell,
    /// each pixel then [`faded`](crate::march::faded)).
    #[allow(clippy::too_many_arguments)] // device, queue, the twin's five inputs, the limit
    pub fn prepare_limited(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        field: &F,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
        max_distance: Option<&wgpu::Buffer>,
    ) -> Result<(), MarchGpuError> {
        self.prepare_lit_through(
            device,
            queue,
            field,
            camera,
            size,
            settings,
            lighting,
            max_distance,
            None,
        )
    }

    /// [`FieldMarchPass::prepare_limited`] with the light crossing another cloud too:
    /// `outside`, when given, is its shadow map toward `lighting`'s light
    /// ([`OutsideShadow`], its `frame_height` the march frame's height of altitude 0:
    /// the planet's radius for a shell; `None` is [`FieldMarchPass::prepare_limited`]).
    /// The f32 CPU twin is
    /// [`march_view_lit_through::<f32>`](crate::march::march_view_lit_through) with the
    /// map's lookup as `outside_depth` (for a shell, then [`faded`](crate::march::faded)).
    #[allow(clippy::too_many_arguments)] // device, queue, the twin's inputs, limit, map
    pub fn prepare_lit_through(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        field: &F,
        camera: &PinholeCamera,
        size: [u32; 2],
        settings: &MarchSettings,
        lighting: &Lighting<f32>,
        max_distance: Option<&wgpu::Buffer>,
        outside: Option<&OutsideShadow<'_>>,
    ) -> Result<(), MarchGpuError> {
        self.stage.prepare(device, F::LABEL, size)?;
        let limit = device.limits().max_storage_buffer_binding_size;
        let source =
            SourceBuffers::upload(device, queue, field, F::LABEL, limit).map_err(|bytes| {
                MarchGpuError::BufferTooLarge {
                    what: F::CELLS,
                    bytes,
                    limit,
                }
            })?;
        let image = march_image(device, &format!("{} image", F::LABEL), size, limit)?;
        let words = params_words(
            camera,
            size,
            settings,
            lighting,
            field.horizon_fade(),
            max_distance.is_some(),
            self.phase,
        );
        let params = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(&format!("{} params", F::LABEL)),
            size: PARAMS_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        queue.write_buffer(&params, 0, bytemuck::cast_slice(&words));
        let distance = distance_binding(device, max_distance, size)?;
        let (outside_params, outside_values) = outside_bindings(device, queue, outside)?;
        let bind_group = march_bind_group(
            device,
            &self.layout,
            F::LABEL,
            &[
                (0, &params),
                (1, &image),
                (2, &distance),
                (8, &outside_params),
                (9, &outside_values),
            ],
            &source,
        );
        self.prepared = Some(Prepared {
            bind_group,
            size,
            image,
            params: words,
            _inputs: vec![params, distance, outside_params, outside_values],
            _source: source,
        });
        Ok(())
    }

    /// Records the march into `encoder` (one pass of its own, untimed): a render pass
    /// drawing the full-screen triangle on the fragment stage, a compute pass of one
    /// dispatch on the compute stage.
    pub fn encode(&self, encoder: &mut wgpu::CommandEncoder) -> Result<(), MarchGpuError> {
        self.encode_timed(encoder, None)
    }

    /// [`FieldMarchPass::encode`] with timestamp writes on its pass. They are a render
    /// pass's, the stage [`FieldMarchPass::new`] chooses wherever it can; on the compute
    /// stage the same query set and indices go on its compute pass.
    pub fn encode_timed(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), MarchGpuError> {
        let prepared = self
            .prepared
            .as_ref()
            .ok_or(MarchGpuError::EncodeBeforePrepare)?;
        self.stage.record(
            encoder,
            F::LABEL,
            timestamp_writes,
            &prepared.bind_group,
            prepared.size,
        )
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
