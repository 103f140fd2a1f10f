//! The exact ray-cast horizon: the reference against which baked horizon maps are
//! measured (`cargo xtask tradeoff terrain`). `f64`, CPU only.
//!
//! # Definition
//!
//! The terrain surface is the **bilinear interpolation** of the texel heights, texel
//! `(i, j)` at map position `(x, y) = (i, j)` (texel units, `x` east, `y` rows south),
//! defined on `[0, W − 1] × [0, H − 1]`. From texel `P = (x₀, y₀)` a horizontal ray
//! along azimuth `φ` (clockwise from north) runs through `(x₀ + s·sin φ / L,
//! y₀ − s·cos φ / L)`, `s` in metres, `L` the spacing. Its horizon angle is
//!
//! ```text
//! ray_cast_horizon_angle(P, φ) = sup_{0 < s ≤ S} atan( (h(s) − h(P) − s²/(2R)) / s )
//! ```
//!
//! with `S` the distance to the edge of the domain or the maximum distance, whichever
//! is smaller, and `−π/2` when `S = 0` (`P` on an edge, facing out). Near `s = 0` the
//! quotient tends to the slope of the surface along `φ` (a texel on a slope steeper
//! than the sun shades itself). A sun of elevation `e` on azimuth `φ` lights `P`
//! (hard shadow, the sun's centre) exactly when `e` is above this angle: the ray
//! `P + s·(direction)` then stays above the surface for all `s ≤ S`.
//!
//! # Evaluation (exact, not sampled)
//!
//! The ray crosses the grid lines `x ∈ ℤ` and `y ∈ ℤ` at known `s`; between two
//! crossings it stays in one cell, where the bilinear height is a quadratic
//! `h(s) = a + b·s + c·s²`. The quotient `q(s) = (h(s) − h(P) − s²/(2R))/s` is then
//! `α/s + β + γ·s`, whose only interior extremum is at `s* = sqrt(α/γ)`. The supremum
//! is the largest of `q` at every crossing, at the end `S`, at each in-cell `s*`, and
//! the slope limit at `s → 0⁺`; each is evaluated from the bilinear surface directly
//! (the quadratic's coefficients only locate `s*`). Cost: O(W + H) per ray.

use crate::horizon::HorizonOptions;
use crate::{Heightfield, TerrainError};

/// Direction components below this (per metre, in texel units) are treated as 0, so
/// that the four axis azimuths run exactly along rows and columns (`cos(π/2)` is
/// 6e−17, not 0).
const AXIS_SNAP: f64 = 1e-15;

/// The exact horizon angle of texel `(x, y)` along `azimuth` over the bilinear
/// surface (definition in the [module docs](self)), radians in `[−π/2, π/2]`.
/// `options.threads` is ignored.
pub fn ray_cast_horizon_angle(
    hf: &Heightfield,
    x: usize,
    y: usize,
    azimuth: f64,
    options: &HorizonOptions,
) -> Result<f64, TerrainError> {
    options.validate()?;
    if !azimuth.is_finite() {
        return Err(TerrainError::param("azimuth", azimuth, "must be finite"));
    }
    if x >= hf.width() {
        return Err(TerrainError::param("x", x as f64, "must be < width"));
    }
    if y >= hf.height() {
        return Err(TerrainError::param("y", y as f64, "must be < height"));
    }
    let inv_two_r = options.inv_two_r();
    let spacing = hf.spacing();
    let snap = |v: f64| if v.abs() < AXIS_SNAP { 0.0 } else { v };
    // Texel units per metre along the ray.
    let (dx, dy) = (
        snap(azimuth.sin()) / spacing,
        snap(-azimuth.cos()) / spacing,
    );
    let (x0, y0) = (x as f64, y as f64);
    let (w_max, h_max) = ((hf.width() - 1) as f64, (hf.height() - 1) as f64);
    let exit = |p: f64, d: f64, hi: f64| {
        if d > 0.0 {
            (hi - p) / d
        } else if d < 0.0 {
            -p / d
        } else {
            f64::INFINITY
        }
    };
    let mut end = exit(x0, dx, w_max).min(exit(y0, dy, h_max));
    if let Some(d) = options.max_distance {
        end = end.min(d);
    }
    if end.is_nan() || end <= 0.0 {
        return Ok(-std::f64::consts::FRAC_PI_2);
    }
    let h_p = hf.elevation_at(x, y);
    let at = |s: f64| (x0 + dx * s, y0 + dy * s);
    let quotient = |s: f64| {
        let (px, py) = at(s);
        (hf.bilinear_elevation(px, py) - h_p - s * s * inv_two_r) / s
    };
    // Grid-line crossings: the next integer coordinate ahead on each axis.
    let first_line = |p: f64, d: f64| {
        if d > 0.0 {
            p.floor() + 1.0
        } else {
            p.ceil() - 1.0
        }
    };
    let (mut line_x, mut line_y) = (first_line(x0, dx), first_line(y0, dy));
    let step_x = dx.signum();
    let step_y = dy.signum();
    let crossing = |line: f64, p: f64, d: f64| {
        if d == 0.0 {
            f64::INFINITY
        } else {
            (line - p) / d
        }
    };
    let mut best = f64::NEG_INFINITY;
    let mut s_a = 0.0f64;
    loop {
        let (cx, cy) = (crossing(line_x, x0, dx), crossing(line_y, y0, dy));
        let s_b = cx.min(cy).min(end);
        // The cell of this segment, and the bilinear height along it as a + b t + c t²
        // (t = s − s_a) to locate the in-cell extremum of the quotient.
        let (mx, my) = at(0.5 * (s_a + s_b));
        let i = (mx.floor().max(0.0) as usize).min(hf.width().saturating_sub(2));
        let j = (my.floor().max(0.0) as usize).min(hf.height().saturating_sub(2));
        let (i1, j1) = ((i + 1).min(hf.width() - 1), (j + 1).min(hf.height() - 1));
        let h00 = hf.elevation_at(i, j);
        let e1 = hf.elevation_at(i1, j) - h00;
        let e2 = hf.elevation_at(i, j1) - h00;
        let e3 = hf.elevation_at(i1, j1) - h00 - e1 - e2;
        let (ax, ay) = at(s_a);
        let (fx, fy) = (ax - i as f64, ay - j as f64);
        let a0 = h00 + e1 * fx + e2 * fy + e3 * fx * fy;
        let a1 = e1 * dx + e2 * dy + e3 * (fx * dy + fy * dx);
        let a2 = e3 * dx * dy;
        if s_a == 0.0 {
            // Slope limit at s → 0⁺ (h(0) = h(P), so α = 0 and q is linear here).
            best = best.max(a1);
        } else {
            // In s: α/s + β + γ s.
            let alpha = a0 - a1 * s_a + a2 * s_a * s_a - h_p;
            let gamma = a2 - inv_two_r;
            if gamma != 0.0 {
                let ratio = alpha / gamma;
                if ratio > 0.0 {
                    let s_star = ratio.sqrt();
                    if s_star > s_a && s_star < s_b {
                        best = best.max(quotient(s_star));
                    }
                }
            }
        }
        best = best.max(quotient(s_b));
        if s_b >= end {
            break;
        }
        if cx <= s_b {
            line_x += step_x;
        }
        if cy <= s_b {
            line_y += step_y;
        }
        s_a = s_b;
    }
    Ok(best.atan())
}

/// Hard shadow of the sun's centre by the ray-cast horizon: 1 (lit) when
/// `sun_elevation > ray_cast_horizon_angle(…, sun_azimuth, …)`, else 0.
pub fn ray_cast_hard_shadow(
    hf: &Heightfield,
    x: usize,
    y: usize,
    sun_azimuth: f64,
    sun_elevation: f64,
    options: &HorizonOptions,
) -> Result<f64, TerrainError> {
    if !sun_elevation.is_finite() {
        return Err(TerrainError::param(
            "sun_elevation",
            sun_elevation,
            "must be finite",
        ));
    }
    let horizon = ray_cast_horizon_angle(hf, x, y, sun_azimuth, options)?;
    Ok(if sun_elevation > horizon { 1.0 } else { 0.0 })
}
