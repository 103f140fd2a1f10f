//! The CPU reference renderer of a scene: sky and terrain, composed from the public
//! APIs of `atmos` and `terrain` (rayon across rows).
//!
//! Per pixel (`atmos::frame::frame_view_direction` gives the ray):
//! 1. `terrain::intersect::HeightfieldTracer` finds the first hit on the bilinear
//!    heightfield within `[near, far]` (exact per cell; see its docs).
//! 2. A hit is shaded with seed 000's `terrain_shading` ([`crate::terrain_shading`]):
//!    bilinearly filtered normal and horizon angle at the hit (what a GPU's linear
//!    sampler gives), self-shadow by `terrain::shadow`'s soft shadow against the sun's
//!    disc (atmos' sun radius), lit by the sun through the rung's transmittance from
//!    the point (tabulated per frame over the terrain's elevations) and by `atmos::ground_irradiance`'s sky term (computed once per frame at
//!    the terrain's mean elevation under the camera). It is then seen through the
//!    atmosphere: `surface × transmittance + in-scatter` of the rung's segment
//!    `camera → hit` (`SkyQuery::with_max_distance`).
//! 3. A miss is the rung's sky to the ground or space, plus the sun disc through its
//!    transmittance ([`crate::present::present_radiance`], the one disc formula).
//!
//! Then [`crate::tonemap`]: exposure, `1 − exp(−x)`, sRGB, triangular dither, RGBA8.
//!
//! Frames: the world is `x` east, `y` up, `z` south; the planet-centred frame of
//! `atmos` is the same axes shifted by the planet radius along `y` (the camera's
//! ground is the planet's surface at the origin). The terrain is flat in the world:
//! at 30 km the sphere falls 70 m below it, which the atmosphere (and the flat-baked
//! horizon maps) ignore.

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use crate::RenderError;
use crate::present::PresentParameters;
use crate::scene::prepare::{HorizonMaps, Illuminant, PreparedScene, PreparedTerrain};
use crate::terrain_shading::surface_radiance;
use crate::tonemap::{pack_rgba8, quantize_srgb8, tonemap_exposure};

/// A rendered frame: packed RGBA8 (R in the low byte), row-major, top row first.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// `width × height` packed pixels.
    pub pixels: Vec<u32>,
}

/// What a pixel shows (linear radiance in the unit of the sun irradiance per sr).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelRadiance {
    /// Radiance reaching the camera.
    pub radiance: [f32; 3],
    /// Distance to the terrain hit (m), `None` for the sky.
    pub terrain_distance: Option<f32>,
}

fn atmos_error(e: atmos::AtmosError) -> RenderError {
    RenderError::Atmosphere(e)
}

/// Per-frame lighting of the terrain.
struct TerrainLight<'a> {
    terrain: &'a PreparedTerrain,
    tracer: terrain::intersect::HeightfieldTracer<'a>,
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
    /// The per-vertex aerial perspective's mesh and vertex segments
    /// (`[terrain] aerial_perspective = "per-vertex"`), `None` per pixel.
    vertex_aerial: Option<crate::aerial_vertex::VertexAerial>,
}

/// Elevations at which the sun's transmittance is queried per frame. The terrain is
/// flat in the world frame (as its horizon maps are baked), so the sun's path from a
/// terrain point depends only on the point's elevation; transmittance is smooth in
/// elevation, and linear interpolation between 64 samples over the default scene's
/// 1.8 km relief differs from a query per point by at most 2.3e-5 (sun 4° high,
/// precomputed rung; `cpu_renderer::tests::the_sun_table_matches_a_query_per_point`).
/// That is the f32 rung's own noise, not the interpolation: 128 samples give 2.7e-5.
pub const SUN_TABLE_SIZE: usize = 64;

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
    .map_err(atmos_error)?;
    let t = light.segment_model.evaluate(&query).transmittance;
    let e = a.sun_irradiance;
    Ok(Vec3::new(
        (t[0] * e[0]) as f32,
        (t[1] * e[1]) as f32,
        (t[2] * e[2]) as f32,
    ))
}

/// The precomputed rung's tables for one frame: the CPU twins of the GPU's passes
/// (`atmos::lut::drop_in`) read them, so the two renderers shade alike.
struct PrecomputedFrame<'a> {
    luts: &'a atmos::lut::StaticLuts,
    frame: atmos::lut::FrameLuts,
    sky: atmos::lut::drop_in::SkyPassParameters,
}

/// Linear radiance of every pixel, row-major (the HDR image before display).
pub fn render_radiance(scene: &PreparedScene) -> Result<Vec<PixelRadiance>, RenderError> {
    if let Some(cloud) = scene
        .shell_cloud
        .as_ref()
        .filter(|c| !c.shadows_baked_on_cpu())
    {
        let maps = [&cloud.shadow, &cloud.moon_shadow]
            .into_iter()
            .flatten()
            .count();
        return Err(RenderError::InvalidParameter {
            field: "clouds.shell",
            value: format!("{maps} shadow map(s) without values"),
            reason: "prepared for the GPU (Scene::prepare_for_gpu): call \
                     PreparedScene::bake_shell_shadow_on_cpu first",
        });
    }
    let camera = &scene.camera;
    let (width, height) = (camera.width as usize, camera.height as usize);
    let light = match &scene.terrain {
        Some(terrain) => Some(terrain_light(scene, terrain, scene.sun_light())?),
        None => None,
    };
    let precomputed = precomputed_frame(&scene.sun_light(), camera, scene.sky_objects.is_none())?;
    // At night the moon lights the terrain too (the twin of the GPU's second, additive
    // terrain draw): each hit is shaded by both lights, traced once.
    let moon_light = match (scene.moon_light(), &scene.terrain) {
        (Some(moon), Some(terrain)) => Some((
            terrain_light(scene, terrain, moon)?,
            precomputed_frame(&moon, camera, false)?,
        )),
        _ => None,
    };
    let moon = moon_light
        .as_ref()
        .map(|(light, tables)| (light, tables.as_ref()));
    let mut out = vec![
        PixelRadiance {
            radiance: [0.0; 3],
            terrain_distance: None,
        };
        width * height
    ];
    out.par_chunks_mut(width)
        .enumerate()
        .try_for_each(|(row, pixels)| {
            for (column, pixel) in pixels.iter_mut().enumerate() {
                *pixel = shade_pixel(
                    scene,
                    light.as_ref(),
                    precomputed.as_ref(),
                    moon,
                    [column as u32, row as u32],
                )?;
            }
            Ok::<(), RenderError>(())
        })?;
    if let Some(moon) = &scene.moonlit {
        // The twin of the GPU's second sky pass: the moonlit sky added where the sky
        // shows (no disc: celestial draws the moon).
        let moon_camera = moon.camera(camera);
        let tables = match &moon.precomputed {
            Some(sky) => Some((
                sky.static_luts(),
                atmos::lut::FrameLuts::bake(sky.static_luts(), &moon_camera),
                atmos::lut::drop_in::SkyPassParameters::new(&moon.atmosphere, false, 1.0, 0.0)
                    .map_err(atmos_error)?,
            )),
            None => None,
        };
        let planet = scene.atmosphere.planet_radius;
        out.par_chunks_mut(width)
            .enumerate()
            .try_for_each(|(row, pixels)| {
                for (column, pixel) in pixels.iter_mut().enumerate() {
                    if pixel.terrain_distance.is_some() {
                        continue;
                    }
                    let xy = [column as u32, row as u32];
                    let added = match &tables {
                        Some((luts, frame, parameters)) => {
                            atmos::lut::drop_in::sky_pass_radiance(luts, frame, xy, parameters)
                        }
                        None => {
                            let view = atmos::frame::frame_view_direction(xy, camera);
                            let view = DVec3::from_array(view.map(f64::from)).normalize();
                            let query = atmos::SkyQuery::new(
                                planet,
                                scene.camera_position,
                                view,
                                moon.direction,
                            )
                            .map_err(atmos_error)?;
                            moon.sky_model.evaluate(&query).radiance.map(|v| v as f32)
                        }
                    };
                    for (value, a) in pixel.radiance.iter_mut().zip(added) {
                        *value += a;
                    }
                }
                Ok::<(), RenderError>(())
            })?;
    }
    if let Some(frame) = &scene.sky_objects {
        // The twin of the GPU's sky-objects pass: added where the sky shows (the GPU
        // pass's depth test hides them behind terrain).
        let mut objects = vec![[0.0f32; 3]; width * height];
        celestial::objects::render_sky_objects_cpu(frame, &mut objects)?;
        for (pixel, added) in out.iter_mut().zip(&objects) {
            if pixel.terrain_distance.is_none() {
                for (value, a) in pixel.radiance.iter_mut().zip(added) {
                    *value += a;
                }
            }
        }
    }
    if !scene.cloud_layers.is_empty() {
        // The twin of the GPU's cloud pass: the layers nearer than the terrain.
        let r = scene.viewer_radius as f32;
        out.par_chunks_mut(width)
            .enumerate()
            .for_each(|(row, pixels)| {
                for (column, pixel) in pixels.iter_mut().enumerate() {
                    let view =
                        atmos::frame::frame_view_direction([column as u32, row as u32], camera);
                    pixel.radiance = crate::clouds::composite_cloud_layers(
                        view,
                        r,
                        pixel.terrain_distance.unwrap_or(f32::INFINITY),
                        &scene.cloud_layers,
                        pixel.radiance,
                    );
                }
            });
    }
    // A marched cloud alone; with both, the two by depth per pixel (crate::cloud_order).
    let alone = scene.shell_cloud.is_none() || scene.volume_cloud.is_none();
    if let (Some(shell), true) = (&scene.shell_cloud, alone) {
        // The [clouds.shell] deck (crate::shell_clouds); at night its march lit by the
        // moon is added through the moonlit tables.
        let tables = precomputed.as_ref().map(|p| (p.luts, &p.frame));
        let moon = match (&shell.moon, scene.moon_light()) {
            (Some(_), Some(light)) => Some((precomputed_frame(&light, camera, false)?, light)),
            _ => None,
        };
        let moon = moon
            .as_ref()
            .map(|(frame, light)| (light, frame.as_ref().map(|p| (p.luts, &p.frame))));
        crate::shell_clouds::composite_shell_cloud(scene, shell, tables, moon, &mut out)?;
    }
    if let (Some(cloud), true) = (&scene.volume_cloud, alone) {
        composite_volume_cloud(scene, cloud, precomputed.as_ref(), &mut out)?;
    }
    if let (Some(shell), Some(cloud)) = (&scene.shell_cloud, &scene.volume_cloud) {
        let tables = precomputed.as_ref().map(|p| (p.luts, &p.frame));
        let moon = match scene.moon_light() {
            Some(light) if shell.moon.is_some() || cloud.moon.is_some() => {
                Some((precomputed_frame(&light, camera, false)?, light))
            }
            _ => None,
        };
        let moon = moon
            .as_ref()
            .map(|(frame, light)| (light, frame.as_ref().map(|p| (p.luts, &p.frame))));
        crate::cloud_order::composite_clouds_by_depth(scene, shell, cloud, tables, moon, &mut out)?;
    }
    if let Some(cloud) = &scene.billboard_cloud {
        let tables = precomputed.as_ref().map(|p| (p.luts, &p.frame));
        crate::billboard_clouds::composite_billboards_cpu(scene, cloud, tables, &mut out)?;
    }
    Ok(out)
}

/// The twin of the GPU's march and volume-cloud composite (`crate::volume_clouds`):
/// each pixel's f32 march through the scene's cloud, drawn where its depth is nearer
/// than the terrain, seen through the air (the precomputed rung's aerial-perspective
/// table, else the segment model) over what is behind it. At night the cloud is
/// marched again lit by the moon and seen through the moonlit air, added.
fn composite_volume_cloud(
    scene: &PreparedScene,
    cloud: &crate::volume_clouds::PreparedVolume,
    precomputed: Option<&PrecomputedFrame<'_>>,
    out: &mut [PixelRadiance],
) -> Result<(), RenderError> {
    use crate::volume_clouds::{composite_marched_cloud, march_pixel_lit, pinhole_camera};
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let pinhole = pinhole_camera(camera, scene.atmosphere.planet_radius)?;
    let moon = match (&cloud.moon, scene.moon_light()) {
        (Some(moonlit), Some(light)) => {
            let tables = precomputed_frame(&light, camera, false)?;
            Some((moonlit, light, tables))
        }
        _ => None,
    };
    fn tables<'a>(p: Option<&'a PrecomputedFrame<'_>>) -> crate::air::AirTables<'a> {
        p.map(|p| (p.luts, &p.frame))
    }
    composite_marched_cloud(
        scene,
        &cloud.lighting,
        tables(precomputed),
        moon.as_ref()
            .map(|(moonlit, light, frame)| (&moonlit.lighting, light, tables(frame.as_ref()))),
        |lighting, xy, behind| march_pixel_lit(cloud, lighting, &pinhole, size, xy, behind),
        out,
    )
}

/// The scene on the CPU, tone-mapped and dithered to RGBA8.
pub fn render_cpu(scene: &PreparedScene) -> Result<Frame, RenderError> {
    let radiance: Vec<[f32; 3]> = render_radiance(scene)?.iter().map(|p| p.radiance).collect();
    let camera = &scene.camera;
    Ok(Frame {
        width: camera.width,
        height: camera.height,
        pixels: display_pixels(&radiance, camera.width, &scene.present),
    })
}

/// Row-major radiance `width` pixels wide to display pixels: the exposure, the tone
/// map, sRGB and the triangular dither of `present` (the display pass's twin), packed
/// RGBA8.
pub fn display_pixels(radiance: &[[f32; 3]], width: u32, present: &PresentParameters) -> Vec<u32> {
    let width = width.max(1) as usize;
    radiance
        .par_iter()
        .enumerate()
        .map(|(i, radiance)| {
            let pixel = [(i % width) as u32, (i / width) as u32];
            let display = tonemap_exposure(*radiance, present.exposure);
            pack_rgba8(quantize_srgb8(display, pixel, present.dither_seed))
        })
        .collect()
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
        &ModelRef(light.sky_model),
        light.atmosphere,
        here,
        light.direction,
        atmos::ground_irradiance::HemisphereQuadrature::default(),
    )
    .map_err(atmos_error)?;
    let s = light.direction.as_vec3();
    let sun_enu = Vec3::new(s.x, -s.z, s.y);
    Ok(TerrainLighting {
        sky_irradiance: Vec3::from_array(irradiance.sky.map(|v| v as f32)),
        sun_enu,
        sun_elevation: terrain::shadow::sun_elevation(sun_enu),
        sun_azimuth: terrain::shadow::sun_azimuth(sun_enu),
        elevation_range: [low, high],
    })
}

fn terrain_light<'a>(
    scene: &PreparedScene,
    terrain: &'a PreparedTerrain,
    illuminant: Illuminant<'a>,
) -> Result<TerrainLight<'a>, RenderError> {
    let tracer = terrain::intersect::HeightfieldTracer::new(&terrain.heightfield);
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
        tracer,
        offset,
        camera: illuminant.camera(&scene.camera),
        illuminant,
        sky_irradiance: lighting.sky_irradiance,
        sun_enu: lighting.sun_enu,
        sun_elevation: lighting.sun_elevation,
        sun_azimuth: lighting.sun_azimuth,
        sun_table,
        elevation_range: [low, high],
        vertex_aerial: terrain.aerial_perspective.per_vertex().then(|| {
            crate::aerial_vertex::VertexAerial::new(
                scene,
                terrain,
                crate::aerial_vertex::TERRAIN_ERROR_PX,
            )
        }),
    })
}

/// `ground_irradiance` takes a sized model; this lends it the scene's boxed one.
struct ModelRef<'a>(&'a (dyn atmos::SkyModel + Send + Sync));

impl atmos::SkyModel for ModelRef<'_> {
    fn label(&self) -> String {
        self.0.label()
    }
    fn evaluate(&self, query: &atmos::SkyQuery) -> atmos::SkySample {
        self.0.evaluate(query)
    }
}

/// The moon as a second terrain light and its tables (nights with a moonlit sky).
type MoonTerrainLight<'a, 'b> = (&'a TerrainLight<'b>, Option<&'a PrecomputedFrame<'b>>);

fn shade_pixel(
    scene: &PreparedScene,
    light: Option<&TerrainLight<'_>>,
    precomputed: Option<&PrecomputedFrame<'_>>,
    moon: Option<MoonTerrainLight<'_, '_>>,
    pixel: [u32; 2],
) -> Result<PixelRadiance, RenderError> {
    let camera = &scene.camera;
    let view32 = atmos::frame::frame_view_direction(pixel, camera);
    let view = DVec3::from_array(view32.map(f64::from)).normalize();
    let planet = scene.atmosphere.planet_radius;
    if let Some(light) = light
        && let Some((view, hit)) = trace_terrain(scene, light, pixel)
    {
        let mut radiance = shade_terrain(scene, light, precomputed, view, &hit)?;
        if let Some((moon_light, moon_tables)) = moon {
            let added = shade_terrain(scene, moon_light, moon_tables, view, &hit)?;
            for (value, a) in radiance.iter_mut().zip(added) {
                *value += a;
            }
        }
        return Ok(PixelRadiance {
            radiance,
            terrain_distance: Some(hit.distance as f32),
        });
    }
    if let Some(p) = precomputed {
        // The twin of the GPU's sky pass (the sun's disc included).
        return Ok(PixelRadiance {
            radiance: atmos::lut::drop_in::sky_pass_radiance(p.luts, &p.frame, pixel, &p.sky),
            terrain_distance: None,
        });
    }
    let query = atmos::SkyQuery::new(planet, scene.camera_position, view, scene.sun)
        .map_err(atmos_error)?;
    let sample = scene.sky_model.evaluate(&query);
    let radiance = crate::present::present_radiance(
        view32,
        sample.radiance.map(|v| v as f32),
        sample.transmittance.map(|v| v as f32),
        camera,
        &scene.present,
    );
    Ok(PixelRadiance {
        radiance,
        terrain_distance: None,
    })
}

/// The first terrain hit of pixel `pixel`'s ray within `[near, far]`, with the ray's
/// unit world direction.
fn trace_terrain(
    scene: &PreparedScene,
    light: &TerrainLight<'_>,
    pixel: [u32; 2],
) -> Option<(DVec3, terrain::intersect::SurfaceHit)> {
    let view32 = atmos::frame::frame_view_direction(pixel, &scene.camera);
    let view = DVec3::from_array(view32.map(f64::from)).normalize();
    let c = scene.camera_position;
    let origin = [
        c.x + light.offset[0],
        c.z + light.offset[1],
        c.y - scene.atmosphere.planet_radius,
    ];
    let direction = [view.x, view.z, view.y];
    light
        .tracer
        .intersect(origin, direction, scene.near, scene.far)
        .map(|hit| (view, hit))
}

/// The precomputed rung's tables of one light for one frame (`None` for the other
/// rungs); `sun_disc`: whether its sky pass draws the light's disc.
fn precomputed_frame<'a>(
    light: &Illuminant<'a>,
    camera: &atmos::frame::FrameCamera,
    sun_disc: bool,
) -> Result<Option<PrecomputedFrame<'a>>, RenderError> {
    let Some(sky) = light.precomputed else {
        return Ok(None);
    };
    Ok(Some(PrecomputedFrame {
        luts: sky.static_luts(),
        frame: atmos::lut::FrameLuts::bake(sky.static_luts(), &light.camera(camera)),
        sky: atmos::lut::drop_in::SkyPassParameters::new(light.atmosphere, sun_disc, 1.0, 0.0)
            .map_err(atmos_error)?,
    }))
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
    let albedo = terrain.albedo.albedo(elevation as f32, normal_enu.z);
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

/// Writes `frame` as an 8-bit RGBA PNG, atomically: to a temporary file beside
/// `path`, renamed over it only when complete (an existing file is replaced only on
/// success). A missing folder is an error (it is not created). Behind the `png`
/// feature (on with the default `cli`), so the library needs no PNG encoder otherwise.
#[cfg(feature = "png")]
pub fn write_png(path: &std::path::Path, frame: &Frame) -> Result<(), image::ImageError> {
    let bytes: Vec<u8> = frame.pixels.iter().flat_map(|p| p.to_le_bytes()).collect();
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(".partial");
    let temporary = std::path::PathBuf::from(temporary);
    image::save_buffer_with_format(
        &temporary,
        &bytes,
        frame.width,
        frame.height,
        image::ExtendedColorType::Rgba8,
        image::ImageFormat::Png,
    )?;
    std::fs::rename(&temporary, path).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        image::ImageError::IoError(e)
    })
}

/// Writes linear HDR radiance (`width × height` RGB, row-major, the unit of the sun's
/// irradiance per sr, before exposure) as a 32-bit float OpenEXR, atomically like
/// [`write_png`]. Behind the `exr` feature (on with the default `cli`).
#[cfg(feature = "exr")]
pub fn write_exr(
    path: &std::path::Path,
    width: u32,
    height: u32,
    radiance: &[[f32; 3]],
) -> Result<(), image::ImageError> {
    let floats: Vec<f32> = radiance.iter().flatten().copied().collect();
    let image = image::Rgb32FImage::from_raw(width, height, floats).ok_or_else(|| {
        image::ImageError::Parameter(image::error::ParameterError::from_kind(
            image::error::ParameterErrorKind::DimensionMismatch,
        ))
    })?;
    let mut temporary = path.as_os_str().to_owned();
    temporary.push(".partial");
    let temporary = std::path::PathBuf::from(temporary);
    image.save_with_format(&temporary, image::ImageFormat::OpenExr)?;
    std::fs::rename(&temporary, path).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        image::ImageError::IoError(e)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

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
