//! The digital-line geometry of one azimuth on one map (module docs, "Which samples").

use crate::Heightfield;

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
    pub(super) fn dominant_at(&self, i: usize) -> usize {
        if self.march > 0 {
            i
        } else {
            self.n_dominant - 1 - i
        }
    }

    /// Texel index of dominant coordinate `u` and minor coordinate `m`.
    #[inline]
    pub(super) fn texel(&self, u: usize, m: usize) -> usize {
        if self.dominant_is_x {
            m * self.width + u
        } else {
            u * self.width + m
        }
    }

    /// The heights in metres laid out dominant-major (`grid[u · n_minor + m]`), so
    /// that walking a line reads memory almost in order.
    pub(super) fn dominant_major(&self, hf: &Heightfield) -> Vec<f64> {
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
    pub(super) fn height_between(&self, grid: &[f64], u: usize, x: f64) -> Option<f64> {
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
    pub(super) fn locate(&self, x: usize, y: usize) -> (i64, usize) {
        let (u, m) = if self.dominant_is_x { (x, y) } else { (y, x) };
        (m as i64 - self.offsets[u], u)
    }

    /// Texel indices of line `c` in marching order (appended to `out`).
    pub(super) fn texels(&self, c: i64, out: &mut Vec<usize>) {
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
    pub(super) fn max_steps(&self, max_distance: Option<f64>) -> usize {
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

/// The height at minor position `x` (`0 ≤ x ≤ row.len() − 1`) of a dominant-major row,
/// linear between the two texels around `x`: [`Lines::height_between`] without its
/// range checks (`x as i64` truncates to the floor for `x ≥ 0`).
#[inline(always)]
pub(super) fn lerp_row(row: &[f64], x: f64) -> f64 {
    let m = x as i64 as usize;
    let f = x - m as i64 as f64;
    let a = row[m];
    if f == 0.0 {
        a
    } else {
        a + (row[m + 1] - a) * f
    }
}
