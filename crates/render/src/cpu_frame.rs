//! The CPU renderer's frame: what its passes composite into (the CPU twins of the GPU's
//! render targets) and the per-frame state they share.

use glam::DVec3;
use rayon::prelude::*;

use crate::RenderError;
use crate::scene::prepare::{Illuminant, PreparedScene, PreparedTerrain};

/// What a pixel shows (linear radiance in the unit of the sun irradiance per sr).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelRadiance {
    /// Radiance reaching the camera.
    pub radiance: [f32; 3],
    /// Distance to the terrain hit (m), `None` for the sky.
    pub terrain_distance: Option<f32>,
}

/// The precomputed rung's tables of one light for one frame: the CPU twins of the
/// GPU's passes (`atmos::lut::drop_in`) read them, so the two renderers shade alike.
pub(crate) struct PrecomputedFrame<'a> {
    pub(crate) luts: &'a atmos::lut::StaticLuts,
    pub(crate) frame: atmos::lut::FrameLuts,
    pub(crate) sky: atmos::lut::drop_in::SkyPassParameters,
}

impl PrecomputedFrame<'_> {
    /// The tables as the air's functions read them (`crate::air`).
    pub(crate) fn air(&self) -> crate::air::AirTables<'_> {
        Some((self.luts, &self.frame))
    }
}

/// One light of the frame (the sun; at night also the moon) and its tables.
pub(crate) struct LightFrame<'a> {
    /// The light, its atmosphere and rung.
    pub(crate) illuminant: Illuminant<'a>,
    /// Its precomputed tables for this frame (the precomputed rung; `None` for the
    /// others): the CPU twin of the GPU's LUT bakes, set by the tables pass.
    pub(crate) tables: Option<PrecomputedFrame<'a>>,
}

impl<'a> LightFrame<'a> {
    /// The light's tables as the air's functions read them.
    pub(crate) fn air(&self) -> crate::air::AirTables<'_> {
        self.tables.as_ref().and_then(PrecomputedFrame::air)
    }
}

/// The CPU renderer's frame: the image the passes composite into, the rays' terrain
/// hits (its depth buffer) and the lights' per-frame tables.
pub(crate) struct CpuFrame<'a> {
    /// The scene drawn.
    pub(crate) scene: &'a PreparedScene,
    /// Linear radiance per pixel, row-major, and the terrain's distance where a ray hit
    /// it (set by the terrain pass).
    pub(crate) pixels: Vec<PixelRadiance>,
    /// Each pixel's first terrain hit and its ray's unit world direction (`None`: the
    /// ray sees the sky), traced before the passes.
    pub(crate) hits: Vec<Option<(DVec3, terrain::intersect::SurfaceHit)>>,
    /// The scene's lights, the sun first ([`PreparedScene::lights`]).
    pub(crate) lights: Vec<LightFrame<'a>>,
    /// The display pass's RGBA8 pixels (after it runs).
    pub(crate) display: Option<Vec<u32>>,
}

impl<'a> CpuFrame<'a> {
    pub(crate) fn new(scene: &'a PreparedScene) -> Self {
        let camera = &scene.camera;
        let (width, height) = (camera.width as usize, camera.height as usize);
        let hits = match &scene.terrain {
            Some(terrain) => trace_hits(scene, terrain),
            None => vec![None; width * height],
        };
        Self {
            scene,
            pixels: vec![
                PixelRadiance {
                    radiance: [0.0; 3],
                    terrain_distance: None,
                };
                width * height
            ],
            hits,
            lights: scene
                .lights()
                .into_iter()
                .map(|illuminant| LightFrame {
                    illuminant,
                    tables: None,
                })
                .collect(),
            display: None,
        }
    }

    /// The image's width, pixels.
    pub(crate) fn width(&self) -> usize {
        self.scene.camera.width as usize
    }
}

/// The precomputed rung's tables of one light for one frame (`None` for the other
/// rungs); `sun_disc`: whether its sky pass draws the light's disc.
pub(crate) fn precomputed_frame<'a>(
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
            .map_err(RenderError::Atmosphere)?,
    }))
}

/// Each pixel's first terrain hit within `[near, far]` and its ray's unit world
/// direction: the CPU's depth buffer (rayon across rows).
fn trace_hits(
    scene: &PreparedScene,
    terrain: &PreparedTerrain,
) -> Vec<Option<(DVec3, terrain::intersect::SurfaceHit)>> {
    let camera = &scene.camera;
    let width = camera.width as usize;
    let tracer = terrain::intersect::HeightfieldTracer::new(&terrain.heightfield);
    let offset = terrain.map_offset();
    let mut hits = vec![None; width * camera.height as usize];
    hits.par_chunks_mut(width)
        .enumerate()
        .for_each(|(row, hits)| {
            for (column, hit) in hits.iter_mut().enumerate() {
                let pixel = [column as u32, row as u32];
                let view32 = atmos::frame::frame_view_direction(pixel, camera);
                let view = DVec3::from_array(view32.map(f64::from)).normalize();
                let c = scene.camera_position;
                let origin = [
                    c.x + offset[0],
                    c.z + offset[1],
                    c.y - scene.atmosphere.planet_radius,
                ];
                let direction = [view.x, view.z, view.y];
                *hit = tracer
                    .intersect(origin, direction, scene.near, scene.far)
                    .map(|hit| (view, hit));
            }
        });
    hits
}
