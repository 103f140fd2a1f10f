//! A camera given the way an engine has it: a view matrix, a projection matrix (any
//! perspective: symmetric, off-centre, jittered, reversed-z, infinite far plane) and the
//! viewport of the colour target it is drawn into. Twin of `FrameView` and its
//! functions in `shaders/atmos/frame.wgsl`.
//!
//! [`ViewCamera::from_matrices`] turns them into two uniforms:
//!
//! * a [`FrameView`]: the exact map from a target pixel position to the planet-frame
//!   view direction through it (viewport, projection and view rotation in one 3×3
//!   matrix) and the inverse projection, from which a depth value gives a distance.
//!   The sky pass and the depth-buffer aerial-perspective pass read it per pixel.
//! * a [`FrameCamera`] whose symmetric frustum **covers** the view's: the tables that
//!   depend on the view (the aerial-perspective volume) are laid over it, and every
//!   lookup goes through the direction of the point, so any projection inside it reads
//!   the right texel.

use glam::{DMat3, DMat4, DVec3, DVec4};

use crate::AtmosError;
use crate::frame::{FrameCamera, LocalFrame};

/// A rectangle of the colour target, in pixels (origin at the top-left corner, y down),
/// as given to `wgpu::RenderPass::set_viewport`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Viewport {
    /// Left edge (pixels).
    pub x: f32,
    /// Top edge (pixels).
    pub y: f32,
    /// Width (pixels, > 0).
    pub width: f32,
    /// Height (pixels, > 0).
    pub height: f32,
}

impl Viewport {
    /// The whole of a `width × height` target.
    pub fn full(width: u32, height: u32) -> Self {
        Self {
            x: 0.0,
            y: 0.0,
            width: width as f32,
            height: height as f32,
        }
    }

    fn validate(&self) -> Result<(), AtmosError> {
        for (field, value, positive) in [
            ("viewport.x", self.x, false),
            ("viewport.y", self.y, false),
            ("viewport.width", self.width, true),
            ("viewport.height", self.height, true),
        ] {
            if !value.is_finite() || (positive && value <= 0.0) {
                return Err(invalid(
                    field,
                    f64::from(value),
                    "must be finite (and > 0 for a size, pixels)",
                ));
            }
        }
        Ok(())
    }
}

/// The per-view uniform of the pixel passes (WGSL `FrameView`, 128 bytes).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameView {
    /// Columns of the 3×3 matrix that takes a target position `(x, y, 1)` (pixels,
    /// pixel centres at `+0.5`, the fragment's `@builtin(position).xy`) to a
    /// planet-frame direction through it (not normalised). The fourth component of each
    /// column is padding.
    pub direction_from_position: [[f32; 4]; 3],
    /// Columns of the inverse projection: clip space (`ndc.xy`, depth, 1) to view space
    /// (homogeneous; metres when the view matrix is rigid).
    pub view_from_clip: [[f32; 4]; 4],
    /// The viewport: x, y, width, height (pixels).
    pub viewport: [f32; 4],
}

/// A view ready for the GPU: the uniform of the pixel passes and the covering camera of
/// the view's tables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewCamera {
    /// The symmetric camera whose frustum covers the view's (position, sun and segment
    /// limit as given): the sky-view and aerial-perspective tables are baked for it.
    pub camera: FrameCamera,
    /// The exact per-pixel mapping.
    pub view: FrameView,
}

fn invalid(field: &str, value: f64, reason: &'static str) -> AtmosError {
    AtmosError::InvalidCamera {
        field: field.to_owned(),
        value,
        reason,
    }
}

fn check_finite(name: &str, matrix: &DMat4) -> Result<(), AtmosError> {
    for (c, column) in matrix.to_cols_array_2d().iter().enumerate() {
        for (r, value) in column.iter().enumerate() {
            if !value.is_finite() {
                return Err(invalid(
                    &format!("{name}[column {c}][row {r}]"),
                    *value,
                    "must be finite",
                ));
            }
        }
    }
    Ok(())
}

fn columns3(m: DMat3) -> [[f32; 4]; 3] {
    [m.x_axis, m.y_axis, m.z_axis].map(|c| [c.x as f32, c.y as f32, c.z as f32, 0.0])
}

impl ViewCamera {
    /// A view of a caller's world, a [`LocalFrame`] (+y up, −z north, +x east, metres):
    /// `view` takes world points to view space (right-handed, looking down −z, rigid:
    /// rotation and translation only), `projection` view space to wgpu's clip space
    /// (depth in [0, 1], either way round, any perspective), drawn into `viewport` of
    /// the target. `sun` is the world direction toward the sun; `max_distance` as in
    /// [`FrameCamera::look_at`]. Errors name the matrix entry or field: non-finite or
    /// singular matrices, a view matrix that scales, a projection that is not a
    /// perspective through the eye (orthographic), or a field of view of 180° or more.
    pub fn from_matrices(
        frame: &LocalFrame,
        view: DMat4,
        projection: DMat4,
        viewport: Viewport,
        sun: DVec3,
        max_distance: Option<f64>,
    ) -> Result<Self, AtmosError> {
        check_finite("view", &view)?;
        check_finite("projection", &projection)?;
        viewport.validate()?;
        let rotation = DMat3::from_mat4(view);
        for (axis, column) in ["x", "y", "z"].iter().zip(rotation.to_cols_array_2d()) {
            let length = DVec3::from_array(column).length();
            if (length - 1.0).abs() > 1e-4 {
                return Err(invalid(
                    &format!("|view {axis} column|"),
                    length,
                    "the view matrix must be rigid (rotation and translation, metres)",
                ));
            }
        }
        let world_from_view = view.inverse();
        let determinant = projection.determinant();
        if determinant == 0.0 || !determinant.is_finite() {
            return Err(invalid(
                "det(projection)",
                determinant,
                "the projection must be invertible",
            ));
        }
        let view_from_clip = projection.inverse();
        // The clip depth of the near plane: the one whose point lies nearer the eye
        // (0 for a standard projection, 1 for a reversed one; the other may be at
        // infinity).
        let distance_at = |depth: f64| {
            let q = view_from_clip * DVec4::new(0.0, 0.0, depth, 1.0);
            if q.w == 0.0 {
                f64::INFINITY
            } else {
                q.truncate().length() / q.w.abs()
            }
        };
        let near_depth = if distance_at(0.0) <= distance_at(1.0) {
            0.0
        } else {
            1.0
        };
        let far_depth = 1.0 - near_depth;
        // View-space point on the near plane, homogeneous, linear in (ndc.x, ndc.y, 1).
        let c = |i: usize| view_from_clip.col(i);
        let near_homogeneous = DMat3::from_cols(
            c(0).truncate(),
            c(1).truncate(),
            (c(2) * near_depth + c(3)).truncate(),
        );
        let near_w = DVec3::new(c(0).w, c(1).w, c(2).w * near_depth + c(3).w);
        let corners = [[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0], [1.0, 1.0]];
        let centre_w = near_w.z;
        for [x, y] in corners {
            let ndc = DVec3::new(x, y, 1.0);
            let w = near_w.dot(ndc);
            if w * centre_w <= 0.0 {
                return Err(invalid(
                    "projection",
                    w,
                    "the near plane must lie on one side of the eye over the viewport",
                ));
            }
            // A perspective projection maps each pixel to a ray through the eye: the
            // near and far points of a corner are collinear with the view-space origin.
            let near = near_homogeneous * ndc / w;
            let far = view_from_clip * DVec4::new(x, y, far_depth, 1.0);
            let far_direction = far.truncate() * far.w.signum();
            let far_direction = if far.w == 0.0 {
                far.truncate()
            } else {
                far_direction
            };
            let sine = near.normalize().cross(far_direction.normalize()).length();
            if sine.is_nan() || sine >= 1e-6 {
                return Err(invalid(
                    "projection",
                    sine,
                    "must be a perspective projection through the eye (not orthographic); \
                     sine between a corner's near and far points shown",
                ));
            }
        }
        // Target position (x, y, 1) → (ndc.x, ndc.y, 1).
        let (vx, vy) = (f64::from(viewport.x), f64::from(viewport.y));
        let (vw, vh) = (f64::from(viewport.width), f64::from(viewport.height));
        let ndc_from_position = DMat3::from_cols(
            DVec3::new(2.0 / vw, 0.0, 0.0),
            DVec3::new(0.0, -2.0 / vh, 0.0),
            DVec3::new(-2.0 * vx / vw - 1.0, 1.0 + 2.0 * vy / vh, 1.0),
        );
        let planet_from_world = DMat3::from_cols(
            frame.to_planet_direction(DVec3::X),
            frame.to_planet_direction(DVec3::Y),
            frame.to_planet_direction(DVec3::Z),
        );
        let direction_from_position = planet_from_world
            * DMat3::from_mat4(world_from_view)
            * (near_homogeneous * centre_w.signum())
            * ndc_from_position;

        // The covering symmetric camera.
        let eye = frame.to_planet_position(world_from_view.transform_point3(DVec3::ZERO));
        let forward =
            (direction_from_position * DVec3::new(vx + 0.5 * vw, vy + 0.5 * vh, 1.0)).normalize();
        let up_hint = -direction_from_position.y_axis;
        let right = forward.cross(up_hint).normalize();
        let up = right.cross(forward);
        let (mut tan_x, mut tan_y) = (0.0f64, 0.0f64);
        for [x, y] in [[vx, vy], [vx + vw, vy], [vx, vy + vh], [vx + vw, vy + vh]] {
            let d = direction_from_position * DVec3::new(x, y, 1.0);
            let depth = d.dot(forward);
            if depth.is_nan() || depth <= 1e-6 * d.length() {
                return Err(invalid(
                    "projection",
                    depth / d.length(),
                    "the field of view must be under 180° (cosine of a corner to the \
                     view's centre shown)",
                ));
            }
            tan_x = tan_x.max((d.dot(right) / depth).abs());
            tan_y = tan_y.max((d.dot(up) / depth).abs());
        }
        let height = viewport.height.round().max(1.0) as u32;
        let width = (f64::from(height) * tan_x / tan_y - 1e-6).ceil().max(1.0) as u32;
        let camera = FrameCamera::look_at(
            eye,
            forward,
            up_hint,
            2.0 * tan_y.atan(),
            width,
            height,
            frame.to_planet_direction(sun),
            max_distance,
        )?;
        Ok(Self {
            camera,
            view: FrameView {
                direction_from_position: columns3(direction_from_position),
                view_from_clip: view_from_clip.as_mat4().to_cols_array_2d(),
                viewport: [viewport.x, viewport.y, viewport.width, viewport.height],
            },
        })
    }

    /// The view of a pinhole [`FrameCamera`] filling a `camera.width × camera.height`
    /// target from its top-left corner: the camera itself, and the mapping of its
    /// pixels ([`crate::frame::frame_view_direction`]'s rays). Its inverse projection is
    /// `perspective_infinite_reverse_rh(fov_y, aspect, 1 m)`: a depth buffer for the
    /// depth-buffer passes must use that projection, or prepare the view with
    /// [`Self::from_matrices`] instead.
    pub fn from_frame_camera(camera: &FrameCamera) -> Self {
        let v = |a: [f32; 3]| DVec3::from_array(a.map(f64::from));
        let (width, height) = (f64::from(camera.width), f64::from(camera.height));
        let tan_y = f64::from(camera.tan_half_fov_y);
        let tan_x = tan_y * width / height;
        let (right, up, forward) = (v(camera.right), v(camera.up), v(camera.forward));
        let direction_from_position = DMat3::from_cols(
            right * (2.0 * tan_x / width),
            up * (-2.0 * tan_y / height),
            forward - right * tan_x + up * tan_y,
        );
        let projection = glam::dcamera::rh::proj::directx::perspective_infinite_reverse(
            2.0 * tan_y.atan(),
            width / height,
            1.0,
        );
        Self {
            camera: *camera,
            view: FrameView {
                direction_from_position: columns3(direction_from_position),
                view_from_clip: projection.inverse().as_mat4().to_cols_array_2d(),
                viewport: [0.0, 0.0, camera.width as f32, camera.height as f32],
            },
        }
    }
}

/// Unit planet-frame view direction through the target position `position` (pixels,
/// pixel centres at `+0.5`: the fragment's `@builtin(position).xy`).
pub fn frame_view_direction_at(position: [f32; 2], view: &FrameView) -> [f32; 3] {
    let [c0, c1, c2] = view.direction_from_position;
    let d: [f32; 3] = std::array::from_fn(|i| c0[i] * position[0] + c1[i] * position[1] + c2[i]);
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    d.map(|c| c / length)
}

/// The normalised device coordinates of a target position in the view's viewport.
pub fn frame_view_ndc(position: [f32; 2], view: &FrameView) -> [f32; 2] {
    let [x, y, width, height] = view.viewport;
    let u = (position[0] - x) / width;
    let v = (position[1] - y) / height;
    [2.0 * u - 1.0, 1.0 - 2.0 * v]
}

/// The distance (view-space units: metres for a rigid view matrix) from the eye to the
/// point a depth buffer holds at `position`: the inverse projection of (ndc, `depth`).
/// Infinite at a reversed infinite projection's depth 0.
pub fn frame_view_distance(position: [f32; 2], depth: f32, view: &FrameView) -> f32 {
    let [x, y] = frame_view_ndc(position, view);
    let m = view.view_from_clip;
    let point: [f32; 4] =
        std::array::from_fn(|i| m[0][i] * x + m[1][i] * y + m[2][i] * depth + m[3][i]);
    let p = [
        point[0] / point[3],
        point[1] / point[3],
        point[2] / point[3],
    ];
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Atmosphere;
    use crate::frame::frame_view_direction;
    use glam::dcamera::rh::proj::directx as proj;

    fn frame() -> LocalFrame {
        LocalFrame::new(&Atmosphere::earth(), 100.0).unwrap()
    }

    fn look() -> DMat4 {
        glam::dcamera::rh::view::look_to_mat4(
            DVec3::new(10.0, 200.0, -30.0),
            DVec3::new(0.3, -0.1, -1.0).normalize(),
            DVec3::Y,
        )
    }

    #[test]
    fn layout_matches_the_wgsl_struct() {
        assert_eq!(std::mem::size_of::<FrameView>(), 128);
    }

    #[test]
    fn a_frame_cameras_view_gives_its_pixels_rays() {
        let camera = frame()
            .frame_camera(
                DVec3::new(0.0, 10.0, 0.0),
                DVec3::new(0.2, 0.1, -1.0),
                DVec3::Y,
                1.1,
                64,
                48,
                DVec3::Y,
                None,
            )
            .unwrap();
        let view = ViewCamera::from_frame_camera(&camera).view;
        for pixel in [[0, 0], [63, 0], [31, 24], [0, 47], [63, 47]] {
            let expected = frame_view_direction(pixel, &camera);
            let got =
                frame_view_direction_at([pixel[0] as f32 + 0.5, pixel[1] as f32 + 0.5], &view);
            for i in 0..3 {
                assert!(
                    (got[i] - expected[i]).abs() < 1e-6,
                    "{pixel:?}: {got:?} {expected:?}"
                );
            }
        }
    }

    /// Standard, reversed, infinite and off-centre projections give the rays of the
    /// same pinhole, and a depth gives back the distance it was made from.
    #[test]
    fn every_projection_gives_the_pinholes_rays_and_distances() {
        let (fov, aspect) = (0.9, 1.5);
        let viewport = Viewport {
            x: 100.0,
            y: 20.0,
            width: 300.0,
            height: 200.0,
        };
        let reference = ViewCamera::from_matrices(
            &frame(),
            look(),
            proj::perspective(fov, aspect, 0.5, 1e5),
            viewport,
            DVec3::Y,
            None,
        )
        .unwrap();
        for projection in [
            proj::perspective_infinite(fov, aspect, 0.5),
            glam::dcamera::rh::proj::directx::perspective_infinite_reverse(fov, aspect, 0.5),
            proj::perspective(fov, aspect, 2.0, 1e4),
        ] {
            let got =
                ViewCamera::from_matrices(&frame(), look(), projection, viewport, DVec3::Y, None)
                    .unwrap();
            for position in [[100.5, 20.5], [250.0, 120.0], [399.5, 219.5]] {
                let a = frame_view_direction_at(position, &got.view);
                let b = frame_view_direction_at(position, &reference.view);
                for i in 0..3 {
                    assert!((a[i] - b[i]).abs() < 1e-6, "{projection:?}: {a:?} {b:?}");
                }
            }
            // A point 1234 m along the centre ray, projected, gives 1234 m back.
            let point = DVec4::new(0.0, 0.0, -1234.0, 1.0);
            let clip = projection * point;
            let depth = (clip.z / clip.w) as f32;
            let distance = frame_view_distance([250.0, 120.0], depth, &got.view);
            assert!((distance - 1234.0).abs() < 0.5, "{distance}");
        }
        // An off-centre frustum (the right half of the symmetric one) sees the right
        // half's rays.
        let (near, top) = (0.5, 0.5 * (0.5 * fov).tan());
        let right = top * aspect;
        let half = Viewport {
            x: 250.0,
            width: 150.0,
            ..viewport
        };
        let off = ViewCamera::from_matrices(
            &frame(),
            look(),
            proj::frustum(0.0, right, -top, top, near, 1e5),
            half,
            DVec3::Y,
            None,
        )
        .unwrap();
        for position in [[250.5, 20.5], [320.0, 120.0], [399.5, 219.5]] {
            let a = frame_view_direction_at(position, &off.view);
            let b = frame_view_direction_at(position, &reference.view);
            for i in 0..3 {
                assert!((a[i] - b[i]).abs() < 1e-6, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn bad_matrices_name_the_field() {
        let e = |view: DMat4, projection: DMat4| {
            ViewCamera::from_matrices(
                &frame(),
                view,
                projection,
                Viewport::full(4, 4),
                DVec3::Y,
                None,
            )
            .unwrap_err()
            .to_string()
        };
        let perspective = proj::perspective(1.0, 1.0, 0.1, 100.0);
        let ortho = proj::orthographic(-1.0, 1.0, -1.0, 1.0, 0.1, 100.0);
        assert!(e(look(), ortho).contains("orthographic"));
        assert!(e(look() * DMat4::from_scale(DVec3::splat(2.0)), perspective).contains("rigid"));
        let mut nan = perspective;
        nan.x_axis.y = f64::NAN;
        assert!(e(look(), nan).contains("projection[column 0][row 1]"));
        assert!(e(look(), DMat4::ZERO).contains("det(projection)"));
        let wide = ViewCamera::from_matrices(
            &frame(),
            look(),
            perspective,
            Viewport {
                width: 0.0,
                ..Viewport::full(4, 4)
            },
            DVec3::Y,
            None,
        );
        assert!(wide.unwrap_err().to_string().contains("viewport.width"));
    }
}
