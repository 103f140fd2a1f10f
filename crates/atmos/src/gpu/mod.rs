//! GPU passes of `atmos` (feature `gpu`, on by default). Bring your own device: every
//! type takes `&wgpu::Device` / `&wgpu::Queue`, `prepare` only writes buffers and
//! `encode` records into the caller's encoder; nothing here creates a device or submits.
//!
//! Every rung's renderer follows one convention, so a caller (and
//! `cargo xtask tradeoff atmos`) can swap them: `new(device, &Atmosphere, settings)`,
//! `prepare(queue, &FrameCamera)`, `encode(encoder, &FrameOutput, timestamp_writes)`.

pub mod closed_form;
pub mod frame_output;
pub mod luts;
pub mod precomputed;
pub mod resources;
pub mod single_scattering;

pub use closed_form::{ClosedFormRenderer, EvaluationFrequency};
pub use frame_output::FrameOutput;
pub use single_scattering::SingleScatteringRenderer;
