//! [`FieldMarchPass`]: the view ray-march (after Schneider's Nubis talks) of a density
//! field on a GPU, bring your own device: one pass over a
//! [`GpuDensitySource`](crate::gpu::GpuDensitySource), the WGSL march written once
//! (`shaders/cloudlight/field_march.wgsl`) and composed with the field's source module.
//! [`MarchPass`] marches a [`CloudVolume`] (`march_pass.wgsl`, the volume's density a
//! storage buffer read with manual trilinear interpolation, as the CPU's
//! [`CloudVolume::density_at`] does), [`MarchShellPass`] a procedural [`CloudShell`]
//! (`march_shell_pass.wgsl`, which fades each pixel toward the horizon).
//!
//! [`FieldMarchPass::new`] builds the pipeline; [`FieldMarchPass::prepare`] uploads the
//! field's source, the camera, settings and lighting, and creates the output buffer and
//! the bind group; [`FieldMarchPass::encode`] only records the march's one pass
//! ([`FieldMarchPass::encode_timed`] adds timestamp writes).
//! [`FieldMarchPass::prepare_limited`] also binds a per-pixel distance buffer (`f32`
//! metres along each pixel's ray, x fastest, row 0 at the top) where each march stops:
//! terrain in front of or inside the cloud. A caller with a depth buffer converts depth
//! to distance along the ray itself.
//!
//! The output is a storage buffer of two `vec4<f32>` per pixel (x fastest, row 0 at the
//! top): `(radiance r, g, b, transmittance)` and `(depth, 0, 0, 0)` — the fields of
//! [`MarchResult`]; [`FieldMarchPass::decode`] turns its bytes into them. The f32 CPU
//! twin is [`render_image::<f32>`](crate::march::render_image) on the same field.
//!
//! # The stage
//!
//! Each entry's per-pixel function (`march_pass_pixel`, `march_shell_pass_pixel`: the
//! pixel's `march_pixel`, written to the output at the pixel's index) runs on one of two
//! stages, [`MarchStage`]:
//!
//! * **Fragment** (the choice wherever the device allows it): a render pass draws one
//!   full-screen triangle (`march_raster.wgsl`) and the fragment at pixel
//!   `floor(position.xy)` marches that pixel. Lavapipe (Mesa's software Vulkan driver)
//!   spreads fragment work over every core but runs a compute dispatch on one thread,
//!   so there the fragment stage is the fast one (llvmpipe's GL driver threads both
//!   alike); on a GPU the two run the same code on the same hardware. A render pass
//!   needs an attachment: the pass owns an image-sized `Depth16Unorm` one (created in
//!   `prepare` when the size changes), cleared, neither tested nor written, and
//!   discarded — the cheapest attachment every backend (Vulkan, GL, Metal, DX12)
//!   renders to, there only to size the pass. The image is then limited to the
//!   device's `max_texture_dimension_2d` pixels along each axis.
//! * **Compute**, the fallback: one invocation per pixel, [`MARCH_WORKGROUP_SIZE`]² per
//!   workgroup, for a device whose fragment shaders cannot write storage buffers
//!   (`wgpu::DownlevelFlags::FRAGMENT_WRITABLE_STORAGE`: some GLES and older mobile
//!   Vulkan devices). A `wgpu::Device` does not report its adapter's downlevel flags,
//!   so [`FieldMarchPass::new`] builds the fragment pipeline inside error scopes and
//!   builds the compute one if the device refuses it; a caller holding the adapter
//!   may choose with [`MarchStage::supported`] and [`FieldMarchPass::with_stage`].
//!
//! Both stages bind the same buffers (visible to that stage only), read the same
//! uniform and write the same output, so every reader of the output — a composite, the
//! [`TemporalMarch`] (whose phase check sits in the per-pixel function, so a pixel left
//! to the reprojection writes nothing on either stage), [`FieldMarchPass::decode`] — is
//! the same; `tests/march_stage_gpu.rs` compares the two stages' outputs bit for bit.
//!
//! [`CloudVolume`]: crate::CloudVolume
//! [`CloudVolume::density_at`]: crate::CloudVolume::density_at
//! [`MarchResult`]: crate::march::MarchResult
//! [`CloudShell`]: crate::CloudShell

mod pass;
mod shared;
mod stage;
mod temporal;

pub use pass::{
    FieldMarchPass, MarchPass, MarchShellPass, MarchedField, compose_march_shader,
    compose_march_shell_shader,
};
pub use stage::MarchStage;
pub use temporal::{SKY_DISTANCE_M, TemporalMarch};

/// Pixels per workgroup along each image axis (the compute stage).
pub const MARCH_WORKGROUP_SIZE: u32 = 8;

/// Another cloud's shadow map a march reads (`shaders/cloudlight/outside_shadow.wgsl`,
/// bindings 8 and 9 of the march pass): at each view sample `p` the light march's optical
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
    /// The image is empty or larger than the march's stage allows.
    #[error("{field} = {value} pixels: must be between 1 and {limit} on the {stage} stage")]
    ImageSize {
        /// `size.x` or `size.y`.
        field: &'static str,
        /// Pixels along it.
        value: u32,
        /// The stage the pass runs on.
        stage: MarchStage,
        /// The most pixels it allows: the device's `max_texture_dimension_2d` (the
        /// fragment stage's attachment) or [`MARCH_WORKGROUP_SIZE`] ×
        /// `max_compute_workgroups_per_dimension` (the compute stage's dispatch).
        limit: u32,
    },
    /// The device refused the pass's pipeline on a stage (on the fragment stage: a
    /// device whose fragment shaders cannot write storage buffers).
    #[error("the device refused the march's {stage}-stage pipeline: {message}")]
    Pipeline {
        /// The stage.
        stage: MarchStage,
        /// wgpu's error, on one line.
        message: String,
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
    /// Bytes handed to [`FieldMarchPass::decode`] have the wrong length.
    #[error("readback has {got} bytes, expected {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}
