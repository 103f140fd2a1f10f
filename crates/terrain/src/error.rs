//! The crate's error type.

use std::path::PathBuf;

/// Everything that can go wrong when loading, generating or baking terrain.
///
/// Every variant names the offending field and its value; bad input never panics.
#[derive(Debug, thiserror::Error)]
pub enum TerrainError {
    /// A file could not be read or written.
    #[error("I/O error on `{path}`: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        source: std::io::Error,
    },
    /// The PNG decoder or encoder failed (corrupt or truncated data).
    #[error("PNG {operation} failed: {source}")]
    Png {
        /// `decode` or `encode`.
        operation: &'static str,
        /// The codec's error.
        source: image::ImageError,
    },
    /// The PNG has the wrong pixel layout or bit depth for the loader that was called.
    #[error("PNG pixel format is {found}, expected {expected}")]
    PixelFormat {
        /// What the loader accepts, e.g. `16-bit greyscale (L16)`.
        expected: &'static str,
        /// What the file holds, e.g. `L8`.
        found: String,
    },
    /// A width or height of zero.
    #[error("heightfield `{field}` is 0: maps need at least one texel per side")]
    ZeroSize {
        /// `width` or `height`.
        field: &'static str,
    },
    /// A dimension beyond [`crate::MAX_SIDE`] or a texel count beyond [`crate::MAX_TEXELS`].
    #[error("`{field}` = {value} exceeds the limit of {limit}")]
    TooLarge {
        /// `width`, `height` or `width * height`.
        field: &'static str,
        /// The requested value.
        value: u64,
        /// The limit.
        limit: u64,
    },
    /// A buffer's length does not match the stated dimensions.
    #[error("`{field}` has length {found}, expected {expected}")]
    SizeMismatch {
        /// Which buffer (`samples`, `raw f32 bytes`, `horizon`, …).
        field: &'static str,
        /// The length the dimensions require.
        expected: u64,
        /// The length given.
        found: u64,
    },
    /// A height sample is NaN or infinite (or becomes so after scaling).
    #[error("height at (x = {x}, y = {y}) is {value}, not a finite number")]
    NonFiniteHeight {
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The value found.
        value: f64,
    },
    /// An index (texel column or row, layer count) outside what the map holds.
    #[error("`{field}` = {value} is out of range: must be < {limit}")]
    OutOfRange {
        /// `x`, `y` or `count`.
        field: &'static str,
        /// The index given.
        value: u64,
        /// One past the largest valid index (0 when nothing is valid).
        limit: u64,
    },
    /// An elevation that the requested encoding cannot hold (instead of a clamp).
    #[error(
        "elevation at (x = {x}, y = {y}) is {value} m, outside the {min}..={max} m \
         that `{field}` can encode"
    )]
    ElevationNotRepresentable {
        /// The encoding's parameters, e.g. `scale, offset` of a 16-bit PNG.
        field: &'static str,
        /// Column.
        x: usize,
        /// Row.
        y: usize,
        /// The elevation, metres.
        value: f64,
        /// Lowest representable elevation, metres.
        min: f64,
        /// Highest representable elevation, metres.
        max: f64,
    },
    /// A horizon angle that is NaN or outside `[−π/2, π/2]` cannot be encoded
    /// (a NaN would otherwise become −π/2, "fully shadowed", without a word).
    #[error("horizon angle `{field}` = {value} rad is not in [-pi/2, pi/2]")]
    HorizonAngle {
        /// `angle`, or the texel, e.g. `horizon (x = 3, y = 7)`.
        field: String,
        /// The angle given, radians.
        value: f32,
    },
    /// A scalar parameter is out of its valid range.
    #[error("`{field}` = {value} is invalid: {reason}")]
    InvalidParameter {
        /// Parameter name, e.g. `spacing`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// What is required.
        reason: &'static str,
    },
}

impl TerrainError {
    /// Checks `value < limit` for an index called `field`.
    pub(crate) fn check_index(field: &'static str, value: usize, limit: usize) -> Result<(), Self> {
        if value < limit {
            Ok(())
        } else {
            Err(Self::OutOfRange {
                field,
                value: value as u64,
                limit: limit as u64,
            })
        }
    }

    pub(crate) fn param(field: &'static str, value: f64, reason: &'static str) -> Self {
        Self::InvalidParameter {
            field,
            value,
            reason,
        }
    }
}
