//! The cloud layers (celestial's SGSky layers: coverage, thickness, wind): composited
//! over the opaque scene farthest first, each hidden where the terrain is nearer; then
//! the in-cloud fog of the layers the camera is in or near (`crate::in_cloud_fog`).

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
    runs: |scene| !scene.cloud_layers.is_empty() || scene.in_cloud_fog.is_some(),
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
    /// The in-cloud fog around the camera.
    pub fog: crate::in_cloud_fog::InCloudFogUniforms,
}

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let layers: Result<String, String> = if scene.cloud_layers.is_empty() {
        Err("no [[clouds.layers]] in front of the viewer: no layer drawn".into())
    } else {
        Ok(format!(
            "{} celestial layer(s) farthest first over the opaque scene, each hidden where \
             the terrain's depth is nearer",
            scene.cloud_layers.len()
        ))
    };
    let fog: Result<String, String> = match &scene.in_cloud_fog {
        Some(fog) => Ok(format!(
            "the camera is in layer {}'s band: in-cloud fog (celestial's Sky::in_cloud_fog, \
             the layers' own {:.0} m visibility at the camera) over terrain and sky: \
             {:.3e}/m at the camera, columns of optical depth {:.2} up and {:.2} down \
             through bands reaching {:.0} m above and {:.0} m below",
            fog.layer,
            celestial::visibility::visibility_from_extinction(fog.extinction_per_m),
            fog.extinction_per_m,
            fog.optical_depth_up,
            fog.optical_depth_down,
            fog.band_above_m,
            fog.band_below_m
        )),
        None => Err("the camera is in no cloud layer's band: no in-cloud fog".into()),
    };
    let status = if layers.is_err() && fog.is_err() {
        Err(
            "no [[clouds.layers]] in front of the viewer and none around it: no cloud \
             pipeline"
                .into(),
        )
    } else {
        layers.clone().or_else(|_| fog.clone())
    };
    vec![
        PlanLine::timed("clouds", status),
        PlanLine::untimed("in-cloud fog", fog),
    ]
}

/// The CPU twin: the layers nearer than the terrain over each pixel.
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let scene = frame.scene;
    let camera = &scene.camera;
    let r = scene.viewer_radius as f32;
    let width = frame.width();
    let fog = crate::in_cloud_fog::InCloudFogUniforms::new(scene.in_cloud_fog.as_ref());
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
                    &fog,
                    pixel.radiance,
                );
            }
        });
    Ok(())
}
