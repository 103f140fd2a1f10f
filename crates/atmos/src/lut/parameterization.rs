//! Texture parameterisations of the LUTs: how (r, μ, …) map to texture coordinates
//! and back. Twin of `shaders/atmos/lut_parameterization.wgsl` (same names, argument
//! order and units: metres, cosines).
//!
//! * Texel-centre mapping (Bruneton 2017): a unit-range coordinate x ∈ [0, 1] lands on
//!   the centres of the first (x = 0) and last (x = 1) texels, so the LUT holds values
//!   at the domain's ends instead of extrapolating half a texel past them.
//! * Transmittance (Bruneton 2017 §4.1): v = ρ/H (ρ the distance to the horizon,
//!   H its value at the top) and u = (d − d_min)/(d_max − d_min) (d the distance to the
//!   top boundary): rays that see the horizon map to u = 1, so resolution follows the
//!   optical depth, which varies fastest near the horizon.
//! * Multiple scattering (Hillaire 2020 §5.5): linear in μ_s and altitude.
//! * Sky view (Hillaire 2020 §5.3): the view zenith angle is mapped quadratically
//!   around the horizon (v = ½ exactly at the horizon of the viewer's altitude) and the
//!   azimuth relative to the sun as sin(φ/2), concentrating texels at the horizon and
//!   near the sun.

use crate::geometry::ray_sphere_intersect;
use skyscape_wgsl::common::PI;

/// x ∈ [0, 1] → texture coordinate whose 0 and 1 are the first and last texel centres.
pub fn unit_range_to_texel_uv(x: f32, texel_count: u32) -> f32 {
    let n = texel_count as f32;
    0.5 / n + x * (1.0 - 1.0 / n)
}

/// Inverse of [`unit_range_to_texel_uv`].
pub fn texel_uv_to_unit_range(u: f32, texel_count: u32) -> f32 {
    let n = texel_count as f32;
    (u - 0.5 / n) / (1.0 - 1.0 / n)
}

/// √((a − b)(a + b)) for a ≥ b ≥ 0 (0 otherwise): a horizon distance without the
/// cancellation of a² − b² at Earth radii.
pub fn horizon_distance(a: f32, b: f32) -> f32 {
    ((a - b) * (a + b)).max(0.0).sqrt()
}

/// Transmittance LUT coordinates of a ray from radius `r` (clamped to
/// [planet_radius, top_radius], the LUT's domain) with zenith cosine `mu`.
pub fn transmittance_lut_uv(
    r: f32,
    mu: f32,
    planet_radius: f32,
    top_radius: f32,
    width: u32,
    height: u32,
) -> [f32; 2] {
    let r = r.clamp(planet_radius, top_radius);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = horizon_distance(r, planet_radius);
    // Distance to the top boundary (the far root: the origin is inside the shell).
    let d = ray_sphere_intersect(r, mu, top_radius)[1].max(0.0);
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let x_mu = ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0);
    let x_r = rho / top_horizon;
    [
        unit_range_to_texel_uv(x_mu, width),
        unit_range_to_texel_uv(x_r, height),
    ]
}

/// Inverse of [`transmittance_lut_uv`]: `[r, mu]` of a texture coordinate.
pub fn transmittance_lut_r_mu(
    uv: [f32; 2],
    planet_radius: f32,
    top_radius: f32,
    width: u32,
    height: u32,
) -> [f32; 2] {
    let x_mu = texel_uv_to_unit_range(uv[0], width).clamp(0.0, 1.0);
    let x_r = texel_uv_to_unit_range(uv[1], height).clamp(0.0, 1.0);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = top_horizon * x_r;
    let r = (rho * rho + planet_radius * planet_radius).sqrt();
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let d = d_min + x_mu * (d_max - d_min);
    // Law of cosines: top² = r² + d² + 2 r d μ, with top² − r² = H² − ρ².
    let mu = if d == 0.0 {
        1.0
    } else {
        ((top_horizon - rho) * (top_horizon + rho) - d * d) / (2.0 * r * d)
    };
    [r, mu.clamp(-1.0, 1.0)]
}

/// Multiple-scattering LUT coordinates of (altitude via `r`, sun zenith cosine `mu_s`).
pub fn multiple_scattering_lut_uv(
    r: f32,
    mu_s: f32,
    planet_radius: f32,
    top_radius: f32,
    width: u32,
    height: u32,
) -> [f32; 2] {
    let x_mu_s = (mu_s * 0.5 + 0.5).clamp(0.0, 1.0);
    let x_r = ((r - planet_radius) / (top_radius - planet_radius)).clamp(0.0, 1.0);
    [
        unit_range_to_texel_uv(x_mu_s, width),
        unit_range_to_texel_uv(x_r, height),
    ]
}

/// Inverse of [`multiple_scattering_lut_uv`]: `[r, mu_s]`.
pub fn multiple_scattering_lut_r_mu_s(
    uv: [f32; 2],
    planet_radius: f32,
    top_radius: f32,
    width: u32,
    height: u32,
) -> [f32; 2] {
    let x_mu_s = texel_uv_to_unit_range(uv[0], width).clamp(0.0, 1.0);
    let x_r = texel_uv_to_unit_range(uv[1], height).clamp(0.0, 1.0);
    [
        planet_radius + x_r * (top_radius - planet_radius),
        x_mu_s * 2.0 - 1.0,
    ]
}

/// Zenith angle (rad) of the horizon seen from radius `r` ≥ planet_radius:
/// atan2(R, −ρ) ∈ [π/2, π).
pub fn horizon_zenith_angle(r: f32, planet_radius: f32) -> f32 {
    let r = r.max(planet_radius);
    planet_radius.atan2(-horizon_distance(r, planet_radius))
}

/// Sky-view LUT coordinates of a view direction (zenith cosine `mu`, cosine of the
/// azimuth from the sun's vertical plane `cos_azimuth`) seen from radius `r`.
pub fn sky_view_lut_uv(
    r: f32,
    mu: f32,
    cos_azimuth: f32,
    planet_radius: f32,
    width: u32,
    height: u32,
) -> [f32; 2] {
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt().atan2(mu);
    let y = if zenith_angle < horizon {
        // Sky: quadratic towards the horizon (v = 0 zenith, v = ½ horizon).
        let coord = 1.0 - (1.0 - zenith_angle / horizon).max(0.0).sqrt();
        0.5 * coord
    } else {
        // Ground: quadratic away from the horizon (v = 1 nadir).
        let coord = ((zenith_angle - horizon) / (PI - horizon)).max(0.0).sqrt();
        0.5 + 0.5 * coord.min(1.0)
    };
    // sin(φ/2): fine near the sun (φ = 0), coarse opposite it.
    let x = (0.5 - 0.5 * cos_azimuth).max(0.0).sqrt().min(1.0);
    [
        unit_range_to_texel_uv(x, width),
        unit_range_to_texel_uv(y, height),
    ]
}

/// Inverse of [`sky_view_lut_uv`]: `[mu, cos_azimuth]` of a texture coordinate.
pub fn sky_view_lut_direction(
    uv: [f32; 2],
    r: f32,
    planet_radius: f32,
    width: u32,
    height: u32,
) -> [f32; 2] {
    let x = texel_uv_to_unit_range(uv[0], width).clamp(0.0, 1.0);
    let y = texel_uv_to_unit_range(uv[1], height).clamp(0.0, 1.0);
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = if y < 0.5 {
        let coord = 1.0 - 2.0 * y;
        horizon * (1.0 - coord * coord)
    } else {
        let coord = 2.0 * y - 1.0;
        horizon + (PI - horizon) * coord * coord
    };
    [zenith_angle.cos(), 1.0 - 2.0 * x * x]
}

/// Cosine of the azimuth between the view and the sun around the local zenith, from
/// the three cosines (1 when either direction is vertical: the azimuth is then moot).
pub fn view_sun_cos_azimuth(mu: f32, mu_s: f32, nu: f32) -> f32 {
    let denominator = ((1.0 - mu) * (1.0 + mu) * (1.0 - mu_s) * (1.0 + mu_s))
        .max(0.0)
        .sqrt();
    if denominator < 1e-6 {
        return 1.0;
    }
    ((nu - mu * mu_s) / denominator).clamp(-1.0, 1.0)
}

/// Where bilinear interpolation reads: the four texels (x0/x1 columns, y0/y1 rows) and
/// the weights of x1 and y1. Texel i's centre is at uv (i + ½)/n; coordinates are
/// clamped to the texel centres of columns [0, width − 1] and rows
/// [first_row, last_row] (the sky-view lookup keeps sky and ground rows apart).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BilinearFootprint {
    /// Left column.
    pub x0: u32,
    /// Top row.
    pub y0: u32,
    /// Right column (x0 + 1, or x0 at the edge).
    pub x1: u32,
    /// Bottom row.
    pub y1: u32,
    /// Weight of column x1.
    pub fx: f32,
    /// Weight of row y1.
    pub fy: f32,
}

/// The bilinear footprint of `uv` in a `width × height` LUT (rows limited to
/// `first_row..=last_row`).
pub fn bilinear_footprint(
    uv: [f32; 2],
    width: u32,
    height: u32,
    first_row: u32,
    last_row: u32,
) -> BilinearFootprint {
    let x = (uv[0] * width as f32 - 0.5).clamp(0.0, (width - 1) as f32);
    let y = (uv[1] * height as f32 - 0.5).clamp(first_row as f32, last_row as f32);
    // x, y ≥ 0 after the clamps, where truncation is floor (WGSL's `floor`): a
    // conversion instead of a libm call on CPUs without SSE4.1's round instruction
    // (a tenth of a sky-view lookup's cost).
    let x0 = x as u32;
    let y0 = y as u32;
    BilinearFootprint {
        x0,
        y0,
        x1: (x0 + 1).min(width - 1),
        y1: (y0 + 1).min(last_row),
        fx: x - x0 as f32,
        fy: y - y0 as f32,
    }
}
