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
//! the bind group; [`FieldMarchPass::encode`] only records one dispatch (8×8 pixels per
//! workgroup; [`FieldMarchPass::encode_timed`] adds timestamp writes).
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
//! [`CloudVolume`]: crate::CloudVolume
//! [`CloudVolume::density_at`]: crate::CloudVolume::density_at
//! [`MarchResult`]: crate::march::MarchResult
//! [`CloudShell`]: crate::CloudShell

mod pass;
mod shared;
mod temporal;

pub use pass::{
    FieldMarchPass, MarchPass, MarchShellPass, MarchedField, compose_march_shader,
    compose_march_shell_shader,
};
pub use temporal::{SKY_DISTANCE_M, TemporalMarch};

/// Pixels per workgroup along each image axis.
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
    /// Bytes handed to [`FieldMarchPass::decode`] have the wrong length.
    #[error("readback has {got} bytes, expected {expected}")]
    ReadbackSize {
        /// Bytes given.
        got: usize,
        /// Bytes expected.
        expected: usize,
    },
}
