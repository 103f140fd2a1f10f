//! Seed 002's billboards: the cloud drawn as one soft, screen-aligned splat per dense cell,
//! coloured by the slice propagation's light, composited back to front.
//!
//! * **Particles** ([`billboards`]): one per cell whose density exceeds
//!   [`BillboardSettings::density_threshold`] (seed 002: `> 0.3`), at the cell centre
//!   (metres). Colour = [`BillboardSettings::sun_colour`] × the cell's light from
//!   [`propagate`](crate::propagate::propagate) (seed 002's shading map); alpha from
//!   [`Opacity`]. Sorted back to front: view depth (along the camera's look direction)
//!   descending; equal depths keep cell order (x fastest), so the order is deterministic.
//!   Cells at a view depth ≤ [`BillboardSettings::near`] are dropped.
//! * **Phase and sky light** ([`particle_radiance`]): seed 002 colours a particle by the
//!   sun's attenuated light alone; Dobashi 2000's model, and the ray-march's, scatter it
//!   with a phase function and add the sky. `particle_radiance` gives a particle's
//!   radiance toward the eye from its transmittance toward each light (the slices),
//!   the march's dual-lobe Henyey–Greenstein phase (with its multiple-scattering
//!   octaves) and albedo, and the ambient sky times its visibility
//!   ([`crate::march::ambient_visibility`]); a caller replaces [`Billboard::colour`] with
//!   it.
//! * **Size** ([`SizeRule`]): seed 002's `size = (k·ρ/d)·ρ` pixels by default
//!   (`k` = 9500 px·m, `d` the distance from the eye in metres), or a world-space diameter.
//!   The size is the side of the square sprite, as Direct3D point sizes are; the splat
//!   fills its inscribed disc.
//! * **Splat** ([`splat_alpha`]): the procedural soft falloff `(1 − r²)²` for `r < 1`, 0
//!   beyond (`r` = distance from the centre over the radius, size / 2). Smooth (C¹) at the
//!   rim, 1 at the centre. [`splat_texture`] bakes it into a texture of any size; the GPU
//!   pass evaluates it analytically (WGSL twin `splat_alpha` in
//!   `shaders/cloudlight/billboard.wgsl`, a parity case).
//! * **Rasteriser** ([`rasterise`]): the CPU twin of the GPU pass
//!   ([`gpu::billboard::BillboardPass`](crate::gpu::billboard::BillboardPass)), generic over
//!   the float type (`f64` reference, `f32` twin). Coverage rule, shared with the GPU: a
//!   pixel `(i, j)` takes a billboard's splat at its centre `(i + ½, j + ½)` (rows from the
//!   top), with `r = |centre − billboard| / radius`; pixels with `r ≥ 1` are untouched. The
//!   GPU draws a quad one pixel wider than the disc on every side and evaluates the same
//!   `r` in the fragment shader, so triangle edge rules never decide coverage.
//!   Compositing is premultiplied "over": `dst = (c·a, a) + (1 − a)·dst`, in sorted order.
//!   The output is linear premultiplied RGBA, transparent where no billboard falls.
//!
//! The screen position and radius of a billboard ([`billboard_screen`]) are computed from
//! its position relative to the eye, rounded to the float type once (what the GPU's
//! instance buffer holds), with the camera basis and focal length of a [`ScreenFrame`].
//!
//! ```
//! use cloudlight::CloudVolume;
//! use cloudlight::billboard::{BillboardSettings, Camera, FieldOfView, billboards, rasterise};
//! use cloudlight::propagate::{SliceMode, propagate_f64};
//! use glam::DVec3;
//!
//! // A 4³ block of density 0.8, 50 m cells, lit from above, seen from 2 km.
//! let volume = CloudVolume::new([4; 3], [-100.0; 3], 50.0, 0.01, vec![0.8; 64])?;
//! let light = propagate_f64(&volume, [0.0, 0.0, 1.0], SliceMode::Physical)?;
//! let camera = Camera::looking_at(
//!     DVec3::new(0.0, -2000.0, 0.0),
//!     DVec3::ZERO,
//!     DVec3::Z,
//!     FieldOfView::from_degrees(30.0),
//!     64,
//!     64,
//! )?;
//! let settings = BillboardSettings::default();
//! let particles = billboards(&volume, &light, &settings, &camera)?;
//! assert_eq!(particles.len(), 64);
//! let image = rasterise::<f32>(&particles, &camera, settings.size);
//! assert!(image.rgba[32 * 64 + 32][3] > 0.0); // the block covers the image's centre
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use atmos::real::Real;
use glam::DVec3;

use crate::CloudVolume;

/// Bad input to the billboards, naming the field and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BillboardError {
    /// A setting or camera field is out of its domain.
    #[error("{field} = {value}: {requirement}")]
    BadParameter {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
    /// The light does not hold one value per cell.
    #[error("light has {len} values but the volume has {cells} cells")]
    LightLength {
        /// Values given.
        len: usize,
        /// Cells of the volume.
        cells: usize,
    },
    /// A light value is negative or not finite.
    #[error("light[{index}] = {value}: light must be finite and ≥ 0")]
    BadLight {
        /// Cell index (x fastest).
        index: usize,
        /// The value.
        value: f64,
    },
    /// [`rasterise_limited`]'s depths do not hold one value per pixel.
    #[error("max_depth has {len} values but the image has {pixels} pixels")]
    DepthLength {
        /// Values given.
        len: usize,
        /// Pixels of the camera's image.
        pixels: usize,
    },
    /// [`Opacity::Density`] needs densities ≤ 1 (alpha = ρ).
    #[error("density[{index}] = {value}: Opacity::Density uses α = ρ and needs ρ ≤ 1")]
    DensityAboveOne {
        /// Cell index (x fastest).
        index: usize,
        /// The value.
        value: f64,
    },
}

fn bad(field: &'static str, value: f64, requirement: &'static str) -> BillboardError {
    BillboardError::BadParameter {
        field,
        value,
        requirement,
    }
}

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

/// How big a billboard is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SizeRule {
    /// Seed 002: `size = (k·ρ/d)·ρ` pixels, `d` the distance from the eye in metres and `k`
    /// in pixel·metres (seed: 9500). The seed measures `d` to a point one unit in front of
    /// the eye in view space; here it is the eye itself (a difference of ≤ 1 m at the
    /// ≥ 100 m a cloud is seen from). The seed's `k` was tuned for its own scene scale and
    /// resolution, not for metres: at 3 km a dense cell is 3 px across.
    Seed {
        /// Pixel·metres.
        k: f64,
    },
    /// A world-space diameter `metres_per_density·ρ`, projected: `size = diameter·f/z`
    /// pixels (`f` the focal length in pixels, `z` the view depth).
    World {
        /// Metres of diameter per unit density.
        metres_per_density: f64,
    },
}

impl Default for SizeRule {
    fn default() -> Self {
        Self::Seed { k: 9500.0 }
    }
}

/// How opaque a billboard is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Opacity {
    /// `α = 1 − exp(−σ_t·ρ·voxel·cells)`: the opacity of a slab `cells` cells thick at the
    /// cell's density, seen straight on (physical; the volume's σ_t and voxel size).
    Slab {
        /// Slab thickness in cells (> 0).
        cells: f64,
    },
    /// `α = ρ`, as seed 002 hands the density to its pixel shader; densities must be ≤ 1.
    Density,
}

impl Default for Opacity {
    fn default() -> Self {
        Self::Slab { cells: 1.0 }
    }
}

/// Settings of [`billboards`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BillboardSettings {
    /// A cell becomes a particle when its density is strictly above this (seed: 0.3); in
    /// [0, 1].
    pub density_threshold: f64,
    /// Billboard size.
    pub size: SizeRule,
    /// Billboard opacity.
    pub opacity: Opacity,
    /// Linear RGB of the sun at the cloud (each finite and ≥ 0); the colour of a cell is
    /// this times its light.
    pub sun_colour: [f64; 3],
    /// Cells at a view depth ≤ `near` metres (> 0) are not drawn.
    pub near: f64,
}

impl Default for BillboardSettings {
    fn default() -> Self {
        Self {
            density_threshold: 0.3,
            size: SizeRule::default(),
            opacity: Opacity::default(),
            sun_colour: [1.0; 3],
            near: 1.0,
        }
    }
}

impl BillboardSettings {
    /// Errors naming the first field out of its domain.
    pub fn validate(&self) -> Result<(), BillboardError> {
        let t = self.density_threshold;
        if !(0.0..=1.0).contains(&t) {
            return Err(bad("density_threshold", t, "must lie in [0, 1]"));
        }
        match self.size {
            SizeRule::Seed { k } if !(k.is_finite() && k > 0.0) => {
                return Err(bad("size.k", k, "must be finite and > 0 (pixel·metres)"));
            }
            SizeRule::World { metres_per_density }
                if !(metres_per_density.is_finite() && metres_per_density > 0.0) =>
            {
                return Err(bad(
                    "size.metres_per_density",
                    metres_per_density,
                    "must be finite and > 0 (metres)",
                ));
            }
            _ => {}
        }
        if let Opacity::Slab { cells } = self.opacity
            && !(cells.is_finite() && cells > 0.0)
        {
            return Err(bad("opacity.cells", cells, "must be finite and > 0"));
        }
        for (field, value) in ["sun_colour.r", "sun_colour.g", "sun_colour.b"]
            .into_iter()
            .zip(self.sun_colour)
        {
            if !(value.is_finite() && value >= 0.0) {
                return Err(bad(field, value, "must be finite and ≥ 0 (linear RGB)"));
            }
        }
        if !(self.near.is_finite() && self.near > 0.0) {
            return Err(bad("near", self.near, "must be finite and > 0 (metres)"));
        }
        Ok(())
    }
}

/// One particle: a dense cell seen by the camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Billboard {
    /// Cell index (x fastest).
    pub cell: usize,
    /// The cell centre, metres.
    pub centre: [f64; 3],
    /// The centre relative to the eye, metres (what the GPU's instances hold, in f32).
    pub relative: [f64; 3],
    /// The cell's density.
    pub density: f64,
    /// Linear RGB (sun colour × light), not premultiplied.
    pub colour: [f64; 3],
    /// Opacity at the splat's centre, in [0, 1].
    pub alpha: f64,
    /// View depth, metres (the sort key).
    pub depth: f64,
}

/// The particles of `volume` lit by `light` (one value per cell, x fastest: the output of
/// [`propagate`](crate::propagate::propagate) or the GPU pass), sorted back to front for
/// `camera` (see the module documentation).
pub fn billboards<L: Copy + Into<f64>>(
    volume: &CloudVolume,
    light: &[L],
    settings: &BillboardSettings,
    camera: &Camera,
) -> Result<Vec<Billboard>, BillboardError> {
    settings.validate()?;
    let density = volume.density();
    if light.len() != density.len() {
        return Err(BillboardError::LightLength {
            len: light.len(),
            cells: density.len(),
        });
    }
    if let Some((index, value)) = light
        .iter()
        .map(|&l| l.into())
        .enumerate()
        .find(|(_, l)| !(l.is_finite() && *l >= 0.0))
    {
        return Err(BillboardError::BadLight { index, value });
    }
    if settings.opacity == Opacity::Density
        && let Some((index, &value)) = density.iter().enumerate().find(|(_, d)| **d > 1.0)
    {
        return Err(BillboardError::DensityAboveOne {
            index,
            value: f64::from(value),
        });
    }
    let [nx, ny, _] = volume.dims().map(|n| n as usize);
    let origin = DVec3::from(volume.origin());
    let voxel = volume.voxel_size();
    let sigma = volume.extinction_per_density();
    let mut out = Vec::new();
    for (cell, &rho) in density.iter().enumerate() {
        let rho = f64::from(rho);
        // Densities and the threshold are finite (validated).
        if rho <= settings.density_threshold {
            continue;
        }
        let index = DVec3::new(
            (cell % nx) as f64,
            ((cell / nx) % ny) as f64,
            (cell / (nx * ny)) as f64,
        );
        let centre = origin + (index + 0.5) * voxel;
        let depth = camera.depth(centre);
        if depth <= settings.near {
            continue;
        }
        let l: f64 = light[cell].into();
        let alpha = match settings.opacity {
            Opacity::Slab { cells } => -(-sigma * rho * voxel * cells).exp_m1(),
            Opacity::Density => rho,
        };
        out.push(Billboard {
            cell,
            centre: centre.to_array(),
            relative: (centre - camera.position()).to_array(),
            density: rho,
            colour: settings.sun_colour.map(|s| s * l),
            alpha,
            depth,
        });
    }
    // Stable: equal depths keep cell order.
    out.sort_by(|a, b| b.depth.total_cmp(&a.depth));
    Ok(out)
}

/// One light of a particle ([`particle_radiance`]): the sun, or the moon at night.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleLight<F> {
    /// Unit direction toward the light, in the volume's frame.
    pub direction: [F; 3],
    /// The light's irradiance at the cloud on a surface facing it (linear RGB).
    pub irradiance: [F; 3],
    /// The fraction of it that reaches the particle: the cell's light from the slice
    /// propagation toward this light ([`propagate`](crate::propagate::propagate)).
    pub transmittance: F,
}

/// How a particle scatters ([`particle_radiance`]): the single-scattering albedo, the
/// dual-lobe Henyey–Greenstein phase and the multiple-scattering octaves of the ray-march
/// ([`crate::march::MarchConfig`]'s `albedo`, `g_forward`, `g_back`, `back_weight`,
/// `octaves`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleScattering {
    /// σ_s/σ_t, in [0, 1].
    pub albedo: f64,
    /// Forward lobe anisotropy, in (−1, 1).
    pub g_forward: f64,
    /// Backward lobe anisotropy, in (−1, 1).
    pub g_back: f64,
    /// Weight of the backward lobe, in [0, 1].
    pub back_weight: f64,
    /// The march's octaves (`count = 1`: single scattering).
    pub octaves: crate::march::Octaves,
}

impl ParticleScattering {
    /// The march's albedo and phase (validated by [`crate::march::MarchSettings::new`]).
    pub fn of_march(settings: &crate::march::MarchSettings) -> Self {
        let c = settings.config();
        Self {
            albedo: c.albedo,
            g_forward: c.g_forward,
            g_back: c.g_back,
            back_weight: c.back_weight,
            octaves: c.octaves,
        }
    }
}

impl Default for ParticleScattering {
    /// [`crate::march::MarchConfig::default`]'s: albedo 1, lobes 0.8 and −0.3, back
    /// weight 0.2, single scattering.
    fn default() -> Self {
        Self::of_march(&crate::march::MarchSettings::default())
    }
}

/// The radiance a particle scatters toward the eye, the ray-march's source term with the
/// slices' light in place of the light march (Dobashi 2000: the sunlight attenuated to
/// the particle times the phase function, plus the sky light):
///
/// `L = albedo · (Σ_k E_k · P(τ_k, view · ω_k) + L_amb · V_amb)`
///
/// with `E_k` a light's irradiance, `ω_k` its direction, `τ_k = −ln T_k` the optical
/// depth that the particle's transmittance toward it (the slice propagation) stands for,
/// `P` the march's [`octave_scattering`](crate::march::octave_scattering) (one octave:
/// `T_k · p(view · ω_k)`, `p` the dual-lobe Henyey–Greenstein phase of
/// [`crate::cone::dual_lobe_henyey_greenstein`], 1/sr; `view · ω = 1` looking straight
/// at the light: forward scattering), `L_amb` the isotropic sky radiance and `V_amb` its
/// visibility at the particle ([`crate::march::ambient_visibility`]). `T_k = 0` is taken
/// as the smallest positive `F` (`τ` finite, so that an octave factor `a = 0` still sees
/// `e^0 = 1` as its limit does). A splat of opacity `α` then adds `α · L`: the march's
/// `(S/σ_t) · (1 − e^{−σ_t·d})` over a slab of the cell's density. `view` is the unit
/// direction from the eye to the particle.
pub fn particle_radiance<F: Real>(
    view: [F; 3],
    lights: &[ParticleLight<F>],
    ambient_radiance: [F; 3],
    ambient_visibility: F,
    scattering: &ParticleScattering,
) -> [F; 3] {
    let mut sum = [F::zero(); 3];
    let s = scattering;
    let o = s.octaves;
    for light in lights {
        let d = light.direction;
        let cos_theta = view[0] * d[0] + view[1] * d[1] + view[2] * d[2];
        let optical_depth = -light.transmittance.max(F::min_positive_value()).ln();
        let scattered = crate::march::octave_scattering(
            optical_depth,
            cos_theta,
            F::of(s.g_forward),
            F::of(s.g_back),
            F::of(s.back_weight),
            o.count,
            F::of(o.a),
            F::of(o.b),
            F::of(o.c),
        );
        for (sum, e) in sum.iter_mut().zip(light.irradiance) {
            *sum = *sum + e * scattered;
        }
    }
    let albedo = F::of(s.albedo);
    std::array::from_fn(|k| albedo * (sum[k] + ambient_radiance[k] * ambient_visibility))
}

/// Seed 002's soft splat: `(1 − r²)²` for `r < 1`, else 0 (`r` = distance from the
/// billboard's centre over its radius). WGSL twin `splat_alpha`.
pub fn splat_alpha<F: Real>(r: F) -> F {
    if r < F::one() {
        let q = F::one() - r * r;
        q * q
    } else {
        F::zero()
    }
}

/// [`splat_alpha`] baked into a `size × size` texture (row-major, f32), sampled at texel
/// centres: texel `(i, j)` holds `splat_alpha(r)` at `r = |((i, j) + ½)·2/size − 1|`.
/// The GPU pass evaluates the falloff analytically instead (the limit of a fine texture);
/// this is the seed's texture for users who sample one.
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
    /// 0: [`SizeRule::Seed`], 1: [`SizeRule::World`].
    pub size_mode: u32,
    /// `k` or `metres_per_density`.
    pub size_scale: F,
}

impl<F: Real> ScreenFrame<F> {
    /// The frame of `camera` with `size`, rounded to `F` once.
    pub fn new(camera: &Camera, size: SizeRule) -> Self {
        let v = |d: DVec3| d.to_array().map(F::of);
        let (size_mode, scale) = match size {
            SizeRule::Seed { k } => (0, k),
            SizeRule::World { metres_per_density } => (1, metres_per_density),
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
    } else {
        frame.size_scale * density * frame.focal / z
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

/// Draws `billboards` (in their order: [`billboards`] sorts them back to front) as
/// `camera` sees them, onto a transparent image (see the module documentation for the
/// coverage rule). `rasterise::<f32>` is the GPU pass's twin, `rasterise::<f64>` the
/// reference.
pub fn rasterise<F: Real>(billboards: &[Billboard], camera: &Camera, size: SizeRule) -> Image<F> {
    rasterise_behind(billboards, camera, size, None)
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
    max_depth: &[F],
) -> Result<Image<F>, BillboardError> {
    let pixels = camera.width() as usize * camera.height() as usize;
    if max_depth.len() != pixels {
        return Err(BillboardError::DepthLength {
            len: max_depth.len(),
            pixels,
        });
    }
    Ok(rasterise_behind(billboards, camera, size, Some(max_depth)))
}

fn rasterise_behind<F: Real>(
    billboards: &[Billboard],
    camera: &Camera,
    size: SizeRule,
    max_depth: Option<&[F]>,
) -> Image<F> {
    let (width, height) = (camera.width(), camera.height());
    let mut rgba = vec![[F::zero(); 4]; width as usize * height as usize];
    let frame = ScreenFrame::<F>::new(camera, size);
    let half = F::of(0.5);
    for b in billboards {
        let relative = b.relative.map(F::of);
        let [cx, cy, radius] = billboard_screen(&frame, relative, F::of(b.density));
        if !(radius > F::zero() && cx.is_finite() && cy.is_finite() && radius.is_finite()) {
            continue;
        }
        let colour = b.colour.map(F::of);
        let alpha = F::of(b.alpha);
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
                let a = alpha * splat_alpha(r);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        Camera::looking_at(
            DVec3::new(0.0, -1000.0, 0.0),
            DVec3::ZERO,
            DVec3::Z,
            FieldOfView::from_degrees(40.0),
            64,
            48,
        )
        .unwrap()
    }

    fn cube() -> CloudVolume {
        let mut density = vec![0.0f32; 27];
        density[13] = 0.9; // centre
        density[0] = 0.5;
        density[26] = 0.2; // below the threshold
        CloudVolume::new([3, 3, 3], [-75.0, -75.0, -75.0], 50.0, 0.01, density).unwrap()
    }

    #[test]
    fn bad_input_names_field_and_value() {
        let v = cube();
        let light = vec![1.0f32; 27];
        let cam = camera();
        let mut s = BillboardSettings {
            density_threshold: f64::NAN,
            ..Default::default()
        };
        let e = billboards(&v, &light, &s, &cam).unwrap_err();
        assert!(e.to_string().contains("density_threshold = NaN"), "{e}");
        s.density_threshold = 1.5;
        let e = billboards(&v, &light, &s, &cam).unwrap_err();
        assert!(e.to_string().contains("density_threshold = 1.5"), "{e}");
        s.density_threshold = 0.3;
        assert_eq!(
            billboards(&v, &light[..5], &s, &cam),
            Err(BillboardError::LightLength { len: 5, cells: 27 })
        );
        let mut bad_light = light.clone();
        bad_light[4] = -1.0;
        assert_eq!(
            billboards(&v, &bad_light, &s, &cam),
            Err(BillboardError::BadLight {
                index: 4,
                value: -1.0
            })
        );
        s.sun_colour[1] = f64::INFINITY;
        let e = billboards(&v, &light, &s, &cam).unwrap_err();
        assert!(e.to_string().contains("sun_colour.g = inf"), "{e}");
        let e = Camera::new(
            DVec3::ZERO,
            DVec3::Z,
            DVec3::Z * 2.0,
            FieldOfView::from_degrees(40.0),
            8,
            8,
        )
        .unwrap_err();
        assert!(e.to_string().contains("camera.up = 0"), "{e}");
        let e = Camera::new(
            DVec3::ZERO,
            DVec3::X,
            DVec3::Z,
            FieldOfView::from_degrees(180.0),
            8,
            8,
        )
        .unwrap_err();
        assert!(e.to_string().contains("camera.vertical_fov"), "{e}");
        let e = Camera::new(
            DVec3::new(f64::NAN, 0.0, 0.0),
            DVec3::X,
            DVec3::Z,
            FieldOfView::from_degrees(40.0),
            8,
            8,
        )
        .unwrap_err();
        assert!(e.to_string().contains("camera.position.x = NaN"), "{e}");
        let e = Camera::new(
            DVec3::ZERO,
            DVec3::ZERO,
            DVec3::Z,
            FieldOfView::from_degrees(40.0),
            8,
            8,
        )
        .unwrap_err();
        assert!(e.to_string().contains("camera.look = 0"), "{e}");
        let e = Camera::new(
            DVec3::ZERO,
            DVec3::X,
            DVec3::Z,
            FieldOfView::from_degrees(40.0),
            0,
            8,
        )
        .unwrap_err();
        assert!(e.to_string().contains("camera.width = 0"), "{e}");
        let dense = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, 0.1, vec![1.5]).unwrap();
        let s = BillboardSettings {
            opacity: Opacity::Density,
            ..Default::default()
        };
        assert_eq!(
            billboards(&dense, &[1.0f64], &s, &cam),
            Err(BillboardError::DensityAboveOne {
                index: 0,
                value: 1.5
            })
        );
        assert!(splat_texture(0).is_err());
    }

    #[test]
    fn particles_above_threshold_coloured_and_sorted_back_to_front() {
        let v = cube();
        let light: Vec<f64> = (0..27).map(|i| f64::from(i) / 26.0).collect();
        let s = BillboardSettings {
            sun_colour: [1.0, 0.5, 0.25],
            ..Default::default()
        };
        let b = billboards(&v, &light, &s, &camera()).unwrap();
        // Cells 0 (y = 0, nearer the camera at y = −1000) and 13; 26 is below 0.3.
        assert_eq!(b.iter().map(|b| b.cell).collect::<Vec<_>>(), vec![13, 0]);
        assert_eq!(b[0].centre, [0.0, 0.0, 0.0]);
        assert_eq!(b[1].centre, [-50.0, -50.0, -50.0]);
        assert!(b[0].depth > b[1].depth);
        let l = 13.0 / 26.0;
        assert_eq!(b[0].colour, [l, 0.5 * l, 0.25 * l]);
        let alpha = 1.0 - (-0.01f64 * 0.9f32 as f64 * 50.0).exp();
        assert!((b[0].alpha - alpha).abs() < 1e-15);
        // Equal depths keep cell order: a row of cells across the view.
        let row =
            CloudVolume::new([4, 1, 1], [-100.0, 0.0, 0.0], 50.0, 0.01, vec![0.5; 4]).unwrap();
        let b = billboards(&row, &[1.0f32; 4], &s, &camera()).unwrap();
        assert_eq!(b.iter().map(|b| b.cell).collect::<Vec<_>>(), [0, 1, 2, 3]);
        // Behind the camera or nearer than `near`: dropped.
        let behind = Camera::looking_at(
            DVec3::new(0.0, 1000.0, 0.0),
            DVec3::new(0.0, 2000.0, 0.0),
            DVec3::Z,
            FieldOfView::from_degrees(40.0),
            8,
            8,
        )
        .unwrap();
        assert!(billboards(&v, &light, &s, &behind).unwrap().is_empty());
    }

    #[test]
    fn camera_inside_the_cloud_and_extreme_inputs_give_finite_images() {
        // A 6³ block of density 0…1e6 around the eye; huge σ_t; both size rules.
        let n = 6u32;
        let density: Vec<f32> = (0..n * n * n)
            .map(|i| [0.0, 0.31, 1.0, 1e6][i as usize % 4])
            .collect();
        let v = CloudVolume::new([n; 3], [-150.0; 3], 50.0, 1.0, density).unwrap();
        let light: Vec<f32> = (0..n * n * n).map(|i| [0.0, 1.0][i as usize % 2]).collect();
        for (eye, near) in [(DVec3::ZERO, 1.0), (DVec3::new(10.0, 3.0, -7.0), 1e-3)] {
            let cam = Camera::new(
                eye,
                DVec3::new(0.3, 1.0, 0.2),
                DVec3::Z,
                FieldOfView::from_degrees(90.0),
                32,
                24,
            )
            .unwrap();
            for size in [
                SizeRule::default(),
                SizeRule::World {
                    metres_per_density: 100.0,
                },
            ] {
                let s = BillboardSettings {
                    size,
                    near,
                    ..Default::default()
                };
                let b = billboards(&v, &light, &s, &cam).unwrap();
                assert!(!b.is_empty());
                assert!(
                    b.iter()
                        .all(|b| b.depth > near && (0.0..=1.0).contains(&b.alpha))
                );
                assert!(b.windows(2).all(|w| w[0].depth >= w[1].depth));
                let image = rasterise::<f64>(&b, &cam, size);
                assert!(image.rgba.iter().flatten().all(|c| c.is_finite()));
                // Premultiplied: 0 ≤ colour ≤ alpha ≤ 1 (sun colour 1, light ≤ 1).
                assert!(image.rgba.iter().all(|p| (0.0..=1.0).contains(&p[3])
                    && p[..3].iter().all(|c| (0.0..=p[3] + 1e-12).contains(c))));
                let image = rasterise::<f32>(&b, &cam, size);
                assert!(
                    image
                        .rgba
                        .iter()
                        .flatten()
                        .all(|c| c.is_finite() && *c >= 0.0)
                );
            }
        }
    }

    #[test]
    fn limited_rasteriser_hides_billboards_behind_the_surface() {
        // Two billboards straight ahead at 1000 m and 1050 m (World size 100 m).
        let cam = camera();
        let two =
            CloudVolume::new([1, 2, 1], [-25.0, -25.0, -25.0], 50.0, 0.01, vec![1.0; 2]).unwrap();
        let s = BillboardSettings {
            size: SizeRule::World {
                metres_per_density: 100.0,
            },
            ..Default::default()
        };
        let b = billboards(&two, &[0.5f32, 1.0], &s, &cam).unwrap();
        let pixels = 64 * 48;
        let open = rasterise::<f64>(&b, &cam, s.size);
        let unlimited =
            rasterise_limited::<f64>(&b, &cam, s.size, &vec![f64::INFINITY; pixels]).unwrap();
        assert_eq!(open, unlimited);
        // A wall at 1025 m: only the nearer billboard (light 0.5) shows.
        let wall = rasterise_limited::<f64>(&b, &cam, s.size, &vec![1025.0; pixels]).unwrap();
        let near_only = rasterise::<f64>(&b[1..], &cam, s.size);
        assert_eq!(b[1].depth, 1000.0);
        assert_eq!(wall, near_only);
        // A wall at exactly a billboard's depth hides it (strictly less is drawn).
        let flush = rasterise_limited::<f32>(&b, &cam, s.size, &vec![1000.0; pixels]).unwrap();
        assert!(flush.rgba.iter().all(|p| *p == [0.0; 4]));
        assert_eq!(
            rasterise_limited::<f32>(&b, &cam, s.size, &[1.0; 3]),
            Err(BillboardError::DepthLength { len: 3, pixels })
        );
    }

    #[test]
    fn splat_is_smooth_one_at_the_centre_zero_at_the_rim() {
        assert_eq!(splat_alpha(0.0f64), 1.0);
        assert_eq!(splat_alpha(1.0f64), 0.0);
        assert_eq!(splat_alpha(3.0f32), 0.0);
        assert!((splat_alpha(0.5f64) - 0.5625).abs() < 1e-15);
        // C¹ at the rim: the slope −4r(1 − r²) → 0.
        let e = 1e-6;
        assert!(splat_alpha(1.0 - e) / e < 1e-5);
        let t = splat_texture(4).unwrap();
        assert_eq!(t.len(), 16);
        let inner = splat_alpha((2.0f64 * 0.25 * 0.25).sqrt()) as f32;
        assert_eq!(t[5], inner);
        assert_eq!(t[0], 0.0); // corner texel: r = √(0.75² · 2) > 1
    }

    #[test]
    fn rasteriser_composites_over_in_order_at_pixel_centres() {
        // One billboard straight ahead at 1000 m, World size 100 m: radius = 50·f/1000.
        let cam = camera();
        let one =
            CloudVolume::new([1, 1, 1], [-25.0, -25.0, -25.0], 50.0, 0.01, vec![1.0]).unwrap();
        let s = BillboardSettings {
            size: SizeRule::World {
                metres_per_density: 100.0,
            },
            ..Default::default()
        };
        let b = billboards(&one, &[0.5f32], &s, &cam).unwrap();
        let image = rasterise::<f64>(&b, &cam, s.size);
        let f = cam.focal_pixels();
        let radius = 50.0 * f / 1000.0;
        // Centre of the image (32, 24) is a pixel corner: the 4 nearest pixels are at
        // r = √0.5 / radius.
        let a = b[0].alpha * splat_alpha(0.5f64.sqrt() / radius);
        let p = image.rgba[31 + 64 * 23];
        assert!((p[3] - a).abs() < 1e-12, "{p:?} vs {a}");
        assert!((p[0] - 0.5 * a).abs() < 1e-12);
        // Outside the disc: untouched.
        assert_eq!(image.rgba[0], [0.0; 4]);
        let covered = image.rgba.iter().filter(|p| p[3] > 0.0).count() as f64;
        let disc = std::f64::consts::PI * radius * radius;
        assert!(
            (covered - disc).abs() < 2.0 * std::f64::consts::PI * radius,
            "{covered} vs {disc}"
        );
        // Two billboards at one pixel: over in order.
        let twice = [b[0], b[0]];
        let two = rasterise::<f64>(&twice, &cam, s.size);
        let q = two.rgba[31 + 64 * 23];
        assert!((q[3] - (a + (1.0 - a) * a)).abs() < 1e-12);
        // The f32 twin agrees with the reference to rounding.
        let image32 = rasterise::<f32>(&b, &cam, s.size);
        let worst = image
            .rgba
            .iter()
            .zip(&image32.rgba)
            .flat_map(|(p, q)| (0..4).map(move |c| (p[c] - f64::from(q[c])).abs()))
            .fold(0.0, f64::max);
        assert!(worst < 1e-5, "{worst}");
    }

    #[test]
    fn particle_radiance_scatters_forward_and_adds_the_sky() {
        let scattering = ParticleScattering::default();
        let sun = |transmittance: f64| ParticleLight {
            direction: [1.0, 0.0, 0.0],
            irradiance: [2.0, 1.0, 0.5],
            transmittance,
        };
        let toward = particle_radiance([1.0, 0.0, 0.0], &[sun(0.5)], [0.0; 3], 1.0, &scattering);
        let away = particle_radiance([-1.0, 0.0, 0.0], &[sun(0.5)], [0.0; 3], 1.0, &scattering);
        // E · T · p(±1) with the march's phase.
        let p = |c: f64| crate::cone::dual_lobe_henyey_greenstein(c, 0.8, -0.3, 0.2);
        assert!((toward[0] - 2.0 * 0.5 * p(1.0)).abs() < 1e-12, "{toward:?}");
        assert!((away[2] - 0.5 * 0.5 * p(-1.0)).abs() < 1e-12, "{away:?}");
        assert!(toward[1] > 10.0 * away[1], "{toward:?} {away:?}");
        // In full shadow only the sky, times its visibility; two lights add.
        let shadowed = particle_radiance(
            [0.0, 1.0, 0.0],
            &[sun(0.0)],
            [0.1, 0.2, 0.3],
            0.5,
            &scattering,
        );
        assert_eq!(shadowed, [0.05, 0.1, 0.15]);
        let both = particle_radiance(
            [0.0, 1.0, 0.0],
            &[sun(0.5), sun(0.25)],
            [0.0; 3],
            1.0,
            &scattering,
        );
        let one = particle_radiance([0.0, 1.0, 0.0], &[sun(0.75)], [0.0; 3], 1.0, &scattering);
        assert!((both[0] - one[0]).abs() < 1e-12);
    }
}
