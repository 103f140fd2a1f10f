//! Horizon angles: brute-force reference and the exact convex-hull sweep.
//!
//! # Definition and sampling
//!
//! The **horizon angle** of texel `P` for azimuth `φ` (radians clockwise from north:
//! east `π/2`, west `3π/2`) is the largest elevation angle, seen from `P`, of the
//! terrain samples `Q_1, Q_2, …` lying along `φ`:
//!
//! ```text
//! horizon(P, φ) = max_k atan( (h(Q_k) − h(P) − d_k² / (2 R)) / d_k ),   d_k = k · L
//! ```
//!
//! in `(−π/2, π/2)`, or [`NO_HORIZON`] (`−π/2`) when no sample lies in range (a texel
//! on the map edge facing outwards, or a maximum distance shorter than one step).
//! The term `d²/(2R)` is the drop of the surface below the tangent plane of `P` on a
//! sphere of radius `R`; it is left out when curvature is off.
//!
//! **Which samples**: write the horizontal direction of `φ` in texel axes as
//! `(sin φ, −cos φ)` (columns east, rows south). The *dominant* axis is the one with
//! the larger absolute component; `t` is the minor component divided by the dominant
//! one (`|t| ≤ 1`). With `u` the dominant and `m` the minor coordinate, the texels of
//! the map are partitioned into lines `{(u, c + round(u·t))}` for integer `c`
//! (`round` is half away from zero). One step is one dominant texel; its distance
//! along `φ` is `L = spacing · sqrt(1 + t²)`, and the samples lie on the grid lines
//! `u = u₀ ± 1, u₀ ± 2, …` (the sign of the dominant component), where the bilinear
//! surface is linear in `m`: a sample at minor position `x` is the linear
//! interpolation of the two texels around it.
//!
//! * **Axes and diagonals** (`t ∈ {0, ±1}`): every `u·t` is an integer, the line of
//!   `P = (u₀, m₀)` is its exact ray, and `Q_k` is the texel `k` steps along it,
//!   `d_k = k · L`.
//! * **Any other azimuth**: the exact line `c` runs through `m = c + u·t`; texel `P`
//!   lies `δ = round(u₀·t) − u₀·t` (`|δ| ≤ ½`) beside it. For `k ≤ NEAR_STEPS`
//!   ([`NEAR_STEPS`]) `Q_k` lies on `P`'s own ray, `m = m₀ ± k·t`, at `d_k = k · L`
//!   (the near field, where half a texel matters most). Beyond, `Q_k` is the line's
//!   sample at `u₀ ± k`, at its distance along `φ` from `P`'s foot on the line,
//!   `d_k = k · L − δ·t·L/(1 + t²)` (the sample is `|δ|/sqrt(1 + t²)` texels beside
//!   the ray, at most 0.36). A ray stops where its line's texels end.
//!
//! Sampling the ray rather than the texels of the digital line keeps the odd
//! multiples of 22.5° as accurate as the diagonals and unbiased towards shadow
//! (`docs/tradeoffs/terrain.md`, per-azimuth table).
//!
//! With a maximum distance `D`, only `k ≤ K` count, `K` the largest integer with
//! `K · L ≤ D`.
//!
//! # Algorithms
//!
//! [`Algorithm::BruteForce`] evaluates the formula for every `k` (O(n²) per line): the
//! reference. [`Algorithm::HullSweep`] is exact (the same samples, the same maximum)
//! and is the one to use. Both give the same angles bit for bit; the tests hold them
//! to that.
//!
//! * **Axes and diagonals** (`exact`): the sweep of Timonen & Westerholm (2010),
//!   "Scalable height field self-shadowing" (Computer Graphics Forum 29(2)): walking
//!   each line from its far end, it keeps the upper convex hull of the samples ahead
//!   and finds the horizon point as the tangent from `P`, popping hull points that
//!   `P` cannot see (amortised O(1) per texel).
//! * **Any other azimuth** (`sampler`): the viewpoints are texels beside the line,
//!   not its samples, so no sample can be discarded for good: walking back along the
//!   line, each line sample `NEAR_STEPS + 1` steps behind the current texel enters an
//!   upper hull (monotone chain, amortised O(1)), and the texel's horizon point is its
//!   tangent point on that hull, found by binary search (the positions along the line
//!   are linear, so the hull in `(s, g)` is exact with `s_P` the foot's position).
//!   The near field of every texel is computed once per azimuth, row by row (step `k`
//!   of a whole row reads one other row at one offset), and looked up as each line
//!   is built.
//!
//! **Curvature** is exact in the sweep: with `s` the position along the line and
//! `g = h − s²/(2R)`, the curved elevation tangent from `P` is
//! `(g(Q) − g(P)) / (s(Q) − s(P)) + s(P)/R`; the last term does not depend on `Q`,
//! so the horizon point is the ordinary hull tangent in the `(s, g)` frame. The
//! angle is then evaluated with the same formula as the brute force.
//!
//! Every tangent search starts from the previous texel's tangent point, galloping
//! (1, 2, 4, … hull points) to bracket the answer before bisecting: the same point as
//! a bisection of the whole hull, in O(1) where neighbouring texels share it.
//!
//! # A maximum distance
//!
//! A maximum distance makes the window slide, which a single hull cannot follow.
//! The hull sweep runs it one of three ways, picked by `K` (`window`: the thresholds and
//! their measurements are in `docs/tradeoffs/terrain_max_distance.md`):
//!
//! * **Windowed sweep.** Each line is cut into blocks of `K` samples: the window of
//!   `P` is the rest of its own block (a fresh sweep per block) plus a prefix of the
//!   next block, whose upper hull is built incrementally and undone point by point as
//!   `P` moves back, the tangent found by binary search (O(n log K) per line). Each
//!   part of a window is searched only when its highest sample, at its nearest
//!   distance, could rise above what the near field and the other part gave; a
//!   part's hull is built only when it is searched. On the axes and diagonals the
//!   same walk also keeps the unlimited sweep's hull of every sample ahead: where
//!   `P`'s horizon point over the whole line lies within the window it is the
//!   window's (the largest tangent of a set is the largest of any subset holding it),
//!   and where it lies beyond, it bounds the next block's part, which is skipped when
//!   that bound lies clearly below the own block's horizon point (a margin against
//!   rounding).
//! * **Through the unlimited sweep** (long windows off the axes and diagonals): a
//!   texel's tangent point on the hull of every sample ahead is its horizon point
//!   over the whole line, and where it lies within `K` steps it is also the window's.
//!   Only the other texels go through the windowed sweep, starting from a tangent the
//!   unlimited hull gives: the tangents rise along its vertices up to the horizon
//!   point, so the last vertex within the window has the largest tangent of the
//!   window's samples up to it.
//! * **Row by row** (short windows): the brute force of every window, for a whole
//!   grid row at a time. Off the axes and diagonals the far sample `k` of every texel
//!   of grid row `u₀` lies on row `u₀ ± k` at the same fractional offset and the same
//!   distance, so each step is a loop over contiguous slices that the compiler
//!   vectorises (one division per sample, no branches); on the axes and diagonals
//!   each step reads a shifted row. The samples, the arithmetic and the order of the
//!   maximum are [`Algorithm::BruteForce`]'s, so the angles are the same bit for bit.
//!   Its cost grows with `K` (the sweep's does not), so it is used only for short
//!   windows.
//!
//! # Threads
//!
//! [`bake_azimuths`] hands whole azimuths to the threads (`std::thread::scope`), each
//! baked on one thread; [`bake_horizon`] distributes one azimuth's lines. Every line
//! is computed the same way whatever the thread count, so the result does not depend
//! on it.

use crate::TerrainError;

mod bake;
mod exact;
mod hull;
mod lines;
mod maps;
mod options;
mod sampler;
#[cfg(test)]
mod tests;
mod window;

pub use bake::{bake_azimuths, bake_east_west, bake_horizon, horizon_angle};
pub(crate) use lines::{Lines, max_steps_for};
pub use maps::{AzimuthHorizonMaps, EastWestHorizon, HorizonMap};
pub use options::{Algorithm, HorizonOptions};
pub use sampler::NEAR_STEPS;

/// Mean Earth radius, metres.
pub const EARTH_RADIUS: f64 = 6_371_000.0;
/// The usual effective radius for standard atmospheric refraction, `4/3` of
/// [`EARTH_RADIUS`] (metres): light bends down with about a quarter of the Earth's
/// curvature, which lifts distant terrain as if the Earth were flatter.
pub const EFFECTIVE_EARTH_RADIUS: f64 = EARTH_RADIUS * 4.0 / 3.0;
/// The horizon angle when no sample lies along the line: nothing occludes.
pub const NO_HORIZON: f32 = -std::f32::consts::FRAC_PI_2;
/// Azimuth of east, radians clockwise from north.
pub const EAST: f64 = std::f64::consts::FRAC_PI_2;
/// Azimuth of west, radians clockwise from north.
pub const WEST: f64 = 3.0 * std::f64::consts::FRAC_PI_2;
/// Fewest azimuths accepted by [`bake_azimuths`].
pub const MIN_AZIMUTHS: usize = 4;
/// Most azimuths accepted by [`bake_azimuths`].
pub const MAX_AZIMUTHS: usize = 64;

/// `x as f64` for an index (`x < 2^53`): the same value, one instruction on x86-64
/// (`usize as f64` converts an unsigned 64-bit integer, a sequence of several).
#[inline(always)]
fn fl(x: usize) -> f64 {
    x as i64 as f64
}

/// The angle of the largest tangent `best` (`−∞`: [`NO_HORIZON`]). A zero is `+0`
/// whatever its sign: `+0` and `−0` tangents tie, and which of them the brute
/// force's maximum keeps depends on their order along the ray, which the sweeps do
/// not follow (a `−0` arises only from a `−0` height without curvature).
fn angle_from_tangent(best: f64) -> f32 {
    if best == f64::NEG_INFINITY {
        NO_HORIZON
    } else if best == 0.0 {
        0.0
    } else {
        best.atan() as f32
    }
}

pub(crate) fn check_azimuth(azimuth: f64) -> Result<f64, TerrainError> {
    if !azimuth.is_finite() {
        return Err(TerrainError::param("azimuth", azimuth, "must be finite"));
    }
    Ok(azimuth.rem_euclid(std::f64::consts::TAU))
}
