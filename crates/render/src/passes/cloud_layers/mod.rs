//! The cloud layers (celestial's SGSky layers: coverage, thickness, wind): composited
//! over the opaque scene farthest first, each hidden where the terrain is nearer.

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use rayon::prelude::*;

use super::{PassEntry, PlanLine};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::scene::prepare::PreparedScene;

/// The cloud layers' entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "cloud layers",
    runs: |scene| !scene.cloud_layers.is_empty(),
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

/// The cloud pass's uniform (WGSL `CloudComposite`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CloudComposite {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The viewer's distance from the planet's centre (m).
    pub viewer_radius: f32,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Layers in the storage buffer.
    pub layer_count: u32,
    /// Multiplies the layers' own light (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
}

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let status = if scene.cloud_layers.is_empty() {
        Err("no [[clouds.layers]] in front of the viewer: no cloud pipeline".into())
    } else {
        Ok(format!(
            "{} celestial layer(s) farthest first over the opaque scene, each hidden where \
             the terrain's depth is nearer",
            scene.cloud_layers.len()
        ))
    };
    vec![PlanLine::timed("clouds", status)]
}

/// The CPU twin: the layers nearer than the terrain over each pixel.
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let scene = frame.scene;
    let camera = &scene.camera;
    let r = scene.viewer_radius as f32;
    let width = frame.width();
    frame
        .pixels
        .par_chunks_mut(width)
        .enumerate()
        .for_each(|(row, pixels)| {
            for (column, pixel) in pixels.iter_mut().enumerate() {
                let view = atmos::frame::frame_view_direction([column as u32, row as u32], camera);
                pixel.radiance = crate::clouds::composite_cloud_layers(
                    view,
                    r,
                    pixel.terrain_distance.unwrap_or(f32::INFINITY),
                    &scene.cloud_layers,
                    pixel.radiance,
                );
            }
        });
    Ok(())
}
