//! Configuration (what users set) and [`Model`] (the validated configuration plus the
//! derived tables every implementation reads: mask levels, thresholds, wind).

use crate::Error;
use crate::regions::RegionTable;
use crate::rng::{MASK_FULL, THRESHOLD_ONE, probability_threshold, wind_velocity_fixed};

/// Largest allowed `nx`, `ny` or `nz`.
pub const MAX_DIMENSION: u32 = 1 << 16;
/// Largest allowed cell count (`nx * ny * nz`); cell indices then fit a `u32` draw counter.
pub const MAX_CELLS: u64 = 1 << 30;
/// Largest allowed wind speed per component, in cells per step.
pub const MAX_WIND: f32 = 16.0;
/// Largest allowed [`Smoothing::radius_cells`].
pub const MAX_SMOOTHING_RADIUS_CELLS: u32 = 8;
/// Largest allowed [`Smoothing::radius_steps`].
pub const MAX_SMOOTHING_RADIUS_STEPS: u32 = 15;
/// The mask level of mask 1: levels run over `0..=256`, level `l` meaning `l / 256`.
pub const MASK_LEVEL_MAX: u16 = MASK_FULL;

/// Grid dimensions in cells; `z` is up. Cell `(x, y, z)` has linear index
/// `x + nx * (y + ny * z)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GridSize {
    /// Cells along x.
    pub nx: u32,
    /// Cells along y.
    pub ny: u32,
    /// Cells along z (up).
    pub nz: u32,
}

impl GridSize {
    /// A grid of `nx * ny * nz` cells (checked by [`GridSize::validate`]).
    pub const fn new(nx: u32, ny: u32, nz: u32) -> Self {
        Self { nx, ny, nz }
    }

    /// Errors for zero or oversized dimensions.
    pub fn validate(&self) -> Result<(), Error> {
        for (field, value) in [
            ("size.nx", self.nx),
            ("size.ny", self.ny),
            ("size.nz", self.nz),
        ] {
            if value == 0 {
                return Err(Error::ZeroSize { field });
            }
            if value > MAX_DIMENSION {
                return Err(Error::DimensionTooLarge {
                    field,
                    value,
                    max: MAX_DIMENSION,
                });
            }
        }
        let cells = u64::from(self.nx) * u64::from(self.ny) * u64::from(self.nz);
        if cells > MAX_CELLS {
            return Err(Error::TooManyCells {
                nx: self.nx,
                ny: self.ny,
                nz: self.nz,
                cells,
                max: MAX_CELLS,
            });
        }
        Ok(())
    }

    /// `nx * ny * nz`.
    pub fn cells(&self) -> usize {
        self.nx as usize * self.ny as usize * self.nz as usize
    }

    /// Linear cell index of `(x, y, z)`; [`Error::CellOutOfRange`] naming the first
    /// coordinate outside the grid.
    pub fn index(&self, x: u32, y: u32, z: u32) -> Result<usize, Error> {
        self.check_cell(x, y, z)?;
        Ok(self.index_unchecked(x, y, z))
    }

    /// Errors when `(x, y, z)` lies outside the grid.
    pub fn check_cell(&self, x: u32, y: u32, z: u32) -> Result<(), Error> {
        for (field, value, limit) in [("x", x, self.nx), ("y", y, self.ny), ("z", z, self.nz)] {
            if value >= limit {
                return Err(Error::CellOutOfRange {
                    field,
                    value,
                    limit,
                });
            }
        }
        Ok(())
    }

    /// [`GridSize::index`] without the range check, for loops whose coordinates are
    /// inside the grid by construction: an `x >= nx` silently names a cell of the next
    /// row (checked only in debug builds).
    pub fn index_unchecked(&self, x: u32, y: u32, z: u32) -> usize {
        debug_assert!(
            self.check_cell(x, y, z).is_ok(),
            "cell ({x}, {y}, {z}) outside {self:?}"
        );
        x as usize + self.nx as usize * (y as usize + self.ny as usize * z as usize)
    }

    /// Packed `u32` words per row along x: `ceil(nx / 32)`.
    pub fn words_per_row(&self) -> usize {
        (self.nx as usize).div_ceil(32)
    }

    /// Packed words per field: `words_per_row * ny * nz`.
    pub fn words(&self) -> usize {
        self.words_per_row() * self.ny as usize * self.nz as usize
    }

    /// Rows (`ny * nz`).
    pub fn rows(&self) -> usize {
        self.ny as usize * self.nz as usize
    }

    /// Bits of the last word of a row that hold cells (the rest are always zero).
    pub fn last_word_mask(&self) -> u32 {
        match self.nx % 32 {
            0 => u32::MAX,
            r => (1u32 << r) - 1,
        }
    }
}

/// What lies beyond the horizontal (x, y) edges. Vertically, cells outside the grid
/// always read as empty.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum Boundary {
    /// Cells outside the grid read as empty (Dobashi et al. 2000). Wind moves cells out and empty
    /// cells in.
    #[default]
    Empty,
    /// x and y wrap around. Needs `nx` to be a multiple of 32 (rows of whole words);
    /// other widths are rejected with [`Error::PeriodicWidth`].
    Periodic,
}

/// A region where clouds grow, in cell units (cell `(x, y, z)` has its centre at
/// `(x + 0.5, y + 0.5, z + 0.5)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// Centre, in cells.
    pub center: [f32; 3],
    /// Semi-axes along x, y, z, in cells; finite and positive.
    pub radii: [f32; 3],
}

/// Base probabilities per cell and step.
///
/// Each must lie in `[0, 1]` and is quantised *down* to a multiple of 2^-16
/// (`threshold = floor(p * 2^16)`, see [`crate::rng`]); a non-zero value below 2^-16,
/// which would quantise to 0, is rejected ([`Error::ProbabilityResolution`]).
///
/// Without ellipsoids they apply everywhere as they are. With ellipsoids, a cell whose
/// quantised mask is `m = level / 256` (see [`Model::mask_level`]) uses `humidity * m`,
/// `activation * m` and `extinction * (1 - m)`, and loses its cloud where the level is
/// 0 (Dobashi et al. 2000).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probabilities {
    /// `p_ext`: a cloud cell vanishes.
    pub extinction: f32,
    /// `p_hum`: a cell becomes humid.
    pub humidity: f32,
    /// `p_act`: a cell becomes active.
    pub activation: f32,
}

impl Default for Probabilities {
    /// Factors 0.1, 0.1 and 0.001 after Dobashi et al. 2000.
    fn default() -> Self {
        Self {
            extinction: 0.1,
            humidity: 0.1,
            activation: 0.001,
        }
    }
}

/// Dobashi's space-time smoothing of `cld` into a continuous density.
///
/// The weight of cell offset `(dx, dy, dz)` and age `tau` steps is
/// `(R+1-|dx|)(R+1-|dy|)(R+1-|dz|) * (T+1-tau)` for `|d*| <= R = radius_cells` and
/// `tau <= T = radius_steps` (tent filters), normalised by the full kernel's weight.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Smoothing {
    /// Spatial radius in cells (0 = no spatial smoothing), at most 8.
    pub radius_cells: u32,
    /// How many past steps are blended in (0 = current only), at most 15.
    pub radius_steps: u32,
}

impl Default for Smoothing {
    fn default() -> Self {
        Self {
            radius_cells: 1,
            radius_steps: 2,
        }
    }
}

/// Everything a user sets. Validated by [`Model::new`].
#[derive(Debug, Clone, PartialEq)]
pub struct Config {
    /// Grid dimensions.
    pub size: GridSize,
    /// Horizontal boundary behaviour.
    pub boundary: Boundary,
    /// Seed of the counter-based random draws.
    pub seed: u32,
    /// Base probabilities.
    pub probabilities: Probabilities,
    /// Cloud regions; empty means the base probabilities apply uniformly.
    pub ellipsoids: Vec<Ellipsoid>,
    /// Wind per z slice, `[vx, vy]` in cells per step (`|v| <= 16`); empty = no wind.
    pub wind: Vec<[f32; 2]>,
    /// Density scale per z slice (Dobashi et al. 2000's 1D table); empty = 1 everywhere.
    pub slice_density: Vec<f32>,
    /// Density smoothing kernel.
    pub smoothing: Smoothing,
}

impl Config {
    /// Defaults for a grid: empty boundaries, seed 0, Dobashi et al. 2000's probabilities, no
    /// ellipsoids, no wind, unit slice density, default smoothing.
    pub fn new(size: GridSize) -> Self {
        Self {
            size,
            boundary: Boundary::Empty,
            seed: 0,
            probabilities: Probabilities::default(),
            ellipsoids: Vec::new(),
            wind: Vec::new(),
            slice_density: Vec::new(),
            smoothing: Smoothing::default(),
        }
    }
}

/// A validated [`Config`] with everything the implementations derive from it.
#[derive(Debug, Clone)]
pub struct Model {
    config: Config,
    /// Mask level per cell (linear index), `0..=256`.
    mask: Vec<u16>,
    /// `[extinction, humidity, activation]` thresholds, `floor(p * 2^16)`.
    thresholds: [u32; 3],
    /// With ellipsoids, the per-lane threshold planes of the words they touch.
    regions: Option<RegionTable>,
    /// Wind per slice as 16.16 fixed point.
    wind_q: Vec<[i32; 2]>,
    slice_density: Vec<f32>,
}

/// `floor(p * 2^16)` for a valid probability, or the typed error.
pub(crate) fn checked_threshold(field: &'static str, value: f32) -> Result<u32, Error> {
    let threshold =
        probability_threshold(f64::from(value)).ok_or(Error::Probability { field, value })?;
    if threshold == 0 && value > 0.0 {
        return Err(Error::ProbabilityResolution {
            field,
            value,
            resolution: 1.0 / f64::from(THRESHOLD_ONE),
        });
    }
    Ok(threshold)
}

impl Model {
    /// Validates `config` and derives the tables.
    pub fn new(config: Config) -> Result<Self, Error> {
        let size = config.size;
        size.validate()?;
        if config.boundary == Boundary::Periodic && !size.nx.is_multiple_of(32) {
            return Err(Error::PeriodicWidth { nx: size.nx });
        }
        let p = config.probabilities;
        let thresholds = [
            checked_threshold("probabilities.extinction", p.extinction)?,
            checked_threshold("probabilities.humidity", p.humidity)?,
            checked_threshold("probabilities.activation", p.activation)?,
        ];
        const AXES: [&str; 3] = ["x", "y", "z"];
        for (index, e) in config.ellipsoids.iter().enumerate() {
            for axis in 0..3 {
                let r = e.radii[axis];
                if !(r.is_finite() && r > 0.0) {
                    return Err(Error::EllipsoidRadius {
                        index,
                        field: ["radii.x", "radii.y", "radii.z"][axis],
                        value: r,
                    });
                }
                if !e.center[axis].is_finite() {
                    return Err(Error::EllipsoidCenter {
                        index,
                        field: ["center.x", "center.y", "center.z"][axis],
                        value: e.center[axis],
                    });
                }
            }
        }
        let nz = size.nz as usize;
        for (field, len) in [
            ("wind", config.wind.len()),
            ("slice_density", config.slice_density.len()),
        ] {
            if len != 0 && len != nz {
                return Err(Error::SliceTableLength {
                    field,
                    len,
                    expected: nz,
                });
            }
        }
        for (index, &value) in config.slice_density.iter().enumerate() {
            if !(value.is_finite() && value >= 0.0) {
                return Err(Error::SliceDensity { index, value });
            }
        }
        for (index, v) in config.wind.iter().enumerate() {
            for (component, &value) in AXES[..2].iter().zip(v) {
                if !(value.is_finite() && value.abs() <= MAX_WIND) {
                    return Err(Error::Wind {
                        index,
                        component,
                        value,
                        max: MAX_WIND,
                    });
                }
            }
        }
        let s = config.smoothing;
        if s.radius_cells > MAX_SMOOTHING_RADIUS_CELLS {
            return Err(Error::Smoothing {
                field: "radius_cells",
                value: s.radius_cells,
                min: 0,
                max: MAX_SMOOTHING_RADIUS_CELLS,
            });
        }
        if s.radius_steps > MAX_SMOOTHING_RADIUS_STEPS {
            return Err(Error::Smoothing {
                field: "radius_steps",
                value: s.radius_steps,
                min: 0,
                max: MAX_SMOOTHING_RADIUS_STEPS,
            });
        }

        let mask = mask_levels(size, &config.ellipsoids);
        let regions =
            (!config.ellipsoids.is_empty()).then(|| RegionTable::new(size, &mask, thresholds));
        let wind_q = config
            .wind
            .iter()
            .map(|v| [wind_velocity_fixed(v[0]), wind_velocity_fixed(v[1])])
            .collect();
        let slice_density = if config.slice_density.is_empty() {
            vec![1.0; nz]
        } else {
            config.slice_density.clone()
        };
        Ok(Self {
            config,
            mask,
            thresholds,
            regions,
            wind_q,
            slice_density,
        })
    }

    /// The validated configuration.
    pub fn config(&self) -> &Config {
        &self.config
    }

    /// Grid dimensions.
    pub fn size(&self) -> GridSize {
        self.config.size
    }

    /// Horizontal boundary behaviour.
    pub fn boundary(&self) -> Boundary {
        self.config.boundary
    }

    /// Seed of the random draws.
    pub fn seed(&self) -> u32 {
        self.config.seed
    }

    /// Quantised region mask of every cell (linear index), `0..=256` (level `l` is
    /// mask `l / 256`).
    ///
    /// Per ellipsoid `m_e = max(0, 1 - d^2)` with `d` the cell centre's normalised
    /// distance from the ellipsoid centre; `m = max_e m_e`; level `= round(256 m)`
    /// (computed once, in f64, on the CPU). Without ellipsoids every level is 256.
    pub fn mask_levels(&self) -> &[u16] {
        &self.mask
    }

    /// The mask level of one cell; [`Error::CellOutOfRange`] outside the grid.
    pub fn mask_level(&self, x: u32, y: u32, z: u32) -> Result<u16, Error> {
        Ok(self.mask[self.size().index(x, y, z)?])
    }

    /// [`Model::mask_level`] for the crate's cell loops (coordinates inside the grid).
    pub(crate) fn mask_level_unchecked(&self, x: u32, y: u32, z: u32) -> u16 {
        self.mask[self.size().index_unchecked(x, y, z)]
    }

    /// True when ellipsoids scale the probabilities (and extinction uses `1 - m`).
    pub fn has_regions(&self) -> bool {
        !self.config.ellipsoids.is_empty()
    }

    /// `[extinction, humidity, activation]` base thresholds `floor(p * 2^16)` in
    /// `[0, 2^16]` (see [`crate::rng`]); the effective base probability is
    /// `threshold / 2^16`.
    pub fn thresholds(&self) -> [u32; 3] {
        self.thresholds
    }

    /// With ellipsoids, the words they touch with their lanes' threshold planes
    /// ([`crate::rng::lane_threshold`] of each cell's level); `None` without ellipsoids
    /// (the base thresholds then apply to every cell).
    pub fn regions(&self) -> Option<&RegionTable> {
        self.regions.as_ref()
    }

    /// Wind per z slice as 16.16 fixed point `[vx, vy]`; empty when there is no wind.
    pub fn wind_fixed(&self) -> &[[i32; 2]] {
        &self.wind_q
    }

    /// True when any slice has a non-zero wind.
    pub fn has_wind(&self) -> bool {
        self.wind_q.iter().any(|v| v[0] != 0 || v[1] != 0)
    }

    /// Wind shift `[dx, dy]` (cells) of slice `z` during `step`.
    pub fn wind_shift(&self, z: u32, step: u32) -> [i32; 2] {
        match self.wind_q.get(z as usize) {
            Some(v) => [
                crate::rng::wind_shift(v[0], step),
                crate::rng::wind_shift(v[1], step),
            ],
            None => [0, 0],
        }
    }

    /// Density scale per z slice (length `nz`).
    pub fn slice_density(&self) -> &[f32] {
        &self.slice_density
    }

    /// Smoothing kernel.
    pub fn smoothing(&self) -> Smoothing {
        self.config.smoothing
    }
}

fn mask_levels(size: GridSize, ellipsoids: &[Ellipsoid]) -> Vec<u16> {
    if ellipsoids.is_empty() {
        return vec![MASK_LEVEL_MAX; size.cells()];
    }
    // Max over ellipsoids of max(0, 1 - d^2); only each ellipsoid's bounding box can be
    // non-zero, so visit just that (max is order independent).
    let mut mask_value = vec![0.0f64; size.cells()];
    let dims = [size.nx, size.ny, size.nz];
    for e in ellipsoids {
        let mut lo = [0u32; 3];
        let mut hi = [0u32; 3];
        for axis in 0..3 {
            let c = f64::from(e.center[axis]);
            let r = f64::from(e.radii[axis]);
            let first = (c - r - 0.5).floor().max(0.0);
            let last = (c + r - 0.5).ceil().min(f64::from(dims[axis]) - 1.0);
            if last < first {
                lo[axis] = 1;
                hi[axis] = 0;
            } else {
                lo[axis] = first as u32;
                hi[axis] = last as u32;
            }
        }
        if (0..3).any(|a| lo[a] > hi[a]) {
            continue;
        }
        let inv_r = e.radii.map(|r| 1.0 / f64::from(r));
        for z in lo[2]..=hi[2] {
            let dz = (f64::from(z) + 0.5 - f64::from(e.center[2])) * inv_r[2];
            for y in lo[1]..=hi[1] {
                let dy = (f64::from(y) + 0.5 - f64::from(e.center[1])) * inv_r[1];
                for x in lo[0]..=hi[0] {
                    let dx = (f64::from(x) + 0.5 - f64::from(e.center[0])) * inv_r[0];
                    let m = 1.0 - (dx * dx + dy * dy + dz * dz);
                    let slot = &mut mask_value[size.index_unchecked(x, y, z)];
                    if m > *slot {
                        *slot = m;
                    }
                }
            }
        }
    }
    mask_value
        .into_iter()
        .map(|m| (m.clamp(0.0, 1.0) * f64::from(MASK_LEVEL_MAX)).round() as u16)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn config() -> Config {
        Config::new(GridSize::new(8, 8, 8))
    }

    #[test]
    fn bad_sizes_are_named() {
        for (size, field) in [
            (GridSize::new(0, 4, 4), "size.nx"),
            (GridSize::new(4, 0, 4), "size.ny"),
            (GridSize::new(4, 4, 0), "size.nz"),
        ] {
            assert_eq!(
                Model::new(Config::new(size)).unwrap_err(),
                Error::ZeroSize { field }
            );
        }
        assert_eq!(
            Model::new(Config::new(GridSize::new(4, MAX_DIMENSION + 1, 4))).unwrap_err(),
            Error::DimensionTooLarge {
                field: "size.ny",
                value: MAX_DIMENSION + 1,
                max: MAX_DIMENSION
            }
        );
        let err = Model::new(Config::new(GridSize::new(65_536, 65_536, 1))).unwrap_err();
        assert!(
            matches!(err, Error::TooManyCells { cells, .. } if cells == 1 << 32),
            "{err:?}"
        );
        let mut c = Config::new(GridSize::new(33, 4, 4));
        c.boundary = Boundary::Periodic;
        assert_eq!(Model::new(c).unwrap_err(), Error::PeriodicWidth { nx: 33 });
    }

    #[test]
    fn bad_probabilities_are_named() {
        for value in [f32::NAN, -0.01, 1.01, f32::INFINITY] {
            let mut c = config();
            c.probabilities.humidity = value;
            let err = Model::new(c).unwrap_err();
            assert!(
                matches!(err, Error::Probability { field: "probabilities.humidity", value: v } if v.to_bits() == value.to_bits()),
                "{err:?}"
            );
            assert!(err.to_string().contains("probabilities.humidity"));
        }
        let mut c = config();
        c.probabilities.extinction = 2.0;
        assert!(matches!(
            Model::new(c),
            Err(Error::Probability {
                field: "probabilities.extinction",
                ..
            })
        ));
        let mut c = config();
        c.probabilities.activation = -1.0;
        assert!(matches!(
            Model::new(c),
            Err(Error::Probability {
                field: "probabilities.activation",
                ..
            })
        ));
        // the ends are fine
        let mut c = config();
        c.probabilities = Probabilities {
            extinction: 0.0,
            humidity: 1.0,
            activation: 1.0,
        };
        assert!(Model::new(c).is_ok());
    }

    #[test]
    fn degenerate_ellipsoids_are_named() {
        for (radii, field, bad) in [
            ([0.0, 1.0, 1.0], "radii.x", 0.0),
            ([1.0, -2.0, 1.0], "radii.y", -2.0),
            ([1.0, 1.0, f32::NAN], "radii.z", f32::NAN),
            ([1.0, f32::INFINITY, 1.0], "radii.y", f32::INFINITY),
        ] {
            let mut c = config();
            c.ellipsoids = vec![
                Ellipsoid {
                    center: [4.0; 3],
                    radii: [2.0; 3],
                },
                Ellipsoid {
                    center: [4.0; 3],
                    radii,
                },
            ];
            let err = Model::new(c).unwrap_err();
            assert!(
                matches!(&err, Error::EllipsoidRadius { index: 1, field: f, value } if *f == field && value.to_bits() == f32::to_bits(bad)),
                "{err:?}"
            );
            assert!(err.to_string().contains(&format!("ellipsoids[1].{field}")));
        }
        let mut c = config();
        c.ellipsoids = vec![Ellipsoid {
            center: [1.0, f32::NAN, 1.0],
            radii: [1.0; 3],
        }];
        assert!(matches!(
            Model::new(c),
            Err(Error::EllipsoidCenter {
                index: 0,
                field: "center.y",
                ..
            })
        ));
    }

    #[test]
    fn bad_tables_are_named() {
        let mut c = config();
        c.wind = vec![[0.0, 0.0]; 3];
        assert_eq!(
            Model::new(c).unwrap_err(),
            Error::SliceTableLength {
                field: "wind",
                len: 3,
                expected: 8
            }
        );
        let mut c = config();
        c.wind = vec![[0.0, 0.0]; 8];
        c.wind[5][1] = 17.0;
        assert!(matches!(
            Model::new(c),
            Err(Error::Wind {
                index: 5,
                component: "y",
                ..
            })
        ));
        let mut c = config();
        c.slice_density = vec![1.0; 8];
        c.slice_density[2] = -1.0;
        assert!(matches!(
            Model::new(c),
            Err(Error::SliceDensity { index: 2, .. })
        ));
        let mut c = config();
        c.smoothing.radius_cells = 9;
        assert!(matches!(
            Model::new(c),
            Err(Error::Smoothing {
                field: "radius_cells",
                value: 9,
                ..
            })
        ));
        let mut c = config();
        c.smoothing.radius_steps = 16;
        assert!(matches!(
            Model::new(c),
            Err(Error::Smoothing {
                field: "radius_steps",
                value: 16,
                ..
            })
        ));
    }

    #[test]
    fn tiny_probabilities_are_rejected_not_rounded_to_zero() {
        let mut c = config();
        c.probabilities.activation = 1e-6;
        let err = Model::new(c).unwrap_err();
        assert!(
            matches!(
                err,
                Error::ProbabilityResolution {
                    field: "probabilities.activation",
                    ..
                }
            ),
            "{err:?}"
        );
        assert!(err.to_string().contains("probabilities.activation"));
        let mut c = config();
        c.probabilities.activation = 1.0 / 65536.0;
        assert_eq!(Model::new(c).unwrap().thresholds()[2], 1);
    }

    #[test]
    fn mask_peaks_at_centres_and_vanishes_outside() {
        let mut c = Config::new(GridSize::new(40, 20, 10));
        c.ellipsoids = vec![Ellipsoid {
            center: [10.5, 10.5, 5.5],
            radii: [8.0, 6.0, 4.0],
        }];
        let m = Model::new(c).unwrap();
        assert!(m.has_regions());
        assert_eq!(m.mask_level(10, 10, 5).unwrap(), 256);
        assert_eq!(m.mask_level(30, 10, 5).unwrap(), 0);
        assert_eq!(m.mask_level(0, 0, 0).unwrap(), 0);
        // (x - 10.5) / 8 = 0.5 -> 1 - 0.25 = 0.75 -> 192
        assert_eq!(m.mask_level(14, 10, 5).unwrap(), 192);
        // (x - 10.5) / 8 = 0.625 -> 1 - 0.390625 = 0.609375 -> 156
        assert_eq!(m.mask_level(15, 10, 5).unwrap(), 156);
        let p = Probabilities::default();
        assert_eq!(
            m.thresholds(),
            [p.extinction, p.humidity, p.activation].map(|v| (f64::from(v) * 65536.0) as u32)
        );
        // the region table's planes agree with the cells' own thresholds
        let size = m.size();
        let wpr = size.words_per_row();
        let table = m.regions().unwrap();
        let mut seen = 0;
        for row in 0..size.rows() {
            let (y, z) = ((row % 20) as u32, (row / 20) as u32);
            let entries = table.row_entries(row);
            let any_alive = (0..40).any(|x| m.mask_level(x, y, z).unwrap() > 0);
            assert_eq!(entries.is_empty(), !any_alive, "row {row}");
            for e in entries {
                seen += 1;
                let w = table.word(e) as usize;
                assert_eq!(w / wpr, row);
                let wx = w % wpr;
                for (s, stream) in crate::regions::STREAMS.iter().enumerate() {
                    let planes = table.planes(e, s);
                    for lane in 0..32 {
                        let x = (wx * 32 + lane) as u32;
                        let bit = |k: usize| planes[k] >> lane & 1;
                        let t = if x >= 40 {
                            0
                        } else {
                            let l = u32::from(m.mask_level(x, y, z).unwrap());
                            assert_eq!(table.alive(e) >> lane & 1 == 1, l > 0);
                            crate::rng::lane_threshold(m.thresholds()[s], l, *stream)
                        };
                        let low: u32 = (0..16).fold(0, |v, k| v << 1 | bit(k));
                        let always = bit(crate::rng::PLANE_ALWAYS) == 1;
                        assert_eq!(if always { 65536 } else { low }, t);
                        assert_eq!(bit(crate::rng::PLANE_NONZERO) == 1, t > 0);
                    }
                }
            }
        }
        assert_eq!(seen, table.len());
    }

    #[test]
    fn uniform_without_ellipsoids() {
        let m = Model::new(config()).unwrap();
        assert!(!m.has_regions());
        assert!(m.regions().is_none());
        assert!(m.mask_levels().iter().all(|&l| l == 256));
    }
}
