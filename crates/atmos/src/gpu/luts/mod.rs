//! The precomputed rung's lookup tables on the GPU: textures a caller can bind in their
//! own pipelines, and the compute passes that bake them (one WGSL file per pass in
//! `shaders/atmos/lut_*.wgsl`). Bring your own device: [`AtmosphereLuts::new`] creates
//! the textures, bind groups and pipelines (uniforms initialised at creation, no queue
//! work), [`AtmosphereLuts::prepare`] writes the frame camera, and each `encode_*`
//! records one compute pass into the caller's encoder, optionally timed.
//!
//! **Reading the tables in your own shader.** The lookups of `atmos::lut_sampling`
//! (`lookup_transmittance`, `lookup_sky_view`, `lookup_aerial_perspective`,
//! `sun_transmittance`, …) read module-scope bindings declared by
//! `atmos::lut_bindings`: the uniforms (atmosphere, settings, frame camera) in one bind
//! group and the tables in another. Compose your shader with
//! [`composer_with_lut_groups`] to put them at the groups your pipeline has free, put
//! [`LutLayouts::uniforms`] and [`LutLayouts::tables`] at those indices of your
//! pipeline layout, and set the view's [`AtmosphereView::uniform_bind_group`] and
//! [`AtmosphereView::table_bind_group`] there (or [`AtmosphereLuts`]' own).
//!
//! | group (default) | binding | WGSL name | resource |
//! |---|---|---|---|
//! | uniforms (0) | 0 | `lut_atmosphere` | `AtmosphereParameters` |
//! | uniforms (0) | 1 | `lut_settings` | `LutSettings` ([`crate::lut::LutSettingsUniform`]) |
//! | uniforms (0) | 2 | `frame_camera` | [`FrameCamera`](crate::frame::FrameCamera) |
//! | uniforms (0) | 3 | `frame_view` | [`FrameView`](crate::view::FrameView) |
//! | tables (1) | 0 | `transmittance_lut` | `texture_2d<f32>` |
//! | tables (1) | 1 | `multiple_scattering_lut` | `texture_2d_array<f32>`, 6 layers |
//! | tables (1) | 2 | `sky_view_lut` | `texture_2d_array<f32>`: radiance, transmittance |
//! | tables (1) | 3 | `aerial_perspective_radiance` | `texture_3d<f32>` |
//! | tables (1) | 4 | `aerial_perspective_transmittance` | `texture_3d<f32>` |
//! | tables (1) | 5 | `sky_irradiance_lut` | `texture_2d_array<f32>`, one layer per normal |
//!
//! Every table is `rgba32float` (the CPU twin's values exactly; writable by compute
//! passes on every WebGPU adapter), read with `textureLoad` and filtered by hand in
//! the WGSL, so no sampler is needed and adapters without float32 filtering work.
//! Texel (x, y) of layer m is entry `x + w·(y + h·m)` of the CPU twin's table.

mod create;
mod encode;
mod passes;
mod view;

pub(crate) use passes::compute_pipeline;
use passes::{BakePass, Table, ViewBakes};

use crate::AtmosError;
use crate::gpu::resources::{float_texture_entry, shared_uniform_entry};
use crate::lut::LutSettingsUniform;
use wgpu::TextureViewDimension as Dim;

const WORKGROUP: u32 = 8;
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The WGSL of `atmos::lut_bindings` with its uniforms at `@group(uniform_group)` and
/// its tables at `@group(table_group)`: the file's own text, the two group attributes
/// rewritten (nothing else differs).
pub fn lut_bindings_wgsl(uniform_group: u32, table_group: u32) -> String {
    let source = include_str!("../../../shaders/lut_bindings.wgsl");
    source
        .lines()
        .map(|line| {
            if let Some(rest) = line.strip_prefix("@group(0) ") {
                format!("@group({uniform_group}) {rest}")
            } else if let Some(rest) = line.strip_prefix("@group(1) ") {
                format!("@group({table_group}) {rest}")
            } else {
                line.to_owned()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A composer that knows every module of `atmos` (and the common ones), with the LUT
/// bindings (`atmos::lut_bindings`) at the groups a caller's pipeline has free: compose
/// your shader, which `#import`s `atmos::lut_sampling`, with it. Errors when the two
/// groups are equal (they hold different layouts).
pub fn composer_with_lut_groups(
    uniform_group: u32,
    table_group: u32,
) -> Result<skyscape_wgsl::Composer, AtmosError> {
    if uniform_group == table_group {
        return Err(AtmosError::InvalidSetting {
            setting: "LUT bind groups",
            field: "table_group".to_owned(),
            value: f64::from(table_group),
            reason: "must differ from uniform_group (the uniforms and the tables are two layouts)",
        });
    }
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer
        .add_modules(crate::WGSL_MODULES)
        .expect("atmos WGSL module names are unique and well formed");
    let bindings = lut_bindings_wgsl(uniform_group, table_group);
    // `Module` holds `&'static str`: a composer lives for a pipeline's creation, and
    // one bindings text per (uniform, table) pair a program asks for is leaked once.
    let bindings: &'static str = Box::leak(bindings.into_boxed_str());
    let modules: Vec<skyscape_wgsl::Module> = crate::lut::WGSL_MODULES
        .iter()
        .map(|module| {
            if module.name == "atmos::lut_bindings" {
                skyscape_wgsl::Module {
                    name: module.name,
                    source: bindings,
                }
            } else {
                *module
            }
        })
        .collect();
    composer
        .add_modules(&modules)
        .expect("atmos LUT WGSL module names are unique and well formed");
    Ok(composer)
}

/// The two bind-group layouts of the LUTs: the uniforms and the tables (see the module
/// documentation for the bindings). Readable from compute, vertex and fragment stages.
#[derive(Debug)]
pub struct LutLayouts {
    /// Atmosphere, settings, frame camera, frame view (uniform buffers at bindings
    /// 0 … 3).
    pub uniforms: wgpu::BindGroupLayout,
    /// The six tables (unfilterable-float textures at bindings 0 … 5).
    pub tables: wgpu::BindGroupLayout,
}

impl LutLayouts {
    /// Creates both layouts.
    pub fn new(device: &wgpu::Device) -> Self {
        let uniforms = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUT uniforms"),
            entries: &[
                shared_uniform_entry(0),
                shared_uniform_entry(1),
                shared_uniform_entry(2),
                shared_uniform_entry(3),
            ],
        });
        let tables = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUT tables"),
            entries: &[
                float_texture_entry(0, Dim::D2),
                float_texture_entry(1, Dim::D2Array),
                float_texture_entry(2, Dim::D2Array),
                float_texture_entry(3, Dim::D3),
                float_texture_entry(4, Dim::D3),
                float_texture_entry(5, Dim::D2Array),
            ],
        });
        Self { uniforms, tables }
    }
}

/// The tables every view of one atmosphere shares — transmittance, multiple
/// scattering and sky irradiance — with their bakes, and the pipelines of the per-view bakes. Made once per
/// atmosphere and settings; [`AtmosphereTables::encode_static_luts`] records their bakes
/// (no queue writes: the atmosphere and settings uniforms are written at creation).
#[derive(Debug)]
pub struct AtmosphereTables {
    pub(crate) device: wgpu::Device,
    settings: LutSettingsUniform,
    /// The atmosphere the tables are for (what [`AtmosphereTables::write_static_luts`]
    /// checks a CPU bake against).
    atmosphere: crate::AtmosphereParameters,
    multiple_scattering_orders: u32,
    atmosphere_buffer: wgpu::Buffer,
    settings_buffer: wgpu::Buffer,
    transmittance: Table,
    multiple_scattering: Table,
    sky_irradiance: Table,
    layouts: LutLayouts,
    /// The static bakes' uniforms (a zero camera: they do not read it).
    uniforms: wgpu::BindGroup,
    passes: [BakePass; 3],
    /// Orders 3… of the multiple-scattering bake, each reading the order before (two
    /// ping-pong textures) and adding to the sum; then the copy of the sum into the
    /// LUT. Recorded right after the order-2 pass.
    higher_orders: Vec<BakePass>,
    /// What each view's bakes share: pipelines, the tables they read, output layouts.
    view_bakes: ViewBakes,
}

/// One view of an atmosphere: its camera (a [`ViewCamera`](crate::view::ViewCamera):
/// the caller's view and projection matrices and viewport), the tables that depend on
/// it (sky view, aerial perspective) and the bind groups a pipeline reads them through.
/// Any number of views of one [`AtmosphereTables`] can be prepared and recorded into
/// one encoder: each holds its own uniforms and tables.
///
/// Queue writes: [`AtmosphereView::prepare`] only (this view's camera uniforms).
/// [`AtmosphereView::encode`] records its bakes and nothing else.
#[derive(Debug)]
pub struct AtmosphereView {
    camera: wgpu::Buffer,
    frame_view: wgpu::Buffer,
    sky_view: Table,
    aerial_perspective_radiance: Table,
    aerial_perspective_transmittance: Table,
    uniforms: wgpu::BindGroup,
    tables: wgpu::BindGroup,
    bakes: [BakePass; 2],
    prepared: std::sync::atomic::AtomicBool,
}

/// The precomputed rung's tables for **one** view: an [`AtmosphereTables`] and one
/// [`AtmosphereView`], behind the calls of a single-camera program.
///
/// **One camera per `AtmosphereLuts`.** [`AtmosphereLuts::prepare`] writes the one
/// camera buffer through the queue, and queue writes land before the submit's commands
/// run: preparing a second camera before submitting the first one's work gives the
/// first the second's sky and haze. For two or more cameras in one submit (split
/// screen, reflections, VR) make one [`AtmosphereView`] per camera of one
/// [`AtmosphereTables`].
#[derive(Debug)]
pub struct AtmosphereLuts {
    tables: AtmosphereTables,
    view: AtmosphereView,
}
