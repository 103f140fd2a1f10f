//! What lights the terrain, per frame and per light: the light's irradiance through
//! the atmosphere at the terrain's elevations and the sky's irradiance. Shared by the
//! CPU twin and the GPU's terrain pass (and the rungs' light tables).

use glam::{DVec3, Vec3};

use crate::RenderError;
use crate::scene::prepare::{Illuminant, PreparedScene, PreparedTerrain};

/// Elevations at which the sun's transmittance is queried per frame. The terrain is
/// flat in the world frame (as its horizon maps are baked), so the sun's path from a
/// terrain point depends only on the point's elevation; transmittance is smooth in
/// elevation, and linear interpolation between 64 samples over the default scene's
/// 1.8 km relief differs from a query per point by at most 2.3e-5 (sun 4° high,
/// precomputed rung; `passes::terrain::cpu::tests::the_sun_table_matches_a_query_per_point`).
/// That is the f32 rung's own noise, not the interpolation: 128 samples give 2.7e-5.
pub const SUN_TABLE_SIZE: usize = 64;

/// The sun's irradiance (above the atmosphere × transmittance) at `elevation` metres
/// above the camera's ground point: zero when the planet hides the sun, else the
/// rung's transmittance of the finite segment to the top of the atmosphere (a finite
/// segment: the precomputed rung answers it without a per-viewpoint table).
pub fn sun_irradiance_at(scene: &PreparedScene, elevation: f64) -> Result<Vec3, RenderError> {
    light_irradiance_at(scene, &scene.sun_light(), elevation)
}

/// [`sun_irradiance_at`] for any of the scene's lights (the moon's: its irradiance
/// through the same atmosphere).
pub fn light_irradiance_at(
    scene: &PreparedScene,
    light: &Illuminant<'_>,
    elevation: f64,
) -> Result<Vec3, RenderError> {
    let a = light.atmosphere;
    let c = scene.camera_position;
    let point = DVec3::new(c.x, a.planet_radius + elevation, c.z);
    let r = point.length();
    let mu_s = point.dot(light.direction) / r;
    let ground =
        atmos::geometry::ray_sphere_intersect(r as f32, mu_s as f32, a.planet_radius as f32);
    if ground[0] >= 0.0 {
        return Ok(Vec3::ZERO);
    }
    let top = atmos::geometry::ray_sphere_intersect(r as f32, mu_s as f32, a.top_radius as f32);
    let query = atmos::SkyQuery::with_max_distance(
        a.planet_radius,
        point,
        light.direction,
        light.direction,
        f64::from(top[1].max(0.0)),
    )
    .map_err(RenderError::Atmosphere)?;
    let t = light.segment_model.evaluate(&query).transmittance;
    let e = a.sun_irradiance;
    Ok(Vec3::new(
        (t[0] * e[0]) as f32,
        (t[1] * e[1]) as f32,
        (t[2] * e[2]) as f32,
    ))
}

/// What lights a scene's terrain, per frame, shared by the CPU renderer and the GPU's
/// terrain pass: the sky's irradiance (once per frame, at the terrain's mean elevation
/// under the camera: its change with elevation across the relief is not modelled) and
/// the sun in terrain's east–north–up frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TerrainLighting {
    /// `atmos::ground_irradiance`'s sky term on a horizontal surface.
    pub sky_irradiance: Vec3,
    /// Unit direction toward the sun, east–north–up.
    pub sun_enu: Vec3,
    /// The sun's elevation (rad), `terrain::shadow::sun_elevation`.
    pub sun_elevation: f32,
    /// The sun's azimuth (rad), `terrain::shadow::sun_azimuth`.
    pub sun_azimuth: f32,
    /// The terrain's lowest and highest elevation (m).
    pub elevation_range: [f64; 2],
}

/// The lighting of `terrain` in `scene` (see [`TerrainLighting`]).
pub fn terrain_lighting(
    scene: &PreparedScene,
    terrain: &PreparedTerrain,
) -> Result<TerrainLighting, RenderError> {
    terrain_lighting_for(scene, terrain, &scene.sun_light())
}

/// [`terrain_lighting`] for any of the scene's lights: the moon's is its direction and
/// the irradiance of the sky it lights.
pub fn terrain_lighting_for(
    scene: &PreparedScene,
    terrain: &PreparedTerrain,
    light: &Illuminant<'_>,
) -> Result<TerrainLighting, RenderError> {
    let [low, high] =
        terrain::intersect::HeightfieldTracer::new(&terrain.heightfield).elevation_range();
    let mean = 0.5 * (low + high);
    let c = scene.camera_position;
    let here = DVec3::new(c.x, light.atmosphere.planet_radius + mean, c.z);
    let irradiance = atmos::ground_irradiance::ground_irradiance(
        &crate::light::scattered_queries(light.sky_model, light.precomputed),
        light.atmosphere,
        here,
        light.direction,
        atmos::ground_irradiance::HemisphereQuadrature::default(),
    )
    .map_err(RenderError::Atmosphere)?;
    let sun_enu = Vec3::from_array(crate::frames::world_to_enu(
        light.direction.as_vec3().to_array(),
    ));
    Ok(TerrainLighting {
        sky_irradiance: Vec3::from_array(irradiance.sky.map(|v| v as f32)),
        sun_enu,
        sun_elevation: terrain::shadow::sun_elevation(sun_enu),
        sun_azimuth: terrain::shadow::sun_azimuth(sun_enu),
        elevation_range: [low, high],
    })
}
