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
