//! The crate's typed errors.

/// Everything that can be wrong with a configuration, a state or a call.
///
/// Each variant names the offending field and its value; nothing in this crate
/// panics on bad input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Error {
    /// A grid dimension is zero.
    #[error("grid size `{field}` is 0; every dimension must be at least 1")]
    ZeroSize {
        /// `size.nx`, `size.ny` or `size.nz`.
        field: &'static str,
    },
    /// A grid dimension exceeds [`crate::MAX_DIMENSION`].
    #[error("grid size `{field}` = {value} exceeds the maximum {max}")]
    DimensionTooLarge {
        /// `size.nx`, `size.ny` or `size.nz`.
        field: &'static str,
        /// The requested value.
        value: u32,
        /// The largest allowed value.
        max: u32,
    },
    /// The grid has more cells than [`crate::MAX_CELLS`].
    #[error("grid {nx}x{ny}x{nz} has {cells} cells, more than the maximum {max}")]
    TooManyCells {
        /// Cells along x.
        nx: u32,
        /// Cells along y.
        ny: u32,
        /// Cells along z.
        nz: u32,
        /// nx * ny * nz.
        cells: u64,
        /// The largest allowed count.
        max: u64,
    },
    /// Periodic horizontal boundaries need whole 32-cell words along x.
    #[error("periodic boundaries need `size.nx` to be a multiple of 32, got {nx}")]
    PeriodicWidth {
        /// The requested width.
        nx: u32,
    },
    /// A probability is NaN or outside [0, 1].
    #[error("probability `{field}` = {value} is not in [0, 1]")]
    Probability {
        /// E.g. `probabilities.extinction`.
        field: &'static str,
        /// The offending value.
        value: f32,
    },
    /// A probability is positive but below the 2^-16 resolution of the draws, so it
    /// would silently act as 0.
    #[error(
        "probability `{field}` = {value} is below the draws' resolution {resolution} \
         (thresholds are floor(p * 2^16)); use 0 or at least {resolution}"
    )]
    ProbabilityResolution {
        /// E.g. `probabilities.activation`.
        field: &'static str,
        /// The offending value.
        value: f32,
        /// 2^-16.
        resolution: f64,
    },
    /// An ellipsoid radius is NaN, infinite, zero or negative.
    #[error("`ellipsoids[{index}].{field}` = {value}: radii must be finite and positive")]
    EllipsoidRadius {
        /// Which ellipsoid.
        index: usize,
        /// `radii.x`, `radii.y` or `radii.z`.
        field: &'static str,
        /// The offending value.
        value: f32,
    },
    /// An ellipsoid centre coordinate is NaN or infinite.
    #[error("`ellipsoids[{index}].{field}` = {value}: the centre must be finite")]
    EllipsoidCenter {
        /// Which ellipsoid.
        index: usize,
        /// `center.x`, `center.y` or `center.z`.
        field: &'static str,
        /// The offending value.
        value: f32,
    },
    /// A per-slice table (wind, slice density) has the wrong length.
    #[error("`{field}` has {len} entries; expected {expected} (one per z slice) or none")]
    SliceTableLength {
        /// `wind` or `slice_density`.
        field: &'static str,
        /// Its length.
        len: usize,
        /// `size.nz`.
        expected: usize,
    },
    /// A slice density scale is NaN, infinite or negative.
    #[error("`slice_density[{index}]` = {value}: must be finite and >= 0")]
    SliceDensity {
        /// The slice.
        index: usize,
        /// The offending value.
        value: f32,
    },
    /// A wind velocity is NaN, infinite or faster than [`crate::MAX_WIND`] cells per step.
    #[error("`wind[{index}].{component}` = {value} cells/step: must be finite with |v| <= {max}")]
    Wind {
        /// The slice.
        index: usize,
        /// `x` or `y`.
        component: &'static str,
        /// The offending value.
        value: f32,
        /// [`crate::MAX_WIND`].
        max: f32,
    },
    /// A smoothing parameter is outside its range.
    #[error("`smoothing.{field}` = {value} is outside {min}..={max}")]
    Smoothing {
        /// `radius_cells` or `radius_steps`.
        field: &'static str,
        /// The offending value.
        value: u32,
        /// Smallest allowed.
        min: u32,
        /// Largest allowed.
        max: u32,
    },
    /// A cell coordinate outside the grid (an unchecked `x` would read the next row).
    #[error("cell coordinate `{field}` = {value} is outside the grid: must be < {limit}")]
    CellOutOfRange {
        /// `x`, `y` or `z`.
        field: &'static str,
        /// The coordinate given.
        value: u32,
        /// The grid's extent along that axis.
        limit: u32,
    },
    /// A thread count of zero was requested.
    #[error("`threads` = 0; at least one thread is needed")]
    ZeroThreads,
    /// A state (or buffer) does not match the model's grid.
    #[error("`{what}` has {got} elements but the grid needs {expected}")]
    SizeMismatch {
        /// What was passed.
        what: &'static str,
        /// Its length.
        got: usize,
        /// The expected length.
        expected: usize,
    },
    /// A packed state has bits set past `nx` in a row's last word.
    #[error("`{what}` word {word} has bits set past nx (padding must be zero)")]
    PaddingBits {
        /// `hum`, `act` or `cld`.
        what: &'static str,
        /// Index of the offending word.
        word: usize,
    },
}
