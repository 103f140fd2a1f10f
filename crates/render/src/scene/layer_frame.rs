//! What SGSky's keys leave in a prepared scene and what a moving camera recomputes
//! from it: `[visibility]`'s outcome, and the cloud layers' uniforms for a camera
//! position (their draw order and texture offsets). Apart from their preparation
//! (`super::sgsky_prepare`) so that `super::prepare` depends on nothing that prepares.

/// What `[visibility]` made of the scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PreparedVisibility {
    /// The visibility asked for (m).
    pub distance_m: f64,
    /// The visibility the atmosphere has at the camera (m): the asked one, or the
    /// limit of the air alone when that is shorter ([`PreparedVisibility::rayleigh_limited`]).
    pub aerosol_visibility_m: f64,
    /// Whether Rayleigh scattering and ozone alone already limit the visibility below
    /// the one asked (the aerosol is then zero).
    pub rayleigh_limited: bool,
    /// SGSky's effective visibility at the camera (`Sky::modify_vis`: closed in by the
    /// layers the camera is in or near), with `[time]`.
    pub effective_m: Option<f64>,
}

/// The cloud layers of `sky` for a camera at world `position` (x east, y altitude, z
/// south), farthest first, their texture anchored to the ground: each layer's offset is
/// the camera's east and north plus `drift_m` (by celestial layer index: the layer's
/// wind drift less where the scene starts its camera, so that the offset is SGSky's
/// viewer's travel plus wind drift, 0 at the scene's own camera without wind). A layer
/// the camera is inside is left out (its in-cloud fog draws it).
pub fn cloud_layers_at(
    sky: &celestial::sky::Sky,
    position: glam::DVec3,
    drift_m: &[[f64; 2]],
) -> celestial::Result<Vec<celestial::clouds::CloudLayerUniforms>> {
    Ok(sky
        .cloud_layers_in_draw_order(position.y)?
        .into_iter()
        .map(|(index, mut uniforms)| {
            let drift = drift_m.get(index).copied().unwrap_or_default();
            uniforms.offset = [
                (position.x + drift[0]) as f32,
                (-position.z + drift[1]) as f32,
            ];
            uniforms
        })
        .collect())
}
