//! `render`'s GPU passes, bring-your-own-device: the caller owns the device, the queue
//! and the command encoder; nothing here creates a device or submits.
//!
//! * [`scene::SceneRenderer`]: a whole scene — the sky (`atmos`' sky pass), the
//!   terrain (an instanced quadtree of tiles, Hoffman and Preetham's shading, aerial perspective
//!   per pixel), the display pass (tone map, dither);
//! * [`Presenter`]: a frame of any `atmos` rung's radiance (`atmos::gpu::FrameOutput`)
//!   to RGBA8, for the ladder's image tests;
//! * [`timer::PassTimes`]: GPU timestamps per pass.

pub(crate) mod cloud_air;
pub(crate) mod cloud_composite;
pub(crate) mod cloud_order;
pub(crate) mod frame;
pub(crate) mod layout;
pub mod present;
pub(crate) mod rung_kind;
pub mod rungs;
pub mod scene;
pub mod timer;
pub(crate) mod validation;
pub(crate) mod vertex_air;

pub use frame::MAX_LIGHTS;
pub use present::Presenter;
pub use scene::{SceneRenderer, SceneRendererSettings};
