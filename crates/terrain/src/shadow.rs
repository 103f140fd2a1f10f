//! Shadow queries and the terrain shading term (Hoffman & Preetham 2002): `f32` twins of
//! `shaders/terrain/shadow.wgsl` and `shaders/terrain/shading.wgsl` (same names,
//! argument order and units). The twins only `cargo xtask parity` calls on their own
//! (the horizon decode, the hard shadow, the disc's visible fraction) and their `f64`
//! references are in [`crate::twins`].
//!
//! Directions are unit vectors in the local east–north–up frame (`x` east, `y`
//! north, `z` up), pointing *towards* the sun; angles are radians; azimuths are
//! clockwise from north (east `π/2`).

use glam::Vec3;

use crate::TerrainError;
use skyscape_wgsl::common::{PI, TAU};

/// Angular radius of the sun's disc, radians (`SUN_ANGULAR_RADIUS` in WGSL): the mean
/// value, IAU nominal solar radius over one astronomical unit (0.2664°), the same as
/// `atmos::SUN_ANGULAR_RADIUS` (terrain does not depend on atmos). A default for
/// standalone use: a compositor passes its atmosphere's (or the date's) radius to the
/// functions that take one.
pub const SUN_ANGULAR_RADIUS: f32 = 0.004_650_467;

/// Decodes a horizon angle from a unorm alpha value in `[0, 1]` (as sampled from an
/// 8- or 16-bit texture): `alpha · π − π/2`. Inverse of
/// [`crate::encode_horizon_angle`].
#[doc(hidden)]
pub fn decode_horizon_angle(alpha: f32) -> f32 {
    alpha * PI - 0.5 * PI
}

/// 1 when the sun's centre is above the horizon angle, else 0.
#[doc(hidden)]
pub fn hard_shadow(sun_elevation: f32, horizon_angle: f32) -> f32 {
    if sun_elevation > horizon_angle {
        1.0
    } else {
        0.0
    }
}

/// Visible fraction of a disc whose centre is `x` radii above a horizontal line
/// (`x ≥ 1` → 1, `x ≤ −1` → 0, `x = 0` → ½).
///
/// Exact circular-segment area: the smaller piece cut off at distance `a = |x|` from
/// the centre has the area fraction `(θ − a·sqrt(1 − a²)) / π`, `θ = acos(a)` the half
/// central angle. `θ` is computed as `atan2(sqrt((1 − a)(1 + a)), a)` (no loss near
/// `a = 1`, where `1 − a` is exact), and when the segment is thin (`u = 2θ < 0.5`) the
/// area uses the series of `(u − sin u)/2` instead, so there is no cancellation. The
/// only transcendental is `atan2`: WGSL allows `sin` an absolute error of 2⁻¹¹, and
/// lavapipe's `asin` was measured 1.4e-4 off in this formula, both far too coarse.
#[doc(hidden)]
pub fn sun_disc_visible_fraction(x: f32) -> f32 {
    let a = x.abs().min(1.0);
    let root = ((1.0 - a) * (1.0 + a)).sqrt();
    let theta = root.atan2(a);
    let u = 2.0 * theta;
    let twice_area = if u < 0.5 {
        let u2 = u * u;
        u * u2 * (1.0 / 6.0 - u2 * (1.0 / 120.0 - u2 * (1.0 / 5040.0 - u2 * (1.0 / 362_880.0))))
    } else {
        2.0 * (theta - a * root)
    };
    let segment = twice_area * (0.5 / PI);
    if x >= 0.0 { 1.0 - segment } else { segment }
}

/// Visible fraction of the sun's disc (angular radius `sun_angular_radius`) above a
/// horizon at `horizon_angle`, with the sun's centre at `sun_elevation` (radians).
/// A radius `≤ 0` (or NaN) gives the hard shadow.
pub fn soft_shadow(sun_elevation: f32, horizon_angle: f32, sun_angular_radius: f32) -> f32 {
    if sun_angular_radius > 0.0 {
        sun_disc_visible_fraction((sun_elevation - horizon_angle) / sun_angular_radius)
    } else {
        hard_shadow(sun_elevation, horizon_angle)
    }
}

/// Elevation of a direction above the horizontal plane, radians
/// (`atan2(z, |xy|)`; accurate near the horizon, unlike `asin(z)`).
pub fn sun_elevation(sun_direction: Vec3) -> f32 {
    sun_direction
        .z
        .atan2((sun_direction.x * sun_direction.x + sun_direction.y * sun_direction.y).sqrt())
}

/// Azimuth of a direction, radians clockwise from north, in `[0, 2π)`.
pub fn sun_azimuth(sun_direction: Vec3) -> f32 {
    let a = sun_direction.x.atan2(sun_direction.y);
    if a < 0.0 { a + TAU } else { a }
}

/// The two layers of an `N`-azimuth horizon stack around an azimuth, and the weight
/// of the upper one (`WGSL struct AzimuthLayers`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AzimuthLayers {
    /// Layer at or just below the azimuth.
    pub lower: u32,
    /// The next layer (wrapping to 0).
    pub upper: u32,
    /// Interpolation weight of `upper`, in `[0, 1)`.
    pub weight: f32,
}

/// Layers `k = floor(f)` and `k + 1 (mod N)`, weight `fract(f)`, with
/// `f = azimuth / 2π · N` wrapped into `[0, N)`; layer `k` is at `k · 2π / N`.
///
/// Errors ([`TerrainError`]) when `count` is 0 (there is no layer to pick) or
/// `sun_azimuth` is not finite (the weight would be NaN). The WGSL twin assumes both
/// were checked on the CPU.
pub fn azimuth_layers(sun_azimuth: f32, count: u32) -> Result<AzimuthLayers, TerrainError> {
    if count == 0 {
        return Err(TerrainError::param(
            "count",
            0.0,
            "must be >= 1 (the number of horizon layers)",
        ));
    }
    if !sun_azimuth.is_finite() {
        return Err(TerrainError::param(
            "sun_azimuth",
            f64::from(sun_azimuth),
            "must be finite (radians clockwise from north)",
        ));
    }
    let n = count as f32;
    let f0 = sun_azimuth / TAU * n;
    let f = f0 - (f0 / n).floor() * n;
    let k = f.floor();
    let lower = (k as u32) % count;
    Ok(AzimuthLayers {
        lower,
        upper: (lower + 1) % count,
        weight: f - k,
    })
}

/// Self-shadow from the east/west pair of horizon maps: the east horizon while the sun is in the
/// east (`x ≥ 0`), the west one otherwise, then [`soft_shadow`] against the sun's
/// true elevation.
pub fn self_shadow_east_west(
    horizon_east: f32,
    horizon_west: f32,
    sun_direction: Vec3,
    sun_angular_radius: f32,
) -> f32 {
    let horizon = if sun_direction.x >= 0.0 {
        horizon_east
    } else {
        horizon_west
    };
    soft_shadow(sun_elevation(sun_direction), horizon, sun_angular_radius)
}

/// The surface term of Hoffman & Preetham 2002, `(N·L) · albedo · self_shadow · cloud_shadow`, with
/// `N·L` clamped at 0 (`normal` and `sun_direction` unit, same frame).
pub fn terrain_shading(
    normal: Vec3,
    sun_direction: Vec3,
    albedo: Vec3,
    self_shadow: f32,
    cloud_shadow: f32,
) -> Vec3 {
    let k = normal.dot(sun_direction).max(0.0) * self_shadow * cloud_shadow;
    albedo * k
}

/// `f64` references (parity's, re-exported from [`crate::twins`]).
#[doc(hidden)]
pub mod reference {
    /// Visible fraction of a disc whose centre is `x` radii above a line:
    /// `1/2 + (asin x + x·sqrt(1 − x²)) / π` (clamped outside `[-1, 1]`).
    pub fn sun_disc_visible_fraction_f64(x: f64) -> f64 {
        if x >= 1.0 {
            1.0
        } else if x <= -1.0 {
            0.0
        } else {
            0.5 + (x.asin() + x * (1.0 - x * x).sqrt()) / std::f64::consts::PI
        }
    }

    /// [`super::soft_shadow`] in `f64`.
    pub fn soft_shadow_f64(sun_elevation: f64, horizon_angle: f64, sun_angular_radius: f64) -> f64 {
        if sun_angular_radius > 0.0 {
            sun_disc_visible_fraction_f64((sun_elevation - horizon_angle) / sun_angular_radius)
        } else if sun_elevation > horizon_angle {
            1.0
        } else {
            0.0
        }
    }
}
