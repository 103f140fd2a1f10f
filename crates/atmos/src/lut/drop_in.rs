//! CPU twins of what a caller's own renderer uses from the precomputed rung on the GPU:
//! the sky pass (`shaders/atmos/sky_pass.wgsl`, [`crate::gpu::sky::SkyPass`]) and the
//! aerial perspective and sunlight its shaders apply to their geometry
//! (`shaders/atmos/aerial_perspective.wgsl`). Same names, arguments and units; the
//! WGSL reads the tables and the frame camera from its bind groups where these take
//! them as arguments ([`StaticLuts`], [`FrameLuts`]).

use crate::frame::FrameCamera;
use crate::geometry::ray_sphere_intersect;
use crate::view::{FrameView, ViewCamera, frame_view_direction_at, frame_view_distance};
use crate::{AtmosError, Atmosphere};

use super::Lut2d;
use super::aerial_perspective::{lookup_aerial_perspective, view_cosines};
use super::multiple_scattering_moments::sun_frame_direction;
use super::precomputed_sky::{FrameLuts, StaticLuts, unlimited_view_segment};
use super::raymarch::{ScatteringSegment, march_view_segment, sun_transmittance};
use super::sky_irradiance::lookup_sky_irradiance;

/// The sky pass's uniform (layout identical to WGSL `SkyPassParameters`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct SkyPassParameters {
    /// Radiance of the sun's disc above the atmosphere
    /// ([`Atmosphere::sun_disc_radiance`]); zero draws no disc.
    pub sun_disc_radiance: [f32; 3],
    /// cos(the sun's angular radius).
    pub cos_sun_radius: f32,
    /// Multiplies the output (an exposure, or a change of unit).
    pub radiance_scale: f32,
    /// The clip-space depth of the full-screen triangle (1: the far plane; 0 with
    /// reverse z).
    pub depth: f32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding: [f32; 2],
}

impl SkyPassParameters {
    /// The sun's disc of `atmosphere` (validated), drawn when `sun_disc` is true, and a
    /// `radiance_scale` (finite, ≥ 0) at clip depth `depth` (in [0, 1]).
    pub fn new(
        atmosphere: &Atmosphere,
        sun_disc: bool,
        radiance_scale: f32,
        depth: f32,
    ) -> Result<Self, AtmosError> {
        atmosphere.validate()?;
        let setting = |field: &str, value: f32, reason| AtmosError::InvalidSetting {
            setting: "sky pass",
            field: field.to_owned(),
            value: f64::from(value),
            reason,
        };
        if !(radiance_scale.is_finite() && radiance_scale >= 0.0) {
            return Err(setting(
                "radiance_scale",
                radiance_scale,
                "must be finite and ≥ 0",
            ));
        }
        if !(0.0..=1.0).contains(&depth) {
            return Err(setting("depth", depth, "must be a clip depth in [0, 1]"));
        }
        let disc = atmosphere.sun_disc_radiance();
        Ok(Self {
            sun_disc_radiance: if sun_disc {
                disc.map(|v| v as f32)
            } else {
                [0.0; 3]
            },
            cos_sun_radius: atmosphere.sun_angular_radius.cos() as f32,
            radiance_scale,
            depth,
            padding: [0.0; 2],
        })
    }
}

/// The radiance the sky pass writes at `pixel` of `frame.camera` drawn over a whole
/// target (the view [`ViewCamera::from_frame_camera`] prepares): see
/// [`sky_pass_radiance_at`].
pub fn sky_pass_radiance(
    luts: &StaticLuts,
    frame: &FrameLuts,
    pixel: [u32; 2],
    parameters: &SkyPassParameters,
) -> [f32; 3] {
    let view = ViewCamera::from_frame_camera(&frame.camera).view;
    let position = pixel.map(|p| p as f32 + 0.5);
    sky_pass_radiance_at(luts, frame, &view, position, parameters)
}

/// The radiance the sky pass writes at the target position `position` (pixels, pixel
/// centres at `+0.5`) of `view` (before `radiance_scale`): the whole view ray's
/// in-scatter and, where the ray sees the sun's disc and not the ground, the disc
/// through the ray's transmittance. `frame` holds the tables baked for the view's
/// covering camera ([`ViewCamera::camera`]).
pub fn sky_pass_radiance_at(
    luts: &StaticLuts,
    frame: &FrameLuts,
    view: &FrameView,
    position: [f32; 2],
    parameters: &SkyPassParameters,
) -> [f32; 3] {
    let bindings = luts.bindings();
    let camera = &frame.camera;
    let direction = frame_view_direction_at(position, view);
    let [r, mu, mu_s, nu] = view_cosines(camera, direction, luts.atmosphere.planet_radius);
    let segment = unlimited_view_segment(&bindings, &frame.sky_view, r, mu, mu_s, nu);
    // Rays at the ground: only mu < 0 can meet it (docs/architecture.md).
    let sees_ground =
        mu < 0.0 && ray_sphere_intersect(r, mu, luts.atmosphere.planet_radius)[0] >= 0.0;
    if !sees_ground && nu >= parameters.cos_sun_radius {
        return std::array::from_fn(|c| {
            segment.radiance[c] + segment.transmittance[c] * parameters.sun_disc_radiance[c]
        });
    }
    segment.radiance
}

/// Where a unit direction lands on the frame camera's image: `[u, v, depth]` with `u, v`
/// in [0, 1] over the image (x right, y down) and `depth` the cosine to the camera's
/// forward axis (≤ 0: behind the camera). Inverse of [`crate::frame::frame_view_direction`].
#[doc(hidden)]
pub fn frame_screen_position(camera: &FrameCamera, direction: [f32; 3]) -> [f32; 3] {
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let aspect = camera.width as f32 / camera.height as f32;
    let depth = dot(direction, camera.forward);
    let x = dot(direction, camera.right) / (depth * camera.tan_half_fov_y * aspect);
    let y = dot(direction, camera.up) / (depth * camera.tan_half_fov_y);
    [0.5 * (x + 1.0), 0.5 * (1.0 - y), depth]
}

/// In-scattered radiance (the sun irradiance included) and transmittance between the
/// frame camera and the point `offset` metres from it (planet-frame axes): the
/// aerial-perspective volume where the point is in the camera's frustum and range, a
/// LUT march of `pixel_samples` steps elsewhere.
pub fn aerial_perspective(
    luts: &StaticLuts,
    frame: &FrameLuts,
    offset: [f32; 3],
) -> ScatteringSegment {
    let distance = (offset[0] * offset[0] + offset[1] * offset[1] + offset[2] * offset[2]).sqrt();
    if distance <= 0.0 {
        return ScatteringSegment {
            radiance: [0.0; 3],
            transmittance: [1.0; 3],
        };
    }
    let camera = &frame.camera;
    let settings = &luts.settings;
    let direction = offset.map(|c| c / distance);
    let [u, v, depth] = frame_screen_position(camera, direction);
    let on_screen = depth > 0.0 && (0.0..=1.0).contains(&u) && (0.0..=1.0).contains(&v);
    if on_screen && distance <= settings.aerial_perspective_range {
        let [radiance, transmittance] =
            lookup_aerial_perspective(&frame.aerial_perspective, settings, [u, v], distance);
        return ScatteringSegment {
            radiance,
            transmittance,
        };
    }
    let [r, mu, mu_s, nu] = view_cosines(camera, direction, luts.atmosphere.planet_radius);
    march_view_segment(
        &luts.bindings(),
        r,
        mu,
        mu_s,
        nu,
        distance,
        settings.pixel_samples,
    )
}

/// In-scatter and transmittance between `view`'s camera and the surface at `depth`
/// (the caller's depth buffer) seen through the target position `position` (pixels,
/// pixel centres at `+0.5`): what the depth-buffer aerial-perspective pass
/// ([`crate::gpu::AerialPerspectivePass`]) applies there. `frame` holds the tables
/// baked for the view's covering camera.
pub fn depth_aerial_perspective(
    luts: &StaticLuts,
    frame: &FrameLuts,
    view: &FrameView,
    position: [f32; 2],
    depth: f32,
) -> ScatteringSegment {
    let distance = frame_view_distance(position, depth, view);
    let direction = frame_view_direction_at(position, view);
    aerial_perspective(luts, frame, direction.map(|c| c * distance))
}

/// A surface's radiance (seen at the surface) as the frame camera sees it through the
/// atmosphere: attenuated by the segment's transmittance, plus its in-scatter.
pub fn apply_aerial_perspective(
    luts: &StaticLuts,
    frame: &FrameLuts,
    surface_radiance: [f32; 3],
    offset: [f32; 3],
) -> [f32; 3] {
    let segment = aerial_perspective(luts, frame, offset);
    std::array::from_fn(|c| surface_radiance[c] * segment.transmittance[c] + segment.radiance[c])
}

/// The sun's irradiance (per unit area facing the sun) reaching the point `offset`
/// metres from `camera` (planet-frame axes): `sun_irradiance` through the
/// transmittance LUT, 0 in the planet's shadow.
pub fn sunlight_at(luts: &StaticLuts, camera: &FrameCamera, offset: [f32; 3]) -> [f32; 3] {
    let position: [f32; 3] = std::array::from_fn(|i| camera.position[i] + offset[i]);
    let r =
        (position[0] * position[0] + position[1] * position[1] + position[2] * position[2]).sqrt();
    let mu_s =
        ((camera.sun[0] * position[0] + camera.sun[1] * position[1] + camera.sun[2] * position[2])
            / r)
            .clamp(-1.0, 1.0);
    let transmittance =
        sun_transmittance(&luts.bindings(), r.max(luts.atmosphere.planet_radius), mu_s);
    std::array::from_fn(|c| luts.atmosphere.sun_irradiance[c] * transmittance[c])
}

/// The sun's transmittance to the planet-centred point `position` (m) with the sun
/// along `camera.sun`: through the transmittance LUT, 0 in the planet's shadow.
pub fn sun_transmittance_at(
    luts: &StaticLuts,
    camera: &FrameCamera,
    position: [f32; 3],
) -> [f32; 3] {
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let r = dot(position, position).sqrt();
    let mu_s = (dot(camera.sun, position) / r).clamp(-1.0, 1.0);
    sun_transmittance(&luts.bindings(), r.max(luts.atmosphere.planet_radius), mu_s)
}

/// Irradiance (the unit of `sun_irradiance`) that a surface of unit `normal`
/// (planet-frame axes) at the planet-centred point `position` (m) receives from the
/// sky, the sun along `camera.sun`: every order of scattered sunlight and the ground's
/// Lambertian radiance, from the sky-irradiance LUT `table`
/// ([`super::sky_irradiance::bake_sky_irradiance_lut`]). The direct sun is not
/// included ([`sun_transmittance_at`]). Points above the atmosphere read its top.
pub fn sky_irradiance(
    luts: &StaticLuts,
    table: &Lut2d,
    camera: &FrameCamera,
    position: [f32; 3],
    normal: [f32; 3],
) -> [f32; 3] {
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let r = dot(position, position).sqrt();
    let zenith = position.map(|c| c / r);
    let mu_s = dot(camera.sun, zenith).clamp(-1.0, 1.0);
    let mu_n = dot(normal, zenith).clamp(-1.0, 1.0);
    let nu_n = dot(normal, camera.sun).clamp(-1.0, 1.0);
    let direction = sun_frame_direction(mu_n, mu_s, nu_n);
    let atmosphere = &luts.atmosphere;
    lookup_sky_irradiance(
        &luts.bindings(),
        table,
        r.clamp(atmosphere.planet_radius, atmosphere.top_radius),
        mu_s,
        direction,
    )
}
