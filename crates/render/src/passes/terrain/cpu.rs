//! The terrain pass's CPU twin: each pixel whose ray hit the terrain is shaded with
//! Hoffman and Preetham's terrain colour ([`crate::terrain_shading`]) for each light of
//! the frame (the sun; at night the moon's light added, the twin of the GPU's second,
//! additive draw), then seen through the atmosphere.
//!
//! Per light and hit: bilinearly filtered normal and horizon angle at the hit (what a
//! GPU's linear sampler gives), self-shadow by `terrain::shadow`'s soft shadow against
//! the light's disc, lit through the rung's transmittance from the point (tabulated per
//! frame over the terrain's elevations) and by `atmos::ground_irradiance`'s sky term
//! (once per frame at the terrain's mean elevation), then `surface × transmittance +
//! in-scatter` of the rung's segment camera → hit.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::lighting::{SUN_TABLE_SIZE, light_irradiance_at, terrain_lighting_for};
use crate::RenderError;
use crate::cpu_frame::{CpuFrame, PrecomputedFrame};
use crate::scene::prepare::{HorizonMaps, Illuminant, PreparedScene, PreparedTerrain};
use crate::terrain_materials::{detail_noise, pixel_footprint, procedural_albedo};
use crate::terrain_shading::surface_radiance;

/// Shades the frame's terrain hits by every light (the CPU twin of the terrain pass).
pub(crate) fn composite(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let scene = frame.scene;
    let Some(terrain) = &scene.terrain else {
        return Ok(());
    };
    // The frame's lights (the sun, then the moon when it lights the scene).
    let lights = frame
        .lights
        .iter()
        .map(|light| {
            terrain_light(scene, terrain, light.illuminant)
                .map(|terrain_light| (terrain_light, light.tables.as_ref()))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let width = frame.width();
    let hits = &frame.hits;
    frame
        .pixels
        .par_chunks_mut(width)
        .zip(hits.par_chunks(width))
        .try_for_each(|(pixels, hits)| {
            for (pixel, hit) in pixels.iter_mut().zip(hits) {
                let Some((view, hit)) = hit else {
                    continue;
                };
                let mut radiance = [0.0f32; 3];
                for (index, (light, tables)) in lights.iter().enumerate() {
                    let lit = shade_terrain(scene, light, *tables, *view, hit)?;
                    if index == 0 {
                        radiance = lit;
                    } else {
                        for (value, a) in radiance.iter_mut().zip(lit) {
                            *value += a;
                        }
                    }
                }
                pixel.radiance = radiance;
                pixel.terrain_distance = Some(hit.distance as f32);
            }
            Ok::<(), RenderError>(())
        })
}

/// Per-frame lighting of the terrain.
pub(crate) struct TerrainLight<'a> {
    terrain: &'a PreparedTerrain,
    offset: [f64; 2],
    /// The light (the sun, or the moon at night) and its atmosphere, rung and layers.
    illuminant: Illuminant<'a>,
    /// The scene camera with this light as its "sun" (its tables' camera).
    camera: atmos::frame::FrameCamera,
    sky_irradiance: Vec3,
    /// The sun in terrain's east–north–up frame.
    sun_enu: Vec3,
    sun_elevation: f32,
    sun_azimuth: f32,
    /// The sun's irradiance through the atmosphere at [`SUN_TABLE_SIZE`] elevations
    /// spanning the terrain's range, first to last.
    sun_table: Vec<Vec3>,
    elevation_range: [f64; 2],
    /// Radians per pixel (`super::pixel_angle`).
    pixel_angle: f32,
    /// The per-vertex aerial perspective's mesh and vertex segments
    /// (`[terrain] aerial_perspective = "per-vertex"`), `None` per pixel.
    vertex_aerial: Option<crate::aerial_vertex::VertexAerial>,
}

impl TerrainLight<'_> {
    /// The sun's irradiance through the atmosphere at `elevation` (m), interpolated.
    fn sun_at_elevation(&self, elevation: f64) -> Vec3 {
        let [low, high] = self.elevation_range;
        let f = if high > low {
            ((elevation - low) / (high - low)).clamp(0.0, 1.0) * (SUN_TABLE_SIZE - 1) as f64
        } else {
            0.0
        };
        let k = (f.floor() as usize).min(SUN_TABLE_SIZE - 2);
        let t = (f - k as f64) as f32;
        self.sun_table[k].lerp(self.sun_table[k + 1], t)
    }
}

pub(crate) fn terrain_light<'a>(
    scene: &PreparedScene,
    terrain: &'a PreparedTerrain,
    illuminant: Illuminant<'a>,
) -> Result<TerrainLight<'a>, RenderError> {
    let offset = terrain.map_offset();
    let lighting = terrain_lighting_for(scene, terrain, &illuminant)?;
    let [low, high] = lighting.elevation_range;
    let sun_table = (0..SUN_TABLE_SIZE)
        .map(|k| {
            let f = k as f64 / (SUN_TABLE_SIZE - 1) as f64;
            light_irradiance_at(scene, &illuminant, low + (high - low) * f)
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(TerrainLight {
        terrain,
        offset,
        camera: illuminant.camera(&scene.camera),
        illuminant,
        sky_irradiance: lighting.sky_irradiance,
        sun_enu: lighting.sun_enu,
        sun_elevation: lighting.sun_elevation,
        sun_azimuth: lighting.sun_azimuth,
        sun_table,
        elevation_range: [low, high],
        pixel_angle: super::pixel_angle(&scene.camera),
        vertex_aerial: terrain.aerial_perspective.per_vertex().then(|| {
            crate::aerial_vertex::VertexAerial::new(
                scene,
                terrain,
                crate::aerial_vertex::TERRAIN_ERROR_PX,
            )
        }),
    })
}

/// The marched clouds' shadow at world point `world` (x east, y up, z south, metres
/// from the camera's ground point) toward `light`: the volume's map times the shell's
/// (each 1 without its map; `CloudShadow::on_terrain`, faded inside the cloud's
/// altitudes). The GPU terrain pass's `volume_cloud_shadow` does the same in f32, in the
/// same order.
fn volume_shadow_at(light: &TerrainLight<'_>, world: Vec3) -> f32 {
    let at = |map: Option<&crate::volume_clouds::CloudShadow>| {
        map.map_or(1.0, |shadow| {
            shadow.on_terrain([world.x, -world.z, world.y])
        })
    };
    at(light.illuminant.volume_shadow) * at(light.illuminant.shell_shadow)
}

/// Bilinear weights and the four texels around a fractional texel position.
fn bilinear_texels(texel: [f64; 2], width: usize, height: usize) -> ([usize; 4], [f32; 4]) {
    let i = (texel[0].floor() as usize).min(width - 2);
    let j = (texel[1].floor() as usize).min(height - 2);
    let (fx, fy) = ((texel[0] - i as f64) as f32, (texel[1] - j as f64) as f32);
    (
        [
            j * width + i,
            j * width + i + 1,
            (j + 1) * width + i,
            (j + 1) * width + i + 1,
        ],
        [
            (1.0 - fx) * (1.0 - fy),
            fx * (1.0 - fy),
            (1.0 - fx) * fy,
            fx * fy,
        ],
    )
}

fn filtered(values: &[f32], texels: &[usize; 4], weights: &[f32; 4]) -> f32 {
    texels
        .iter()
        .zip(weights)
        .map(|(&t, &w)| values[t] * w)
        .sum()
}

/// The terrain's albedo at map position `map` (m east and south of texel (0, 0)),
/// `elevation` (m), with unit normal `normal` (east, north, up), seen from the camera at
/// `offset` (world axes, camera → point): the colour texture or the ramp, or the
/// procedural materials over the colour texture's or the grass's albedo, their detail
/// band-limited by the pixel's footprint. Twin of WGSL `surface_albedo`
/// (`shaders/render/terrain.wgsl`).
fn surface_albedo(
    terrain: &PreparedTerrain,
    map: [f32; 2],
    elevation: f32,
    normal: Vec3,
    offset: Vec3,
    pixel_angle: f32,
) -> Vec3 {
    let colour = terrain.colour.as_ref().map(|c| c.colour_at(map));
    let Some(params) = &terrain.materials else {
        return colour.unwrap_or_else(|| terrain.albedo.albedo(elevation, normal.z));
    };
    let ground = colour.unwrap_or(Vec3::from_array(params.grass_albedo));
    let distance = offset.length().max(1e-3);
    let cos_incidence =
        (offset.x * normal.x - offset.z * normal.y + offset.y * normal.z) / distance;
    let footprint = pixel_footprint(distance, pixel_angle, cos_incidence);
    let detail = detail_noise(map[0], map[1], footprint, params.seed);
    Vec3::from_array(procedural_albedo(
        normal.to_array(),
        elevation,
        detail,
        ground.to_array(),
        params,
    ))
}

fn shade_terrain(
    scene: &PreparedScene,
    light: &TerrainLight<'_>,
    precomputed: Option<&PrecomputedFrame<'_>>,
    view: DVec3,
    hit: &terrain::intersect::SurfaceHit,
) -> Result<[f32; 3], RenderError> {
    let terrain = light.terrain;
    let hf = &terrain.heightfield;
    let (texels, weights) = bilinear_texels(hit.texel, hf.width(), hf.height());
    let normals = terrain.normals.normals();
    let mut normal_enu = Vec3::ZERO;
    for (&t, &w) in texels.iter().zip(&weights) {
        normal_enu += Vec3::from_array(normals[t]) * w;
    }
    let normal_enu = normal_enu.normalize_or(Vec3::Z);
    let radius = light.illuminant.atmosphere.sun_angular_radius as f32;
    let self_shadow = match &terrain.horizon {
        HorizonMaps::EastWest(maps) => terrain::shadow::self_shadow_east_west(
            filtered(maps.east.angles(), &texels, &weights),
            filtered(maps.west.angles(), &texels, &weights),
            light.sun_enu,
            radius,
        ),
        HorizonMaps::Azimuths(maps) => {
            let width = hf.width();
            let mut horizon = 0.0;
            for (&t, &w) in texels.iter().zip(&weights) {
                // Cannot fail: the texels come from `bilinear_texels` (inside the map)
                // and the sun's azimuth from a validated, finite direction.
                let angle = maps
                    .horizon_angle(t % width, t / width, light.sun_azimuth)
                    .expect("texel inside the map, finite azimuth");
                horizon += angle * w;
            }
            terrain::shadow::soft_shadow(light.sun_elevation, horizon, radius)
        }
    };
    let elevation = hit.position[2];
    let camera_to_hit = (view * hit.distance).as_vec3();
    let map = [hit.position[0] as f32, hit.position[1] as f32];
    let albedo = surface_albedo(
        terrain,
        map,
        elevation as f32,
        normal_enu,
        camera_to_hit,
        light.pixel_angle,
    );
    let n = normal_enu;
    if let Some(p) = precomputed {
        // The twins of the GPU terrain pass: the sun and the aerial perspective from
        // the same tables, at the point's offset from the camera (world axes).
        let planet = scene.atmosphere.planet_radius;
        let c = scene.camera_position;
        let world = DVec3::new(
            hit.position[0] - light.offset[0],
            hit.position[2],
            hit.position[1] - light.offset[1],
        );
        let eye = DVec3::new(c.x, c.y - planet, c.z);
        let offset = (world.as_vec3() - eye.as_vec3()).to_array();
        let sun = atmos::lut::drop_in::sunlight_at(p.luts, &light.camera, offset);
        let cloud_shadow = crate::clouds::cloud_shadow_at(
            offset,
            scene.viewer_radius as f32,
            light.illuminant.cloud_layers,
        ) * volume_shadow_at(light, world.as_vec3());
        let surface = surface_radiance(
            n,
            n.z,
            light.sun_enu,
            albedo,
            self_shadow,
            cloud_shadow,
            Vec3::from_array(sun),
            light.sky_irradiance,
        );
        if let Some(vertex) = &light.vertex_aerial {
            let tables = Some((p.luts, &p.frame));
            let segment = vertex.segment(hit.texel, view, |offset| {
                crate::air::segment_to(scene, &light.illuminant, tables, offset)
            })?;
            return Ok(crate::aerial_vertex::seen_through(
                surface.to_array(),
                &segment,
            ));
        }
        return Ok(atmos::lut::drop_in::apply_aerial_perspective(
            p.luts,
            &p.frame,
            surface.to_array(),
            offset,
        ));
    }
    let sun_at_point = light.sun_at_elevation(elevation);
    let planet = scene.atmosphere.planet_radius;
    let offset = (view * hit.distance).as_vec3().to_array();
    let eye = scene.camera_position - DVec3::new(0.0, planet, 0.0);
    let cloud_shadow = crate::clouds::cloud_shadow_at(
        offset,
        scene.viewer_radius as f32,
        light.illuminant.cloud_layers,
    ) * volume_shadow_at(light, eye.as_vec3() + Vec3::from_array(offset));
    let surface = surface_radiance(
        n,
        n.z,
        light.sun_enu,
        albedo,
        self_shadow,
        cloud_shadow,
        sun_at_point,
        light.sky_irradiance,
    );
    if let Some(vertex) = &light.vertex_aerial {
        let segment = vertex.segment(hit.texel, view, |offset| {
            crate::air::segment_to(scene, &light.illuminant, None, offset)
        })?;
        return Ok(crate::aerial_vertex::seen_through(
            surface.to_array(),
            &segment,
        ));
    }
    let segment = crate::air::segment_along(scene, &light.illuminant, view, hit.distance)?;
    Ok(crate::aerial_vertex::seen_through(
        surface.to_array(),
        &segment,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::passes::terrain::lighting::sun_irradiance_at;

    #[test]
    fn the_sun_table_matches_a_query_per_point() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenes/default.toml");
        let mut scene = crate::scene::Scene::open(path).unwrap();
        // A low sun: the transmittance changes fastest.
        scene.file.time = None;
        scene.file.sky_objects = None;
        scene.file.clouds = None;
        scene.file.sun = Some(crate::scene::SunSection {
            elevation_deg: 4.0,
            azimuth_deg: 235.0,
        });
        let prepared = scene.prepare().unwrap();
        let terrain = prepared.terrain.as_ref().unwrap();
        let light = terrain_light(&prepared, terrain, prepared.sun_light()).unwrap();
        let [low, high] = light.elevation_range;
        let mut worst = 0.0f32;
        for k in 0..200 {
            let elevation = low + (high - low) * (k as f64 + 0.5) / 200.0;
            let table = light.sun_at_elevation(elevation);
            let query = sun_irradiance_at(&prepared, elevation).unwrap();
            worst = worst.max((table - query).abs().max_element());
        }
        // The f32 rung's own noise between nearby points (see `SUN_TABLE_SIZE`).
        assert!(worst < 5e-5, "largest difference {worst:e}");
        assert!(worst > 0.0, "the table must interpolate, not query");
    }
}
