//! `[clouds.volume]` drawn as Dobashi et al. 2000's billboards (`draw = "billboards"`): `cloudsim`
//! grows the cumulus (the same growth, grid and placement as the marched cloud,
//! `crate::volume_clouds`), `cloudlight`'s slice propagation lights every cell toward the
//! scene's sun, and each cell denser than the threshold becomes a soft splat
//! (`cloudlight::billboard`), sorted back to front, depth-tested against the terrain and
//! seen through the aerial perspective. This module owns only the composition: which
//! camera and sun the particles see, the air in front of each, and where the image meets
//! the scene.
//!
//! # Lighting
//!
//! Once per scene: `cloudlight::propagate::propagate::<f32>` (the slices' f32 twin,
//! physical Beer–Lambert mode with Catmull–Rom resampling by default, or Dobashi et al. 2000's
//! faithful mode) through the grown volume toward the sun gives every cell its
//! transmittance `T` toward the sun. The light is the marched cloud's
//! (`crate::volume_clouds`, `PreparedVolume::lighting`), at the grid's centre: the
//! sun's irradiance `E` through the scene's rung (`cloudlight::march::atmos_light`: the
//! atmosphere's sun irradiance × the rung's transmittance toward the sun) and the
//! ambient sky radiance `L_amb` (atmos' sky irradiance on a horizontal surface / π).
//! Each drawn cell's sky visibility `V_amb` is the march's
//! (`cloudlight::march::ambient_visibility`: `e^{−τ}` straight up, the march's
//! `ambient_steps` midpoint steps). Per frame a particle's colour is
//! `cloudlight::billboard::particle_radiance`: `albedo · (E · P(τ, cos θ) + L_amb ·
//! V_amb)` with `P` the march's `octave_scattering` of `τ = −ln T` (its dual-lobe
//! Henyey–Greenstein phase and `[clouds.volume]`'s octaves, 8 by default; one octave is
//! `T · p(cos θ)`, Dobashi 2000's single scattering; Dobashi et al. 2000 had `E · T` alone)
//! and the march's albedo, `θ` between the view ray to the particle and the sun. The same for each of the
//! scene's lights (`PreparedScene::lights`, as the marched cloud: the moon too on a
//! moonlit night): the slices run toward each light and each light's term and its
//! ambient sky are added ([`PreparedBillboards::lights`]); the cloud's shadow map toward
//! each light shades the terrain that light draws. The particle's colour is computed on the CPU for both renderers (the
//! particles are selected and sorted there per frame): the GPU's instances carry it.
//!
//! # Drawing
//!
//! Per frame the particles are selected and sorted for the scene's camera
//! (`cloudlight::billboard::billboards`, the camera rotated into the volume's
//! east/north/up frame, [`billboard_camera`]). Each particle is seen through the air
//! between the camera and its centre (`atmos::lut::drop_in::aerial_perspective` on the
//! precomputed rung, WGSL `aerial_perspective`, else the rung's
//! `SkyQuery::with_max_distance`; on the GPU a compute pass of the rung's own functions
//! per particle before the draw, `shaders/render/billboard_air_rung.wgsl` with the
//! rung's module, read per instance by `billboard_clouds_rung.wgsl`):
//! `colour' = colour · T_air + L_air`
//! ([`billboard_seen_through_air`]), so the premultiplied splat adds
//! `α · (colour · T_air + L_air)` over `(1 − α)` of what is behind, the marched cloud's
//! `L_c · T_air + L_air · (1 − T_c)`. The other lights' air in front of each
//! particle (the moonlit air at night) is added to `L_air` ([`other_lights_air`]: each
//! light's segment model, summed, computed on the CPU and read by the GPU's vertex stage
//! per instance; under the closed form and single scattering with one other light the
//! GPU runs the rung's pass for it instead; the sun's air comes from the tables or the
//! rung's pass). A particle covers a pixel
//! only where its view depth is less than the terrain's: on the CPU `cloudlight::billboard::rasterise_limited`
//! with the ray-cast terrain's view depth per pixel, on the GPU a depth test `Greater`
//! of `near / z` against the terrain's reverse-z depth (`shaders/render/billboard_clouds.wgsl`,
//! which draws cloudlight's instanced quads with `cloudlight::billboard`'s
//! `billboard_screen` and `splat_alpha`).

mod cpu;
#[cfg(feature = "gpu")]
mod gpu;
mod prepare;
mod section;

use cloudlight::CloudVolume;
use cloudlight::billboard::{BillboardSettings, ParticleScattering};
use cloudlight::march::Lighting;
use cloudlight::propagate::SliceMode;

use crate::cloud_shadow::CloudShadow;

pub use cpu::{
    billboard_camera, billboard_near, composite_billboards_cpu, explain, other_lights_air,
    particles, world_offset,
};
#[cfg(feature = "gpu")]
pub(crate) use gpu::BillboardCloudPass;
#[cfg(feature = "gpu")]
pub use gpu::{PARAMS_BYTES, params_bytes};
pub use section::{BillboardsSection, OpacityName, SlicesName, VolumeDraw};

/// The scene's billboard cloud, built once per scene.
#[derive(Debug, Clone)]
pub struct PreparedBillboards {
    /// The grown density in the east/north/up frame (as `PreparedVolume::volume`).
    pub volume: CloudVolume,
    /// The particles' settings: threshold, size, opacity, the sun's colour (its
    /// irradiance at the cloud / π), the near plane.
    pub settings: BillboardSettings,
    /// The slices' mode.
    pub slices: SliceMode,
    /// The automaton steps grown.
    pub steps: u32,
    /// Cells denser than the threshold (billboards before the camera's culling).
    pub dense_cells: usize,
    /// The ambient sky's visibility at every cell centre denser than the threshold
    /// (`cloudlight::march::ambient_visibility`), x fastest; 0 at the cells not drawn.
    pub ambient_visibility: Vec<f32>,
    /// The particles' albedo and phase: the march's (`ParticleScattering::of_march`).
    pub scattering: ParticleScattering,
    /// The cloud lit by each of the scene's lights, in
    /// [`crate::scene::PreparedScene::lights`]' order (the sun first).
    pub lights: Vec<BillboardLight>,
}

/// The billboards lit by one light (the marched cloud's `crate::light::CloudLight` and
/// the slices' light toward it).
#[derive(Debug, Clone)]
pub struct BillboardLight {
    /// The light and the ambient sky at the grid's centre, east/north/up.
    pub lighting: Lighting<f32>,
    /// The slices' light toward it at every cell centre, x fastest (`propagate::<f32>`).
    pub light: Vec<f32>,
    /// The cloud's shadow on the terrain toward it (`None` with the light below 1° or
    /// no terrain in the scene).
    pub shadow: Option<CloudShadow>,
}

/// The air in front of a particle: `colour · T_air + L_air` per channel (the colour the
/// premultiplied splat carries, module docs). WGSL twin of the same name in
/// `shaders/render/billboard_air.wgsl` (parity case `render::billboard_seen_through_air`).
pub fn billboard_seen_through_air(
    colour: [f32; 3],
    air_transmittance: [f32; 3],
    air_radiance: [f32; 3],
) -> [f32; 3] {
    std::array::from_fn(|k| colour[k] * air_transmittance[k] + air_radiance[k])
}
