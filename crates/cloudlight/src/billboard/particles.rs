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
    /// A world-space diameter of `diameter` metres whatever the density, projected:
    /// `size = diameter·f/z` pixels. Set by the lattice ([`SizeRule::lattice`]: a diameter
    /// of [`LATTICE_DIAMETER_CELLS`] cells), it makes the splats' sum over a uniform
    /// block nearly flat, so that no dot grid shows; the density is then carried by the
    /// opacity ([`Opacity::OpticalDepth`]).
    Fixed {
        /// Metres of diameter.
        diameter: f64,
    },
}

/// The diameter, in cells, of [`SizeRule::lattice`]'s splats: where the lattice sum
/// `Σ_n k(|x − n·s|)` of the [`splat_alpha`](super::splat_alpha) kernel `(1 − r²)²` on a
/// square lattice of spacing `s` is flattest for a diameter under four cells. Its
/// Fourier series (Poisson summation) has the kernel's 2-D transform,
/// `∝ J₃(q)/q³` with `q = 2π·f·R`, at the lattice's frequencies: near 3.1 cells the
/// first harmonic falls on a zero of `J₃` and the others are small, a peak-to-peak
/// ripple of a few per cent (narrower diameters ripple by tens of per cent; the test
/// `billboard::spectrum_tests` holds the measured figures).
pub const LATTICE_DIAMETER_CELLS: f64 = 3.1;

impl SizeRule {
    /// [`SizeRule::Fixed`] at [`LATTICE_DIAMETER_CELLS`] cells of `voxel_size` metres.
    pub fn lattice(voxel_size: f64) -> Self {
        Self::Fixed {
            diameter: LATTICE_DIAMETER_CELLS * voxel_size,
        }
    }
}

impl Default for SizeRule {
    fn default() -> Self {
        Self::Seed { k: 9500.0 }
    }
}

/// How opaque a billboard is, and how its kernel `k(r)` ([`splat_alpha`](super::splat_alpha))
/// spreads that opacity over its disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Opacity {
    /// The cell's optical depth `τ = σ_t·ρ·voxel·cells` spread over the kernel:
    /// `α(r) = 1 − exp(−τ·k(r)/K̄)`, `K̄ = π·R²/(3·s²)` the kernel's mean lattice sum
    /// (its integral, `π·R²/3` for `(1 − r²)²` of radius `R`, over a cell's projected
    /// area `s²`, both at the particle's depth). Composited "over", a block of particles
    /// transmits `Π(1 − α_i) = exp(−Σ τ·k_i/K̄)`, `exp(−σ_t·ρ·L)` along any ray through
    /// `L` metres of uniform density up to the lattice sum's ripple: the volume's own
    /// optical depth, whatever the size rule. [`BillboardSettings::lattice`]'s opacity.
    OpticalDepth {
        /// Cells of optical depth per particle (1: the volume's own; > 0).
        cells: f64,
    },
    /// `α = 1 − exp(−σ_t·ρ·voxel·cells)`: the opacity of a slab `cells` cells thick at the
    /// cell's density, seen straight on (physical; the volume's σ_t and voxel size), at
    /// the splat's centre: `α(r) = α·k(r)`, Dobashi et al. 2000's texture alpha times
    /// the particle's.
    Slab {
        /// Slab thickness in cells (> 0).
        cells: f64,
    },
    /// `α = ρ`, the density handed straight to the pixel shader; densities must be ≤ 1.
    /// `α(r) = α·k(r)` as [`Opacity::Slab`].
    Density,
}

impl Opacity {
    /// How the kernel becomes opacity on the image ([`splat_opacity`](super::splat_opacity)'s
    /// `opacity_mode`): 0 scales it (`α(r) = weight·k(r)`), 1 spreads an optical depth
    /// (`α(r) = 1 − exp(−weight·k(r))`).
    pub fn mode(&self) -> u32 {
        match self {
            Self::OpticalDepth { .. } => 1,
            Self::Slab { .. } | Self::Density => 0,
        }
    }
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
    /// Splats set by the lattice of cells `voxel_size` metres across
    /// ([`SizeRule::lattice`]) carrying the volume's optical depth
    /// ([`Opacity::OpticalDepth`] of one cell): no dot grid on a uniform cloud, and its
    /// transmittance the volume's. The other settings are the defaults.
    pub fn lattice(voxel_size: f64) -> Self {
        Self {
            size: SizeRule::lattice(voxel_size),
            opacity: Opacity::OpticalDepth { cells: 1.0 },
            ..Self::default()
        }
    }

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
            SizeRule::Fixed { diameter } if !(diameter.is_finite() && diameter > 0.0) => {
                return Err(bad(
                    "size.diameter",
                    diameter,
                    "must be finite and > 0 (metres)",
                ));
            }
            _ => {}
        }
        if let Opacity::Slab { cells } | Opacity::OpticalDepth { cells } = self.opacity
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
    /// What the splat's kernel `k(r)` multiplies ([`splat_opacity`](super::splat_opacity)):
    /// `alpha` itself under [`Opacity::Slab`] and [`Opacity::Density`]; the optical depth
    /// at the centre, `τ/K̄`, under [`Opacity::OpticalDepth`] (`alpha = 1 − exp(−weight)`).
    pub weight: f64,
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
        let (alpha, weight) = match settings.opacity {
            Opacity::Slab { cells } => {
                let alpha = -(-sigma * rho * voxel * cells).exp_m1();
                (alpha, alpha)
            }
            Opacity::Density => (rho, rho),
            Opacity::OpticalDepth { cells } => {
                let radius_cells = splat_radius_cells(settings.size, camera, centre, rho, voxel);
                let mean_lattice_sum = std::f64::consts::FRAC_PI_3 * radius_cells * radius_cells;
                let weight = sigma * rho * voxel * cells / mean_lattice_sum;
                (-(-weight).exp_m1(), weight)
            }
        };
        out.push(Billboard {
            cell,
            centre: centre.to_array(),
            relative: (centre - camera.position()).to_array(),
            density: rho,
            colour: settings.sun_colour.map(|s| s * l),
            alpha,
            weight,
            depth,
        });
    }
    // Stable: equal depths keep cell order.
    out.sort_by(|a, b| b.depth.total_cmp(&a.depth));
    Ok(out)
}

/// A splat's radius over its cell's size, both projected at the splat's depth (the
/// radius of [`billboard_screen`](super::billboard_screen) in f64 over `voxel·f/z`).
fn splat_radius_cells(size: SizeRule, camera: &Camera, centre: DVec3, rho: f64, voxel: f64) -> f64 {
    let diameter_m = match size {
        SizeRule::Seed { k } => {
            // (k·ρ/d)·ρ pixels at depth z: (k·ρ/d)·ρ·z/f metres.
            let distance = (centre - camera.position()).length();
            (k * rho / distance) * rho * camera.depth(centre) / camera.focal_pixels()
        }
        SizeRule::World { metres_per_density } => metres_per_density * rho,
        SizeRule::Fixed { diameter } => diameter,
    };
    0.5 * diameter_m / voxel
}
