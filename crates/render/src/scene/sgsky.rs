//! The scene keys of SimGear's SGSky (Curtis Olson's `SGSky`, `simgear/scene/sky/`)
//! that `celestial::sky::Sky` implements: `[visibility]` (SGSky's `set_visibility`)
//! and the `[[clouds.layers]]` tables (`SGCloudLayer`: kind, altitude, thickness,
//! transition, span, coverage by fraction or by SimGear's coverage names, wind drift).

use serde::Deserialize;

/// `[visibility]`: the meteorological visibility at the camera. It sets the
/// atmosphere's aerosol (`celestial::visibility::aerosol_for_visibility`: the total
/// extinction in green at the camera's altitude is Koschmieder's 3.912 / V, so terrain
/// and sky are fogged by the rung itself on both renderers) and the fog the cloud layers
/// fade into (`celestial::sky::Sky::set_visibility`). Needs neither `[time]` nor
/// layers; with `[time]` and layers the visibility closes in around a camera inside or
/// near a layer (`Sky::modify_vis`), drawn as the in-cloud fog.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VisibilitySection {
    /// Meteorological visibility at the camera, metres (Koschmieder's 2 % contrast
    /// distance), in [1 m, 1,000 km].
    pub distance_m: f64,
}

/// One `[[clouds.layers]]` table (`celestial::clouds::CloudLayer`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CloudLayerSection {
    /// The type: its texture and optical thickness.
    pub kind: CloudKindName,
    /// Base above sea level (m).
    pub base_m: f64,
    /// Thickness (m).
    pub thickness_m: f64,
    /// Transition zone above and below, where visibility closes in (m).
    #[serde(default = "default_transition_m")]
    pub transition_m: f64,
    /// Size of the layer's patch around the viewer (m).
    #[serde(default = "default_span_m")]
    pub span_m: f64,
    /// Fraction of the sky covered, 0 to 1, or one of SimGear's coverage names
    /// (default: the kind's).
    pub coverage: Option<Coverage>,
    /// The texture's seed.
    #[serde(default)]
    pub seed: u32,
    /// A horizontal plane instead of a sphere concentric with the planet.
    #[serde(default)]
    pub flat: bool,
    /// The wind carrying the layer, `[east, north]` m/s: its texture drifts downwind by
    /// the wind × `[time] offset_s` (SGSky's layers scroll their texture with the wind).
    #[serde(default)]
    pub wind_m_per_s: [f64; 2],
}

fn default_transition_m() -> f64 {
    100.0
}
fn default_span_m() -> f64 {
    80_000.0
}

/// The cloud kinds by name (`celestial::clouds::CloudKind`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CloudKindName {
    /// High fibrous streaks.
    Cirrus,
    /// Small high cells.
    Cirrocumulus,
    /// A grey middle sheet.
    Altostratus,
    /// Heaped low cells.
    Cumulus,
    /// A thick low sheet.
    Stratus,
    /// A thick sheet covering the sky.
    Overcast,
}

impl CloudKindName {
    /// The name as written in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Cirrus => "cirrus",
            Self::Cirrocumulus => "cirrocumulus",
            Self::Altostratus => "altostratus",
            Self::Cumulus => "cumulus",
            Self::Stratus => "stratus",
            Self::Overcast => "overcast",
        }
    }
}

impl From<CloudKindName> for celestial::clouds::CloudKind {
    fn from(name: CloudKindName) -> Self {
        use celestial::clouds::CloudKind as K;
        match name {
            CloudKindName::Cirrus => K::Cirrus,
            CloudKindName::Cirrocumulus => K::Cirrocumulus,
            CloudKindName::Altostratus => K::Altostratus,
            CloudKindName::Cumulus => K::Cumulus,
            CloudKindName::Stratus => K::Stratus,
            CloudKindName::Overcast => K::Overcast,
        }
    }
}

/// SimGear's coverage names (`SGCloudLayer::getCoverageType`: overcast, broken,
/// scattered, few, clear; its sixth, cirrus, is a kind here). SGSky's 2-D layers take
/// the name as a texture choice; the fraction each stands for is the middle of its
/// METAR class in oktas (WMO Manual on Codes, FM 15: FEW 1–2, SCT 3–4, BKN 5–7,
/// OVC 8 eighths of the sky), the classes FlightGear's weather fills the names from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoverageName {
    /// No cloud: 0.
    Clear,
    /// 1–2 oktas: 1.5/8.
    Few,
    /// 3–4 oktas: 3.5/8.
    Scattered,
    /// 5–7 oktas: 6/8.
    Broken,
    /// 8 oktas: 1.
    Overcast,
}

impl CoverageName {
    /// Every name, in order of coverage.
    pub const ALL: [CoverageName; 5] = [
        Self::Clear,
        Self::Few,
        Self::Scattered,
        Self::Broken,
        Self::Overcast,
    ];

    /// The name as written in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Self::Clear => "clear",
            Self::Few => "few",
            Self::Scattered => "scattered",
            Self::Broken => "broken",
            Self::Overcast => "overcast",
        }
    }

    /// The fraction of the sky covered: the middle of the name's okta class.
    pub fn fraction(self) -> f64 {
        match self {
            Self::Clear => 0.0,
            Self::Few => 1.5 / 8.0,
            Self::Scattered => 3.5 / 8.0,
            Self::Broken => 6.0 / 8.0,
            Self::Overcast => 1.0,
        }
    }
}

/// A layer's `coverage`: a fraction in [0, 1] or a [`CoverageName`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Coverage {
    /// A fraction of the sky, as typed.
    Fraction(f64),
    /// One of SimGear's names.
    Named(CoverageName),
}

impl Coverage {
    /// The fraction of the sky covered.
    pub fn fraction(self) -> f64 {
        match self {
            Self::Fraction(f) => f,
            Self::Named(name) => name.fraction(),
        }
    }

    /// The value as typed, for messages.
    pub fn typed(self) -> String {
        match self {
            Self::Fraction(f) => f.to_string(),
            Self::Named(name) => format!("\"{}\"", name.name()),
        }
    }
}

impl<'de> Deserialize<'de> for Coverage {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = Coverage;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(
                    "a fraction of the sky in [0, 1] or one of \"clear\", \"few\", \
                     \"scattered\", \"broken\", \"overcast\"",
                )
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<Coverage, E> {
                Ok(Coverage::Fraction(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Coverage, E> {
                Ok(Coverage::Fraction(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Coverage, E> {
                Ok(Coverage::Fraction(v as f64))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Coverage, E> {
                CoverageName::ALL
                    .into_iter()
                    .find(|name| name.name() == v)
                    .map(Coverage::Named)
                    .ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(v), &self))
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}
