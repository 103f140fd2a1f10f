//! GPU passes of `atmos` (feature `gpu`, on by default). Bring your own device: every
//! type takes `&wgpu::Device` / `&wgpu::Queue`; `new` creates pipelines and long-lived
//! resources, `prepare` writes uniforms and creates the frame's bind groups, `encode`
//! only records into the caller's encoder; nothing here creates a device or submits.
//!
//! Two ways in:
//!
//! * **Into your own engine**: [`AtmosphereTables`] bakes the precomputed rung's
//!   shared tables, one [`AtmosphereView`] per camera its per-view tables (any number
//!   of views in one encoder; [`AtmosphereLuts`] is the two for a single camera), all
//!   with public bind-group layouts. A camera is your view and projection matrices and
//!   viewport ([`crate::view::ViewCamera::from_matrices`]: any perspective, off-centre,
//!   jittered or reversed-z). [`sky::SkyPass`] draws the sky into your colour target
//!   (inside your render pass); [`AerialPerspectivePass`] hazes what your depth buffer
//!   holds, or your own shaders apply aerial perspective to your geometry with
//!   `atmos::aerial_perspective`'s WGSL (`apply_aerial_perspective`, composed at the
//!   bind groups you choose with [`composer_with_lut_groups`]);
//!   [`crate::frame::LocalFrame`] converts between your frame (+y up, metres from an
//!   origin on the ground) and the planet's.
//! * **Whole frames of radiance** (the ladder, for measurements and the CPU/GPU image
//!   tests): every rung's renderer follows one convention, so a caller (and
//!   `cargo xtask tradeoff atmos`) can swap them: `new(device, &Atmosphere, settings)`,
//!   `prepare(queue, &FrameCamera, &FrameOutput)`, `encode(encoder, timestamp_writes)`,
//!   writing a [`FrameOutput`] (two textures).

pub mod aerial_perspective_pass;
pub mod closed_form;
pub mod frame_output;
pub mod luts;
pub mod precomputed;
pub mod resources;
pub mod single_scattering;
pub mod sky;

pub use aerial_perspective_pass::{AerialPerspectivePass, DepthConvention};
pub use closed_form::{ClosedFormRenderer, EvaluationFrequency};
pub use frame_output::FrameOutput;
pub use luts::{
    AtmosphereLuts, AtmosphereTables, AtmosphereView, LutLayouts, composer_with_lut_groups,
    lut_bindings_wgsl,
};
pub use precomputed::PrecomputedRenderer;
pub use single_scattering::SingleScatteringRenderer;
pub use sky::{SkyPass, SkyPassDescriptor};
