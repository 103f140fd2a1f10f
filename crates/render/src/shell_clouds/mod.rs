//! Schneider's (GPU Pro 7, Nubis) ray-marched cloud shell in a scene (`[clouds.shell]`): `cloudlight`'s
//! procedural shell (two spheres about the planet centre, tileable Perlin–Worley noise,
//! procedural weather, height profiles per cloud type) marched per pixel with Schneider's (GPU Pro 7)
//! lighting and composited over the opaque scene, depth-aware, exactly as the volume
//! cloud is (`crate::volume_clouds`): the march stops at the terrain, so a ridge in front
//! of the deck hides it and the deck in front of a ridge covers it, and the cloud is seen
//! through the air up to its transmittance-weighted depth. This module owns only the
//! section, the frame and the lighting point; the shell, its density and validation are
//! `cloudlight::CloudShell`'s, the march is `cloudlight::march` (CPU, the f32 twin) and
//! `cloudlight::gpu::MarchShellPass` (GPU), the air and the composite are the volume
//! cloud's (`shaders/render/volume_air.wgsl`, `shaders/render/volume_clouds.wgsl`;
//! `render::marched_cloud::cloud_through_air` on the CPU).
//!
//! # Frame
//!
//! cloudlight's shell is planet-centred with the viewer near the +z pole; the render
//! world is `x` east, `y` up, `z` south with the planet centre at `(0, −R, 0)`, so a
//! world point's planet-centred position `(x, y + R, z)` becomes the shell's
//! `(x, −z, y + R)` ([`crate::volume_clouds::world_to_enu`] without removing the
//! radius): [`shell_camera`] is the scene camera there. The weather and the noise are
//! sampled at the shell frame's `x` (east) and `y` (north).
//!
//! # Lighting
//!
//! Once per scene, at the middle of the shell straight above the camera: the sun's
//! irradiance through the scene's rung and the ambient sky (`cloudlight::march::atmos_light`,
//! as the volume cloud); the same for each of the scene's other lights (the moon on a
//! moonlit night: `atmos_light` of celestial's moonlit atmosphere along the moon), the
//! deck marched once per light and the marches added, each through its light's air
//! ([`PreparedShell::lights`]).
//!
//! # Shadow on the terrain
//!
//! Over a scene's terrain the deck shades it as the volume cloud does: cloudlight's
//! shadow map of the shell's density field toward each light that is up ([`shell_shadow`],
//! [`crate::volume_clouds::CloudShadow::over`]), baked once on the CPU at prepare (not by
//! [`Scene::prepare_for_gpu`](crate::scene::Scene::prepare_for_gpu)), on the
//! plane of the shell's base over the heightfield's extent swept along the light. The
//! GPU renderer bakes the same map again on the GPU (`crate::gpu::shell_shadow`:
//! cloudlight's `ShellShadowMapPass` over [`shell_shadow_map_plan`], whose f32 twin
//! `cloudlight::shell_shadow::shell_shadow_map` equals the CPU bake bit for bit) and
//! uses it instead of the CPU's values. Both renderers read the map with the same
//! bilinear lookup, faded inside the deck's altitudes (`CloudShadow::on_terrain`, the
//! terrain pass's `shadow_map_at`) and multiply
//! the terrain's direct light by it times the volume cloud's map (the terrain pass holds
//! one map per marched cloud: `crate::gpu::cloud_shadow`), each light's terrain draw
//! its own light's map.
//!
//! # What it costs
//!
//! Nothing without the section: no shell, no march pipeline, no buffer, no shadow map.
//! The GPU pass evaluates the noise procedurally per sample (cloudlight's
//! `MarchShellPass` has no baked-noise variant), so there is no noise bake either. The
//! shadow map is [`SHADOW_SIDE`]² texels × [`SHADOW_STEPS`] noise samples on the CPU
//! (its time is [`PreparedShell::shadow_seconds`], printed by `skyscape explain`).

mod cpu;
#[cfg(feature = "gpu")]
mod gpu;
mod plan;
mod prepare;
mod section;
mod shadow;
mod weather;

use cloudlight::CloudShell;
use cloudlight::march::MarchSettings;

use crate::cloud_shadow::CloudShadow;

pub(crate) use cpu::composite_shell_cloud;
pub use cpu::{march_shell_pixel, march_shell_pixel_lit, shell_camera};
#[cfg(feature = "gpu")]
pub(crate) use gpu::ShellCloudPass;
pub use plan::shell_pass_plans;
pub(crate) use plan::shell_shadow_plan;
pub use section::CloudShellSection;
pub use shadow::{shell_shadow, shell_shadow_map_plan, shell_shadow_unbaked};

/// The most view-march steps per pixel.
pub const MAX_VIEW_STEPS: u32 = 1024;
/// The most light-march steps per sample.
pub const MAX_LIGHT_STEPS: u32 = 256;
/// The most ambient-visibility steps per sample.
pub const MAX_AMBIENT_STEPS: u32 = 64;
/// The most multiple-scattering octaves.
pub const MAX_OCTAVES: u32 = 8;
/// Texels along the longer side of the deck's shadow map ([`shell_shadow`]): 125 m
/// texels over the shipped scene's 16 km, 6 per period of its 800 m detail noise.
pub const SHADOW_SIDE: u32 = 128;
/// Midpoint steps of the deck's shadow map per span toward the light: 78 m steps
/// through the shipped 800 m deck under a 40° sun.
pub const SHADOW_STEPS: u32 = 16;

/// The scene's cloud shell, built once per scene.
#[derive(Debug, Clone)]
pub struct PreparedShell {
    /// The shell about the scene's planet (planet-centred, the camera near +z).
    pub shell: CloudShell,
    /// The march's settings (midpoint samples, a full light march).
    pub settings: MarchSettings,
    /// The deck lit by each of the scene's lights, in
    /// [`crate::scene::PreparedScene::lights`]' order (the sun first): the light and the
    /// ambient sky at the middle of the shell above the camera, in the shell's frame, and
    /// the deck's shadow on the terrain toward it ([`shell_shadow`]: `None` in a scene
    /// without terrain or with that light below 1°, and nothing is baked then).
    pub lights: Vec<crate::light::CloudLight>,
    /// Seconds the shadow maps took to bake on this machine's CPU (0 without one).
    pub shadow_seconds: f64,
    /// The deck's shadow on the scene's volume cloud toward each light, in `lights`'
    /// order (`crate::mutual_shadow::deck_over_volume`, always baked on the CPU): `None`
    /// without a marched volume cloud or with that light below 1°.
    pub over_volume: Vec<Option<CloudShadow>>,
}

impl PreparedShell {
    /// Whether the shadow maps hold their values (a scene from `Scene::prepare`), or only
    /// their grids (from [`Scene::prepare_for_gpu`](crate::scene::Scene::prepare_for_gpu): the GPU renderer bakes them; the CPU
    /// renderer needs [`crate::scene::PreparedScene::bake_shell_shadow_on_cpu`] first).
    pub fn shadows_baked_on_cpu(&self) -> bool {
        self.lights
            .iter()
            .filter_map(|light| light.shadow.as_ref())
            .all(|map| !map.values.is_empty())
    }
}
