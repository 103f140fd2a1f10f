//! `render`: composes skyscape's subsystems into images. It owns only what is
//! specific to composition (the sky pass, display encoding, [`scene`] files and the
//! [`cpu_renderer`] that draws them); every piece of physics comes from the subsystem
//! crates, in Rust and by `#import` in WGSL.
//!
//! ```
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/default.toml");
//! let mut scene = render::scene::Scene::open(path)?;
//! scene.file.output.width = 16;
//! scene.file.output.height = 9;
//! let frame = render::cpu_renderer::render_cpu(&scene.prepare()?)?;
//! assert_eq!(frame.pixels.len(), 16 * 9);
//! # Ok(())
//! # }
//! ```

pub mod aerial_vertex;
pub mod air;
pub mod billboard_clouds;
pub mod cloud_order;
pub mod cloud_shadow;
pub mod clouds;
pub mod cpu_frame;
pub mod cpu_renderer;
pub mod error;
pub mod frames;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod in_cloud_fog;
pub mod light;
pub mod marched_cloud;
pub mod mutual_shadow;
pub mod passes;
pub mod present;
pub mod projection;
pub mod scene;
pub mod shell_clouds;
pub mod terrain_colour;
pub mod terrain_materials;
pub mod terrain_mesh;
pub mod terrain_shading;
pub mod tonemap;
pub mod volume_clouds;
mod wgsl;

pub use error::RenderError;

/// What a typical user needs: scene files, the CPU reference renderer, the GPU scene
/// renderer (feature `gpu`) and the projections.
///
/// ```
/// use render::prelude::*;
/// let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/sunset.toml");
/// let mut scene = Scene::open(path).unwrap();
/// scene.file.output.width = 8;
/// scene.file.output.height = 4;
/// let frame = render_cpu(&scene.prepare().unwrap()).unwrap();
/// assert_eq!(frame.pixels.len(), 32);
/// ```
pub mod prelude {
    pub use crate::RenderError;
    pub use crate::cpu_renderer::{Frame, render_cpu, render_radiance};
    #[cfg(feature = "gpu")]
    pub use crate::gpu::{SceneRenderer, SceneRendererSettings};
    pub use crate::projection::Projection;
    pub use crate::scene::{PreparedScene, Scene, SceneError};
}

pub use wgsl::{WGSL_MODULES, add_composed_crates, composer};

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
