//! The deck's shadow map on the terrain (baked on the CPU, or planned for the GPU's
//! bake).

use glam::DVec3;

use super::{SHADOW_SIDE, SHADOW_STEPS};
use crate::cloud_shadow::CloudShadow;
use crate::frames::world_to_enu;

/// The deck's shadow on `terrain` toward unit world direction `toward` (the sun, or the
/// moon at night), or `None` with the light below 1° (as the volume's,
/// [`CloudShadow::new`]): cloudlight's shadow map of the shell's density field
/// ([`CloudShadow::over`], `shadow_map::<f32, _>`, [`SHADOW_STEPS`] midpoint steps per
/// span) on the plane of the shell's base altitude, over the heightfield's extent swept
/// along the light to that plane from its lowest and highest points ([`SHADOW_SIDE`]
/// texels along its longer side, none finer than the heightfield's). Every terrain point below the base reads its exact
/// transmittance up to the map's sampling (clear air between it and the plane); a peak
/// standing in the deck is shaded by the faded column of [`CloudShadow::on_terrain`]
/// (none above the deck's top). The plane is flat and the
/// shell's base a sphere: at `d` metres from the camera's ground point the plane lies
/// `d²/2R` inside the deck (5 m at 8 km), where the march starts a few metres in.
pub fn shell_shadow(
    shell: &cloudlight::CloudShell,
    terrain: &crate::scene::prepare::PreparedTerrain,
    toward: DVec3,
) -> Option<CloudShadow> {
    shell_shadow_of(shell, shell, terrain, toward)
}

/// A [`shell_shadow`]'s grid, plane and light without its values (`values` empty): what
/// [`Scene::prepare_for_gpu`](crate::scene::Scene::prepare_for_gpu) keeps for the GPU renderer, which bakes the values itself
/// (`crate::gpu::shell_shadow`). Its texels cost nothing: the march runs over a field
/// without spans.
pub fn shell_shadow_unbaked(
    shell: &cloudlight::CloudShell,
    terrain: &crate::scene::prepare::PreparedTerrain,
    toward: DVec3,
) -> Option<CloudShadow> {
    struct NoCloud;
    impl cloudlight::DensityField<f32> for NoCloud {
        fn density(&self, _: [f32; 3]) -> f32 {
            0.0
        }
        fn extinction_per_density(&self) -> f32 {
            0.0
        }
        fn ray_spans(&self, _: [f32; 3], _: [f32; 3]) -> cloudlight::RaySpans<f32> {
            cloudlight::RaySpans::none()
        }
    }
    let mut map = shell_shadow_of(&NoCloud, shell, terrain, toward)?;
    map.values = Vec::new();
    Some(map)
}

/// [`shell_shadow`] marching `field` (the shell, or a field without spans for the grid
/// alone).
fn shell_shadow_of<D: cloudlight::DensityField<f32> + Sync + ?Sized>(
    field: &D,
    shell: &cloudlight::CloudShell,
    terrain: &crate::scene::prepare::PreparedTerrain,
    toward: DVec3,
) -> Option<CloudShadow> {
    let to_light = world_to_enu(toward.to_array());
    if to_light[2] < 1f64.to_radians().sin() {
        return None;
    }
    let planet = shell.planet_radius();
    let plane = shell.settings().inner_radius - planet;
    let hf = &terrain.heightfield;
    let [half_east, half_south] = terrain.map_offset();
    let (low, high) = hf
        .elevations()
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
            (lo.min(h), hi.max(h))
        });
    // A point at altitude h meets the plane (plane − h)/l_z along the light (capped at
    // 100 km as the volume's sweep).
    let sweep = |h: f64| ((plane - h) / to_light[2]).clamp(-1e5, 1e5);
    let (near, far) = (sweep(high), sweep(low));
    let lo =
        [0, 1].map(|a| -[half_east, half_south][a] + (near * to_light[a]).min(far * to_light[a]));
    let hi =
        [0, 1].map(|a| [half_east, half_south][a] + (near * to_light[a]).max(far * to_light[a]));
    let longer = (hi[0] - lo[0]).max(hi[1] - lo[1]);
    CloudShadow::over(
        field,
        [lo, hi],
        hf.spacing().max(longer / f64::from(SHADOW_SIDE)),
        [plane, planet],
        shell.settings().outer_radius - planet,
        to_light,
        SHADOW_STEPS,
    )
}

/// The plan of `map` (a [`shell_shadow`] of `shell` toward unit world direction
/// `toward`) in the shell's planet-centred frame: its texels, the plane of the shell's
/// base, the light and [`SHADOW_STEPS`]; in f32 the same texel centres and direction as
/// the CPU bake's (the GPU bake, `crate::gpu::shell_shadow`, marches this plan with
/// `cloudlight::gpu::ShellShadowMapPass`).
pub fn shell_shadow_map_plan(
    shell: &cloudlight::CloudShell,
    map: &CloudShadow,
    toward: DVec3,
) -> Result<cloudlight::shadow_map::ShadowMapPlan, cloudlight::shadow_map::ShadowMapError> {
    let planet = shell.planet_radius();
    let plane = shell.settings().inner_radius - planet;
    let grid = cloudlight::shadow_map::ShadowGrid::new(
        map.origin.map(f64::from),
        f64::from(map.cell_size),
        map.resolution,
        plane + planet,
    )?;
    cloudlight::shadow_map::ShadowMapPlan::new(grid, world_to_enu(toward.to_array()), SHADOW_STEPS)
}
