//! Texture parameterisations of the LUTs: how (r, μ, …) map to texture coordinates
//! and back. Twin of `shaders/atmos/lut_parameterization.wgsl` (same names, argument
//! order and units: metres, cosines). Each mapping is written once, generic over
//! [`Real`]: the f32 instantiation mirrors the WGSL operation for operation, the f64
//! one is the reference `cargo xtask parity` compares both with
//! ([`super::reference`] re-exports them).
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
use crate::real::{Real, count};

/// x ∈ [0, 1] → texture coordinate whose 0 and 1 are the first and last texel centres.
pub fn unit_range_to_texel_uv<F: Real>(x: F, texel_count: u32) -> F {
    let n = count::<F>(texel_count);
    F::of(0.5) / n + x * (F::one() - F::one() / n)
}

/// Inverse of [`unit_range_to_texel_uv`].
pub fn texel_uv_to_unit_range<F: Real>(u: F, texel_count: u32) -> F {
    let n = count::<F>(texel_count);
    (u - F::of(0.5) / n) / (F::one() - F::one() / n)
}

/// √((a − b)(a + b)) for a ≥ b ≥ 0 (0 otherwise): a horizon distance without the
/// cancellation of a² − b² at Earth radii.
pub fn horizon_distance<F: Real>(a: F, b: F) -> F {
    ((a - b) * (a + b)).max(F::zero()).sqrt()
}

/// Transmittance LUT coordinates of a ray from radius `r` (clamped to
/// [planet_radius, top_radius], the LUT's domain) with zenith cosine `mu`.
pub fn transmittance_lut_uv<F: Real>(
    r: F,
    mu: F,
    planet_radius: F,
    top_radius: F,
    width: u32,
    height: u32,
) -> [F; 2] {
    let r = r.clamp(planet_radius, top_radius);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = horizon_distance(r, planet_radius);
    // Distance to the top boundary (the far root: the origin is inside the shell).
    let d = ray_sphere_intersect(r, mu, top_radius)[1].max(F::zero());
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let x_mu = ((d - d_min) / (d_max - d_min)).clamp(F::zero(), F::one());
    let x_r = rho / top_horizon;
    [
        unit_range_to_texel_uv(x_mu, width),
        unit_range_to_texel_uv(x_r, height),
    ]
}

/// Inverse of [`transmittance_lut_uv`]: `[r, mu]` of a texture coordinate.
pub fn transmittance_lut_r_mu<F: Real>(
    uv: [F; 2],
    planet_radius: F,
    top_radius: F,
    width: u32,
    height: u32,
) -> [F; 2] {
    let x_mu = texel_uv_to_unit_range(uv[0], width).clamp(F::zero(), F::one());
    let x_r = texel_uv_to_unit_range(uv[1], height).clamp(F::zero(), F::one());
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = top_horizon * x_r;
    let r = (rho * rho + planet_radius * planet_radius).sqrt();
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let d = d_min + x_mu * (d_max - d_min);
    // Law of cosines: top² = r² + d² + 2 r d μ, with top² − r² = H² − ρ².
    let mu = if d == F::zero() {
        F::one()
    } else {
        ((top_horizon - rho) * (top_horizon + rho) - d * d) / (F::of(2.0) * r * d)
    };
    [r, mu.clamp(-F::one(), F::one())]
}

/// Multiple-scattering LUT coordinates of (altitude via `r`, sun zenith cosine `mu_s`).
pub fn multiple_scattering_lut_uv<F: Real>(
    r: F,
    mu_s: F,
    planet_radius: F,
    top_radius: F,
    width: u32,
    height: u32,
) -> [F; 2] {
    let half = F::of(0.5);
    let x_mu_s = (mu_s * half + half).clamp(F::zero(), F::one());
    let x_r = ((r - planet_radius) / (top_radius - planet_radius)).clamp(F::zero(), F::one());
    [
        unit_range_to_texel_uv(x_mu_s, width),
        unit_range_to_texel_uv(x_r, height),
    ]
}

/// Inverse of [`multiple_scattering_lut_uv`]: `[r, mu_s]`.
pub fn multiple_scattering_lut_r_mu_s<F: Real>(
    uv: [F; 2],
    planet_radius: F,
    top_radius: F,
    width: u32,
    height: u32,
) -> [F; 2] {
    let x_mu_s = texel_uv_to_unit_range(uv[0], width).clamp(F::zero(), F::one());
    let x_r = texel_uv_to_unit_range(uv[1], height).clamp(F::zero(), F::one());
    [
        planet_radius + x_r * (top_radius - planet_radius),
        x_mu_s * F::of(2.0) - F::one(),
    ]
}

/// Zenith angle (rad) of the horizon seen from radius `r` ≥ planet_radius:
/// atan2(R, −ρ) ∈ [π/2, π).
pub fn horizon_zenith_angle<F: Real>(r: F, planet_radius: F) -> F {
    let r = r.max(planet_radius);
    planet_radius.atan2(-horizon_distance(r, planet_radius))
}

/// Sky-view LUT coordinates of a view direction (zenith cosine `mu`, cosine of the
/// azimuth from the sun's vertical plane `cos_azimuth`) seen from radius `r`.
pub fn sky_view_lut_uv<F: Real>(
    r: F,
    mu: F,
    cos_azimuth: F,
    planet_radius: F,
    width: u32,
    height: u32,
) -> [F; 2] {
    let (zero, one, half) = (F::zero(), F::one(), F::of(0.5));
    let pi = F::of(std::f64::consts::PI);
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = ((one - mu) * (one + mu)).max(zero).sqrt().atan2(mu);
    let y = if zenith_angle < horizon {
        // Sky: quadratic towards the horizon (v = 0 zenith, v = ½ horizon).
        let coord = one - (one - zenith_angle / horizon).max(zero).sqrt();
        half * coord
    } else {
        // Ground: quadratic away from the horizon (v = 1 nadir).
        let coord = ((zenith_angle - horizon) / (pi - horizon)).max(zero).sqrt();
        half + half * coord.min(one)
    };
    // sin(φ/2): fine near the sun (φ = 0), coarse opposite it.
    let x = (half - half * cos_azimuth).max(zero).sqrt().min(one);
    [
        unit_range_to_texel_uv(x, width),
        unit_range_to_texel_uv(y, height),
    ]
}

/// Inverse of [`sky_view_lut_uv`]: `[mu, cos_azimuth]` of a texture coordinate.
pub fn sky_view_lut_direction<F: Real>(
    uv: [F; 2],
    r: F,
    planet_radius: F,
    width: u32,
    height: u32,
) -> [F; 2] {
    let (zero, one, two) = (F::zero(), F::one(), F::of(2.0));
    let pi = F::of(std::f64::consts::PI);
    let x = texel_uv_to_unit_range(uv[0], width).clamp(zero, one);
    let y = texel_uv_to_unit_range(uv[1], height).clamp(zero, one);
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = if y < F::of(0.5) {
        let coord = one - two * y;
        horizon * (one - coord * coord)
    } else {
        let coord = two * y - one;
        horizon + (pi - horizon) * coord * coord
    };
    [zenith_angle.cos(), one - two * x * x]
}

/// Cosine of the azimuth between the view and the sun around the local zenith, from
/// the three cosines (1 when either direction is vertical: the azimuth is then moot).
pub fn view_sun_cos_azimuth<F: Real>(mu: F, mu_s: F, nu: F) -> F {
    let one = F::one();
    let denominator = ((one - mu) * (one + mu) * (one - mu_s) * (one + mu_s))
        .max(F::zero())
        .sqrt();
    if denominator < F::of(1e-6) {
        return one;
    }
    ((nu - mu * mu_s) / denominator).clamp(-one, one)
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
