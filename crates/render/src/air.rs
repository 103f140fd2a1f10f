//! The air between the camera and a point: its transmittance and in-scattered radiance
//! for one light, as the CPU renderer evaluates it for the terrain (per vertex), the
//! marched clouds and the billboards.
//!
//! With the precomputed rung's tables of that light it is atmos' aerial perspective
//! (`atmos::lut::drop_in::aerial_perspective`, the twin of the WGSL the GPU's passes
//! call); otherwise the light's segment model (`SkyQuery::with_max_distance` from the
//! camera), cast to f32 as the GPU reads it. One function builds that query, so every
//! caller sees the same segment for the same direction and distance.

use atmos::lut::raymarch::ScatteringSegment;
use glam::DVec3;

use crate::RenderError;
use crate::scene::prepare::{Illuminant, PreparedScene};

/// A light's precomputed tables as the CPU renderer holds them (`None`: the light's
/// segment model).
pub type AirTables<'a> = Option<(&'a atmos::lut::StaticLuts, &'a atmos::lut::FrameLuts)>;

/// The segment of `distance` metres (> 0) from the camera along the unit world
/// `direction`, by `light`'s segment model, in f32.
pub fn segment_along(
    scene: &PreparedScene,
    light: &Illuminant<'_>,
    direction: DVec3,
    distance: f64,
) -> Result<ScatteringSegment, RenderError> {
    let query = atmos::SkyQuery::with_max_distance(
        scene.atmosphere.planet_radius,
        scene.camera_position,
        direction,
        light.direction,
        distance,
    )?;
    let sample = light.segment_model.evaluate(&query);
    Ok(ScatteringSegment {
        radiance: sample.radiance.map(|v| v as f32),
        transmittance: sample.transmittance.map(|v| v as f32),
    })
}

/// The segment camera → the point `offset` metres from it (world axes) lit by `light`:
/// from its `tables` when given, else its segment model ([`segment_along`]); the empty
/// segment at zero offset.
pub fn segment_to(
    scene: &PreparedScene,
    light: &Illuminant<'_>,
    tables: AirTables<'_>,
    offset: [f32; 3],
) -> Result<ScatteringSegment, RenderError> {
    if let Some((luts, frame)) = tables {
        return Ok(atmos::lut::drop_in::aerial_perspective(luts, frame, offset));
    }
    let vector = DVec3::from_array(offset.map(f64::from));
    let distance = vector.length();
    if distance <= 0.0 {
        return Ok(ScatteringSegment {
            radiance: [0.0; 3],
            transmittance: [1.0; 3],
        });
    }
    segment_along(scene, light, vector / distance, distance)
}

/// The air between the camera and `depth` metres (> 0) along unit world `view` lit by
/// `light` (the sun, or the moon at night), as `(transmittance, radiance)`: from its
/// `tables` at the offset `view · depth` when given (the twin of the GPU's air pass),
/// else its segment model along `view` (the twin of the table-free rungs' pass, which
/// takes the direction and the depth).
pub fn air_in_front(
    scene: &PreparedScene,
    light: &Illuminant<'_>,
    tables: AirTables<'_>,
    view: [f32; 3],
    depth: f32,
) -> Result<([f32; 3], [f32; 3]), RenderError> {
    let segment = match tables {
        Some(_) => segment_to(scene, light, tables, view.map(|v| v * depth))?,
        None => {
            let view = DVec3::from_array(view.map(f64::from)).normalize();
            segment_along(scene, light, view, f64::from(depth))?
        }
    };
    Ok((segment.transmittance, segment.radiance))
}
