//! The deck's march per pixel on the CPU (the f32 twin of `MarchShellPass`) and its
//! composite over the scene.

use cloudlight::march::{Lighting, MarchError, MarchResult, PinholeCamera};

use super::PreparedShell;

/// The scene camera as a pinhole camera in the shell's planet-centred frame (module
/// documentation): [`crate::volume_clouds::pinhole_camera`] with the planet centre as
/// the origin, so [`cloudlight::march::pixel_direction`] gives the scene's pixel rays.
pub fn shell_camera(camera: &atmos::frame::FrameCamera) -> Result<PinholeCamera, MarchError> {
    crate::volume_clouds::pinhole_camera(camera, 0.0)
}

/// The march of pixel `pixel` through the shell (f32, the twin of `MarchShellPass`'s
/// pixel): along [`cloudlight::march::pixel_direction`] of `camera` from its origin, up
/// to `max_distance` metres (the terrain's hit; infinite for the sky), then faded by the
/// shell's horizon fade at the result's depth.
pub fn march_shell_pixel(
    cloud: &PreparedShell,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    let sun = &cloud.lights[0].lighting;
    march_shell_pixel_lit(cloud, sun, camera, size, pixel, max_distance)
}

/// [`march_shell_pixel`] lit by `lighting` (one of [`PreparedShell::lights`]).
pub fn march_shell_pixel_lit(
    cloud: &PreparedShell,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    let result = crate::volume_clouds::march_field_pixel(
        &cloud.shell,
        &cloud.settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
    );
    cloudlight::march::faded(result, cloud.shell.horizon_fade(result.depth))
}

/// The CPU twin of the GPU's shell march and composite: per pixel, the f32 march through
/// the shell up to the terrain's hit (`PixelRadiance::terrain_distance`; the sky: no
/// limit), faded toward the horizon, in the volume cloud's composite
/// (`crate::volume_clouds::composite_marched_cloud`: drawn where it has opacity in front
/// of the scene, seen through the air of [`crate::air::air_in_front`] with each light's
/// tables), once per light of `lights` (the frame's), added.
pub(crate) fn composite_shell_cloud(
    scene: &crate::scene::PreparedScene,
    cloud: &PreparedShell,
    lights: &[crate::cpu_frame::LightFrame<'_>],
    out: &mut [crate::cpu_frame::PixelRadiance],
) -> Result<(), crate::RenderError> {
    let camera = &scene.camera;
    let size = [camera.width, camera.height];
    let pinhole = shell_camera(camera)?;
    crate::marched_cloud::composite_marched_cloud(
        scene,
        &crate::marched_cloud::lit_by(&cloud.lights, lights),
        |lighting, xy, behind| march_shell_pixel_lit(cloud, lighting, &pinhole, size, xy, behind),
        out,
    )
}
