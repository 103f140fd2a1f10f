//! The splat and the CPU rasteriser, twin of the GPU pass.

use atmos::real::Real;
use glam::DVec3;

use super::{Billboard, BillboardError, Camera, MAX_IMAGE_SIDE, Opacity, SizeRule, bad};

/// The soft splat: `(1 − r²)²` for `r < 1`, else 0 (`r` = distance from the
/// billboard's centre over its radius). WGSL twin `splat_alpha`.
pub fn splat_alpha<F: Real>(r: F) -> F {
    if r < F::one() {
        let q = F::one() - r * r;
        q * q
    } else {
        F::zero()
    }
}

/// The opacity a splat gives a pixel where its kernel is `kernel` ([`splat_alpha`]) and
/// its [`Billboard::weight`] is `weight`: `weight·kernel` for `opacity_mode` 0
/// ([`Opacity::Slab`], [`Opacity::Density`]: Dobashi et al. 2000's texture alpha times the
/// particle's), `1 − exp(−weight·kernel)` for 1 ([`Opacity::OpticalDepth`]: an optical
/// depth spread over the kernel). WGSL twin `splat_opacity`.
pub fn splat_opacity<F: Real>(weight: F, kernel: F, opacity_mode: u32) -> F {
    let x = weight * kernel;
    if opacity_mode == 1 {
        F::one() - (-x).exp()
    } else {
        x
    }
}

/// [`splat_alpha`] baked into a `size × size` texture (row-major, f32), sampled at texel
/// centres: texel `(i, j)` holds `splat_alpha(r)` at `r = |((i, j) + ½)·2/size − 1|`.
/// The GPU pass evaluates the falloff analytically instead (the limit of a fine texture);
/// this is the texture for users who sample one.
pub fn splat_texture(size: u32) -> Result<Vec<f32>, BillboardError> {
    if size == 0 || size > MAX_IMAGE_SIDE {
        return Err(bad(
            "splat size",
            f64::from(size),
            "must be 1 ..= 8192 texels",
        ));
    }
    let n = f64::from(size);
    let mut texels = Vec::with_capacity((size * size) as usize);
    for j in 0..size {
        for i in 0..size {
            let u = (f64::from(i) + 0.5) * 2.0 / n - 1.0;
            let v = (f64::from(j) + 0.5) * 2.0 / n - 1.0;
            texels.push(splat_alpha((u * u + v * v).sqrt()) as f32);
        }
    }
    Ok(texels)
}

/// The camera and size rule in the float type `F`: what the GPU's uniforms hold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScreenFrame<F> {
    /// Unit right, up, forward.
    pub right: [F; 3],
    /// Unit up.
    pub up: [F; 3],
    /// Unit forward.
    pub forward: [F; 3],
    /// Focal length, pixels.
    pub focal: F,
    /// Half the image width, pixels.
    pub half_width: F,
    /// Half the image height, pixels.
    pub half_height: F,
    /// 0: [`SizeRule::Seed`], 1: [`SizeRule::World`], 2: [`SizeRule::Fixed`].
    pub size_mode: u32,
    /// `k`, `metres_per_density` or the diameter in metres.
    pub size_scale: F,
    /// [`Opacity::mode`]: how the kernel becomes opacity ([`splat_opacity`]).
    pub opacity_mode: u32,
}

impl<F: Real> ScreenFrame<F> {
    /// The frame of `camera` with `size` and `opacity`, rounded to `F` once.
    pub fn new(camera: &Camera, size: SizeRule, opacity: Opacity) -> Self {
        let v = |d: DVec3| d.to_array().map(F::of);
        let (size_mode, scale) = match size {
            SizeRule::Seed { k } => (0, k),
            SizeRule::World { metres_per_density } => (1, metres_per_density),
            SizeRule::Fixed { diameter } => (2, diameter),
        };
        Self {
            right: v(camera.right()),
            up: v(camera.up()),
            forward: v(camera.forward()),
            focal: F::of(camera.focal_pixels()),
            half_width: F::of(0.5 * f64::from(camera.width())),
            half_height: F::of(0.5 * f64::from(camera.height())),
            size_mode,
            size_scale: F::of(scale),
            opacity_mode: opacity.mode(),
        }
    }
}

fn dot<F: Real>(a: [F; 3], b: [F; 3]) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// A billboard's centre on the image `(x, y)` in pixels from the top-left corner and its
/// radius in pixels (half the [`SizeRule`]'s size), from its position relative to the eye
/// and its density. WGSL twin `billboard_screen`, operation for operation.
pub fn billboard_screen<F: Real>(frame: &ScreenFrame<F>, relative: [F; 3], density: F) -> [F; 3] {
    let x = dot(relative, frame.right);
    let y = dot(relative, frame.up);
    let z = dot(relative, frame.forward);
    let cx = frame.half_width + frame.focal * (x / z);
    let cy = frame.half_height - frame.focal * (y / z);
    let size = if frame.size_mode == 0 {
        let distance = dot(relative, relative).sqrt();
        (frame.size_scale * density / distance) * density
    } else if frame.size_mode == 1 {
        frame.size_scale * density * frame.focal / z
    } else {
        frame.size_scale * frame.focal / z
    };
    [cx, cy, F::of(0.5) * size]
}

/// A linear, premultiplied RGBA image, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image<F> {
    /// Pixels across.
    pub width: u32,
    /// Pixels down.
    pub height: u32,
    /// `width × height` pixels, rows from the top, premultiplied linear RGBA.
    pub rgba: Vec<[F; 4]>,
}

/// Draws `billboards` (in their order: [`billboards`](super::billboards) sorts them back to front) as
/// `camera` sees them with the settings' `size` and `opacity` (those they were made with),
/// onto a transparent image (see the module documentation for the coverage rule).
/// `rasterise::<f32>` is the GPU pass's twin, `rasterise::<f64>` the reference.
pub fn rasterise<F: Real>(
    billboards: &[Billboard],
    camera: &Camera,
    size: SizeRule,
    opacity: Opacity,
) -> Image<F> {
    rasterise_behind(billboards, camera, size, opacity, None)
}

/// [`rasterise`] in front of an opaque scene: `max_depth` holds, per pixel (row-major,
/// rows from the top), the view depth (metres along the look direction) of the nearest
/// opaque surface, `F::infinity()` where there is none (the sky). A billboard covers a
/// pixel only where its view depth `z` (its relative position · the camera's forward, in
/// `F`, the `z` of [`billboard_screen`]) is strictly less: a mountain in front hides it.
/// The GPU twin is a depth test `Greater` against a reverse-z depth `near / z`.
/// `max_depth` shorter or longer than the image is [`BillboardError::DepthLength`].
pub fn rasterise_limited<F: Real>(
    billboards: &[Billboard],
    camera: &Camera,
    size: SizeRule,
    opacity: Opacity,
    max_depth: &[F],
) -> Result<Image<F>, BillboardError> {
    let pixels = camera.width() as usize * camera.height() as usize;
    if max_depth.len() != pixels {
        return Err(BillboardError::DepthLength {
            len: max_depth.len(),
            pixels,
        });
    }
    Ok(rasterise_behind(
        billboards,
        camera,
        size,
        opacity,
        Some(max_depth),
    ))
}

fn rasterise_behind<F: Real>(
    billboards: &[Billboard],
    camera: &Camera,
    size: SizeRule,
    opacity: Opacity,
    max_depth: Option<&[F]>,
) -> Image<F> {
    let (width, height) = (camera.width(), camera.height());
    let mut rgba = vec![[F::zero(); 4]; width as usize * height as usize];
    let frame = ScreenFrame::<F>::new(camera, size, opacity);
    let half = F::of(0.5);
    for b in billboards {
        let relative = b.relative.map(F::of);
        let [cx, cy, radius] = billboard_screen(&frame, relative, F::of(b.density));
        if !(radius > F::zero() && cx.is_finite() && cy.is_finite() && radius.is_finite()) {
            continue;
        }
        let colour = b.colour.map(F::of);
        let weight = F::of(b.weight);
        let z = dot(relative, frame.forward);
        // Pixel i's centre i + ½ can lie within the radius only for i in this range.
        let range = |c: F, n: u32| {
            let lo = (c - radius - half).floor().max(F::zero());
            let hi = (c + radius - half).ceil().min(F::of(f64::from(n) - 1.0));
            (lo.to_i64().unwrap_or(0), hi.to_i64().unwrap_or(-1))
        };
        let (x0, x1) = range(cx, width);
        let (y0, y1) = range(cy, height);
        for j in y0..=y1 {
            for i in x0..=x1 {
                let dx = F::of(i as f64) + half - cx;
                let dy = F::of(j as f64) + half - cy;
                let r = (dx * dx + dy * dy).sqrt() / radius;
                let a = splat_opacity(weight, splat_alpha(r), frame.opacity_mode);
                let index = i as usize + width as usize * j as usize;
                let in_front = max_depth.is_none_or(|limit| z < limit[index]);
                if a > F::zero() && in_front {
                    let keep = F::one() - a;
                    let pixel = &mut rgba[index];
                    for c in 0..3 {
                        pixel[c] = colour[c] * a + keep * pixel[c];
                    }
                    pixel[3] = a + keep * pixel[3];
                }
            }
        }
    }
    Image {
        width,
        height,
        rgba,
    }
}
