//! Storage encodings of horizon angles: how many bits an angle keeps.
//!
//! A horizon angle `a ∈ [−π/2, π/2]` (radians) is stored either as `f32` (unchanged,
//! 4 bytes) or as a **unorm** integer of `b` bits (`b = 8` or `16`), exactly as a
//! texture channel holds it:
//!
//! ```text
//! encode:  q = round( (a + π/2) / π · (2^b − 1) )          (round half away from zero)
//! decode:  a' = decode_horizon_angle(q / (2^b − 1)) = (q / (2^b − 1)) · π − π/2
//! ```
//!
//! The normalisation `(a + π/2)/π` is [`crate::encode_horizon_angle`] (computed in
//! `f64`), so the east/west RGBA PNGs ([`crate::NormalMap::to_rgba_png`]) hold the same
//! integers. The decode is what a shader does after sampling a unorm texture: the
//! hardware returns `q / (2^b − 1)` and [`crate::twins::decode_horizon_angle`] (WGSL
//! twin in `terrain::shadow`) maps it back. The round trip is off by at most half a
//! step, `π / (2 (2^b − 1))`: 6.2e−3 rad (0.36°) for 8 bits, more than the sun's
//! angular radius (4.65e−3 rad); 2.4e−5 rad for 16 bits (plus `f32` rounding of the
//! decode, ≤ 3e−7 rad).

use crate::TerrainError;
use crate::shadow::decode_horizon_angle;

/// How a horizon angle is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HorizonEncoding {
    /// 8-bit unorm (an `Rgba8Unorm` alpha channel): 1 byte.
    Unorm8,
    /// 16-bit unorm (an `Rgba16Unorm` alpha channel or a 16-bit PNG): 2 bytes.
    Unorm16,
    /// `f32` radians, unquantised: 4 bytes.
    F32,
}

impl HorizonEncoding {
    /// All encodings, smallest first.
    pub const ALL: [HorizonEncoding; 3] = [Self::Unorm8, Self::Unorm16, Self::F32];

    /// Bytes per stored angle.
    pub fn bytes(self) -> usize {
        match self {
            Self::Unorm8 => 1,
            Self::Unorm16 => 2,
            Self::F32 => 4,
        }
    }

    /// Short name (`u8`, `u16`, `f32`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Unorm8 => "u8",
            Self::Unorm16 => "u16",
            Self::F32 => "f32",
        }
    }

    /// The angle after storing and loading it in this encoding. Every encoding
    /// rejects what [`crate::encode_horizon_angle`] rejects (NaN, beyond ±π/2), `F32`
    /// included, so the choice of encoding never decides whether bad data passes.
    pub fn round_trip(self, angle: f32) -> Result<f32, TerrainError> {
        Ok(match self {
            Self::Unorm8 => decode_horizon_unorm8(encode_horizon_unorm8(angle)?),
            Self::Unorm16 => decode_horizon_unorm16(encode_horizon_unorm16(angle)?),
            Self::F32 => {
                crate::encode_horizon_angle(angle)?;
                angle
            }
        })
    }

    /// Largest quantisation error of [`HorizonEncoding::round_trip`], radians (half a
    /// step; 0 for `f32`, whose decode is the identity).
    pub fn max_quantisation_error(self) -> f64 {
        match self {
            Self::Unorm8 => std::f64::consts::PI / (2.0 * 255.0),
            Self::Unorm16 => std::f64::consts::PI / (2.0 * 65535.0),
            Self::F32 => 0.0,
        }
    }
}

/// `round((angle + π/2)/π · 255)`; NaN and angles outside `[−π/2, π/2]` (which no
/// bake produces) are [`TerrainError::HorizonAngle`], as in
/// [`crate::encode_horizon_angle`].
pub fn encode_horizon_unorm8(angle: f32) -> Result<u8, TerrainError> {
    Ok((crate::encode_horizon_angle(angle)? * 255.0).round() as u8)
}

/// `round((angle + π/2)/π · 65535)`, rejecting what [`encode_horizon_unorm8`] rejects.
pub fn encode_horizon_unorm16(angle: f32) -> Result<u16, TerrainError> {
    Ok((crate::encode_horizon_angle(angle)? * 65535.0).round() as u16)
}

/// `decode_horizon_angle(q / 255)`: what a shader gets from an 8-bit unorm texel.
pub fn decode_horizon_unorm8(q: u8) -> f32 {
    decode_horizon_angle(f32::from(q) / 255.0)
}

/// `decode_horizon_angle(q / 65535)`: what a shader gets from a 16-bit unorm texel.
pub fn decode_horizon_unorm16(q: u16) -> f32 {
    decode_horizon_angle(f32::from(q) / 65535.0)
}
