//! Variant (c): the east and west horizons measured in the **tilted plane of the sun's
//! daily path**.
//!
//! # Definition
//!
//! At latitude `φ` (radians, north positive) the sun's daily path (at the equinox) is
//! a great circle in the plane that contains the east–west axis and is tilted from
//! the vertical toward the equator by `φ`. Through texel `P` that plane is spanned by
//! `E = (1, 0, 0)` (east) and `U' = (0, −sin φ, cos φ)` (east–north–up: up, tilted
//! south for `φ > 0`, north for `φ < 0`). A direction of the plane makes the **in-plane
//! angle** `θ` with `E` (or `−E` for the west side): `cos θ · (±E) + sin θ · U'`. The
//! sun lights `P` when its in-plane angle is above the tilted horizon `θ_h(P)`; at
//! `φ = 0` the plane is vertical and `θ_h` is the ordinary east/west horizon angle of
//! [`crate::horizon`] (variant (a)), bit for bit.
//!
//! **Sampling.** The plane cuts each map column `x = x_P ± k` (`k = 1, 2, …`, `a = k·L`
//! metres away along the east–west axis) along a straight line rising toward the
//! equator. For a texel `Q` of that column, `r` rows from `P` toward the equator
//! (negative: away from it), with `Δh = h(Q) − h(P) − d²/(2R)` (`d` the horizontal
//! distance `P→Q`, curvature as in [`crate::horizon`]), its coordinates in the plane are
//!
//! ```text
//! b = r·L·sin|φ| + Δh·cos|φ|     (along U')
//! c = r·L·cos|φ| − Δh·sin|φ|     (out of the plane: c ≤ 0 ⇔ Q is on or above it)
//! ```
//!
//! The column is treated as a piecewise-linear profile through its texels. The ray of
//! in-plane angle `θ` crosses the column at `b = a·tan θ`, and is blocked there while
//! the profile is above the plane's line; the column's occluding height is the `b` of
//! the **last** crossing from above to below, walking toward the equator: the texel
//! `j`, the last with `c_j ≤ 0`, and its successor (`c > 0`) interpolated linearly to
//! `c = 0`, i.e. `b = b_j + λ (b_{j+1} − b_j)` with `λ = c_j / (c_j − c_{j+1})`
//! (`b = b_j` when `j` is the map edge). Columns entirely below the plane's line
//! within the map occlude nothing. Then
//!
//! ```text
//! θ_h(P) = max_k atan(b_k / a_k)        (−π/2 when no column occludes)
//! ```
//!
//! over `k` up to the map edge and, with a maximum distance `D`, `k·L ≤ D` (the same
//! `K` as variant (a)). At `φ = 0`, `c_j = r·L` and the crossing is `Q = P`'s row
//! (`λ = 0`), so `b = Δh`: the east/west horizon.
//!
//! # Why brute force only
//!
//! The hull sweep of Timonen & Westerholm needs one fixed set of points per line,
//! shared by every `P` on it. Here the point that column `k` contributes depends on
//! `h(P)` (the plane's line through `P` cuts the column at a height-dependent row), so
//! the points differ from texel to texel of a row and no hull can be reused. The bake
//! scans, per texel and column, only the rows where the column can reach the plane (the
//! column's maximum toward the equator bounds `r ≤ Δh_max·tan|φ|/L`): cost
//! O(W · (1 + relief·tan|φ|/L)) per texel.

use std::num::NonZeroUsize;

use crate::horizon::{EAST, EastWestHorizon, HorizonMap, HorizonOptions, NO_HORIZON, WEST};
use crate::{Heightfield, TerrainError};

/// Which half of the plane: looking east or west along the east–west axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Toward `+x` (morning sun).
    East,
    /// Toward `−x` (afternoon sun).
    West,
}

/// The heightfield reordered so that row index increases toward the equator, with
/// the per-column maximum of every suffix (rows at or beyond a row, toward the equator).
struct TiltedGrid<'a> {
    hf: &'a Heightfield,
    toward_south: bool,
    /// `suffix_max[j' · W + x]`: highest elevation of column `x` over rows `j' ..` in
    /// equator-ward order.
    suffix_max: Vec<f64>,
}

impl<'a> TiltedGrid<'a> {
    fn new(hf: &'a Heightfield, latitude: f64) -> Self {
        let (w, h) = (hf.width(), hf.height());
        let toward_south = latitude >= 0.0;
        let mut suffix_max = vec![f64::NEG_INFINITY; w * h];
        for jp in (0..h).rev() {
            for x in 0..w {
                let here = hf.elevation_at(x, Self::row_of(toward_south, h, jp));
                let next = if jp + 1 < h {
                    suffix_max[(jp + 1) * w + x]
                } else {
                    f64::NEG_INFINITY
                };
                suffix_max[jp * w + x] = here.max(next);
            }
        }
        Self {
            hf,
            toward_south,
            suffix_max,
        }
    }

    fn row_of(toward_south: bool, height: usize, jp: usize) -> usize {
        if toward_south { jp } else { height - 1 - jp }
    }
}

/// Per-bake constants.
struct Plane {
    sin: f64,
    cos: f64,
    tan: f64,
    spacing: f64,
    inv_two_r: f64,
    max_steps: usize,
}

fn check_latitude(latitude: f64) -> Result<(), TerrainError> {
    if !(latitude.is_finite() && latitude.abs() < std::f64::consts::FRAC_PI_2) {
        return Err(TerrainError::param(
            "latitude",
            latitude,
            "must be finite and strictly between -pi/2 and pi/2 radians",
        ));
    }
    Ok(())
}

fn plane(hf: &Heightfield, latitude: f64, options: &HorizonOptions) -> Plane {
    let phi = latitude.abs();
    Plane {
        sin: phi.sin(),
        cos: phi.cos(),
        tan: phi.tan(),
        spacing: hf.spacing(),
        inv_two_r: options.inv_two_r(),
        max_steps: crate::horizon::max_steps_for(hf.spacing(), options.max_distance),
    }
}

/// The tilted horizon of one texel, `(x, jp)` with `jp` in equator-ward row order.
fn texel(grid: &TiltedGrid<'_>, p: &Plane, x: usize, jp: usize, side: Side) -> f32 {
    let hf = grid.hf;
    let (w, h) = (hf.width(), hf.height());
    let row = |jp: usize| TiltedGrid::row_of(grid.toward_south, h, jp);
    let h_p = hf.elevation_at(x, row(jp));
    let columns = match side {
        Side::East => w - 1 - x,
        Side::West => x,
    };
    let far = (h - 1 - jp) as i64; // rows ahead toward the equator
    let near = jp as i64; // rows behind
    let mut best = f64::NEG_INFINITY;
    for k in 1..=columns.min(p.max_steps) {
        let col = match side {
            Side::East => x + k,
            Side::West => x - k,
        };
        let a = k as f64 * p.spacing;
        // (b, c) of the column's texel r rows toward the equator.
        let point = |r: i64| {
            let q = hf.elevation_at(col, row((jp as i64 + r) as usize));
            let lateral = r as f64 * p.spacing;
            let dh = q - h_p - (a * a + lateral * lateral) * p.inv_two_r;
            (lateral * p.sin + dh * p.cos, lateral * p.cos - dh * p.sin)
        };
        // Beyond `start` the column cannot reach the plane's line (c > 0).
        let rise = grid.suffix_max[jp * w + col] - h_p;
        let bound = if rise > 0.0 {
            (rise * p.tan / p.spacing).floor() + 2.0
        } else {
            1.0
        };
        let start = if bound >= far as f64 {
            far
        } else {
            bound as i64
        };
        let mut r = start;
        let mut after: Option<(f64, f64)> = None; // (b, c) of r + 1, when inside the map
        let mut found = None;
        while r >= -near {
            let (b, c) = point(r);
            if c <= 0.0 {
                found = Some((b, c));
                break;
            }
            after = Some((b, c));
            r -= 1;
        }
        let Some((b_j, c_j)) = found else { continue };
        let b = if r == far {
            b_j
        } else {
            let (b_next, c_next) = after.unwrap_or_else(|| point(r + 1));
            let lambda = c_j / (c_j - c_next);
            b_j + lambda * (b_next - b_j)
        };
        best = best.max(b / a);
    }
    if best == f64::NEG_INFINITY {
        NO_HORIZON
    } else {
        best.atan() as f32
    }
}

/// The tilted-plane horizon (in-plane angle, radians) of texel `(x, y)` at `latitude`.
pub fn tilted_horizon_angle(
    hf: &Heightfield,
    x: usize,
    y: usize,
    side: Side,
    latitude: f64,
    options: &HorizonOptions,
) -> Result<f32, TerrainError> {
    options.validate()?;
    check_latitude(latitude)?;
    if x >= hf.width() {
        return Err(TerrainError::param("x", x as f64, "must be < width"));
    }
    if y >= hf.height() {
        return Err(TerrainError::param("y", y as f64, "must be < height"));
    }
    let grid = TiltedGrid::new(hf, latitude);
    let jp = TiltedGrid::row_of(grid.toward_south, hf.height(), y);
    Ok(texel(&grid, &plane(hf, latitude, options), x, jp, side))
}

/// Bakes the east and west maps measured in the tilted plane of the sun's path at
/// `latitude` (radians, `|latitude| < π/2`). Brute force (see the module docs for why
/// the hull sweep does not apply); rows are split over `options.threads`.
pub fn bake_east_west_tilted(
    hf: &Heightfield,
    latitude: f64,
    options: &HorizonOptions,
) -> Result<EastWestHorizon, TerrainError> {
    options.validate()?;
    check_latitude(latitude)?;
    let grid = TiltedGrid::new(hf, latitude);
    let p = plane(hf, latitude, options);
    let (w, h) = (hf.width(), hf.height());
    let threads = options
        .threads
        .map_or_else(
            || std::thread::available_parallelism().map_or(1, NonZeroUsize::get),
            NonZeroUsize::get,
        )
        .clamp(1, h);
    let bake_side = |side: Side| -> Vec<f32> {
        let mut angles = vec![NO_HORIZON; w * h];
        let rows_per_thread = h.div_ceil(threads);
        std::thread::scope(|scope| {
            for (t, block) in angles.chunks_mut(rows_per_thread * w).enumerate() {
                let (grid, p) = (&grid, &p);
                scope.spawn(move || {
                    for (i, out) in block.chunks_mut(w).enumerate() {
                        let y = t * rows_per_thread + i;
                        let jp = TiltedGrid::row_of(grid.toward_south, h, y);
                        for (x, o) in out.iter_mut().enumerate() {
                            *o = texel(grid, p, x, jp, side);
                        }
                    }
                });
            }
        });
        angles
    };
    Ok(EastWestHorizon {
        east: HorizonMap::from_angles(w, h, EAST, bake_side(Side::East)),
        west: HorizonMap::from_angles(w, h, WEST, bake_side(Side::West)),
    })
}
