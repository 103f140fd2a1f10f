//! The `[clouds.volume]` cumulus drawn as Dobashi et al. (2000)'s billboards: one
//! splat per dense cell, lit by slice propagation, drawn back to front, depth-tested
//! against the terrain and seen through the air.

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use super::{PassEntry, PlanLine, rung_model};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::scene::prepare::PreparedScene;

/// The billboards' entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "billboards",
    runs: |scene| scene.billboard_cloud.is_some(),
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let status = crate::billboard_clouds::explain(scene).map(|text| match rung_model(scene) {
        // The billboards' air: the rung's functions per particle, not atmos' tables.
        Some(model) => format!(
            "{text} ({model}'s in-scatter and transmittance of the segment to each particle \
             per light: a compute pass before the draw, untimed, render::billboard_clouds)"
        ),
        None => text,
    });
    vec![PlanLine::timed("billboard clouds", status)]
}

/// The CPU twin: the splats rasterised back to front over the scene.
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let Some(cloud) = &frame.scene.billboard_cloud else {
        return Ok(());
    };
    let tables = frame.lights[0].air();
    crate::billboard_clouds::composite_billboards_cpu(frame.scene, cloud, tables, &mut frame.pixels)
}
