//! Billboards after Dobashi et al. 2000: the cloud drawn as one soft, screen-aligned splat
//! per dense cell, coloured by the slice propagation's light, composited back to front.
//!
//! * **Particles** ([`billboards`]): one per cell whose density exceeds
//!   [`BillboardSettings::density_threshold`] (default `> 0.3`), at the cell centre
//!   (metres). Colour = [`BillboardSettings::sun_colour`] × the cell's light from
//!   [`propagate`](crate::propagate::propagate) (the shading map); alpha from
//!   [`Opacity`]. Sorted back to front: view depth (along the camera's look direction)
//!   descending; equal depths keep cell order (x fastest), so the order is deterministic.
//!   Cells at a view depth ≤ [`BillboardSettings::near`] are dropped.
//! * **Phase and sky light** ([`particle_radiance`]): the shading map alone colours a particle by
//!   the sun's attenuated light; Dobashi et al. 2000's model, and the ray-march's, scatter it
//!   with a phase function and add the sky. `particle_radiance` gives a particle's
//!   radiance toward the eye from its transmittance toward each light (the slices),
//!   the march's dual-lobe Henyey–Greenstein phase (with its multiple-scattering
//!   octaves) and albedo, and the ambient sky times its visibility
//!   ([`crate::march::ambient_visibility`]); a caller replaces [`Billboard::colour`] with
//!   it.
//! * **Size** ([`SizeRule`]): `size = (k·ρ/d)·ρ` pixels by default
//!   (`k` = 9500 px·m, `d` the distance from the eye in metres), a world-space diameter
//!   per unit density, or a fixed world diameter ([`SizeRule::lattice`]: 3.1 cells,
//!   where the splats' lattice sum is flat, so a uniform cloud shows no dot grid).
//!   The size is the side of the square sprite, as Direct3D point sizes are; the splat
//!   fills its inscribed disc.
//! * **Opacity** ([`Opacity`]): a slab's opacity at the splat's centre times the kernel
//!   (Dobashi et al. 2000), or the cell's optical depth spread over the kernel
//!   ([`Opacity::OpticalDepth`], [`splat_opacity`]), which gives a uniform cloud the
//!   volume's transmittance. [`BillboardSettings::lattice`] pairs the fixed size with it.
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
//! let image = rasterise::<f32>(&particles, &camera, settings.size, settings.opacity);
//! assert!(image.rgba[32 * 64 + 32][3] > 0.0); // the block covers the image's centre
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod camera;
mod particles;
mod raster;
mod shading;
#[cfg(test)]
mod spectrum_tests;
#[cfg(test)]
mod tests;

pub use camera::{Camera, FieldOfView, MAX_IMAGE_SIDE};
pub use particles::{
    Billboard, BillboardSettings, LATTICE_DIAMETER_CELLS, Opacity, SizeRule, billboards,
};
pub use raster::{
    Image, ScreenFrame, billboard_screen, rasterise, rasterise_limited, splat_alpha, splat_opacity,
    splat_texture,
};
pub use shading::{ParticleLight, ParticleScattering, particle_radiance};

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

pub(super) fn bad(field: &'static str, value: f64, requirement: &'static str) -> BillboardError {
    BillboardError::BadParameter {
        field,
        value,
        requirement,
    }
}
