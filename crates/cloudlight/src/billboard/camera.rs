//! The camera the billboards are sorted, sized and rasterised for.

use glam::DVec3;

use super::{BillboardError, bad};

/// A vertical field of view (a typed angle: build it from degrees or radians).
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd)]
pub struct FieldOfView {
    radians: f64,
}

impl FieldOfView {
    /// `degrees` degrees.
    pub fn from_degrees(degrees: f64) -> Self {
        Self {
            radians: degrees.to_radians(),
        }
    }

    /// `radians` radians.
    pub const fn from_radians(radians: f64) -> Self {
        Self { radians }
    }

    /// The angle in radians.
    pub const fn radians(self) -> f64 {
        self.radians
    }
}

/// A pinhole camera: position (metres, world frame), look direction, up, vertical field
/// of view and image size in pixels. Pixel `(i, j)` counts from the top-left corner; the
/// view's x axis is to the right, y up, depth along the look direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    position: DVec3,
    forward: DVec3,
    right: DVec3,
    up: DVec3,
    fov: FieldOfView,
    width: u32,
    height: u32,
}

/// The largest image side a [`Camera`] accepts (wgpu's default 2-D texture limit).
pub const MAX_IMAGE_SIDE: u32 = 8192;

impl Camera {
    /// A camera at `position` looking along `look` (any non-zero length) with `up` (not
    /// parallel to `look`) as the image's up, `vertical_fov` in (0, π), `width × height`
    /// pixels (each 1 ..= [`MAX_IMAGE_SIDE`]).
    pub fn new(
        position: DVec3,
        look: DVec3,
        up: DVec3,
        vertical_fov: FieldOfView,
        width: u32,
        height: u32,
    ) -> Result<Self, BillboardError> {
        let named = [
            ("camera.position.x", position.x),
            ("camera.position.y", position.y),
            ("camera.position.z", position.z),
            ("camera.look.x", look.x),
            ("camera.look.y", look.y),
            ("camera.look.z", look.z),
            ("camera.up.x", up.x),
            ("camera.up.y", up.y),
            ("camera.up.z", up.z),
        ];
        for (field, value) in named {
            if !value.is_finite() {
                return Err(bad(field, value, "must be finite"));
            }
        }
        let look_length = look.length();
        if !(look_length > 0.0 && look_length.is_finite()) {
            return Err(bad(
                "camera.look",
                look_length,
                "must have a non-zero, finite length",
            ));
        }
        let forward = look / look_length;
        let up_length = up.length();
        if !(up_length > 0.0 && up_length.is_finite()) {
            return Err(bad(
                "camera.up",
                up_length,
                "must have a non-zero, finite length",
            ));
        }
        let side = forward.cross(up / up_length);
        let sine = side.length();
        if sine <= 1e-9 {
            return Err(bad(
                "camera.up",
                sine,
                "sine of the angle to camera.look must be > 1e-9 (up not parallel to look)",
            ));
        }
        let right = side / sine;
        let fov_radians = vertical_fov.radians();
        if !(fov_radians > 0.0 && fov_radians < std::f64::consts::PI) {
            return Err(bad(
                "camera.vertical_fov (radians)",
                fov_radians,
                "must lie in (0, π)",
            ));
        }
        for (field, value) in [("camera.width", width), ("camera.height", height)] {
            if value == 0 || value > MAX_IMAGE_SIDE {
                return Err(bad(field, f64::from(value), "must be 1 ..= 8192 pixels"));
            }
        }
        Ok(Self {
            position,
            forward,
            right,
            up: right.cross(forward),
            fov: vertical_fov,
            width,
            height,
        })
    }

    /// A camera at `position` looking at `target`.
    pub fn looking_at(
        position: DVec3,
        target: DVec3,
        up: DVec3,
        vertical_fov: FieldOfView,
        width: u32,
        height: u32,
    ) -> Result<Self, BillboardError> {
        Self::new(position, target - position, up, vertical_fov, width, height)
    }

    /// The eye, metres.
    pub fn position(&self) -> DVec3 {
        self.position
    }

    /// Unit look direction.
    pub fn forward(&self) -> DVec3 {
        self.forward
    }

    /// Unit right (image +x).
    pub fn right(&self) -> DVec3 {
        self.right
    }

    /// Unit up (image −y), orthogonal to `forward`.
    pub fn up(&self) -> DVec3 {
        self.up
    }

    /// The vertical field of view.
    pub fn vertical_fov(&self) -> FieldOfView {
        self.fov
    }

    /// Image width, pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height, pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Focal length in pixels: `(height / 2) / tan(fov / 2)`.
    pub fn focal_pixels(&self) -> f64 {
        0.5 * f64::from(self.height) / (0.5 * self.fov.radians()).tan()
    }

    /// View depth of world point `p` (metres along the look direction from the eye).
    pub fn depth(&self, p: DVec3) -> f64 {
        (p - self.position).dot(self.forward)
    }
}
