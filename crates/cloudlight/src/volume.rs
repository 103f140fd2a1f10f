//! [`CloudVolume`]: a density grid placed in metres, the input of every lighting method.

/// Bad input to [`CloudVolume::new`], naming the field and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum VolumeError {
    /// A grid dimension is zero.
    #[error("{field} = 0: a cloud volume needs at least one cell along each axis")]
    ZeroSize {
        /// `nx`, `ny` or `nz`.
        field: &'static str,
    },
    /// The density slice does not hold `nx · ny · nz` values (or that product overflows).
    #[error("density has {len} values but nx · ny · nz = {nx} · {ny} · {nz}")]
    SizeMismatch {
        /// Values given.
        len: usize,
        /// Cells along x.
        nx: u32,
        /// Cells along y.
        ny: u32,
        /// Cells along z.
        nz: u32,
    },
    /// A density value is negative or not finite.
    #[error("density[{index}] = {value}: densities must be finite and ≥ 0")]
    BadDensity {
        /// Linear index (x fastest).
        index: usize,
        /// The value.
        value: f32,
    },
    /// A placement value or coefficient is out of its domain.
    #[error("{field} = {value}: {requirement}")]
    BadParameter {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
}

/// An f32 density grid with its placement in the world frame of `docs/architecture.md`.
///
/// Axis order matches `cloudsim`: cell `(x, y, z)` is `density[x + nx·(y + ny·z)]`
/// (x fastest, z slowest), so `cloudsim::density`'s output is accepted as is.
/// Cell `(x, y, z)`'s value sits at its centre, `origin + (x + ½, y + ½, z + ½)·voxel_size`
/// metres; `origin` is the volume's minimum corner. Extinction at a point is
/// `extinction_per_density · ρ` in 1/m, with `ρ` the trilinear interpolation of the
/// cell-centre densities (clamped to the outermost centres inside the volume, zero outside).
#[derive(Debug, Clone, PartialEq)]
pub struct CloudVolume {
    dims: [u32; 3],
    origin: [f64; 3],
    voxel_size: f64,
    extinction_per_density: f64,
    density: Vec<f32>,
}

impl CloudVolume {
    /// A volume of `dims = [nx, ny, nz]` cells of edge `voxel_size` metres whose minimum
    /// corner is at `origin` (metres), with extinction `extinction_per_density` (1/m per unit
    /// density, σ_t). Errors name the offending field and value.
    pub fn new(
        dims: [u32; 3],
        origin: [f64; 3],
        voxel_size: f64,
        extinction_per_density: f64,
        density: Vec<f32>,
    ) -> Result<Self, VolumeError> {
        for (field, n) in ["nx", "ny", "nz"].into_iter().zip(dims) {
            if n == 0 {
                return Err(VolumeError::ZeroSize { field });
            }
        }
        let cells = (dims[0] as usize)
            .checked_mul(dims[1] as usize)
            .and_then(|c| c.checked_mul(dims[2] as usize));
        if cells != Some(density.len()) {
            return Err(VolumeError::SizeMismatch {
                len: density.len(),
                nx: dims[0],
                ny: dims[1],
                nz: dims[2],
            });
        }
        for (field, value) in ["origin.x", "origin.y", "origin.z"].into_iter().zip(origin) {
            if !value.is_finite() {
                return Err(VolumeError::BadParameter {
                    field,
                    value,
                    requirement: "must be finite (metres)",
                });
            }
        }
        if !(voxel_size.is_finite() && voxel_size > 0.0) {
            return Err(VolumeError::BadParameter {
                field: "voxel_size",
                value: voxel_size,
                requirement: "must be finite and > 0 (metres)",
            });
        }
        if !(extinction_per_density.is_finite() && extinction_per_density >= 0.0) {
            return Err(VolumeError::BadParameter {
                field: "extinction_per_density",
                value: extinction_per_density,
                requirement: "must be finite and ≥ 0 (1/m)",
            });
        }
        if let Some((index, &value)) = density
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v >= 0.0))
        {
            return Err(VolumeError::BadDensity { index, value });
        }
        Ok(Self {
            dims,
            origin,
            voxel_size,
            extinction_per_density,
            density,
        })
    }

    /// `[nx, ny, nz]`.
    pub fn dims(&self) -> [u32; 3] {
        self.dims
    }

    /// Minimum corner, metres.
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }

    /// Cell edge, metres.
    pub fn voxel_size(&self) -> f64 {
        self.voxel_size
    }

    /// σ_t per unit density, 1/m.
    pub fn extinction_per_density(&self) -> f64 {
        self.extinction_per_density
    }

    /// The densities, x fastest.
    pub fn density(&self) -> &[f32] {
        &self.density
    }

    /// Density of cell `(x, y, z)`; `None` outside the grid.
    pub fn cell(&self, x: u32, y: u32, z: u32) -> Option<f32> {
        let [nx, ny, nz] = self.dims;
        (x < nx && y < ny && z < nz).then(|| {
            self.density[x as usize + nx as usize * (y as usize + ny as usize * z as usize)]
        })
    }

    /// Trilinear density at world point `p` (metres): zero outside the volume, the
    /// cell-centre values interpolated inside (clamped to the outermost centres).
    pub fn density_at(&self, p: [f64; 3]) -> f64 {
        let mut base = [0u32; 3];
        let mut frac = [0f64; 3];
        for axis in 0..3 {
            let n = self.dims[axis];
            let u = (p[axis] - self.origin[axis]) / self.voxel_size;
            if !(u >= 0.0 && u <= n as f64) {
                return 0.0;
            }
            // Cell-centre coordinates, clamped so the outermost half-cells hold the edge value.
            let c = (u - 0.5).clamp(0.0, (n - 1) as f64);
            let i = (c.floor() as u32).min(n.saturating_sub(2));
            base[axis] = i;
            frac[axis] = if n == 1 { 0.0 } else { c - i as f64 };
        }
        let mut sum = 0.0;
        for corner in 0..8u32 {
            let mut weight = 1.0;
            let mut cell = [0u32; 3];
            for axis in 0..3 {
                let bit = (corner >> axis) & 1;
                cell[axis] = (base[axis] + bit).min(self.dims[axis] - 1);
                weight *= if bit == 1 {
                    frac[axis]
                } else {
                    1.0 - frac[axis]
                };
            }
            if weight != 0.0 {
                sum += weight * f64::from(self.cell(cell[0], cell[1], cell[2]).unwrap_or(0.0));
            }
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: u32, value: f32) -> Vec<f32> {
        vec![value; (n * n * n) as usize]
    }

    #[test]
    fn bad_input_names_field_and_value() {
        assert_eq!(
            CloudVolume::new([0, 1, 1], [0.0; 3], 1.0, 0.1, vec![]),
            Err(VolumeError::ZeroSize { field: "nx" })
        );
        assert!(matches!(
            CloudVolume::new([2, 2, 2], [0.0; 3], 1.0, 0.1, grid(1, 0.0)),
            Err(VolumeError::SizeMismatch { len: 1, .. })
        ));
        let mut d = grid(2, 0.5);
        d[3] = -1.0;
        assert_eq!(
            CloudVolume::new([2, 2, 2], [0.0; 3], 1.0, 0.1, d),
            Err(VolumeError::BadDensity {
                index: 3,
                value: -1.0
            })
        );
        let err = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, -0.1, grid(1, 0.0)).unwrap_err();
        assert!(
            err.to_string().contains("extinction_per_density = -0.1"),
            "{err}"
        );
        let err = CloudVolume::new([1, 1, 1], [0.0; 3], f64::NAN, 0.1, grid(1, 0.0)).unwrap_err();
        assert!(err.to_string().contains("voxel_size = NaN"), "{err}");
        let mut d = grid(2, 0.5);
        d[7] = f32::NAN;
        assert!(matches!(
            CloudVolume::new([2, 2, 2], [0.0; 3], 1.0, 0.1, d),
            Err(VolumeError::BadDensity { index: 7, .. })
        ));
    }

    #[test]
    fn trilinear_density_interpolates_centres_and_is_zero_outside() {
        // Density = x index along x on a 4×1×1 grid of 10 m cells at origin (100, 0, 0).
        let v = CloudVolume::new(
            [4, 1, 1],
            [100.0, 0.0, 0.0],
            10.0,
            0.1,
            vec![0.0, 1.0, 2.0, 3.0],
        )
        .unwrap();
        assert_eq!(v.density_at([105.0, 5.0, 5.0]), 0.0); // centre of cell 0
        assert!((v.density_at([120.0, 5.0, 5.0]) - 1.5).abs() < 1e-12); // between centres 1 and 2
        assert_eq!(v.density_at([139.0, 5.0, 5.0]), 3.0); // outer half-cell: clamped
        assert_eq!(v.density_at([141.0, 5.0, 5.0]), 0.0); // outside
        assert_eq!(v.density_at([120.0, -1.0, 5.0]), 0.0);
        let one = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, 0.1, vec![0.7]).unwrap();
        assert!((one.density_at([0.3, 0.9, 0.1]) - 0.7).abs() < 1e-7);
    }
}
