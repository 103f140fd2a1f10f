//! Particles from a volume's dense cells: settings, size and opacity rules.

use glam::DVec3;

use super::{BillboardError, Camera, bad};
use crate::CloudVolume;

/// How big a billboard is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SizeRule {
    /// `size = (k·ρ/d)·ρ` pixels, `d` the distance from the eye in metres and `k` in
    /// pixel·metres (default 9500). `d` is measured to the eye itself rather than to a
    /// point one unit in front of it in view space (a difference of ≤ 1 m at the
    /// ≥ 100 m a cloud is seen from). The default `k` suits a scene scale and
    /// resolution, not metres: at 3 km a dense cell is 3 px across.
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
    /// `α = ρ`, the density handed straight to the pixel shader; densities must be ≤ 1.
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
    /// A cell becomes a particle when its density is strictly above this (default 0.3); in
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
