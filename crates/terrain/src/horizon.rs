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
//! Before this sampling (up to 2026-11) every azimuth read the texels of its digital
//! line at `k · L`: up to one texel beside the ray, at the distance along the line.
//! At odd multiples of 22.5° that gave several times the diagonals' error and a bias
//! towards shadow (`docs/tradeoffs/terrain.md`, per-azimuth table).
//!
//! With a maximum distance `D`, only `k ≤ K` count, `K` the largest integer with
//! `K · L ≤ D`.
//!
//! # Algorithms
//!
//! [`Algorithm::BruteForce`] evaluates the formula for every `k` (O(n²) per line).
//! [`Algorithm::HullSweep`] is exact (the same samples, the same maximum). On the axes
//! and diagonals it is the sweep of Timonen & Westerholm (2010): walking
//! each line from its far end, it keeps the upper convex hull of the samples ahead
//! and finds the horizon point as the tangent from `P`, popping hull points that `P`
//! cannot see (amortised O(1) per texel).
//!
//! Curvature is exact in the sweep: with `s` the position along the line and
//! `g = h − s²/(2R)`, the curved elevation tangent from `P` is
//! `(g(Q) − g(P)) / (s(Q) − s(P)) + s(P)/R`; the last term does not depend on `Q`,
//! so the horizon point is the ordinary hull tangent in the `(s, g)` frame. The
//! angle is then evaluated with the same formula as the brute force.
//!
//! A maximum distance makes the window slide, which a single hull cannot follow. The
//! sweep then cuts each line into blocks of `K` samples: the window of `P` is the rest
//! of its own block (a fresh sweep per block) plus a prefix of the next block, whose
//! upper hull is built incrementally and undone point by point as `P` moves back, the
//! tangent found by binary search (O(n log K) per line). The next block's part is
//! searched only when its highest sample, at its nearest distance, could rise above
//! what the own block gave; its hull is built at the first such search, up to that
//! window's end.
//!
//! On the axes and diagonals the same walk also keeps the unlimited sweep's hull of
//! every sample ahead (a second Timonen–Westerholm stack): where `P`'s horizon point
//! over the whole line lies within the window it is the window's (the largest
//! tangent of a set is the largest of any subset holding it), and where it lies
//! beyond, it bounds the next block's part, which is skipped when that bound lies
//! clearly below the own block's horizon point (a margin against rounding). On the
//! 1024² speed-study map at 6 km (`K` 200 on the axes, 141 on the diagonals) 57 % of
//! these texels take the whole line's horizon point, 27 % the own block's and 12 %
//! search the next block. Counted with valgrind (`--tool=cachegrind`, instructions of
//! the 16-azimuth bake, 1 thread, `examples/horizon_speed.rs`), these 8 azimuths'
//! lines take 2.13 G instructions at 6 km and 1.64 G at 12 km against 1.03 G
//! unlimited (before, an unlimited pass and then the windowed sweep over every
//! texel: 2.44 G and 2.03 G).
//!
//! Every tangent search starts from the previous texel's tangent point, galloping
//! (1, 2, 4, … hull points) to bracket the answer before bisecting: the same point as
//! a bisection of the whole hull, in O(1) where neighbouring texels share it.
//!
//! Off the axes and diagonals the viewpoints are texels beside the line, not its
//! samples, so no sample can be discarded for good: walking back along the line, each
//! line sample `NEAR_STEPS + 1` steps behind the current texel enters an upper hull
//! (monotone chain, amortised O(1)), and the texel's horizon point is its tangent point
//! on that hull, found by binary search (the positions along the line are linear, so
//! the hull in `(s, g)` is exact with `s_P` the foot's position). A maximum distance
//! uses the same blocks as above. Each part of a window (the whole line ahead; or the
//! rest of the own block, and the next block's prefix) is searched only when its
//! highest sample, at its nearest distance, could rise above the near field's horizon
//! and the other part's; with a maximum distance a part's hull is built only when it
//! is searched. On mountainous maps these tests skip few searches (for most texels a
//! far sample rises above the near field), so a maximum distance, which needs two
//! hulls and up to two searches per window where the unlimited sweep needs one of
//! each, costs more than no limit. Counted on the 1024² speed-study map (16
//! azimuths; `examples/horizon_speed.rs`): off the axes and diagonals the unlimited
//! sweep searches for 94 % of the texels, a 6 km window for 87 % (own block) + 34 %
//! (next block), 2 km for 81 % + 41 %; on the axes and diagonals the unlimited sweep
//! never searches (the viewpoint pops what it hides), a window searches the next
//! block for 38 % (6 km) and 48 % (2 km) of the texels, and every block's prefix
//! hull is built and undone besides.
//!
//! A maximum distance of at most 128 steps off the axes and diagonals (`K`; 3.8–5.4
//! km at 30 m by azimuth) and 66 on them (1.98 km on the axes, 2.8 km on the
//! diagonals) is baked row by row instead (`horizon_window.rs`): the brute force of every window,
//! for a whole grid row at a time. Off the axes and diagonals the far sample `k` of
//! every texel of grid row `u₀` lies on row `u₀ ± k` at the same fractional offset
//! and the same distance, so each step is a loop over contiguous slices that the
//! compiler vectorises (one division per sample, no branches); on the axes and
//! diagonals each step reads a shifted row. The samples, the arithmetic and the
//! order of the maximum are [`Algorithm::BruteForce`]'s, so the angles are the same
//! bit for bit. The cost grows with `K` (the sweep's does not): on the 1024²
//! speed-study map (`examples/horizon_speed.rs`, 16 azimuths) a 2 km limit takes
//! 0.8–1.0 × the CPU time of no limit (the windowed sweep: 1.3–1.6 ×; noisy runs at
//! load 4–9, 2026-11-27); from about 4 km on the windowed sweep is the cheaper, and
//! it is used; on the axes and diagonals, whose sweep keeps the unlimited hull in
//! the same walk, from about 2 km (`EXACT_ROW_MAX_STEPS` in `horizon_window.rs`).
//!
//! Off the axes and diagonals, from `K` = 167 steps (about 5 km at 30 m) a maximum
//! distance runs through the unlimited sweep first: a texel's tangent point on the
//! hull of every sample ahead is its horizon point over the whole line, and where it
//! lies within `K` steps it is also the window's (the largest tangent of a set is
//! the largest of any subset holding it). Only the other texels go through the
//! windowed sweep, whose hulls are built only where one of them searches, starting
//! from a tangent the unlimited hull gives: the tangents rise along its vertices up to the horizon
//! point, so the last vertex within the window has the largest tangent of the
//! window's samples up to it (the own block's search is skipped when that covers
//! the block). On the speed-study map the horizon point lies beyond the window for
//! 35 % of the searched texels at 2 km and 16 % at 6 km (of 16.2 million). That
//! fraction keeps a window dearer than no limit: within the window their horizon
//! point lies anywhere (at the window's last sample for about a third of them, at
//! the last hull vertex within it for 12–18 %, elsewhere for half), and the hull of
//! the whole line does not lead to it (its vertices' pockets, the hulls each vertex
//! hid when it was added, reach the window's end about one sample per pocket: 35
//! pockets per texel at 2 km, 78 at 6 km), so those texels pay for the windowed
//! sweep on top of the unlimited one. Against the windowed sweep alone this costs
//! more at 4 km, about the same at 5–12 km (within the noise of a loaded machine)
//! and 10–25 % less at 20 km (`UNLIMITED_MIN_STEPS` in `horizon_window.rs`).
//!
//! The near field of every texel is computed once per azimuth, row by row (step `k`
//! of a whole row reads one other row at one offset), and looked up as each line is
//! built.
//!
//! [`bake_azimuths`] hands whole azimuths to the threads (`std::thread::scope`), each
//! baked on one thread; [`bake_horizon`] distributes one azimuth's lines. Every line
//! is computed the same way whatever the thread count, so the result does not depend
//! on it.

use std::num::NonZeroUsize;

use crate::{Heightfield, TerrainError};

#[path = "horizon_window.rs"]
mod window;

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

/// Which algorithm computes the horizon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Algorithm {
    /// Evaluate every sample: the reference, O(n²) per line.
    BruteForce,
    /// Timonen & Westerholm's convex-hull sweep: same angles, O(n) per line.
    HullSweep,
}

/// Options of a horizon bake.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HorizonOptions {
    /// Radius of the sphere whose curvature drops distant terrain by `d²/(2R)`,
    /// metres; `None` for a flat Earth. Default [`EFFECTIVE_EARTH_RADIUS`]
    /// = 4/3 × 6,371 km = 8,494,667 m: the Earth's curvature *with* standard
    /// atmospheric refraction (sight lines bend down with about a quarter of the
    /// Earth's curvature, so distant terrain drops less than on the bare sphere). Use
    /// [`EARTH_RADIUS`] for the geometric horizon without refraction.
    pub effective_radius: Option<f64>,
    /// Only samples at most this far (metres) count; `None`: up to the map edge.
    pub max_distance: Option<f64>,
    /// Worker threads; `None` uses `std::thread::available_parallelism`.
    pub threads: Option<NonZeroUsize>,
}

impl Default for HorizonOptions {
    fn default() -> Self {
        Self {
            effective_radius: Some(EFFECTIVE_EARTH_RADIUS),
            max_distance: None,
            threads: None,
        }
    }
}

impl HorizonOptions {
    /// No curvature, no maximum distance.
    pub fn flat() -> Self {
        Self {
            effective_radius: None,
            ..Self::default()
        }
    }

    pub(crate) fn validate(&self) -> Result<(), TerrainError> {
        if let Some(r) = self.effective_radius
            && !(r.is_finite() && r > 0.0)
        {
            return Err(TerrainError::param(
                "effective_radius",
                r,
                "must be finite and > 0 metres",
            ));
        }
        if let Some(d) = self.max_distance
            && (d.is_nan() || d < 0.0)
        {
            return Err(TerrainError::param(
                "max_distance",
                d,
                "must be >= 0 metres (or +inf)",
            ));
        }
        Ok(())
    }

    pub(crate) fn inv_two_r(&self) -> f64 {
        self.effective_radius.map_or(0.0, |r| 0.5 / r)
    }

    fn thread_count(&self) -> usize {
        self.threads.map_or_else(
            || std::thread::available_parallelism().map_or(1, NonZeroUsize::get),
            NonZeroUsize::get,
        )
    }
}

/// One horizon angle per texel for one azimuth.
#[derive(Debug, Clone, PartialEq)]
pub struct HorizonMap {
    width: usize,
    height: usize,
    azimuth: f64,
    angles: Vec<f32>,
}

impl HorizonMap {
    pub(crate) fn from_angles(width: usize, height: usize, azimuth: f64, angles: Vec<f32>) -> Self {
        debug_assert_eq!(angles.len(), width * height);
        Self {
            width,
            height,
            azimuth,
            angles,
        }
    }

    /// Columns.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Rows.
    pub fn height(&self) -> usize {
        self.height
    }
    /// Azimuth, radians clockwise from north, in `[0, 2π)`.
    pub fn azimuth(&self) -> f64 {
        self.azimuth
    }
    /// Angles in radians, row-major.
    pub fn angles(&self) -> &[f32] {
        &self.angles
    }
    /// The angle at `(x, y)`, radians; [`TerrainError::OutOfRange`] naming `x` or `y`
    /// outside the map (an unchecked `x` would read the next row's texel).
    pub fn angle(&self, x: usize, y: usize) -> Result<f32, TerrainError> {
        TerrainError::check_index("x", x, self.width)?;
        TerrainError::check_index("y", y, self.height)?;
        Ok(self.angles[y * self.width + x])
    }
}

/// The two maps of seed 000.
#[derive(Debug, Clone, PartialEq)]
pub struct EastWestHorizon {
    /// Horizon towards the east (used while the sun is in the east).
    pub east: HorizonMap,
    /// Horizon towards the west.
    pub west: HorizonMap,
}

/// Horizon maps for `N` equally spaced azimuths `k · 2π / N`, `k = 0..N`
/// (layer 0 is north), with interpolation for any azimuth.
#[derive(Debug, Clone, PartialEq)]
pub struct AzimuthHorizonMaps {
    layers: Vec<HorizonMap>,
}

impl AzimuthHorizonMaps {
    /// The layers, layer `k` at azimuth `k · 2π / N`.
    pub fn layers(&self) -> &[HorizonMap] {
        &self.layers
    }

    /// Number of azimuths `N`.
    pub fn count(&self) -> usize {
        self.layers.len()
    }

    /// Horizon angle at `(x, y)` for any azimuth (radians clockwise from north),
    /// linearly interpolated between the two neighbouring layers with
    /// [`crate::shadow::azimuth_layers`] (the WGSL twin does the same).
    ///
    /// Errors for `(x, y)` outside the maps or a non-finite `sun_azimuth`.
    pub fn horizon_angle(&self, x: usize, y: usize, sun_azimuth: f32) -> Result<f32, TerrainError> {
        let l = crate::shadow::azimuth_layers(sun_azimuth, self.layers.len() as u32)?;
        let a = self.layers[l.lower as usize].angle(x, y)?;
        let b = self.layers[l.upper as usize].angle(x, y)?;
        Ok(a + (b - a) * l.weight)
    }
}

/// The digital-line geometry of one azimuth on one map.
#[derive(Debug, Clone)]
pub(crate) struct Lines {
    pub(crate) dominant_is_x: bool,
    /// `+1` or `-1`: the direction of travel along the dominant axis.
    pub(crate) march: i64,
    /// `round(u · t)` for every dominant coordinate `u`.
    pub(crate) offsets: Vec<i64>,
    pub(crate) n_dominant: usize,
    pub(crate) n_minor: usize,
    width: usize,
    /// Distance of one step, metres.
    pub(crate) step: f64,
    /// `t`: the minor component over the dominant one (`|t| ≤ 1`).
    pub(crate) slope: f64,
    /// `true` when every `u · t` is an integer (the axes and the diagonals): the
    /// exact line through each texel runs through texels only.
    pub(crate) exact: bool,
}

impl Lines {
    pub(crate) fn new(width: usize, height: usize, spacing: f64, azimuth: f64) -> Self {
        let (east, south) = (azimuth.sin(), -azimuth.cos());
        let dominant_is_x = east.abs() >= south.abs();
        let (dominant, minor, n_dominant, n_minor) = if dominant_is_x {
            (east, south, width, height)
        } else {
            (south, east, height, width)
        };
        // The axes and diagonals exactly (`cos(π/2)` is 6e−17, not 0).
        let t = match minor / dominant {
            t if t.abs() < 1e-12 => 0.0,
            t if (t.abs() - 1.0).abs() < 1e-12 => t.signum(),
            t => t,
        };
        let offsets: Vec<i64> = (0..n_dominant)
            .map(|u| (u as f64 * t).round() as i64)
            .collect();
        let exact = offsets
            .iter()
            .enumerate()
            .all(|(u, &o)| o as f64 == u as f64 * t);
        Self {
            dominant_is_x,
            march: if dominant > 0.0 { 1 } else { -1 },
            offsets,
            n_dominant,
            n_minor,
            width,
            step: spacing * (1.0 + t * t).sqrt(),
            slope: t,
            exact,
        }
    }

    /// Dominant coordinate of marching position `i` (0 = the first in marching order).
    #[inline]
    fn dominant_at(&self, i: usize) -> usize {
        if self.march > 0 {
            i
        } else {
            self.n_dominant - 1 - i
        }
    }

    /// Texel index of dominant coordinate `u` and minor coordinate `m`.
    #[inline]
    fn texel(&self, u: usize, m: usize) -> usize {
        if self.dominant_is_x {
            m * self.width + u
        } else {
            u * self.width + m
        }
    }

    /// The heights in metres laid out dominant-major (`grid[u · n_minor + m]`), so
    /// that walking a line reads memory almost in order.
    fn dominant_major(&self, hf: &Heightfield) -> Vec<f64> {
        let scale = hf.vertical_scale();
        let samples = hf.samples();
        let mut grid = Vec::with_capacity(samples.len());
        for u in 0..self.n_dominant {
            grid.extend((0..self.n_minor).map(|m| f64::from(samples[self.texel(u, m)]) * scale));
        }
        grid
    }

    /// The height at dominant coordinate `u` and minor position `x` (texel units),
    /// linear between the two texels around `x` (the bilinear surface on the grid
    /// line `u`); `None` outside `[0, n_minor − 1]`. `grid` from
    /// [`Lines::dominant_major`].
    #[inline]
    fn height_between(&self, grid: &[f64], u: usize, x: f64) -> Option<f64> {
        // `x ≥ 0` truncates to its floor (`f64::floor` is a libm call on baseline
        // x86-64); NaN and negative positions are outside.
        if x.is_nan() || x < 0.0 || x > (self.n_minor - 1) as f64 {
            return None;
        }
        let m = x as usize;
        let f = x - m as f64;
        let row = &grid[u * self.n_minor..][..self.n_minor];
        let a = row[m];
        if f == 0.0 {
            return Some(a);
        }
        let b = *row.get(m + 1)?;
        Some(a + (b - a) * f)
    }

    /// Line ids `c` covering the map, in order.
    pub(crate) fn ids(&self) -> std::ops::RangeInclusive<i64> {
        let last = *self.offsets.last().unwrap_or(&0);
        let (lo, hi) = (last.min(0), last.max(0));
        -hi..=(self.n_minor as i64 - 1 - lo)
    }

    /// The line id and dominant coordinate of texel `(x, y)`.
    fn locate(&self, x: usize, y: usize) -> (i64, usize) {
        let (u, m) = if self.dominant_is_x { (x, y) } else { (y, x) };
        (m as i64 - self.offsets[u], u)
    }

    /// Texel indices of line `c` in marching order (appended to `out`).
    fn texels(&self, c: i64, out: &mut Vec<usize>) {
        out.clear();
        let mut push = |u: usize| {
            let m = c + self.offsets[u];
            if m >= 0 && (m as usize) < self.n_minor {
                let m = m as usize;
                out.push(if self.dominant_is_x {
                    m * self.width + u
                } else {
                    u * self.width + m
                });
            }
        };
        if self.march > 0 {
            (0..self.n_dominant).for_each(&mut push);
        } else {
            (0..self.n_dominant).rev().for_each(&mut push);
        }
    }

    /// `K`: the largest number of steps within `max_distance` (`usize::MAX` for none).
    fn max_steps(&self, max_distance: Option<f64>) -> usize {
        max_steps_for(self.step, max_distance)
    }
}

/// `K`: the largest integer with `K · step ≤ max_distance` (`usize::MAX` for none).
pub(crate) fn max_steps_for(step: f64, max_distance: Option<f64>) -> usize {
    match max_distance {
        None => usize::MAX,
        Some(d) if d.is_infinite() => usize::MAX,
        // Beyond 2^53 steps no map reaches the limit (and the search below would
        // count up to `d / step`, for ever when `d` is huge): no limit.
        Some(d) if d / step >= 9.0e15 => usize::MAX,
        Some(d) => {
            let mut k = (d / step).floor() as usize;
            while k > 0 && k as f64 * step > d {
                k -= 1;
            }
            while ((k + 1) as f64) * step <= d {
                k += 1;
            }
            k
        }
    }
}

/// Profile of one line: heights in marching order and the per-line constants.
struct Profile<'a> {
    h: &'a [f64],
    step: f64,
    inv_two_r: f64,
}

impl Profile<'_> {
    /// Tangent of the elevation of sample `j` seen from sample `k < j`: the one
    /// formula both algorithms evaluate.
    #[inline]
    fn tangent(&self, k: usize, j: usize) -> f64 {
        let d = fl(j - k) * self.step;
        (self.h[j] - self.h[k] - d * d * self.inv_two_r) / d
    }
}

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

/// Brute force over one line.
fn brute_line(p: &Profile<'_>, max_steps: usize, out: &mut [f32]) {
    let n = p.h.len();
    for (k, o) in out.iter_mut().enumerate() {
        let end = k.saturating_add(max_steps).min(n - 1);
        let mut best = f64::NEG_INFINITY;
        for j in k + 1..=end {
            best = best.max(p.tangent(k, j));
        }
        *o = angle_from_tangent(best);
    }
}

/// `true` when, seen from `q` (left of both), `b` is at least as high in slope as
/// `a`, in the curvature-corrected frame `g` (indices are positions along the line).
#[inline]
fn not_lower(g: &[f64], q: usize, a: usize, b: usize) -> bool {
    (g[b] - g[q]) * fl(a - q) >= (g[a] - g[q]) * fl(b - q)
}

/// Adds sample `p`, left of every point, to the upper hull `hull` (indices along the
/// line, leftmost last) in the curvature-corrected frame `g`.
#[inline]
fn push_left(g: &[f64], hull: &mut Vec<usize>, p: usize) {
    while hull.len() >= 2 {
        let t = hull[hull.len() - 1];
        let s = hull[hull.len() - 2];
        if (g[t] - g[p]) * fl(s - p) <= (g[s] - g[p]) * fl(t - p) {
            hull.pop();
        } else {
            break;
        }
    }
    hull.push(p);
}

/// The hull sweep over one line of the axes or diagonals (the samples are the
/// viewpoints).
///
/// With a maximum distance `K` the line is cut into blocks of `K` samples, walked
/// from the far end. The window of texel `k` is the rest of its own block (part A)
/// plus a prefix `[e, k + K]` of what follows (part B), `e` the block's end. One walk
/// keeps two Timonen–Westerholm hulls: the block's own (part A's horizon point) and
/// that of every sample ahead (the unlimited sweep's). Where the horizon point over
/// the whole line lies within the window it is the window's (the largest tangent of
/// a set is the largest of any subset holding it). Otherwise it lies beyond `e` and
/// bounds part B; where it lies clearly below part A's horizon point (a margin
/// against rounding, without a division), part B cannot rise above part A. Only the
/// other texels search part B's own hull, built at the block's first such search
/// and undone point by point as the window slides back.
fn sweep_line(p: &Profile<'_>, max_steps: usize, g: &mut Vec<f64>, out: &mut [f32]) {
    let n = p.h.len();
    g.clear();
    g.extend(p.h.iter().enumerate().map(|(i, &h)| {
        let s = fl(i) * p.step;
        h - s * s * p.inv_two_r
    }));
    let g = &g[..];
    if max_steps == 0 {
        out.fill(NO_HORIZON);
        return;
    }
    // Block length: the whole line when the window reaches the end anyway.
    let block = if max_steps >= n - 1 { n } else { max_steps };
    // The magnitudes a tangent's rounding error scales with (metres): heights and
    // the largest curvature drop.
    let reach = fl(n) * p.step;
    let scale =
        2.0 * p.h.iter().fold(0.0f64, |m, &h| m.max(h.abs())) + reach * reach * p.inv_two_r + 1.0;
    let mut hull: Vec<usize> = Vec::new();
    // The upper hull of every sample ahead (leftmost last), the unlimited sweep's.
    let mut whole: Vec<usize> = Vec::new();
    let mut prefix: Vec<usize> = Vec::new();
    let mut undo_log: Vec<(usize, usize)> = Vec::new(); // (added point, popped count)
    let mut popped: Vec<usize> = Vec::new();
    let mut prefix_max: Vec<f64> = Vec::new();
    let mut block_start = (n - 1) / block * block;
    loop {
        let block_end = (block_start + block).min(n); // exclusive
        let mut prefix_built = false;
        prefix_max.clear();
        let mut prefix_end = 0; // the last sample offered to `prefix`
        let mut tangent = 0; // the last tangent point's position on `prefix`
        hull.clear();
        for k in (block_start..block_end).rev() {
            // Part A: rest of the own block, Timonen–Westerholm popping.
            while hull.len() >= 2 && not_lower(g, k, hull[hull.len() - 1], hull[hull.len() - 2]) {
                hull.pop();
            }
            let own = hull.last().copied();
            hull.push(k);
            if block_end < n {
                // The horizon point over the whole line ahead (Timonen–Westerholm).
                while whole.len() >= 2
                    && not_lower(g, k, whole[whole.len() - 1], whole[whole.len() - 2])
                {
                    whole.pop();
                }
                let j = *whole.last().expect("samples ahead");
                whole.push(k);
                let target = (k + max_steps).min(n - 1);
                if j <= target {
                    out[k] = angle_from_tangent(p.tangent(k, j));
                    continue;
                }
                // Part B's samples have no larger tangent than `j`'s: none can rise above
                // part A's tangent point `a` where `j` lies clearly below it, in the
                // curvature-corrected frame without a division (the tangents' rounding
                // errors, about 1e-16 of `scale` over the distance, times the two
                // distances, stay below the margin).
                let clear = own.is_some_and(|a| {
                    (g[a] - g[k]) * fl(j - k) - (g[j] - g[k]) * fl(a - k)
                        > 2e-12 * scale * fl(j - k)
                });
                let mut best = own.map_or(f64::NEG_INFINITY, |a| p.tangent(k, a));
                if clear {
                    out[k] = angle_from_tangent(best);
                    continue;
                }
                // Part B: prefix of the next block up to k + K, searched only when its
                // highest sample, at its nearest distance, could rise above part A's.
                if prefix_max.is_empty() {
                    let mut running = f64::NEG_INFINITY;
                    for &x in &g[block_end..(block_end + block).min(n)] {
                        running = running.max(x);
                        prefix_max.push(running);
                    }
                }
                let lift = 2.0 * fl(k) * p.step * p.inv_two_r;
                let (near, far) = (fl(block_end - k), fl(target - k));
                let g_max = prefix_max[target - block_end];
                if !can_rise(best, lift, g_max, g[k], || near * p.step, || far * p.step) {
                    out[k] = angle_from_tangent(best);
                    continue;
                }
                if !prefix_built {
                    prefix_built = true;
                    prefix.clear();
                    undo_log.clear();
                    popped.clear();
                    for j in block_end..=target {
                        let mut count = 0;
                        while prefix.len() >= 2 {
                            let t = prefix[prefix.len() - 1];
                            let s = prefix[prefix.len() - 2];
                            // Pop `t` when it is on or below the segment s → j.
                            if (g[t] - g[s]) * fl(j - s) <= (g[j] - g[s]) * fl(t - s) {
                                popped.push(t);
                                prefix.pop();
                                count += 1;
                            } else {
                                break;
                            }
                        }
                        prefix.push(j);
                        undo_log.push((j, count));
                    }
                    prefix_end = target;
                }
                while prefix_end > target {
                    let (added, count) = undo_log.pop().expect("undo log matches prefix");
                    debug_assert_eq!(prefix.last(), Some(&added));
                    prefix.pop();
                    for _ in 0..count {
                        prefix.push(popped.pop().expect("popped log matches"));
                    }
                    prefix_end -= 1;
                }
                // Tangent: first i whose successor is not above the line k → prefix[i],
                // searched from the previous texel's.
                tangent = first_true(prefix.len(), tangent, |i| {
                    not_lower(g, k, prefix[i + 1], prefix[i])
                });
                best = best.max(p.tangent(k, prefix[tangent]));
                out[k] = angle_from_tangent(best);
                continue;
            }
            out[k] = angle_from_tangent(own.map_or(f64::NEG_INFINITY, |a| p.tangent(k, a)));
        }
        if block_start == 0 {
            break;
        }
        if whole.is_empty() {
            // The last block's own hull is that of every sample from its start.
            whole.extend_from_slice(&hull);
        }
        block_start -= block;
    }
}

/// The first `i < len` with `pred(i)`, `pred` monotone (false, then true) on
/// `0..len − 1` and taken as true at `len − 1`: galloping from `guess` (1, 2, 4, …
/// positions towards the answer), then bisecting the bracket. The same answer as a
/// bisection of the whole range, in O(1) when the guess is at or next to it.
#[inline]
fn first_true(len: usize, guess: usize, pred: impl Fn(usize) -> bool) -> usize {
    let last = len - 1;
    let p = |i: usize| i >= last || pred(i);
    let x = guess.min(last);
    // The answer lies in [lo, hi] and p(hi) holds.
    let (mut lo, mut hi);
    if p(x) {
        hi = x;
        lo = 0;
        let mut step = 1;
        while hi >= step {
            let c = hi - step;
            if p(c) {
                hi = c;
                step *= 2;
            } else {
                lo = c + 1;
                break;
            }
        }
    } else {
        lo = x + 1;
        let mut step = 1;
        loop {
            let c = (lo - 1 + step).min(last);
            if p(c) {
                hi = c;
                break;
            }
            lo = c + 1;
            step *= 2;
        }
    }
    while lo < hi {
        let mid = (lo + hi) / 2;
        if p(mid) {
            hi = mid;
        } else {
            lo = mid + 1;
        }
    }
    lo
}

/// `false` when no sample whose curvature-corrected height is at most `g_max`, at a
/// distance between `near()` and `far()`, can have a tangent above `best`, seen from
/// a viewpoint at curvature-corrected height `g_view` whose tangents carry `lift`
/// (module docs: the tangent is `(g(Q) − g(P)) / d + lift`): `(g_max − g_view) / d`
/// at the nearest distance bounds the others, at the farthest when it is negative.
/// Margins of 1e-12 of the magnitudes involved keep the test conservative against
/// rounding (the tangents themselves are rounded at about 1e-16 of them).
#[inline]
fn can_rise(
    best: f64,
    lift: f64,
    g_max: f64,
    g_view: f64,
    near: impl Fn() -> f64,
    far: impl Fn() -> f64,
) -> bool {
    let threshold = best - lift - 1e-12 * (best.abs() + lift.abs());
    let rise = g_max - g_view + 1e-12 * (g_max.abs() + g_view.abs() + 1.0);
    let d = if rise >= 0.0 { near() } else { far() };
    // rise / d + lift ≥ best, without the division (d > 0; best = −∞ gives
    // threshold · d = −∞: search).
    rise >= threshold * d
}

/// The height at minor position `x` (`0 ≤ x ≤ row.len() − 1`) of a dominant-major row,
/// linear between the two texels around `x`: [`Lines::height_between`] without its
/// range checks (`x as i64` truncates to the floor for `x ≥ 0`).
#[inline(always)]
fn lerp_row(row: &[f64], x: f64) -> f64 {
    let m = x as i64 as usize;
    let f = x - m as i64 as f64;
    let a = row[m];
    if f == 0.0 {
        a
    } else {
        a + (row[m + 1] - a) * f
    }
}

/// Neighbouring lines built, swept and written together (off the axes and diagonals).
const LINE_BATCH: usize = 8;

/// Steps along each texel's own exact ray before the shared line takes over (off the
/// axes and diagonals): the near field, where a lateral offset of half a texel matters
/// most, is sampled exactly; beyond it every texel of a line reads the line's samples.
pub const NEAR_STEPS: usize = 4;

/// One texel (viewpoint) of a line off the axes and diagonals.
#[derive(Debug, Clone, Copy)]
struct View {
    /// Marching position of the texel's dominant coordinate.
    i: usize,
    /// Row-major texel index.
    texel: usize,
    /// Height, metres.
    h: f64,
    /// Minor coordinate of the texel.
    m: f64,
    /// Where the texel's foot lies along the line, relative to the line's sample at the
    /// same marching position, metres (`s_P = i · L + e`).
    e: f64,
    /// Curvature-corrected height of the viewpoint, `h − s_P² / (2R)`.
    g: f64,
    /// The near field's largest tangent ([`Sampler::near_best`]).
    near: f64,
}

/// Scratch buffers of one worker for the lines off the axes and diagonals.
#[derive(Debug, Default)]
struct LineScratch {
    /// Line samples in marching order (NaN where the line is outside the map).
    h: Vec<f64>,
    /// `h − s² / (2R)`, `s = i · L`.
    g: Vec<f64>,
    views: Vec<View>,
    hull: Vec<usize>,
    prefix: Vec<usize>,
    /// (sample, added, popped count) per sample offered to the prefix hull.
    undo_log: Vec<(usize, bool, usize)>,
    popped: Vec<usize>,
    /// Per view: its largest tangent where the unlimited sweep found it, else NaN
    /// ([`Sampler::sweep_by_unlimited`]).
    known: Vec<f64>,
    /// Per view whose `known` is NaN: where its window's maximum starts (the near
    /// field, or a larger tangent of a window sample) and the last sample up to which
    /// that is the window's maximum (none: `0`).
    lower: Vec<(f64, usize)>,
    /// The running maximum of `g` over the next block, from its first sample: the
    /// bound that lets a window skip its part-B search.
    prefix_max: Vec<f64>,
    out: Vec<f32>,
}

/// One azimuth's sampling off the axes and diagonals (module docs, "Which samples").
struct Sampler<'a> {
    lines: &'a Lines,
    /// [`Lines::dominant_major`].
    grid: &'a [f64],
    inv_two_r: f64,
    max_steps: usize,
    /// Every texel's near field, dominant-major ([`Sampler::near_field`]).
    near: Vec<f64>,
    /// A maximum distance runs through the unlimited sweep
    /// ([`Sampler::sweep_by_unlimited`]) rather than the windowed one.
    by_unlimited: bool,
}

impl<'a> Sampler<'a> {
    fn new(lines: &'a Lines, grid: &'a [f64], inv_two_r: f64, max_steps: usize) -> Self {
        let mut sampler = Self {
            lines,
            grid,
            inv_two_r,
            max_steps,
            near: Vec::new(),
            by_unlimited: false,
        };
        sampler.near = sampler.near_field();
        sampler
    }

    /// [`Sampler::near_best`] of every texel, dominant-major (`near[u · n_minor + m]`),
    /// without its stop at the line's last texel (which [`Sampler::build`] applies),
    /// row by row: step `k` of every texel of row `u` reads row `u ± k` at
    /// `m + dx_k` (`dx_k = ±k · t`), the same offset for the whole row. Where
    /// `dx_k` is not within 2^−20 of an integer, `m + dx_k` (rounded) lies strictly
    /// between `m + ⌊dx_k⌋` and the next integer for every `m < 2^30`, so the two
    /// texels and the weight need no per-texel floor: contiguous slices the compiler
    /// vectorises, with `near_best`'s arithmetic operation for operation (the same
    /// values; the maximum is taken in the same order of `k`).
    fn near_field(&self) -> Vec<f64> {
        let l = self.lines;
        let (n, nm) = (l.n_dominant, l.n_minor);
        let top = (nm - 1) as f64;
        let mut near = vec![f64::NEG_INFINITY; n * nm];
        let m_f: Vec<f64> = (0..nm).map(fl).collect();
        for k in 1..=NEAR_STEPS.min(self.max_steps) {
            let dx = (l.march * k as i64) as f64 * l.slope;
            let d = k as f64 * l.step;
            let drop = d * d * self.inv_two_r;
            let q = dx.floor();
            let w = dx - q;
            let fast = (1.0 / 1_048_576.0..=1.0 - 1.0 / 1_048_576.0).contains(&w)
                && nm < 1 << 30
                && q.abs() < 1e6;
            let q = q as i64;
            // Texels m with m + q in [0, nm − 2] (fast path): both texels in the row.
            let lo = (-q).max(0) as usize;
            let hi = (nm as i64 - 2 - q).min(nm as i64 - 1);
            for u in 0..n {
                let uk = u as i64 + l.march * k as i64;
                if uk < 0 || uk >= n as i64 {
                    continue;
                }
                let src = &self.grid[uk as usize * nm..][..nm];
                let own = &self.grid[u * nm..][..nm];
                let out = &mut near[u * nm..][..nm];
                if fast {
                    if hi < lo as i64 {
                        continue;
                    }
                    let hi = hi as usize;
                    let a0 = (lo as i64 + q) as usize;
                    let len = hi + 1 - lo;
                    let iter = out[lo..=hi]
                        .iter_mut()
                        .zip(&own[lo..=hi])
                        .zip(&m_f[lo..=hi])
                        .zip(&src[a0..a0 + len])
                        .zip(&src[a0 + 1..a0 + 1 + len]);
                    for ((((o, &hp), &mf), &a), &b) in iter {
                        let x = mf + dx;
                        // `x − ⌊x⌋`: ⌊x⌋ = m + q, exact in f64.
                        let f = x - (mf + q as f64);
                        let h = a + (b - a) * f;
                        *o = o.max((h - hp - drop) / d);
                    }
                } else {
                    for m in 0..nm {
                        let x = m_f[m] + dx;
                        if x >= 0.0 && x <= top {
                            let t = (lerp_row(src, x) - own[m] - drop) / d;
                            out[m] = out[m].max(t);
                        }
                    }
                }
            }
        }
        near
    }
    /// Fills `sc.h`, `sc.g` and `sc.views` (with each view's near field,
    /// [`Sampler::near_best`]) for line `c`.
    ///
    /// One forward pass: the near field of a texel reads the grid rows the line has
    /// just sampled (still in cache); the arithmetic is [`Lines::height_between`]'s and
    /// [`Sampler::near_best`]'s, operation for operation, so the values are the same.
    fn build(&self, c: i64, sc: &mut LineScratch) {
        self.build_batch(&[c], std::slice::from_mut(sc));
    }

    /// [`Sampler::build`] for consecutive lines `cs` at once (`scs[k]` for `cs[k]`),
    /// each row of the grid visited once for all of them: neighbouring lines read
    /// neighbouring texels, so a batch touches each row's memory once instead of once
    /// per line. Every line's values are computed as on its own.
    fn build_batch(&self, cs: &[i64], scs: &mut [LineScratch]) {
        let l = self.lines;
        let (t, step, nm) = (l.slope, l.step, l.n_minor);
        let n = l.n_dominant;
        let top = (nm - 1) as f64;
        // Projection of a minor offset of one texel on the direction, metres.
        let foot = l.march as f64 * t * step / (1.0 + t * t);
        let steps = NEAR_STEPS.min(self.max_steps);
        for sc in scs.iter_mut() {
            sc.h.clear();
            sc.g.clear();
            sc.views.clear();
            sc.h.reserve(n);
            sc.g.reserve(n);
        }
        for i in 0..n {
            let u = l.dominant_at(i);
            let row = &self.grid[u * nm..][..nm];
            let near = &self.near[u * nm..][..nm];
            let exact = fl(u) * t;
            let s = fl(i) * step;
            let drop = s * s * self.inv_two_r;
            let offset = l.offsets[u];
            let e = foot * (offset as f64 - exact);
            let sp = s + e;
            let drop_p = sp * sp * self.inv_two_r;
            for (&c, sc) in cs.iter().zip(scs.iter_mut()) {
                let x = c as f64 + exact;
                let h = if x >= 0.0 && x <= top {
                    lerp_row(row, x)
                } else {
                    f64::NAN
                };
                sc.h.push(h);
                sc.g.push(h - drop);
                let m = c + offset;
                if m >= 0 && (m as usize) < nm {
                    let mu = m as usize;
                    let hp = row[mu];
                    sc.views.push(View {
                        i,
                        texel: l.texel(u, mu),
                        h: hp,
                        m: m as f64,
                        e,
                        g: hp - drop_p,
                        near: near[mu],
                    });
                }
            }
        }
        // The ray stops where its line's texels end ([`Sampler::near_best`]'s `last`).
        // Past a line's minor end the own ray has left the map too (the line's texel
        // is within half a texel of it), so only a guard: it redoes the last views.
        for sc in scs.iter_mut() {
            let last = sc.views.last().map_or(0, |v| v.i);
            for k in (0..sc.views.len()).rev() {
                if sc.views[k].i + steps <= last {
                    break;
                }
                sc.views[k].near = self.near_best(&sc.views[k], last);
            }
        }
    }

    /// The largest tangent over the first `min(NEAR_STEPS, K)` steps of the texel's own
    /// ray (heights linear across the grid line, distance `k · L`).
    ///
    /// The ray stops where the line's texels end (`last`, the last view's position),
    /// as the GPU twin's does.
    fn near_best(&self, v: &View, last: usize) -> f64 {
        let l = self.lines;
        let mut best = f64::NEG_INFINITY;
        for k in 1..=NEAR_STEPS.min(self.max_steps) {
            let i = v.i + k;
            if i > last {
                break;
            }
            let x = v.m + (l.march * k as i64) as f64 * l.slope;
            let Some(h) = l.height_between(self.grid, l.dominant_at(i), x) else {
                break;
            };
            let d = k as f64 * l.step;
            best = best.max((h - v.h - d * d * self.inv_two_r) / d);
        }
        best
    }

    /// Distance along the azimuth from the texel's foot to line sample `j`, metres.
    #[inline]
    fn distance(&self, v: &View, j: usize) -> f64 {
        fl(j - v.i) * self.lines.step - v.e
    }

    /// Tangent of the elevation of line sample `j` seen from `v`: the formula both
    /// algorithms evaluate.
    #[inline]
    fn tangent(&self, sc: &LineScratch, v: &View, j: usize) -> f64 {
        let d = self.distance(v, j);
        (sc.h[j] - v.h - d * d * self.inv_two_r) / d
    }

    /// `true` when, seen from `v`, sample `b` is not above sample `a` (curvature-
    /// corrected frame; both ahead of `v`).
    #[inline]
    fn not_above(&self, g: &[f64], v: &View, a: usize, b: usize) -> bool {
        (g[b] - v.g) * self.distance(v, a) <= (g[a] - v.g) * self.distance(v, b)
    }

    /// The position `k < len` of the tangent point from `v` on an upper hull given
    /// left to right by `at(k)`, searched from position `guess` (the neighbouring
    /// texel's tangent point, usually the same or next to it; [`first_true`]).
    fn tangent_point(
        &self,
        g: &[f64],
        v: &View,
        len: usize,
        guess: usize,
        at: impl Fn(usize) -> usize,
    ) -> usize {
        first_true(len, guess, |k| self.not_above(g, v, at(k), at(k + 1)))
    }

    /// Brute force over line `c` (after [`Sampler::build`]): every sample of each window.
    fn brute(&self, sc: &mut LineScratch) {
        let n = self.lines.n_dominant;
        sc.out.clear();
        for v in &sc.views {
            let mut best = v.near;
            let last = v.i.saturating_add(self.max_steps).min(n - 1);
            for j in v.i + NEAR_STEPS + 1..=last {
                if !sc.h[j].is_nan() {
                    best = best.max(self.tangent(sc, v, j));
                }
            }
            sc.out.push(angle_from_tangent(best));
        }
    }

    /// The hull sweep over line `c` (after [`Sampler::build`]): the same samples as
    /// [`Sampler::brute`]; the far samples of each window enter upper convex hulls as
    /// the sweep walks back along the line, and each texel's horizon point is its
    /// tangent point on them.
    fn sweep(&self, sc: &mut LineScratch) {
        let n = self.lines.n_dominant;
        let far = self.max_steps.saturating_sub(NEAR_STEPS);
        if far > 0 && self.max_steps < n {
            if self.by_unlimited {
                self.sweep_by_unlimited(sc);
            } else {
                self.sweep_windowed(sc, false);
            }
            return;
        }
        sc.out.clear();
        sc.out.resize(sc.views.len(), NO_HORIZON);
        let LineScratch {
            h,
            g,
            views,
            hull,
            out,
            ..
        } = sc;
        let g = &g[..];
        hull.clear();
        let mut next = n; // the next sample to add is next − 1
        let mut from_right = 0usize; // the last tangent point, counted from the right
        // The highest curvature-corrected sample added so far (all ahead of the view).
        let mut g_max = f64::NEG_INFINITY;
        for (slot, v) in views.iter().enumerate().rev() {
            let mut best = v.near;
            let a = v.i + NEAR_STEPS + 1;
            if far > 0 && a < n {
                while next > a {
                    next -= 1;
                    if !h[next].is_nan() {
                        push_left(g, hull, next);
                        g_max = g_max.max(g[next]);
                    }
                }
                // No sample ahead can rise above the near field's horizon: skip the
                // tangent search (the hull is kept up to date regardless).
                if self.can_rise(v, best, g_max, a, n - 1) && !hull.is_empty() {
                    let len = hull.len();
                    // The guess counts from the right end, which stays put as the
                    // hull grows to the left.
                    let guess = len - 1 - from_right.min(len - 1);
                    let k = self.tangent_point(g, v, len, guess, |k| hull[len - 1 - k]);
                    from_right = len - 1 - k;
                    best = best.max(self.tangent_h(h, v, hull[from_right]));
                }
            }
            out[slot] = angle_from_tangent(best);
        }
    }

    /// [`Sampler::sweep`] with a maximum distance (`NEAR_STEPS < K < n`) through the
    /// unlimited sweep: each texel's tangent point on the hull of every far sample
    /// ahead is its horizon point over the whole line; when it lies within `K` steps
    /// it is also the window's (the largest tangent of a set is the largest of any
    /// subset holding it), as is the near field where no sample ahead can rise above
    /// it. Only the other texels go through [`Sampler::sweep_windowed`].
    fn sweep_by_unlimited(&self, sc: &mut LineScratch) {
        let n = self.lines.n_dominant;
        let max_steps = self.max_steps;
        let LineScratch {
            h,
            g,
            views,
            hull,
            known,
            lower,
            ..
        } = sc;
        let g = &g[..];
        hull.clear();
        known.clear();
        known.resize(views.len(), f64::NAN);
        lower.clear();
        lower.resize(views.len(), (f64::NEG_INFINITY, 0));
        let mut next = n;
        let mut from_right = 0usize;
        let mut g_max = f64::NEG_INFINITY;
        for (slot, v) in views.iter().enumerate().rev() {
            let mut best = v.near;
            let a = v.i + NEAR_STEPS + 1;
            if a < n {
                while next > a {
                    next -= 1;
                    if !h[next].is_nan() {
                        push_left(g, hull, next);
                        g_max = g_max.max(g[next]);
                    }
                }
                if self.can_rise(v, best, g_max, a, n - 1) && !hull.is_empty() {
                    let len = hull.len();
                    let guess = len - 1 - from_right.min(len - 1);
                    let k = self.tangent_point(g, v, len, guess, |k| hull[len - 1 - k]);
                    from_right = len - 1 - k;
                    let j = hull[from_right];
                    let b = v.i.saturating_add(max_steps);
                    if j > b {
                        // The tangents rise along the hull's vertices up to `j`: the
                        // last within the window, if any, has the largest tangent of
                        // the window's samples up to it.
                        let first_out = first_true(k + 1, k, |q| hull[len - 1 - q] > b);
                        lower[slot] = match first_out.checked_sub(1) {
                            Some(q) => {
                                let p_m = hull[len - 1 - q];
                                (best.max(self.tangent_h(h, v, p_m)), p_m)
                            }
                            None => (best, 0),
                        };
                        continue;
                    }
                    best = best.max(self.tangent_h(h, v, j));
                }
            }
            known[slot] = best;
        }
        self.sweep_windowed(sc, true);
    }

    /// `false` when no sample of `[lo, hi]` (`v.i < lo ≤ hi`) whose curvature-
    /// corrected height is at most `g_max` (`−∞` when none) can rise, seen from `v`,
    /// above the tangent `best`: the highest such sample at the nearest distance (at
    /// the farthest when it lies below `v`) bounds them all. A margin against rounding
    /// keeps the test conservative; no division.
    #[inline]
    fn can_rise(&self, v: &View, best: f64, g_max: f64, lo: usize, hi: usize) -> bool {
        if g_max == f64::NEG_INFINITY {
            return false;
        }
        let lift = 2.0 * (fl(v.i) * self.lines.step + v.e) * self.inv_two_r;
        can_rise(
            best,
            lift,
            g_max,
            v.g,
            || self.distance(v, lo),
            || self.distance(v, hi),
        )
    }

    /// [`Sampler::sweep`] with a maximum distance shorter than the line: each window
    /// `[a, b]` (`a = i + NEAR_STEPS + 1`, `b = a + far − 1`, `far = K − NEAR_STEPS`)
    /// is the rest of its own block of `far` samples (part A) plus a prefix of the
    /// next block (part B). Each part is searched only when its highest sample, at
    /// its nearest distance, could rise above what the near field and the other part
    /// found; its hull is built only then (part A catching up point by point as the
    /// window slides back, part B built up to `b` at its first search in a block and
    /// then undone point by point), so a window that cannot beat its near field costs
    /// two comparisons and no hull work.
    ///
    /// With `use_known`, the views whose `sc.known` is not NaN take it and skip the
    /// window ([`Sampler::sweep_by_unlimited`]).
    fn sweep_windowed(&self, sc: &mut LineScratch, use_known: bool) {
        let n = self.lines.n_dominant;
        let far = self.max_steps - NEAR_STEPS;
        sc.out.clear();
        sc.out.resize(sc.views.len(), NO_HORIZON);
        let LineScratch {
            h,
            g,
            views,
            hull,
            prefix,
            undo_log,
            popped,
            prefix_max,
            known,
            lower,
            out,
        } = sc;
        let g = &g[..];
        let mut block = usize::MAX;
        let mut next = 0usize; // part A's hull holds the block's samples ≥ next
        let mut scan = 0usize; // a_max covers the block's samples ≥ scan
        let mut a_max = f64::NEG_INFINITY;
        let mut prefix_end = 0usize; // samples < prefix_end were offered to `prefix`
        let mut prefix_built = false;
        // The last tangent points: part A's counted from its right end, part B's
        // from its left end (the ends that stay put as the hulls change).
        let (mut from_right, mut from_left) = (0usize, 0usize);
        for (slot, v) in views.iter().enumerate().rev() {
            let mut best = v.near;
            // Part A's samples up to `done` need no search.
            let mut done = 0;
            if use_known {
                if !known[slot].is_nan() {
                    out[slot] = angle_from_tangent(known[slot]);
                    continue;
                }
                (best, done) = lower[slot];
            }
            let a = v.i + NEAR_STEPS + 1;
            if a < n {
                let b = (a + far - 1).min(n - 1);
                let start = (a / far + 1) * far; // the next block's first sample
                if a / far != block {
                    block = a / far;
                    hull.clear();
                    next = start.min(n);
                    scan = next;
                    a_max = f64::NEG_INFINITY;
                    prefix_built = false;
                    // Running maximum of the next block from its first sample
                    // (`f64::max` skips the NaN outside the map).
                    prefix_max.clear();
                    let mut running = f64::NEG_INFINITY;
                    for &x in &g[start.min(n)..(start + far).min(n)] {
                        running = running.max(x);
                        prefix_max.push(running);
                    }
                }
                while scan > a {
                    scan -= 1;
                    a_max = a_max.max(g[scan]);
                }
                // Part A: the rest of the own block, [a, min(start, n) − 1].
                if done < start.min(n) - 1 && self.can_rise(v, best, a_max, a, start.min(n) - 1) {
                    while next > a {
                        next -= 1;
                        if !h[next].is_nan() {
                            push_left(g, hull, next);
                        }
                    }
                    if !hull.is_empty() {
                        let len = hull.len();
                        let guess = len - 1 - from_right.min(len - 1);
                        let k = self.tangent_point(g, v, len, guess, |k| hull[len - 1 - k]);
                        from_right = len - 1 - k;
                        best = best.max(self.tangent_h(h, v, hull[from_right]));
                    }
                }
                // Part B: the next block's samples [start, b].
                if b >= start && self.can_rise(v, best, prefix_max[b - start], start, b) {
                    if prefix_built {
                        self.shrink_prefix(prefix, undo_log, popped, &mut prefix_end, b);
                    } else {
                        prefix_built = true;
                        prefix.clear();
                        undo_log.clear();
                        popped.clear();
                        for j in start..=b {
                            if h[j].is_nan() {
                                undo_log.push((j, false, 0));
                                continue;
                            }
                            let mut count = 0;
                            while prefix.len() >= 2 {
                                let t = prefix[prefix.len() - 1];
                                let s = prefix[prefix.len() - 2];
                                if (g[t] - g[s]) * fl(j - s) <= (g[j] - g[s]) * fl(t - s) {
                                    popped.push(t);
                                    prefix.pop();
                                    count += 1;
                                } else {
                                    break;
                                }
                            }
                            prefix.push(j);
                            undo_log.push((j, true, count));
                        }
                        prefix_end = b + 1;
                    }
                    if !prefix.is_empty() {
                        let k = self.tangent_point(g, v, prefix.len(), from_left, |k| prefix[k]);
                        from_left = k;
                        best = best.max(self.tangent_h(h, v, prefix[k]));
                    }
                }
            }
            out[slot] = angle_from_tangent(best);
        }
    }
    /// Undoes the prefix hull's additions beyond sample `b`.
    fn shrink_prefix(
        &self,
        prefix: &mut Vec<usize>,
        undo_log: &mut Vec<(usize, bool, usize)>,
        popped: &mut Vec<usize>,
        prefix_end: &mut usize,
        b: usize,
    ) {
        while *prefix_end > b + 1 {
            let (j, added, count) = undo_log.pop().expect("undo log matches prefix");
            debug_assert_eq!(j + 1, *prefix_end);
            if added {
                prefix.pop();
                for _ in 0..count {
                    prefix.push(popped.pop().expect("popped log matches"));
                }
            }
            *prefix_end -= 1;
        }
    }

    #[inline]
    fn tangent_h(&self, h: &[f64], v: &View, j: usize) -> f64 {
        let d = self.distance(v, j);
        (h[j] - v.h - d * d * self.inv_two_r) / d
    }
}

pub(crate) fn check_azimuth(azimuth: f64) -> Result<f64, TerrainError> {
    if !azimuth.is_finite() {
        return Err(TerrainError::param("azimuth", azimuth, "must be finite"));
    }
    Ok(azimuth.rem_euclid(std::f64::consts::TAU))
}

/// The horizon angle of one texel (brute force on the documented sampling).
pub fn horizon_angle(
    hf: &Heightfield,
    x: usize,
    y: usize,
    azimuth: f64,
    options: &HorizonOptions,
) -> Result<f32, TerrainError> {
    options.validate()?;
    let azimuth = check_azimuth(azimuth)?;
    if x >= hf.width() {
        return Err(TerrainError::param("x", x as f64, "must be < width"));
    }
    if y >= hf.height() {
        return Err(TerrainError::param("y", y as f64, "must be < height"));
    }
    let lines = Lines::new(hf.width(), hf.height(), hf.spacing(), azimuth);
    let (c, _) = lines.locate(x, y);
    let target = y * hf.width() + x;
    if !lines.exact {
        let grid = lines.dominant_major(hf);
        let sampler = Sampler::new(
            &lines,
            &grid,
            options.inv_two_r(),
            lines.max_steps(options.max_distance),
        );
        let mut sc = LineScratch::default();
        sampler.build(c, &mut sc);
        sampler.brute(&mut sc);
        let k = sc
            .views
            .iter()
            .position(|v| v.texel == target)
            .expect("every texel lies on its own line");
        return Ok(sc.out[k]);
    }
    let mut texels = Vec::new();
    lines.texels(c, &mut texels);
    let target = y * hf.width() + x;
    let k = texels
        .iter()
        .position(|&t| t == target)
        .expect("every texel lies on its own line");
    let h: Vec<f64> = texels
        .iter()
        .map(|&t| f64::from(hf.samples()[t]) * hf.vertical_scale())
        .collect();
    let p = Profile {
        h: &h,
        step: lines.step,
        inv_two_r: options.inv_two_r(),
    };
    let end = k
        .saturating_add(lines.max_steps(options.max_distance))
        .min(h.len() - 1);
    let mut best = f64::NEG_INFINITY;
    for j in k + 1..=end {
        best = best.max(p.tangent(k, j));
    }
    Ok(angle_from_tangent(best))
}

/// Bakes the horizon map for one azimuth (radians clockwise from north).
pub fn bake_horizon(
    hf: &Heightfield,
    azimuth: f64,
    options: &HorizonOptions,
    algorithm: Algorithm,
) -> Result<HorizonMap, TerrainError> {
    bake_with(hf, azimuth, options, algorithm, None)
}

/// [`bake_horizon`], a maximum distance's hull sweep run by `method` where given
/// (else [`window::choose`]'s).
fn bake_with(
    hf: &Heightfield,
    azimuth: f64,
    options: &HorizonOptions,
    algorithm: Algorithm,
    method: Option<window::Method>,
) -> Result<HorizonMap, TerrainError> {
    options.validate()?;
    let azimuth = check_azimuth(azimuth)?;
    let lines = Lines::new(hf.width(), hf.height(), hf.spacing(), azimuth);
    let max_steps = lines.max_steps(options.max_distance);
    let inv_two_r = options.inv_two_r();
    let scale = hf.vertical_scale();
    let samples = hf.samples();
    let method = method.unwrap_or_else(|| window::choose(&lines, max_steps));
    let by_unlimited = method == window::Method::ByUnlimited;
    if algorithm == Algorithm::HullSweep
        && method == window::Method::Rows
        && window::rows_apply(&lines, max_steps)
    {
        let grid = lines.dominant_major(hf);
        let angles = window::bake_rows(&lines, &grid, inv_two_r, max_steps, options.thread_count());
        return Ok(HorizonMap::from_angles(
            hf.width(),
            hf.height(),
            azimuth,
            angles,
        ));
    }
    let solve = |h: &[f64], g: &mut Vec<f64>, out: &mut [f32]| {
        let p = Profile {
            h,
            step: lines.step,
            inv_two_r,
        };
        match algorithm {
            Algorithm::BruteForce => brute_line(&p, max_steps, out),
            Algorithm::HullSweep => sweep_line(&p, max_steps, g, out),
        }
    };
    if lines.dominant_is_x && lines.offsets.iter().all(|&o| o == 0) {
        // East/west fast path: every line is a row, written in place.
        let width = hf.width();
        let mut angles = vec![NO_HORIZON; width * hf.height()];
        let threads = options.thread_count().clamp(1, hf.height());
        let reverse = lines.march < 0;
        let run_rows = |first_row: usize, block: &mut [f32]| {
            let (mut h, mut g, mut out) = (Vec::new(), Vec::new(), vec![0.0f32; width]);
            for (i, row_out) in block.chunks_mut(width).enumerate() {
                let row = &samples[(first_row + i) * width..][..width];
                h.clear();
                if reverse {
                    h.extend(row.iter().rev().map(|&v| f64::from(v) * scale));
                } else {
                    h.extend(row.iter().map(|&v| f64::from(v) * scale));
                }
                solve(&h, &mut g, &mut out);
                if reverse {
                    row_out
                        .iter_mut()
                        .zip(out.iter().rev())
                        .for_each(|(o, &v)| *o = v);
                } else {
                    row_out.copy_from_slice(&out);
                }
            }
        };
        if threads == 1 {
            run_rows(0, &mut angles);
        } else {
            // Blocks of rows handed out on demand, so that a thread slowed down by other
            // work on the machine does not hold up the others.
            const ROWS_PER_BLOCK: usize = 16;
            let blocks = std::sync::Mutex::new(
                angles
                    .chunks_mut(ROWS_PER_BLOCK * width)
                    .enumerate()
                    .map(|(b, block)| (b * ROWS_PER_BLOCK, block)),
            );
            std::thread::scope(|scope| {
                for _ in 0..threads {
                    let (blocks, run_rows) = (&blocks, &run_rows);
                    scope.spawn(move || {
                        loop {
                            // A poisoned lock means another worker panicked; the scope
                            // re-raises that panic, so this one just stops.
                            let next = match blocks.lock() {
                                Ok(mut iter) => iter.next(),
                                Err(_) => None,
                            };
                            let Some((first_row, block)) = next else {
                                break;
                            };
                            run_rows(first_row, block);
                        }
                    });
                }
            });
        }
        return Ok(HorizonMap {
            width,
            height: hf.height(),
            azimuth,
            angles,
        });
    }
    let ids: Vec<i64> = lines.ids().collect();
    let threads = options.thread_count().clamp(1, ids.len());
    let texels_total = hf.width() * hf.height();
    let grid = if lines.exact {
        Vec::new()
    } else {
        lines.dominant_major(hf)
    };
    let sampler = if lines.exact {
        None
    } else {
        let mut s = Sampler::new(&lines, &grid, inv_two_r, max_steps);
        s.by_unlimited = by_unlimited;
        Some(s)
    };
    // Solves the lines of `chunk` in order, handing each texel's angle to `emit`
    // (texel index, angle) in line order.
    let run_chunk = |chunk: &[i64], emit: &mut dyn FnMut(usize, f32)| {
        if let Some(sampler) = &sampler {
            let mut scs: Vec<LineScratch> =
                (0..LINE_BATCH).map(|_| LineScratch::default()).collect();
            let mut cursors = [0usize; LINE_BATCH];
            for batch in chunk.chunks(LINE_BATCH) {
                let scs = &mut scs[..batch.len()];
                sampler.build_batch(batch, scs);
                for sc in scs.iter_mut() {
                    match algorithm {
                        Algorithm::BruteForce => sampler.brute(sc),
                        Algorithm::HullSweep => sampler.sweep(sc),
                    }
                }
                // Row by row across the batch: neighbouring texels one after another.
                cursors.fill(0);
                for i in 0..lines.n_dominant {
                    for (sc, cursor) in scs.iter().zip(cursors.iter_mut()) {
                        if let Some(v) = sc.views.get(*cursor)
                            && v.i == i
                        {
                            emit(v.texel, sc.out[*cursor]);
                            *cursor += 1;
                        }
                    }
                }
            }
            return;
        }
        let (mut texels, mut h, mut g, mut out) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for &c in chunk {
            lines.texels(c, &mut texels);
            if texels.is_empty() {
                continue;
            }
            h.clear();
            h.extend(texels.iter().map(|&t| f64::from(samples[t]) * scale));
            out.clear();
            out.resize(texels.len(), 0.0f32);
            solve(&h, &mut g, &mut out);
            for (&t, &a) in texels.iter().zip(&out) {
                emit(t, a);
            }
        }
    };
    let mut angles = vec![NO_HORIZON; texels_total];
    if threads == 1 {
        // One worker writes straight into the map.
        run_chunk(&ids, &mut |t, a| angles[t] = a);
    } else {
        // Contiguous chunks of lines with about equal texel counts.
        let mut chunks: Vec<&[i64]> = Vec::with_capacity(threads);
        {
            let mut scratch = Vec::new();
            let mut start = 0;
            let mut acc = 0;
            for (i, &c) in ids.iter().enumerate() {
                lines.texels(c, &mut scratch);
                acc += scratch.len();
                if acc * threads >= texels_total * (chunks.len() + 1) && chunks.len() + 1 < threads
                {
                    chunks.push(&ids[start..=i]);
                    start = i + 1;
                }
            }
            chunks.push(&ids[start..]);
        }
        let per_chunk: Vec<Vec<(usize, f32)>> = std::thread::scope(|scope| {
            let handles: Vec<_> = chunks
                .iter()
                .map(|&chunk| {
                    let run_chunk = &run_chunk;
                    scope.spawn(move || {
                        let mut results = Vec::new();
                        run_chunk(chunk, &mut |t, a| results.push((t, a)));
                        results
                    })
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("horizon worker panicked"))
                .collect()
        });
        // Scatter the line-ordered results into the row-major map.
        for &(t, a) in per_chunk.iter().flatten() {
            angles[t] = a;
        }
    }
    Ok(HorizonMap {
        width: hf.width(),
        height: hf.height(),
        azimuth,
        angles,
    })
}

/// Bakes the east and west maps of seed 000.
pub fn bake_east_west(
    hf: &Heightfield,
    options: &HorizonOptions,
    algorithm: Algorithm,
) -> Result<EastWestHorizon, TerrainError> {
    Ok(EastWestHorizon {
        east: bake_horizon(hf, EAST, options, algorithm)?,
        west: bake_horizon(hf, WEST, options, algorithm)?,
    })
}

/// Bakes `count` (4..=64) equally spaced azimuths, layer `k` at `k · 2π / count`.
pub fn bake_azimuths(
    hf: &Heightfield,
    count: usize,
    options: &HorizonOptions,
    algorithm: Algorithm,
) -> Result<AzimuthHorizonMaps, TerrainError> {
    if !(MIN_AZIMUTHS..=MAX_AZIMUTHS).contains(&count) {
        return Err(TerrainError::param(
            "count",
            count as f64,
            "number of azimuths must be in 4..=64",
        ));
    }
    options.validate()?;
    let azimuth = |k: usize| k as f64 * std::f64::consts::TAU / count as f64;
    let threads = options.thread_count().clamp(1, count);
    if threads == 1 {
        let layers = (0..count)
            .map(|k| bake_horizon(hf, azimuth(k), options, algorithm))
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(AzimuthHorizonMaps { layers });
    }
    // Whole azimuths are handed out on demand to the workers, each baked on one
    // thread (no scatter, no per-azimuth start-up of threads); the azimuths off the
    // axes and diagonals, about twice the work, go first so that the last ones to
    // finish are short. Every map is computed the same way whatever the thread count.
    let one = HorizonOptions {
        threads: NonZeroUsize::new(1),
        ..*options
    };
    let mut order: Vec<usize> = (0..count).collect();
    order.sort_by_key(|&k| Lines::new(hf.width(), hf.height(), 1.0, azimuth(k)).exact);
    let next = std::sync::atomic::AtomicUsize::new(0);
    let slots: Vec<std::sync::Mutex<Option<Result<HorizonMap, TerrainError>>>> =
        (0..count).map(|_| std::sync::Mutex::new(None)).collect();
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&k) = order.get(i) else {
                        break;
                    };
                    let map = bake_horizon(hf, azimuth(k), &one, algorithm);
                    // A poisoned lock means another worker panicked; the scope
                    // re-raises that panic.
                    if let Ok(mut slot) = slots[k].lock() {
                        *slot = Some(map);
                    }
                }
            });
        }
    });
    let layers = slots
        .into_iter()
        .map(|slot| {
            slot.into_inner()
                .ok()
                .flatten()
                .expect("every azimuth was baked")
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(AzimuthHorizonMaps { layers })
}

#[cfg(test)]
mod tests {
    use super::{LineScratch, Lines, NEAR_STEPS, Sampler, first_true};
    use crate::Heightfield;

    /// The near field looked up by [`Sampler::build`] equals
    /// [`Sampler::near_best`] bit for bit for every view of every line, including the
    /// views whose ray reaches the line's last texel or leaves the map, and maximum
    /// distances shorter than the near field; and [`Sampler::build_batch`] gives
    /// every line of a batch exactly what [`Sampler::build`] gives it alone.
    #[test]
    fn build_near_field_is_near_best() {
        let (w, h) = (23, 17);
        let hf = Heightfield::from_fn(w, h, 30.0, |x, y| {
            let (x, y) = (x as f32, y as f32);
            // Rough terrain with exact zeros and negative heights.
            ((x * 1.7 + y * 0.9).sin() * 300.0 + (x * y * 0.37).cos() * 120.0).round() - 60.0
        })
        .unwrap();
        // 32 even azimuths, and slopes t = ±1/2, ±1/4 where some step k·t is (about) an
        // integer: the near field's per-texel path instead of the row-wise one.
        let mut azimuths: Vec<f64> = (0..32)
            .map(|k| k as f64 * std::f64::consts::TAU / 32.0)
            .collect();
        for t in [0.5f64, 0.25] {
            azimuths.extend([
                super::EAST + t.atan(),
                super::EAST - t.atan(),
                super::WEST + t.atan(),
                std::f64::consts::PI - t.atan(),
            ]);
        }
        for (k, &azimuth) in azimuths.iter().enumerate() {
            let lines = Lines::new(w, h, hf.spacing(), azimuth);
            if lines.exact {
                continue;
            }
            let grid = lines.dominant_major(&hf);
            for max_steps in [1, 2, NEAR_STEPS, 7, usize::MAX] {
                for inv_two_r in [0.0, 0.5 / 6.371e6] {
                    let sampler = Sampler::new(&lines, &grid, inv_two_r, max_steps);
                    // A batch of lines is built as each line on its own.
                    let ids: Vec<i64> = lines.ids().collect();
                    let mut batch: Vec<LineScratch> =
                        (0..5).map(|_| LineScratch::default()).collect();
                    let mut sc = LineScratch::default();
                    for group in ids.chunks(5) {
                        sampler.build_batch(group, &mut batch[..group.len()]);
                        for (&c, b) in group.iter().zip(&batch) {
                            sampler.build(c, &mut sc);
                            let bits =
                                |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                            assert_eq!(bits(&b.h), bits(&sc.h), "line {c}");
                            assert_eq!(bits(&b.g), bits(&sc.g), "line {c}");
                            let key = |v: &super::View| {
                                (v.i, v.texel, [v.h, v.m, v.e, v.g, v.near].map(f64::to_bits))
                            };
                            let (kb, ks): (Vec<_>, Vec<_>) = (
                                b.views.iter().map(key).collect(),
                                sc.views.iter().map(key).collect(),
                            );
                            assert_eq!(kb, ks, "line {c}");
                        }
                    }
                    for c in lines.ids() {
                        sampler.build(c, &mut sc);
                        let last = sc.views.last().map_or(0, |v| v.i);
                        for v in &sc.views {
                            let expected = sampler.near_best(v, last);
                            assert_eq!(
                                v.near.to_bits(),
                                expected.to_bits(),
                                "azimuth {k}, K {max_steps}, line {c}, view {}",
                                v.i
                            );
                        }
                    }
                }
            }
        }
    }

    /// The row-by-row bake of a maximum distance ([`super::window::bake_rows`]) gives
    /// [`super::Algorithm::BruteForce`]'s angles bit for bit: every window length from
    /// none to past the map, odd azimuths (the per-texel rows where `u·t` is about an
    /// integer, slopes 1/2, 1/3, 1/4) and the axes and diagonals, curvature on and
    /// off, maps narrower and wider than the window, 1 and 3 threads.
    #[test]
    fn rows_are_brute_force_bit_for_bit() {
        use super::{Algorithm, HorizonOptions, bake_horizon, window};
        let rough = |x: usize, y: usize| {
            let (x, y) = (x as f32, y as f32);
            ((x * 1.7 + y * 0.9).sin() * 300.0 + (x * y * 0.37).cos() * 120.0).round() - 60.0
        };
        let mut azimuths: Vec<f64> = (0..32)
            .map(|k| k as f64 * std::f64::consts::TAU / 32.0)
            .collect();
        azimuths.extend([0.3, 1.0, 2.2, 3.9, 5.5, 0.05]);
        for t in [0.5f64, 1.0 / 3.0, 0.25] {
            azimuths.extend([
                super::EAST + t.atan(),
                super::EAST - t.atan(),
                super::WEST + t.atan(),
                std::f64::consts::PI - t.atan(),
                t.atan(),
            ]);
        }
        // Flat stretches of +0 and −0 and plateaus: tangents that tie at ±0 and at
        // equal values (the maximum must keep the same one).
        let zeros = |x: usize, y: usize| match (x * 7 + y * 3) % 5 {
            0 => -0.0,
            1 | 2 => 0.0,
            3 => 30.0,
            _ => 60.0,
        };
        // 150 columns: blocks of texels whose samples cross 2, 4, …, 128 (weights per
        // binade) and whose windows leave the map.
        type Height<'a> = &'a dyn Fn(usize, usize) -> f32;
        let maps: [(usize, usize, Height); 5] = [
            (150, 61, &rough),
            (23, 17, &rough),
            (9, 40, &rough),
            (40, 3, &rough),
            (19, 21, &zeros),
        ];
        for (w, h, height) in maps {
            let hf = Heightfield::from_fn(w, h, 30.0, height).unwrap();
            for &azimuth in &azimuths {
                let lines = Lines::new(w, h, hf.spacing(), azimuth);
                let grid = lines.dominant_major(&hf);
                for max_steps in [0, 1, 3, NEAR_STEPS, 5, 6, 7, 9, 13, 22, 39, 60] {
                    for effective_radius in [None, Some(6.371e6)] {
                        let options = HorizonOptions {
                            effective_radius,
                            max_distance: Some(max_steps as f64 * lines.step),
                            threads: std::num::NonZeroUsize::new(1),
                        };
                        assert_eq!(lines.max_steps(options.max_distance), max_steps);
                        let brute =
                            bake_horizon(&hf, azimuth, &options, Algorithm::BruteForce).unwrap();
                        for threads in [1, 3] {
                            let rows = window::bake_rows(
                                &lines,
                                &grid,
                                options.inv_two_r(),
                                max_steps,
                                threads,
                            );
                            let bits =
                                |a: &[f32]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                            assert_eq!(
                                bits(&rows),
                                bits(brute.angles()),
                                "{w}x{h}, azimuth {azimuth}, K {max_steps}, {effective_radius:?}, {threads} threads"
                            );
                        }
                    }
                }
            }
        }
    }

    /// A maximum distance baked through the unlimited sweep
    /// ([`super::window::Method::ByUnlimited`]: the window only for the texels whose
    /// horizon point over the whole line lies beyond it) and by the windowed sweep
    /// gives [`super::Algorithm::BruteForce`]'s angles bit for bit: window lengths from
    /// none to past the map, even and odd azimuths (the axes and diagonals' texel
    /// lines and the others' line samples), curvature on and off, a generated
    /// mountain map (horizon points near and far), rough maps, and flat stretches of
    /// `+0` and `−0` (tied zero tangents), 1 and 3 threads.
    #[test]
    fn limited_sweeps_are_brute_force_bit_for_bit() {
        use super::window::Method;
        use super::{Algorithm, HorizonOptions, bake_with};
        let rough = |x: usize, y: usize| {
            let (x, y) = (x as f32, y as f32);
            ((x * 1.7 + y * 0.9).sin() * 300.0 + (x * y * 0.37).cos() * 120.0).round() - 60.0
        };
        let zeros = |x: usize, y: usize| match (x * 7 + y * 3) % 5 {
            0 => -0.0,
            1 | 2 => 0.0,
            3 => 30.0,
            _ => 60.0,
        };
        let mountains = crate::generate::generate(&crate::generate::GeneratorParams {
            amplitude: 2000.0,
            wavelength: 1500.0,
            octaves: 6,
            ..crate::generate::GeneratorParams::new(90, 70, 30.0, 2010)
        })
        .unwrap();
        let mut maps = vec![
            mountains,
            Heightfield::from_fn(61, 23, 30.0, rough).unwrap(),
            Heightfield::from_fn(9, 40, 30.0, rough).unwrap(),
            Heightfield::from_fn(19, 21, 30.0, zeros).unwrap(),
        ];
        maps.push(Heightfield::from_fn(40, 3, 30.0, rough).unwrap());
        let mut azimuths: Vec<f64> = (0..16)
            .map(|k| k as f64 * std::f64::consts::TAU / 16.0)
            .collect();
        azimuths.extend([0.3, 1.0, 2.2, 3.9, 5.5, 0.05]);
        let bits = |a: &[f32]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for hf in &maps {
            for &azimuth in &azimuths {
                let step = Lines::new(hf.width(), hf.height(), hf.spacing(), azimuth).step;
                for max_steps in [0, 1, 3, NEAR_STEPS, 5, 6, 9, 17, 30, 55, 89, 200] {
                    for effective_radius in [None, Some(6.371e6)] {
                        let options = HorizonOptions {
                            effective_radius,
                            max_distance: Some(max_steps as f64 * step),
                            threads: std::num::NonZeroUsize::new(1),
                        };
                        let brute =
                            bake_with(hf, azimuth, &options, Algorithm::BruteForce, None).unwrap();
                        for method in [Method::Windowed, Method::ByUnlimited] {
                            for threads in [1, 3] {
                                let options = HorizonOptions {
                                    threads: std::num::NonZeroUsize::new(threads),
                                    ..options
                                };
                                let sweep = bake_with(
                                    hf,
                                    azimuth,
                                    &options,
                                    Algorithm::HullSweep,
                                    Some(method),
                                )
                                .unwrap();
                                assert_eq!(
                                    bits(sweep.angles()),
                                    bits(brute.angles()),
                                    "{}x{}, azimuth {azimuth}, K {max_steps}, \
                                     {effective_radius:?}, {method:?}, {threads} threads",
                                    hf.width(),
                                    hf.height()
                                );
                            }
                        }
                    }
                }
            }
        }
    }

    /// The galloping search finds the first true position from every guess, as a
    /// bisection of the whole range does (the tangent searches rely on it).
    #[test]
    fn first_true_from_any_guess_is_the_bisection_answer() {
        for len in 1..40 {
            for answer in 0..=len {
                let expected = answer.min(len - 1);
                for guess in 0..len + 3 {
                    let got = first_true(len, guess, |i| {
                        assert!(i + 1 < len, "pred called past len − 2: {i} (len {len})");
                        i >= answer
                    });
                    assert_eq!(got, expected, "len {len}, answer {answer}, guess {guess}");
                }
            }
        }
    }
}
