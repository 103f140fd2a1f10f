//! The sun, moon, planets and stars: celestial's sky objects for the scene's date,
//! time and place, added where the sky shows (depth-tested behind the terrain).

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use super::{PassEntry, PlanLine};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::scene::prepare::PreparedScene;

/// The sky objects' entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "sky objects",
    runs: |scene| scene.sky_objects.is_some(),
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let elevation = scene.sun_elevation_deg();
    let status = match &scene.sky_objects {
        Some(frame) if elevation < -18.0 => Ok(format!(
            "celestial's moon, planets and {} point sources (the sun {elevation:.1}° is below \
             −18°: astronomical night, no sun disc)",
            frame.points.len()
        )),
        Some(frame) => Ok(format!(
            "celestial's sun disc and aureole, moon, planets and {} point sources above the \
             eye's threshold against the sky, depth-tested behind terrain",
            frame.points.len()
        )),
        None => Err(
            "no [time] in the scene (or [sky_objects] enabled = false): no sky-objects \
             pipeline; the sky pass draws the sun's disc"
                .into(),
        ),
    };
    vec![PlanLine::timed("sky objects", status)]
}

/// The CPU twin: celestial's objects added where the sky shows (the GPU pass's depth
/// test hides them behind terrain).
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let Some(objects_frame) = &frame.scene.sky_objects else {
        return Ok(());
    };
    let mut objects = vec![[0.0f32; 3]; frame.pixels.len()];
    celestial::objects::render_sky_objects_cpu(objects_frame, &mut objects)?;
    for (pixel, added) in frame.pixels.iter_mut().zip(&objects) {
        if pixel.terrain_distance.is_none() {
            for (value, a) in pixel.radiance.iter_mut().zip(added) {
                *value += a;
            }
        }
    }
    Ok(())
}
