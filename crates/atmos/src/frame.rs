//! A pinhole camera for rendering a frame of sky radiance, shared by every rung's GPU
//! renderer and its CPU twin. Twin of `shaders/atmos/frame.wgsl`.

use glam::DVec3;

use crate::AtmosError;
use crate::real::Real;

/// Segment lengths at or above this mean "to the ground or space" in [`FrameCamera`].
pub const UNLIMITED_DISTANCE: f32 = 1e30;

/// The camera uniform (std140/std430 compatible, 80 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameCamera {
    /// Planet-centred position (m).
    pub position: [f32; 3],
    /// Frame width (pixels).
    pub width: u32,
    /// Unit vector toward the right of the image.
    pub right: [f32; 3],
    /// Frame height (pixels).
    pub height: u32,
    /// Unit vector toward the top of the image.
    pub up: [f32; 3],
    /// tan(vertical field of view / 2).
    pub tan_half_fov_y: f32,
    /// Unit view direction of the image centre.
    pub forward: [f32; 3],
    /// Segment length limit (m); [`UNLIMITED_DISTANCE`] or more for the whole ray.
    pub max_distance: f32,
    /// Unit direction toward the sun.
    pub sun: [f32; 3],
    /// Keeps the struct a multiple of 16 bytes.
    pub padding: u32,
}

fn invalid(field: &str, value: f64, reason: &'static str) -> AtmosError {
    AtmosError::InvalidCamera {
        field: field.to_owned(),
        value,
        reason,
    }
}

impl FrameCamera {
    /// A camera at `position` (planet-centred, m) looking along `forward`, with `up_hint`
    /// choosing the roll, a vertical field of view `fov_y` (rad, in (0, π)), a frame of
    /// `width × height` pixels and the sun along `sun`.
    #[allow(clippy::too_many_arguments)]
    pub fn look_at(
        position: DVec3,
        forward: DVec3,
        up_hint: DVec3,
        fov_y: f64,
        width: u32,
        height: u32,
        sun: DVec3,
        max_distance: Option<f64>,
    ) -> Result<Self, AtmosError> {
        for (name, v) in [
            ("position", position),
            ("forward", forward),
            ("up_hint", up_hint),
            ("sun", sun),
        ] {
            for (axis, c) in ["x", "y", "z"].iter().zip(v.to_array()) {
                if !c.is_finite() {
                    return Err(invalid(&format!("{name}.{axis}"), c, "must be finite"));
                }
            }
        }
        if !(fov_y > 0.0 && fov_y < std::f64::consts::PI) {
            return Err(invalid("fov_y", fov_y, "must be in (0, π) rad"));
        }
        if width == 0 {
            return Err(invalid("width", 0.0, "must be ≥ 1 pixel"));
        }
        if height == 0 {
            return Err(invalid("height", 0.0, "must be ≥ 1 pixel"));
        }
        let forward = forward
            .try_normalize()
            .ok_or_else(|| invalid("|forward|", forward.length(), "must be a non-zero vector"))?;
        let sun = sun
            .try_normalize()
            .ok_or_else(|| invalid("|sun|", sun.length(), "must be a non-zero vector"))?;
        let right = forward.cross(up_hint).try_normalize().ok_or_else(|| {
            invalid(
                "up_hint",
                up_hint.normalize_or_zero().dot(forward),
                "must not be parallel to forward (cosine shown)",
            )
        })?;
        let up = right.cross(forward);
        let max_distance = match max_distance {
            None => UNLIMITED_DISTANCE,
            Some(d) if d >= 0.0 => d.min(f64::from(UNLIMITED_DISTANCE)) as f32,
            Some(d) => return Err(invalid("max_distance", d, "must be ≥ 0 m")),
        };
        let f = |v: DVec3| v.as_vec3().to_array();
        Ok(Self {
            position: f(position),
            width,
            right: f(right),
            height,
            up: f(up),
            tan_half_fov_y: (0.5 * fov_y).tan() as f32,
            forward: f(forward),
            max_distance,
            sun: f(sun),
            padding: 0,
        })
    }

    /// Number of pixels.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

/// A local-frame vector (+y up, −z north, +x east, the axes of a game engine's world)
/// in the planet frame's axes (x east, y north, z up at the local frame's origin: the
/// east-north-up axes of terrain and celestial): the workspace's one world → ENU
/// rotation, [`skyscape_wgsl::common::world_to_enu`], `(x, −z, y)`. Generic: the f64
/// instantiation is the reference. Twin of `local_to_planet_direction` in
/// `shaders/atmos/aerial_perspective.wgsl`.
pub fn local_to_planet_direction<F: Real>(direction: [F; 3]) -> [F; 3] {
    skyscape_wgsl::common::world_to_enu(direction)
}

/// A caller's world: a local frame with +y up, −z north and +x east, in metres from an
/// origin on the planet's surface at `origin_altitude` above the sea-level sphere
/// (`planet_radius`). The planet frame atmos works in is planet-centred with z up
/// through that origin: `planet = (x, −z, y + planet_radius + origin_altitude)`. The
/// planet's curvature is the frame's: a point 100 km from the origin at y = 0 is
/// 786 m above the ground sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    /// The planet's radius (m).
    pub planet_radius: f64,
    /// Altitude of the local origin above the planet's surface (m).
    pub origin_altitude: f64,
}

impl LocalFrame {
    /// The local frame whose origin is `origin_altitude` metres above the surface of
    /// `atmosphere`'s planet. Errors naming the field for a non-finite altitude or one
    /// below the planet's centre.
    pub fn new(atmosphere: &crate::Atmosphere, origin_altitude: f64) -> Result<Self, AtmosError> {
        atmosphere.validate()?;
        if !origin_altitude.is_finite() || origin_altitude <= -atmosphere.planet_radius {
            return Err(invalid(
                "origin_altitude",
                origin_altitude,
                "must be finite and above the planet's centre (m)",
            ));
        }
        Ok(Self {
            planet_radius: atmosphere.planet_radius,
            origin_altitude,
        })
    }

    /// The planet-frame position of a local point (m).
    pub fn to_planet_position(&self, position: DVec3) -> DVec3 {
        let [x, y, z] = local_to_planet_direction(position.to_array());
        DVec3::new(x, y, z + self.planet_radius + self.origin_altitude)
    }

    /// The planet-frame direction of a local direction (a rotation: lengths are kept).
    pub fn to_planet_direction(&self, direction: DVec3) -> DVec3 {
        DVec3::from_array(local_to_planet_direction(direction.to_array()))
    }

    /// The local position of a planet-frame point (inverse of
    /// [`Self::to_planet_position`]).
    pub fn to_local_position(&self, position: DVec3) -> DVec3 {
        self.to_local_direction(position - DVec3::Z * (self.planet_radius + self.origin_altitude))
    }

    /// The local direction of a planet-frame direction
    /// ([`skyscape_wgsl::common::enu_to_world`]).
    pub fn to_local_direction(&self, direction: DVec3) -> DVec3 {
        DVec3::from_array(skyscape_wgsl::common::enu_to_world(direction.to_array()))
    }

    /// Altitude (m) above the planet's surface of a local point: its distance from the
    /// planet's centre minus the radius (not its `y`, which ignores curvature).
    pub fn altitude(&self, position: DVec3) -> f64 {
        let p = self.to_planet_position(position);
        // |p|² − R² = (|p| − R)(|p| + R): no cancellation for points near the surface.
        (p.length_squared() - self.planet_radius * self.planet_radius)
            / (p.length() + self.planet_radius)
    }

    /// The frame camera of a local camera: `eye` and `forward`/`up` in local
    /// coordinates, a vertical field of view `fov_y` (rad), a `width × height` frame and
    /// the local direction toward the sun. `max_distance` as in
    /// [`FrameCamera::look_at`].
    #[allow(clippy::too_many_arguments)]
    pub fn frame_camera(
        &self,
        eye: DVec3,
        forward: DVec3,
        up: DVec3,
        fov_y: f64,
        width: u32,
        height: u32,
        sun: DVec3,
        max_distance: Option<f64>,
    ) -> Result<FrameCamera, AtmosError> {
        FrameCamera::look_at(
            self.to_planet_position(eye),
            self.to_planet_direction(forward),
            self.to_planet_direction(up),
            fov_y,
            width,
            height,
            self.to_planet_direction(sun),
            max_distance,
        )
    }
}

/// Unit view direction through the centre of `pixel` (x right, y down, row-major).
pub fn frame_view_direction(pixel: [u32; 2], camera: &FrameCamera) -> [f32; 3] {
    let aspect = camera.width as f32 / camera.height as f32;
    let ndc_x = (2.0 * (pixel[0] as f32 + 0.5) / camera.width as f32 - 1.0)
        * camera.tan_half_fov_y
        * aspect;
    let ndc_y =
        (1.0 - 2.0 * (pixel[1] as f32 + 0.5) / camera.height as f32) * camera.tan_half_fov_y;
    let d: [f32; 3] =
        std::array::from_fn(|i| camera.forward[i] + ndc_x * camera.right[i] + ndc_y * camera.up[i]);
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|c| c / length)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(width: u32, height: u32) -> FrameCamera {
        FrameCamera::look_at(
            DVec3::new(0.0, 0.0, 6_361_000.0),
            DVec3::X,
            DVec3::Z,
            1.0,
            width,
            height,
            DVec3::Z,
            None,
        )
        .unwrap()
    }

    #[test]
    fn layout_matches_the_wgsl_struct() {
        assert_eq!(std::mem::size_of::<FrameCamera>(), 80);
    }

    #[test]
    fn centre_pixel_looks_forward_and_corners_span_the_field_of_view() {
        let c = camera(3, 3);
        let centre = frame_view_direction([1, 1], &c);
        assert!((centre[0] - 1.0).abs() < 1e-6, "{centre:?}");
        // Top row looks up by one third of the half field of view's tangent.
        let top = frame_view_direction([1, 0], &c);
        let expected = (2.0 / 3.0 * (0.5f32).tan()).atan();
        assert!((top[2].asin() - expected).abs() < 1e-6, "{top:?}");
        // x right: with forward +x and up +z, right is −y.
        let right = frame_view_direction([2, 1], &c);
        assert!(right[1] < 0.0, "{right:?}");
    }

    #[test]
    fn bad_cameras_name_the_field() {
        let p = DVec3::new(0.0, 0.0, 6_361_000.0);
        let e = |r: Result<FrameCamera, AtmosError>| r.unwrap_err().to_string();
        assert!(
            e(FrameCamera::look_at(
                p,
                DVec3::Z,
                DVec3::Z,
                1.0,
                4,
                4,
                DVec3::Z,
                None
            ))
            .contains("up_hint")
        );
        assert!(
            e(FrameCamera::look_at(
                p,
                DVec3::X,
                DVec3::Z,
                0.0,
                4,
                4,
                DVec3::Z,
                None
            ))
            .contains("fov_y")
        );
        assert!(
            e(FrameCamera::look_at(
                p,
                DVec3::X,
                DVec3::Z,
                1.0,
                0,
                4,
                DVec3::Z,
                None
            ))
            .contains("width")
        );
        assert!(
            e(FrameCamera::look_at(
                p,
                DVec3::X,
                DVec3::Z,
                1.0,
                4,
                4,
                DVec3::ZERO,
                None
            ))
            .contains("sun")
        );
        assert!(
            e(FrameCamera::look_at(
                p,
                DVec3::X,
                DVec3::Z,
                1.0,
                4,
                4,
                DVec3::Z,
                Some(-1.0)
            ))
            .contains("max_distance")
        );
    }
}
