//! The crate's typed errors: each names the field and the value that was rejected.

/// What `celestial` rejects.
#[derive(Debug, thiserror::Error)]
pub enum CelestialError {
    /// A number that must be finite is NaN or infinite.
    #[error("{field} = {value} is not a finite number")]
    NotFinite {
        /// The rejected field.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// A finite number outside the range the field allows.
    #[error("{field} = {value} {unit} is outside [{min}, {max}] {unit}")]
    OutOfRange {
        /// The rejected field.
        field: &'static str,
        /// Its value.
        value: f64,
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
        /// Unit of `value`, `min` and `max`.
        unit: &'static str,
    },
    /// A date-time string that is not an ISO 8601 (RFC 3339 profile) date-time with an
    /// explicit UTC offset.
    #[error(
        "{field} = {input:?} is not an ISO 8601 date-time with a UTC offset (e.g. 2003-10-17T12:30:30-07:00)"
    )]
    Parse {
        /// The rejected field.
        field: &'static str,
        /// The text given.
        input: String,
        /// The parser's diagnosis.
        #[source]
        source: chrono::ParseError,
    },
    /// Calendar fields that name no instant (e.g. 31 April, hour 24).
    #[error("{field} = {value} names no valid UTC calendar date-time")]
    InvalidCalendar {
        /// The rejected field.
        field: &'static str,
        /// The fields as given.
        value: String,
    },
    /// An instant outside the span the ephemerides are validated for.
    #[error("{field} = {value} is outside the supported span [{min}, {max})")]
    OutsideSpan {
        /// The rejected field.
        field: &'static str,
        /// The instant, in RFC 3339.
        value: String,
        /// First supported instant.
        min: &'static str,
        /// First unsupported instant after the span.
        max: &'static str,
    },
    /// The SPA ephemeris (crate `solar-positioning`) rejected its input; `celestial`
    /// validates first, so this signals a disagreement between the two validations.
    #[error("the SPA solar ephemeris rejected {field}")]
    Ephemeris {
        /// What was being computed.
        field: &'static str,
        /// The ephemeris' error.
        #[source]
        source: solar_positioning::Error,
    },
    /// atmos rejected an input `celestial` passed on (an atmosphere, a sky query, a dome
    /// resolution); the source names atmos' field and value.
    #[error("{field}: atmos rejected it")]
    Atmos {
        /// What was being built.
        field: &'static str,
        /// atmos' error.
        #[source]
        source: atmos::AtmosError,
    },
    /// An index past the end of a list (a cloud layer that does not exist).
    #[error("{field} = {index} but there are only {count}")]
    NoSuchIndex {
        /// The rejected field.
        field: &'static str,
        /// The index given.
        index: usize,
        /// How many there are.
        count: usize,
    },
    /// A call that needs an earlier one (e.g. `repaint` before `reposition`).
    #[error("{call} needs {missing} first")]
    OutOfOrder {
        /// The call made.
        call: &'static str,
        /// The call it needs before it.
        missing: &'static str,
    },
    /// The GPU pass cannot run (see [`crate::gpu::GpuError`]).
    #[cfg(feature = "gpu")]
    #[error("GPU: {0}")]
    Gpu(#[source] crate::gpu::GpuError),
    /// WGSL composition failed (a bug in skyscape's shaders, reported, not a panic).
    #[error("WGSL composition: {0}")]
    Shader(#[from] skyscape_wgsl::ComposeError),
    /// The shipped star catalogue could not be loaded.
    #[error("the star catalogue {field} could not be loaded")]
    Catalogue {
        /// Which catalogue.
        field: &'static str,
        /// The catalogue crate's error.
        #[source]
        source: star_catalog::Error,
    },
    /// Data embedded in the crate failed to decode (a bug in the shipped file).
    #[error("the embedded data {field} is corrupt at byte {offset}")]
    CorruptData {
        /// Which file.
        field: &'static str,
        /// Where decoding failed.
        offset: usize,
    },
    /// A star name or Hipparcos number that names no star of the loaded catalogue.
    #[error(
        "{field} = {value:?} names no star of the catalogue (magnitude ≤ {limiting_magnitude})"
    )]
    UnknownStar {
        /// The rejected field.
        field: &'static str,
        /// The text given.
        value: String,
        /// The catalogue's limiting magnitude.
        limiting_magnitude: f64,
    },
}

/// `Result` with [`CelestialError`].
pub type Result<T> = std::result::Result<T, CelestialError>;

/// `value` if finite and within `[min, max]`, else the typed error naming `field`.
pub(crate) fn check_range(
    field: &'static str,
    value: f64,
    min: f64,
    max: f64,
    unit: &'static str,
) -> Result<f64> {
    if !value.is_finite() {
        return Err(CelestialError::NotFinite { field, value });
    }
    if !(min..=max).contains(&value) {
        return Err(CelestialError::OutOfRange {
            field,
            value,
            min,
            max,
            unit,
        });
    }
    Ok(value)
}
