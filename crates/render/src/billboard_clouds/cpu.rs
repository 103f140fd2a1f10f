//! The billboards on the CPU: the particles for the scene's camera, rasterised back to
//! front over the scene (the twin of the GPU's draw), and `skyscape explain`'s line.

use glam::DVec3;

use cloudlight::billboard::{Billboard, Camera, FieldOfView, ParticleLight};
use cloudlight::march::Lighting;
use cloudlight::propagate::SliceMode;

use crate::RenderError;
use crate::cpu_frame::PixelRadiance;
use crate::scene::PreparedScene;
use crate::volume_clouds::world_to_enu;

use super::*;

/// The near plane of the billboards and of the GPU's depth (`near / z`): the scene's,
/// at least 1 cm (as the volume cloud's composite).
pub fn billboard_near(near: f64) -> f64 {
    near.max(0.01)
}

/// The scene camera as `cloudlight::billboard`'s camera in the volume's frame: its
/// position less the planet radius up and its basis rotated to east/north/up, the
/// vertical field of view `2·atan(tan_half_fov_y)`, the image size.
pub fn billboard_camera(
    camera: &atmos::frame::FrameCamera,
    planet_radius: f64,
) -> Result<Camera, cloudlight::billboard::BillboardError> {
    let p = camera.position.map(f64::from);
    let origin = world_to_enu([p[0], p[1] - planet_radius, p[2]]);
    let forward = world_to_enu(camera.forward.map(f64::from));
    let up = world_to_enu(camera.up.map(f64::from));
    Camera::new(
        DVec3::from(origin),
        DVec3::from(forward),
        DVec3::from(up),
        FieldOfView::from_radians(2.0 * f64::from(camera.tan_half_fov_y).atan()),
        camera.width,
        camera.height,
    )
}

fn billboard_error(e: cloudlight::billboard::BillboardError) -> RenderError {
    RenderError::Billboards(e)
}

/// The particles of `cloud` the scene's camera sees, sorted back to front, their colours
/// the light they scatter toward the eye before the air
/// (`cloudlight::billboard::particle_radiance`: each light's — the sun's, the moon's at
/// night — and the ambient sky each scatters).
pub fn particles(
    scene: &PreparedScene,
    cloud: &PreparedBillboards,
) -> Result<(Camera, Vec<Billboard>), RenderError> {
    let camera =
        billboard_camera(&scene.camera, scene.atmosphere.planet_radius).map_err(billboard_error)?;
    let sun = &cloud.lights[0];
    let mut particles =
        cloudlight::billboard::billboards(&cloud.volume, &sun.light, &cloud.settings, &camera)
            .map_err(billboard_error)?;
    let light = |lighting: &Lighting<f32>, transmittance: f32| ParticleLight {
        direction: lighting.sun_direction().map(f64::from),
        irradiance: lighting.sun_irradiance().map(f64::from),
        transmittance: f64::from(transmittance),
    };
    let mut ambient = sun.lighting.ambient_radiance().map(f64::from);
    for other in &cloud.lights[1..] {
        let add = other.lighting.ambient_radiance();
        for (a, m) in ambient.iter_mut().zip(add) {
            *a += f64::from(m);
        }
    }
    let mut lights = Vec::with_capacity(cloud.lights.len());
    for p in &mut particles {
        let r = DVec3::from_array(p.relative);
        let view = (r / r.length()).to_array();
        lights.clear();
        lights.extend(
            cloud
                .lights
                .iter()
                .map(|lit| light(&lit.lighting, lit.light[p.cell])),
        );
        p.colour = cloudlight::billboard::particle_radiance(
            view,
            &lights,
            ambient,
            f64::from(cloud.ambient_visibility[p.cell]),
            &cloud.scattering,
        );
    }
    Ok((camera, particles))
}

/// The world offset (x east, y up, z south) of a particle's position relative to the
/// eye (east/north/up), in f32 as the GPU's instance holds it.
pub fn world_offset(relative: [f64; 3]) -> [f32; 3] {
    let r = relative.map(|c| c as f32);
    [r[0], r[2], -r[1]]
}

/// The air the scene's lights after the sun scatter in front of each particle (the
/// moonlit air at night), summed in the lights' order: each light's in-scattered
/// radiance between the camera and the particle's centre from its segment model
/// ([`crate::air::segment_to`], f32), the same values for both renderers (the GPU's
/// vertex stage adds them to the sun's air, the CPU twin likewise). `None` for a scene
/// lit by the sun alone. The lights' atmospheres differ in irradiance only, so the
/// transmittance is the sun's.
pub fn other_lights_air(
    scene: &PreparedScene,
    cloud: &PreparedBillboards,
    particles: &[Billboard],
) -> Result<Option<Vec<[f32; 3]>>, RenderError> {
    let lights = scene.lights();
    if cloud.lights.len() < 2 || lights.len() < 2 {
        return Ok(None);
    }
    particles
        .iter()
        .map(|p| {
            let offset = world_offset(p.relative);
            let mut sum: Option<[f32; 3]> = None;
            for light in &lights[1..] {
                let radiance = crate::air::segment_to(scene, light, None, offset)?.radiance;
                sum = Some(match sum {
                    Some(s) => std::array::from_fn(|k| s[k] + radiance[k]),
                    None => radiance,
                });
            }
            Ok(sum.unwrap_or_default())
        })
        .collect::<Result<Vec<_>, RenderError>>()
        .map(Some)
}

/// The twin of the GPU's billboard pass: `cloud`'s particles seen through the air
/// (the precomputed rung's `tables`, else the segment model), rasterised by
/// `cloudlight::billboard::rasterise_limited::<f32>` in front of the terrain and
/// composited over `out`.
pub fn composite_billboards_cpu(
    scene: &PreparedScene,
    cloud: &PreparedBillboards,
    tables: crate::air::AirTables<'_>,
    out: &mut [PixelRadiance],
) -> Result<(), RenderError> {
    let (camera, mut particles) = particles(scene, cloud)?;
    let other_air = other_lights_air(scene, cloud, &particles)?;
    let sun = scene.sun_light();
    for (i, p) in particles.iter_mut().enumerate() {
        let offset = world_offset(p.relative);
        let air = crate::air::segment_to(scene, &sun, tables, offset)?;
        let (transmittance, radiance) = (air.transmittance, air.radiance);
        // The other lights' air is added to the sun's, as the GPU's vertex stage does.
        let radiance = match &other_air {
            Some(air) => std::array::from_fn(|k| radiance[k] + air[i][k]),
            None => radiance,
        };
        // The f32 colour the GPU reads, seen through the air in f32.
        let colour = p.colour.map(|c| c as f32);
        p.colour = billboard_seen_through_air(colour, transmittance, radiance).map(f64::from);
    }
    let frame = &scene.camera;
    let width = frame.width as usize;
    let forward = frame.forward;
    let max_depth: Vec<f32> = out
        .iter()
        .enumerate()
        .map(|(i, pixel)| match pixel.terrain_distance {
            Some(distance) => {
                let view = atmos::frame::frame_view_direction(
                    [(i % width) as u32, (i / width) as u32],
                    frame,
                );
                distance * (view[0] * forward[0] + view[1] * forward[1] + view[2] * forward[2])
            }
            None => f32::INFINITY,
        })
        .collect();
    let image = cloudlight::billboard::rasterise_limited::<f32>(
        &particles,
        &camera,
        cloud.settings.size,
        cloud.settings.opacity,
        &max_depth,
    )
    .map_err(billboard_error)?;
    for (pixel, over) in out.iter_mut().zip(&image.rgba) {
        for (value, c) in pixel.radiance.iter_mut().zip(over) {
            *value = c + (1.0 - over[3]) * *value;
        }
    }
    Ok(())
}

/// The scene's lights' names as a phrase: "sun", "sun and moon".
fn light_names(scene: &PreparedScene) -> String {
    let names: Vec<&str> = scene.lights().iter().map(|l| l.name).collect();
    match names.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} and {last}", rest.join(", ")),
        _ => names.concat(),
    }
}

/// `skyscape explain`'s line for the billboard pass.
pub fn explain(scene: &PreparedScene) -> Result<String, String> {
    match &scene.billboard_cloud {
        Some(cloud) => {
            let [nx, ny, nz] = cloud.volume.dims();
            let drawn = particles(scene, cloud).map_or(0, |(_, p)| p.len());
            Ok(format!(
                "Dobashi et al. 2000's billboards of the [clouds.volume] cumulus ({nx}×{ny}×{nz} cells grown \
                 by cloudsim in {} steps, lit on the CPU by cloudlight's {} slice propagation \
                 toward the {}, the march's phase and octaves and the ambient sky): \
                 {drawn} of {} cells denser than {} drawn back to front, depth-tested against \
                 the terrain, through the aerial perspective",
                cloud.steps,
                match cloud.slices {
                    SliceMode::Physical => "physical",
                    SliceMode::Faithful { .. } => "faithful",
                },
                light_names(scene),
                cloud.dense_cells,
                cloud.settings.density_threshold,
            ))
        }
        None => Err(
            "no [clouds.volume] with draw = \"billboards\": no slice propagation, no billboard \
             pipeline"
                .into(),
        ),
    }
}
