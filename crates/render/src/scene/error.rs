//! Errors of scene files: the line, column, field and value, and the typed error of
//! the crate that rejected the value.

use std::path::PathBuf;

pub use super::locate::{Location, Origin};

/// Where the value came from: `line L, column C: `, `line L (default value): ` for a
/// key its table on line L does not give, `` `--flag`: `` for a flag's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct At(pub Option<Location>);

impl std::fmt::Display for At {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0 {
            Some(Location {
                origin: Origin::Flag(flag),
                ..
            }) => write!(f, "{flag}: "),
            Some(Location {
                line,
                origin: Origin::Section,
                ..
            }) => write!(f, "line {line} (default value): "),
            Some(l) => write!(f, "line {}, column {}: ", l.line, l.column),
            None => write!(f, "(default value, not in the file) "),
        }
    }
}

/// What is wrong with a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file could not be read.
    #[error("reading the scene `{path}`: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// TOML syntax, a missing or misspelt key, or a value of the wrong type.
    #[error("{}{}{message}{}", At(*location), field.as_deref().map(|f| format!("`{f}`: ")).unwrap_or_default(), suggestion.as_deref().map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default())]
    Parse {
        /// Where.
        location: Option<Location>,
        /// The dotted key, when the error is about one.
        field: Option<String>,
        /// toml's or serde's message.
        message: String,
        /// The nearest valid key or name, for a misspelt one.
        suggestion: Option<String>,
        /// toml's error.
        source: Box<toml::de::Error>,
    },
    /// A value this crate checks (camera near/far, albedo ramp, output size).
    #[error("{}`{field}` = {value}: {reason}", At(*location))]
    Invalid {
        /// Where.
        location: Option<Location>,
        /// Dotted key.
        field: String,
        /// The value as typed (with its unit).
        value: String,
        /// The rule it breaks.
        reason: String,
    },
    /// `atmos` rejected a value (the atmosphere's parameters, the camera, the sun).
    #[error("{}`{field}` = {value}: rejected by atmos: {source}", At(*location))]
    Atmosphere {
        /// Where.
        location: Option<Location>,
        /// Dotted key.
        field: String,
        /// The value as typed (with its unit).
        value: String,
        /// atmos' error, naming its own field.
        source: Box<atmos::AtmosError>,
    },
    /// `terrain` rejected a value or a file.
    #[error("{}`{field}` = {value}: rejected by terrain: {source}", At(*location))]
    Terrain {
        /// Where.
        location: Option<Location>,
        /// Dotted key.
        field: String,
        /// The value as typed.
        value: String,
        /// terrain's error.
        source: Box<terrain::TerrainError>,
    },
    /// `celestial` rejected a value (the instant, the place, the sky objects).
    #[error("{}`{field}` = {value}: rejected by celestial: {source}", At(*location))]
    Celestial {
        /// Where.
        location: Option<Location>,
        /// Dotted key.
        field: String,
        /// The value as typed.
        value: String,
        /// celestial's error.
        source: Box<celestial::CelestialError>,
    },
    /// `cloudlight` rejected a value (the `[clouds.shell]` shell or its march settings:
    /// `cloudlight::ShellError`, `cloudlight::march::MarchError`).
    #[error("{}`{field}` = {value}: rejected by cloudlight: {source}", At(*location))]
    Cloudlight {
        /// Where.
        location: Option<Location>,
        /// Dotted key.
        field: String,
        /// The value as typed (with its unit).
        value: String,
        /// cloudlight's error, naming its own field.
        source: Box<dyn std::error::Error + Send + Sync>,
    },
}

impl SceneError {
    /// Where in the file the problem is (or the flag that supplied the value), when
    /// known.
    pub fn location(&self) -> Option<Location> {
        match self {
            Self::Read { .. } => None,
            Self::Parse { location, .. }
            | Self::Invalid { location, .. }
            | Self::Atmosphere { location, .. }
            | Self::Terrain { location, .. }
            | Self::Celestial { location, .. }
            | Self::Cloudlight { location, .. } => *location,
        }
    }

    /// The dotted field the problem is about, when known.
    pub fn field(&self) -> Option<&str> {
        match self {
            Self::Read { .. } => None,
            Self::Parse { field, .. } => field.as_deref(),
            Self::Invalid { field, .. }
            | Self::Atmosphere { field, .. }
            | Self::Terrain { field, .. }
            | Self::Celestial { field, .. }
            | Self::Cloudlight { field, .. } => Some(field),
        }
    }

    /// toml's error with its place in `source`, the dotted key it concerns and, for
    /// an unknown key or name, the nearest valid one.
    pub(crate) fn from_toml(source: &str, error: toml::de::Error) -> Self {
        let location = error
            .span()
            .map(|span| Location::of_offset(source, span.start));
        let message = error.message().trim_end().to_owned();
        let mut field = error
            .span()
            .and_then(|span| super::locate::dotted_key_at(source, span));
        // A missing key's span is its table's header, or empty at 0 for a missing
        // section: name the key itself.
        if let Some(name) = message
            .strip_prefix("missing field `")
            .and_then(|rest| rest.split('`').next())
        {
            let whole_document = error.span().is_none_or(|span| {
                span.start == 0 && (span.is_empty() || span.end + 1 >= source.len())
            });
            field = match field {
                Some(parent) if !whole_document => Some(format!("{parent}.{name}")),
                _ => Some(name.to_owned()),
            };
        }
        let suggestion = suggest(&message);
        Self::Parse {
            location,
            field,
            message,
            suggestion,
            source: Box::new(error),
        }
    }
}

/// For serde's "unknown field `x`, expected one of `a`, `b`" and "unknown variant
/// `x`, expected ..." messages: the expected name closest to `x` (Jaro–Winkler ≥ 0.7,
/// or an edit distance of at most 2).
fn suggest(message: &str) -> Option<String> {
    let rest = message
        .strip_prefix("unknown field ")
        .or_else(|| message.strip_prefix("unknown variant "))?;
    let mut quoted = rest.split('`').skip(1).step_by(2);
    let typed = quoted.next()?;
    quoted
        .map(|candidate| {
            (
                strsim::jaro_winkler(typed, candidate),
                strsim::levenshtein(typed, candidate),
                candidate,
            )
        })
        .filter(|&(similarity, distance, _)| similarity >= 0.7 || distance <= 2)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, _, candidate)| candidate.to_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_become_lines_and_columns() {
        let text = "a = 1\nbb = 2\n";
        assert_eq!(
            Location::of_offset(text, 0),
            Location {
                line: 1,
                column: 1,
                origin: Origin::Key
            }
        );
        assert_eq!(
            Location::of_offset(text, 7),
            Location {
                line: 2,
                column: 2,
                origin: Origin::Key
            }
        );
    }

    #[test]
    fn suggestions_pick_the_nearest_expected_name() {
        assert_eq!(
            suggest("unknown field `vertical_fov`, expected one of `position`, `look_at`, `vertical_fov_deg`")
                .as_deref(),
            Some("vertical_fov_deg")
        );
        assert_eq!(
            suggest("unknown variant `precomputd`, expected one of `single`, `precomputed`")
                .as_deref(),
            Some("precomputed")
        );
        assert_eq!(suggest("unknown field `zzz`, expected `position`"), None);
        assert_eq!(suggest("invalid type: string, expected f64"), None);
    }
}
