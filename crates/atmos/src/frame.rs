//! A pinhole camera for rendering a frame of sky radiance, shared by every rung's GPU
//! renderer and its CPU twin. Twin of `shaders/atmos/frame.wgsl`.

use glam::DVec3;

use crate::AtmosError;

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
