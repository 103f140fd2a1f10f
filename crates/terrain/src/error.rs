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
    #[error("PNG {operation} failed: {message}")]
    Png {
        /// `decode` or `encode`.
        operation: &'static str,
        /// The decoder's message.
        message: String,
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
    pub(crate) fn param(field: &'static str, value: f64, reason: &'static str) -> Self {
        Self::InvalidParameter {
            field,
            value,
            reason,
        }
    }
}
