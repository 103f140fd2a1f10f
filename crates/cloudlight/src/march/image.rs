//! Images: a pinhole camera's pixel directions, whole images, faded results.

use atmos::real::{Real, count};
use glam::DVec3;

use super::*;
use crate::density::DensityField;

/// The unit view direction through the centre of pixel `pixel` of a `size[0] × size[1]`
/// image (row 0 at the top) of a pinhole camera looking along unit `forward` with unit
/// `right` and `up`; `tan_half` the tangents of the horizontal and vertical half fields of
/// view. WGSL twin `pixel_direction`.
pub fn pixel_direction<F: Real>(
    pixel: [u32; 2],
    size: [u32; 2],
    forward: [F; 3],
    right: [F; 3],
    up: [F; 3],
    tan_half: [F; 2],
) -> [F; 3] {
    let (one, two, half) = (F::one(), F::of(2.0), F::of(0.5));
    let sx = (two * (count::<F>(pixel[0]) + half) / count::<F>(size[0]) - one) * tan_half[0];
    let sy = (one - two * (count::<F>(pixel[1]) + half) / count::<F>(size[1])) * tan_half[1];
    let v: [F; 3] = std::array::from_fn(|a| forward[a] + sx * right[a] + sy * up[a]);
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n)
}

/// A pinhole camera in the field's frame: position, orthonormal forward / right / up and
/// the horizontal field of view (the vertical one follows from the image's aspect).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PinholeCamera {
    origin: [f64; 3],
    forward: [f64; 3],
    right: [f64; 3],
    up: [f64; 3],
    horizontal_fov: f64,
}

impl PinholeCamera {
    /// A camera at `origin` (m) looking at `target` (m) with `up_hint` roughly up and a
    /// horizontal field of view `horizontal_fov` in radians (0, π). Errors name the field
    /// (a target at the origin, an up hint along the view, NaN, a field of view out of
    /// range).
    pub fn look_at(
        origin: [f64; 3],
        target: [f64; 3],
        up_hint: [f64; 3],
        horizontal_fov: f64,
    ) -> Result<Self, MarchError> {
        let o = DVec3::from_array(origin);
        let t = DVec3::from_array(target);
        for c in origin.into_iter().chain(target).chain(up_hint) {
            if !c.is_finite() {
                return Err(invalid("camera position/target/up", c, "must be finite"));
            }
        }
        if !(horizontal_fov > 0.0 && horizontal_fov < std::f64::consts::PI) {
            return Err(invalid(
                "horizontal_fov",
                horizontal_fov,
                "must be in (0, π) rad",
            ));
        }
        let forward = (t - o).normalize_or_zero();
        if forward == DVec3::ZERO {
            return Err(invalid(
                "target",
                (t - o).length(),
                "must differ from the origin",
            ));
        }
        let right = forward
            .cross(DVec3::from_array(up_hint))
            .normalize_or_zero();
        if right == DVec3::ZERO {
            return Err(invalid("up_hint", 0.0, "must not be parallel to the view"));
        }
        let up = right.cross(forward);
        Ok(Self {
            origin,
            forward: forward.to_array(),
            right: right.to_array(),
            up: up.to_array(),
            horizontal_fov,
        })
    }

    /// [`look_at`](Self::look_at) from a vertical field of view: `vertical_fov` in radians
    /// (0, π) spans the `size[1]` rows of a `size[0] × size[1]` image, and the camera's
    /// horizontal field is the one that gives it, `tan(h/2) = tan(v/2)·size[0]/size[1]`
    /// (the convention of `render`'s scenes and `atmos`' cameras). The camera keeps the
    /// horizontal field, so an image of another aspect sees the same horizontal field and
    /// another vertical one ([`vertical_fov`](Self::vertical_fov)). Errors name the field:
    /// `vertical_fov` out of range or NaN, a zero `size[0]` / `size[1]`, and `look_at`'s.
    pub fn look_at_vertical_fov(
        origin: [f64; 3],
        target: [f64; 3],
        up_hint: [f64; 3],
        vertical_fov: f64,
        size: [u32; 2],
    ) -> Result<Self, MarchError> {
        if !(vertical_fov > 0.0 && vertical_fov < std::f64::consts::PI) {
            return Err(invalid(
                "vertical_fov",
                vertical_fov,
                "must be in (0, π) rad",
            ));
        }
        if size[0] == 0 {
            return Err(invalid("size[0]", 0.0, "must be ≥ 1 (pixels)"));
        }
        if size[1] == 0 {
            return Err(invalid("size[1]", 0.0, "must be ≥ 1 (pixels)"));
        }
        let aspect = f64::from(size[0]) / f64::from(size[1]);
        let horizontal_fov = 2.0 * ((0.5 * vertical_fov).tan() * aspect).atan();
        Self::look_at(origin, target, up_hint, horizontal_fov)
    }

    /// The horizontal field of view, radians.
    pub fn horizontal_fov(&self) -> f64 {
        self.horizontal_fov
    }

    /// The vertical field of view (radians) over an image of `size` (`size[0]` columns,
    /// `size[1]` rows): `2·atan(tan(h/2)·size[1]/size[0])`, the field the rows of that
    /// image span.
    pub fn vertical_fov(&self, size: [u32; 2]) -> f64 {
        2.0 * self.tan_half(size)[1].atan()
    }

    /// Position (m).
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }

    /// Unit forward, right and up.
    pub fn basis(&self) -> [[f64; 3]; 3] {
        [self.forward, self.right, self.up]
    }

    /// `[tan(h/2), tan(h/2)·height/width]` for an image of `size`.
    pub fn tan_half(&self, size: [u32; 2]) -> [f64; 2] {
        let t = (0.5 * self.horizontal_fov).tan();
        [t, t * f64::from(size[1]) / f64::from(size[0])]
    }
}

/// The CPU image of the view march (rows top to bottom, x fastest): each pixel marched by
/// [`march_view_at_pixel`] along [`pixel_direction`]. `render_image::<f32>` on a
/// [`CloudVolume`](crate::CloudVolume) is the twin of the GPU pass
/// `gpu::MarchPass`; a zero-sized image is empty.
pub fn render_image<F: Real>(
    field: &impl DensityField<F>,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
) -> Vec<MarchResult<F>> {
    let [forward, right, up] = camera.basis().map(|v| v.map(F::of));
    let tan_half = camera.tan_half(size).map(F::of);
    let origin = camera.origin.map(F::of);
    let mut out = Vec::with_capacity(size[0] as usize * size[1] as usize);
    for y in 0..size[1] {
        for x in 0..size[0] {
            let d = pixel_direction([x, y], size, forward, right, up, tan_half);
            out.push(march_view_at_pixel(
                field,
                origin,
                d,
                settings,
                lighting,
                [x, y],
            ));
        }
    }
    out
}

/// [`render_image`] with each pixel's march stopped at its `max_distance` (metres along
/// the pixel's ray, x fastest, row 0 at the top: [`march_view_at_pixel_limited`]); the
/// twin of `gpu::MarchPass::prepare_limited`. `max_distance` must hold one value per
/// pixel (`+∞` or NaN: no limit).
pub fn render_image_limited<F: Real>(
    field: &impl DensityField<F>,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<F>,
    max_distance: &[F],
) -> Result<Vec<MarchResult<F>>, MarchError> {
    let pixels = size[0] as usize * size[1] as usize;
    if max_distance.len() != pixels {
        return Err(invalid(
            "max_distance.len()",
            max_distance.len() as f64,
            "must be size[0]·size[1] (one distance per pixel)",
        ));
    }
    let [forward, right, up] = camera.basis().map(|v| v.map(F::of));
    let tan_half = camera.tan_half(size).map(F::of);
    let origin = camera.origin.map(F::of);
    let mut out = Vec::with_capacity(pixels);
    for y in 0..size[1] {
        for x in 0..size[0] {
            let d = pixel_direction([x, y], size, forward, right, up, tan_half);
            let limit = max_distance[x as usize + size[0] as usize * y as usize];
            out.push(march_view_at_pixel_limited(
                field,
                origin,
                d,
                settings,
                lighting,
                [x, y],
                limit,
            ));
        }
    }
    Ok(out)
}

/// A march result faded by `fade` in [0, 1] (e.g. a shell's horizon fade at the result's
/// [`depth`](MarchResult::depth)): the cloud's radiance times `fade` and its opacity
/// times `fade`, i.e. transmittance `1 − fade·(1 − T)`. The GPU shell pass applies it
/// with [`CloudShell::horizon_fade`](crate::CloudShell::horizon_fade).
pub fn faded<F: Real>(result: MarchResult<F>, fade: F) -> MarchResult<F> {
    MarchResult {
        radiance: result.radiance.map(|c| c * fade),
        transmittance: F::one() - fade * (F::one() - result.transmittance),
        depth: result.depth,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A camera built from a vertical field is `look_at` with the matching horizontal one:
    /// every pixel's direction agrees to 1e-12 (the two fields differ only by the
    /// atan/tan round trip, a few ulps), the accessor gives the vertical field back, and
    /// the same vertical field over a wider image is a wider horizontal field.
    #[test]
    fn vertical_fov_round_trips_through_look_at() {
        let (origin, target, up) = (
            [10.0, -20.0, 1500.0],
            [400.0, 300.0, 1200.0],
            [0.0, 0.0, 1.0],
        );
        for (size, vertical_deg) in [([64u32, 36u32], 45.0f64), ([17, 31], 80.0), ([5, 5], 10.0)] {
            let vertical = vertical_deg.to_radians();
            let camera =
                PinholeCamera::look_at_vertical_fov(origin, target, up, vertical, size).unwrap();
            let aspect = f64::from(size[0]) / f64::from(size[1]);
            let horizontal = 2.0 * ((0.5 * vertical).tan() * aspect).atan();
            let reference = PinholeCamera::look_at(origin, target, up, horizontal).unwrap();
            assert!((camera.vertical_fov(size) - vertical).abs() < 1e-12);
            assert!((reference.vertical_fov(size) - vertical).abs() < 1e-12);
            let direction = |c: &PinholeCamera, pixel| {
                let [forward, right, up] = c.basis();
                pixel_direction(pixel, size, forward, right, up, c.tan_half(size))
            };
            for y in 0..size[1] {
                for x in 0..size[0] {
                    let (a, b) = (direction(&camera, [x, y]), direction(&reference, [x, y]));
                    for k in 0..3 {
                        assert!((a[k] - b[k]).abs() < 1e-12, "{size:?} {x},{y}: {a:?} {b:?}");
                    }
                }
            }
            // The top row's centre looks (v/2)·(1 − 1/rows) above the axis at most: the
            // vertical field really spans the rows.
            let [forward, _, _] = camera.basis();
            let top = direction(&camera, [size[0] / 2, 0]);
            let off_axis =
                |d: [f64; 3]| (d[0] * forward[0] + d[1] * forward[1] + d[2] * forward[2]).acos();
            let edge = ((1.0 - 1.0 / f64::from(size[1])) * (0.5 * vertical).tan()).atan();
            if size[0] % 2 == 1 {
                assert!((off_axis(top) - edge).abs() < 1e-12);
            }
        }
        let wide =
            PinholeCamera::look_at_vertical_fov(origin, target, up, 0.8, [200, 100]).unwrap();
        let square =
            PinholeCamera::look_at_vertical_fov(origin, target, up, 0.8, [100, 100]).unwrap();
        assert!(wide.horizontal_fov() > square.horizontal_fov());
        assert!((square.horizontal_fov() - 0.8).abs() < 1e-12);
    }

    #[test]
    fn bad_vertical_fov_and_size_are_named() {
        let make = |fov, size| {
            PinholeCamera::look_at_vertical_fov(
                [0.0; 3],
                [1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                fov,
                size,
            )
            .unwrap_err()
            .to_string()
        };
        for fov in [0.0, -0.5, std::f64::consts::PI, f64::NAN, f64::INFINITY] {
            let e = make(fov, [4, 4]);
            assert!(e.starts_with("vertical_fov = "), "{e}");
        }
        assert!(make(1.0, [0, 4]).starts_with("size[0] = 0"));
        assert!(make(1.0, [4, 0]).starts_with("size[1] = 0"));
        let e =
            PinholeCamera::look_at_vertical_fov([0.0; 3], [0.0; 3], [0.0, 0.0, 1.0], 1.0, [4, 4])
                .unwrap_err()
                .to_string();
        assert!(e.starts_with("target = 0"), "{e}");
    }
}
