//! The volume cloud's march per pixel on the CPU (the f32 twin of the GPU's march).

use cloudlight::march::{Lighting, MarchResult, MarchSettings, PinholeCamera};

use crate::frames::world_to_enu;

use super::PreparedVolume;

/// The scene camera as the march's pinhole camera in the volume's frame: the camera's
/// position (its planet-centred position less the planet radius up) and basis rotated
/// to east/north/up, the horizontal field of view from the vertical one and the aspect,
/// so [`cloudlight::march::pixel_direction`] gives the scene's pixel rays.
pub fn pinhole_camera(
    camera: &atmos::frame::FrameCamera,
    planet_radius: f64,
) -> Result<PinholeCamera, cloudlight::march::MarchError> {
    let p = camera.position.map(f64::from);
    let origin = world_to_enu([p[0], p[1] - planet_radius, p[2]]);
    let forward = world_to_enu(camera.forward.map(f64::from));
    let up = world_to_enu(camera.up.map(f64::from));
    let target = std::array::from_fn(|a| origin[a] + forward[a]);
    let aspect = f64::from(camera.width) / f64::from(camera.height);
    let horizontal_fov = 2.0 * (f64::from(camera.tan_half_fov_y) * aspect).atan();
    PinholeCamera::look_at(origin, target, up, horizontal_fov)
}

/// The march of pixel `pixel` (f32, the twin of `MarchPass`'s pixel): along
/// [`cloudlight::march::pixel_direction`] of `camera` from its origin, up to
/// `max_distance` metres (the terrain's hit; infinite for the sky).
pub fn march_pixel(
    cloud: &PreparedVolume,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    let sun = &cloud.lights[0].lighting;
    march_pixel_lit(cloud, sun, camera, size, pixel, max_distance)
}

/// [`march_pixel`] lit by `lighting` (one of [`PreparedVolume::lights`]): the twin of
/// the GPU's march with that light.
pub fn march_pixel_lit(
    cloud: &PreparedVolume,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    march_field_pixel(
        &cloud.volume,
        &cloud.settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
    )
}

/// The f32 march of pixel `pixel` through any density field (the volume's, the
/// shell's): along [`cloudlight::march::pixel_direction`] of `camera` from its origin,
/// up to `max_distance` metres.
pub(crate) fn march_field_pixel(
    field: &impl cloudlight::DensityField<f32>,
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
) -> MarchResult<f32> {
    march_field_pixel_through(
        field,
        settings,
        lighting,
        camera,
        size,
        pixel,
        max_distance,
        |_| 0.0,
    )
}

/// [`march_field_pixel`] with the light crossing another cloud too: `outside_depth(p)`
/// its optical depth toward the light above view sample `p` (the field's frame;
/// `cloudlight::march::march_view_lit_through`, `crate::mutual_shadow`).
#[allow(clippy::too_many_arguments)] // march_field_pixel's seven inputs and the hook
pub(crate) fn march_field_pixel_through(
    field: &impl cloudlight::DensityField<f32>,
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    camera: &PinholeCamera,
    size: [u32; 2],
    pixel: [u32; 2],
    max_distance: f32,
    outside_depth: impl Fn([f32; 3]) -> f32,
) -> MarchResult<f32> {
    let [forward, right, up] = camera.basis().map(|v| v.map(|c| c as f32));
    let tan_half = camera.tan_half(size).map(|t| t as f32);
    let origin = camera.origin().map(|c| c as f32);
    let direction = cloudlight::march::pixel_direction(pixel, size, forward, right, up, tan_half);
    let offset = settings.config().jitter.offset(pixel);
    cloudlight::march::march_view_lit_through(
        field,
        origin,
        direction,
        settings,
        lighting,
        offset,
        max_distance,
        outside_depth,
    )
}
