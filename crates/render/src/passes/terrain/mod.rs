//! The terrain: an instanced quadtree of tiles shaded as Hoffman and Preetham's terrain colour
//! (`render::terrain`'s `terrain_surface`: self-shadows from the horizon maps, the
//! cloud layers' and marched clouds' shadows), lit by each light of the frame and seen
//! through the air to the camera. Before the draw, the `[clouds.shell]` deck's shadow
//! map is baked on the GPU when it changed; with a rung without tables the aerial
//! perspective is a compute pass of its own (per pixel after the draw, or per vertex
//! before it).

pub(crate) mod cpu;
pub mod lighting;
pub mod uniforms;

#[cfg(feature = "gpu")]
pub(crate) mod cloud_shadow;
#[cfg(feature = "gpu")]
pub(crate) mod gpu;
#[cfg(feature = "gpu")]
pub(crate) mod shell_shadow;

use super::{PassEntry, PlanLine, rung_model};
use crate::scene::prepare::PreparedScene;

/// Radians per pixel of `camera` (its vertical field over its rows): the footprint that
/// band-limits the procedural materials' detail, the same on both renderers.
pub(crate) fn pixel_angle(camera: &atmos::frame::FrameCamera) -> f32 {
    2.0 * camera.tan_half_fov_y / camera.height as f32
}

/// The terrain's entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "terrain",
    runs: |scene| scene.terrain.is_some(),
    plan,
    cpu: cpu::composite,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

/// The shell's shadow bake, the terrain draw and (rungs without tables) its aerial
/// perspective.
fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let mut lines = vec![PlanLine::timed("shell cloud shadow", shell_shadow(scene))];
    let Some(terrain) = &scene.terrain else {
        lines.push(PlanLine::timed(
            "terrain",
            Err("the scene has no [terrain]: no terrain pipeline, no horizon maps".into()),
        ));
        if rung_model(scene).is_some() {
            lines.push(PlanLine::timed(
                "terrain aerial perspective",
                Err("no terrain".into()),
            ));
        }
        return lines;
    };
    let moonlit = super::moonlit(scene);
    let Some(model) = rung_model(scene) else {
        let aerial = crate::aerial_vertex::plan(terrain.aerial_perspective);
        lines.push(PlanLine::timed(
            "terrain",
            Ok(if moonlit {
                format!(
                    "instanced quadtree tiles, Hoffman–Preetham terrain shading, {aerial}; drawn again lit by \
                     the moon through the moonlit tables, added (timed with \"terrain\")"
                )
            } else {
                format!("instanced quadtree tiles, Hoffman–Preetham terrain shading, {aerial}")
            }),
        ));
        return lines;
    };
    let draw = PlanLine::timed(
        "terrain",
        Ok(format!(
            "instanced quadtree tiles, Hoffman–Preetham terrain shading (render::terrain's terrain_surface), \
             lit through {model}'s transmittance to the top of the atmosphere and by its sky's \
             irradiance (once per frame){}",
            if moonlit {
                "; drawn again lit by the moon, added (timed with \"terrain\")"
            } else {
                ""
            }
        )),
    );
    // Per vertex, the vertices' segments are a compute pass before the draw; per pixel,
    // after it (reading the depth).
    let air = PlanLine::timed(
        "terrain aerial perspective",
        Ok(crate::aerial_vertex::rung_plan(
            terrain.aerial_perspective,
            model,
        )),
    );
    if terrain.aerial_perspective.per_vertex() {
        lines.extend([air, draw]);
    } else {
        lines.extend([draw, air]);
    }
    lines
}

/// The `[clouds.shell]` deck's shadow map on the terrain, baked on the GPU before the
/// draw (an empty timed pass on a frame that reuses it).
fn shell_shadow(scene: &PreparedScene) -> Result<String, String> {
    let Some(cloud) = &scene.shell_cloud else {
        return Err("no [clouds.shell]: no shadow map baked".into());
    };
    if scene.terrain.is_none() {
        return Err("no [terrain] under the deck: no shadow map baked".into());
    }
    Ok(crate::shell_clouds::shell_shadow_plan(scene, cloud)
        .unwrap_or_else(|why| format!("an empty pass: {why}")))
}
