//! A volumetric cloud in a scene (`[clouds.volume]`): `cloudsim` grows a cumulus,
//! `cloudlight` ray-marches it with Schneider's (GPU Pro 7) lighting, and this module composites it
//! over the opaque scene (sky and terrain), depth-aware. It owns only the placement,
//! the frames and the compositing; the march is `cloudlight::march` (CPU, the f32 twin)
//! and `cloudlight::gpu::MarchPass` (GPU, `shaders/render/volume_clouds.wgsl` composites).
//!
//! # Frames
//!
//! The render world is `x` east, `y` up, `z` south (metres, the camera's ground at the
//! origin); the cloud's volume frame is east, north, up (cloudsim's `x`, `y`, `z` up):
//! `world_to_enu(x, y, z) = (x, −z, y)`, a rotation, so the march's pixel rays are the
//! scene camera's rays rotated ([`pinhole_camera`]; `tests/volume_clouds.rs` checks them
//! against `atmos::frame::frame_view_direction` within f32 rounding).
//!
//! # Lighting
//!
//! Once per scene, at the grid's centre: the sun's irradiance through the scene's rung
//! (`cloudlight::march::atmos_light`: the atmosphere's sun irradiance × the rung's
//! transmittance toward the sun, zero behind the planet) and the ambient sky (atmos'
//! sky irradiance on a horizontal surface / π). The same for each of the scene's lights
//! (`PreparedScene::lights`: the moon too on a moonlit night — the sun below the
//! horizon, the moon above −2° — passed exactly as the sun is, `atmos_light` of the
//! moonlit atmosphere, `celestial::MoonLight::atmosphere`, along the moon's direction:
//! [`PreparedVolume::lights`]): the cloud is marched once per light and the results
//! are added, each seen through the air its own light scatters; its shadow map toward
//! each light shades the terrain that light draws. The march is linear in the light,
//! and its transmittance and depth do not depend on it, so the sum is the cloud lit by
//! all of them.
//!
//! # Compositing
//!
//! Per pixel the march gives the cloud's radiance `L_c`, its transmittance `T_c` and the
//! transmittance-weighted depth `d` of its opacity along the ray. The pixel becomes
//!
//! `L = L_c · T_air(d) + L_air(d) · (1 − T_c) + T_c · L_behind`
//!
//! where `(L_air, T_air)` are the rung's in-scattering and transmittance of the air
//! between the camera and `d` (the same aerial perspective the terrain gets: for the
//! precomputed rung the aerial-perspective LUT, `atmos::lut::drop_in`; otherwise a
//! `SkyQuery::with_max_distance`, `cloudlight::march::apply_aerial_perspective`) and
//! `L_behind` is the sky or terrain already drawn. Both renderers evaluate the air with
//! the same function: atmos' `aerial_perspective` (the aerial-perspective volume within
//! its range, 32 km by default, a march of the tables beyond it), on the CPU
//! `atmos::lut::drop_in::aerial_perspective`, on the GPU its WGSL twin in a compute pass
//! per pixel (`shaders/render/volume_air.wgsl`) whose result the composite reads. The march stops at the
//! terrain: the CPU's at the ray's terrain hit, the GPU's at the distance its terrain
//! depth gives (`shaders/render/volume_distance.wgsl`, then
//! `cloudlight::gpu::MarchPass::prepare_limited`), so a ridge standing in the cloud
//! hides the part behind it and the part in front is drawn. The aerial perspective is
//! the air's up to the cloud's opacity-weighted depth `d`.

mod cpu;
#[cfg(feature = "gpu")]
mod gpu;
mod prepare;

use cloudlight::CloudVolume;
use cloudlight::march::MarchSettings;

pub use crate::cloud_shadow::{
    CloudShadow, SHADOW_MAP_MAX_SIDE, SHADOW_MAP_STEPS, volume_shadow_texel,
};
pub use crate::frames::world_to_enu;
pub use crate::light::CloudLight;
pub(crate) use cpu::{march_field_pixel, march_field_pixel_through};
pub use cpu::{march_pixel, march_pixel_lit, pinhole_camera};
#[cfg(feature = "gpu")]
pub(crate) use gpu::VolumeCloudPass;

/// The largest grid side along east and north (cells).
pub const MAX_HORIZONTAL_CELLS: u32 = 256;
/// The largest grid side along up (cells).
pub const MAX_VERTICAL_CELLS: u32 = 128;
/// The most automaton steps a scene may ask for.
pub const MAX_STEPS: u32 = 100_000;

/// The scene's volumetric cloud, built once per scene.
#[derive(Debug, Clone)]
pub struct PreparedVolume {
    /// The grown density in the east/north/up frame, metres from the camera's ground
    /// point (its minimum corner at `origin`).
    pub volume: CloudVolume,
    /// The march's settings (the scene's view and light steps; midpoint samples).
    pub settings: MarchSettings,
    /// The automaton steps grown.
    pub steps: u32,
    /// Cells holding density > 0.
    pub cloudy_cells: usize,
    /// The cloud lit by each of the scene's lights, in
    /// [`crate::scene::PreparedScene::lights`]' order (the sun first): the light and the
    /// ambient sky at the grid's centre, east/north/up, and its shadow map toward it.
    pub lights: Vec<CloudLight>,
}
