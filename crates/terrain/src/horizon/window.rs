//! A maximum distance of `K` steps, row by row: the brute force of every texel's
//! window, computed for a whole grid row at a time (`horizon` module docs,
//! "A maximum distance").
//!
//! Off the axes and diagonals, texel `(u₀, m)` lies on line `c = m − round(u₀·t)` and
//! its far sample `k` (`NEAR_STEPS < k ≤ K`) is the line's sample on grid row
//! `u₀ ± k`, at minor position `x = c + u·t` and distance `k·L − e(u₀)`, where
//! `e` depends only on `u₀`. So for one row `u₀` every texel reads, at step `k`, one
//! other row at the same fractional offset; where that offset is not within 2^−20 of
//! an integer, `⌊x⌋ = m − round(u₀·t) + ⌊u·t⌋` for every texel (the argument of
//! [`Sampler::near_field`]), and the step is a loop over contiguous slices that the
//! compiler vectorises. On the axes and diagonals the samples are texels, the row
//! shifted by a whole number of texels.
//!
//! Every sample is evaluated with [`Sampler::brute`]'s (or `brute_line`'s)
//! operations in the same order, skipped where it skips (outside the map), and the
//! maximum is taken from the same start (the near field, or `−∞`) in the same order
//! of `k`, so the angles are those of [`super::Algorithm::BruteForce`] bit for bit.
//! The cost is `O(K)` per texel with no branches, against the windowed hull sweep's
//! two hulls and searches; [`choose`] picks it for short windows.

use super::lines::{Lines, lerp_row};
use super::sampler::{NEAR_STEPS, Sampler, View};
use super::{angle_from_tangent, fl};

/// Most steps `K` for which a limited bake off the axes and diagonals runs row by
/// row rather than as a windowed hull sweep: the rows' cost grows with `K`, the
/// sweep's does not, and they cross at about 4 km at 30 m (`K` 133 on the axes;
/// the timings are in `docs/tradeoffs/terrain_max_distance.md`).
pub(crate) const ROW_MAX_STEPS: usize = 128;

/// [`ROW_MAX_STEPS`] on the axes and diagonals, whose windowed sweep keeps the
/// unlimited hull in the same walk and so costs less there: rows are the cheaper up
/// to about 2 km at 30 m (`K` 66 on the axes, 47 on the diagonals). The instruction
/// counts and CPU times are in `docs/tradeoffs/terrain_max_distance.md`.
pub(crate) const EXACT_ROW_MAX_STEPS: usize = 66;

/// How a hull-sweep bake with a maximum distance is run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Method {
    /// Row by row ([`bake_rows`]), where [`rows_apply`] (else as `Windowed`).
    Rows,
    /// The unlimited sweep, whose horizon point is the window's where it lies
    /// within it; the windowed sweep for the other texels only. On the axes and
    /// diagonals the windowed sweep keeps the unlimited hull itself, so both
    /// methods are the same sweep there.
    ByUnlimited,
    /// The windowed hull sweep for every texel (the unlimited one where the window
    /// reaches the lines' ends).
    Windowed,
}

/// `true` when [`bake_rows`] can bake a maximum distance of `max_steps` (`K`): a
/// window shorter than the lines, with far samples.
pub(crate) fn rows_apply(lines: &Lines, max_steps: usize) -> bool {
    let first = if lines.exact { 1 } else { NEAR_STEPS + 1 };
    max_steps >= first && max_steps < lines.n_dominant - 1
}

/// Fewest steps `K` for which a limited bake runs through the unlimited sweep
/// ([`Method::ByUnlimited`]) rather than the windowed one (`K` is per azimuth: at
/// 6 km, 200 on the axes, 184 at 22.5° off them, 141 on the diagonals). Below about
/// 5 km at 30 m (`K` 166 on the axes) the unlimited sweep first costs more than the
/// windowed sweep alone, up to 12 km the two are about even, and at 20 km it is the
/// cheaper (the timings are in `docs/tradeoffs/terrain_max_distance.md`).
pub(crate) const UNLIMITED_MIN_STEPS: usize = 167;

/// How [`super::bake_horizon`]'s hull sweep runs a maximum distance of `max_steps`
/// (`K`): row by row up to [`ROW_MAX_STEPS`] ([`EXACT_ROW_MAX_STEPS`] on the axes
/// and diagonals), through the unlimited sweep from [`UNLIMITED_MIN_STEPS`],
/// windowed in between; a window as long as the lines is
/// no limit (`Windowed`: the sweep of whole lines).
pub(crate) fn choose(lines: &Lines, max_steps: usize) -> Method {
    let row_max = if lines.exact {
        EXACT_ROW_MAX_STEPS
    } else {
        ROW_MAX_STEPS
    };
    if max_steps >= lines.n_dominant.saturating_sub(1) {
        Method::Windowed
    } else if max_steps <= row_max {
        Method::Rows
    } else if max_steps >= UNLIMITED_MIN_STEPS {
        Method::ByUnlimited
    } else {
        Method::Windowed
    }
}

/// `f64::max` as the brute force's is compiled (`t` replaces the running maximum
/// only when greater: on a tie of `+0` and `−0` the running maximum stays; a NaN `t`
/// is skipped), in one instruction (`maxpd`) where `f64::max` needs four more for a
/// NaN `best`, which cannot occur here.
#[inline(always)]
fn max(best: f64, t: f64) -> f64 {
    if t > best { t } else { best }
}

/// Where the lines' samples lie on one grid row `u`: `u·t`, its floor, and whether
/// every texel's sample on that row has the same two texels relative to it.
#[derive(Debug, Clone, Copy)]
struct RowShift {
    exact: f64,
    floor: i64,
    fast: bool,
}

/// The largest tangent of every texel (dominant-major, `acc[u · n_minor + m]` for
/// `u` in `rows`), starting from `acc`'s values: the far field of each window,
/// [`Sampler::brute`]'s samples and arithmetic.
///
/// On the vectorised path the samples of one step whose positions `x` share a binade
/// (`⌊x⌋ = 0`, or `⌊x⌋` in `[2^j, 2^(j+1))`) have the same weight `x − ⌊x⌋`:
/// `x = c + u·t` rounded, with `c` an integer, is `c` plus `u·t` rounded to the
/// binade's spacing (at most 1/2, so `c` is an even multiple of it and the tie rule
/// does not see `c`). So the weight is computed once per binade, from its first
/// texel, with the brute force's operations.
fn far_rows(
    sampler: &Sampler<'_>,
    shifts: &[RowShift],
    rows: std::ops::Range<usize>,
    acc: &mut [f64],
) {
    let l = sampler.lines;
    let (n, nm) = (l.n_dominant, l.n_minor);
    let (t, step) = (l.slope, l.step);
    let top = (nm - 1) as f64;
    // As in `Sampler::build_batch`.
    let foot = l.march as f64 * t * step / (1.0 + t * t);
    let m_f: Vec<f64> = (0..nm).map(fl).collect();
    let mut ids = Vec::with_capacity(nm);
    for (u0, out) in rows.zip(acc.chunks_mut(nm)) {
        let offset = l.offsets[u0];
        let of = offset as f64;
        let e = foot * (of - shifts[u0].exact);
        let own = &sampler.grid[u0 * nm..][..nm];
        // `c as f64` of every texel's line (exact).
        ids.clear();
        ids.extend(m_f.iter().map(|&m| m - of));
        for k in NEAR_STEPS + 1..=sampler.max_steps {
            let uj = u0 as i64 + l.march * k as i64;
            if uj < 0 || uj >= n as i64 {
                break;
            }
            let uj = uj as usize;
            let d = fl(k) * step - e;
            let drop = d * d * sampler.inv_two_r;
            let src = &sampler.grid[uj * nm..][..nm];
            let RowShift { exact, floor, fast } = shifts[uj];
            if fast {
                // Texels whose sample has both texels in the row: ⌊x⌋ = m − offset +
                // floor in [0, nm − 2].
                let lo = (offset - floor).max(0);
                let hi = (nm as i64 - 2 + offset - floor).min(nm as i64 - 1);
                if hi < lo {
                    continue;
                }
                let qf = floor as f64;
                let (mut lane, hi) = (lo as usize, hi as usize);
                while lane <= hi {
                    // One binade of x: ⌊x⌋ in {0}, or [2^j, 2^(j+1) − 1].
                    let a0 = (lane as i64 - offset + floor) as usize;
                    let a_end = if a0 == 0 { 0 } else { (2 << a0.ilog2()) - 1 };
                    let len = (a_end - a0).min(hi - lane) + 1;
                    // The weight of the binade's first sample, x − ⌊x⌋, ⌊x⌋ = c + floor.
                    let c = ids[lane];
                    let x = c + exact;
                    let f = x - (c + qf);
                    let iter = out[lane..lane + len]
                        .iter_mut()
                        .zip(&own[lane..lane + len])
                        .zip(&src[a0..a0 + len])
                        .zip(&src[a0 + 1..a0 + 1 + len]);
                    for (((o, &hp), &a), &b) in iter {
                        let h = a + (b - a) * f;
                        *o = max(*o, (h - hp - drop) / d);
                    }
                    lane += len;
                }
            } else {
                for m in 0..nm {
                    let x = (m_f[m] - of) + exact;
                    if x >= 0.0 && x <= top {
                        let h = lerp_row(src, x);
                        out[m] = max(out[m], (h - own[m] - drop) / d);
                    }
                }
            }
        }
    }
}

/// [`far_rows`] on the axes and diagonals: the samples are texels, step `k` of row
/// `u₀` reads row `u₀ ± k` shifted by `round(±k·t)` texels, at distance `k·L`, from
/// `−∞` (`brute_line`'s samples and arithmetic).
fn exact_rows(
    lines: &Lines,
    grid: &[f64],
    inv_two_r: f64,
    max_steps: usize,
    rows: std::ops::Range<usize>,
    acc: &mut [f64],
) {
    let (n, nm) = (lines.n_dominant, lines.n_minor);
    for (u0, out) in rows.zip(acc.chunks_mut(nm)) {
        let own = &grid[u0 * nm..][..nm];
        for k in 1..=max_steps {
            let uj = u0 as i64 + lines.march * k as i64;
            if uj < 0 || uj >= n as i64 {
                break;
            }
            let uj = uj as usize;
            let d = fl(k) * lines.step;
            let drop = d * d * inv_two_r;
            let src = &grid[uj * nm..][..nm];
            let shift = lines.offsets[uj] - lines.offsets[u0];
            // Texels whose sample lies in the row: 0 ≤ m + shift < nm.
            let lo = (-shift).max(0);
            let hi = (nm as i64 - 1 - shift).min(nm as i64 - 1);
            if hi < lo {
                continue;
            }
            let a0 = (lo + shift) as usize;
            let (lo, len) = (lo as usize, (hi - lo + 1) as usize);
            let iter = out[lo..lo + len]
                .iter_mut()
                .zip(&own[lo..lo + len])
                .zip(&src[a0..a0 + len]);
            for ((o, &hp), &h) in iter {
                *o = max(*o, (h - hp - drop) / d);
            }
        }
    }
}

/// The near field of every texel as [`Sampler::build_batch`] leaves it in its view:
/// [`Sampler::near_field`], with the rays of the last `NEAR_STEPS` texels of each
/// line stopped at the line's last texel ([`Sampler::near_best`]).
///
/// Takes the sampler's near field (which [`far_rows`] does not read).
fn near_of_views(sampler: &mut Sampler<'_>) -> Vec<f64> {
    let l = sampler.lines;
    let (n, nm) = (l.n_dominant, l.n_minor);
    let mut near = std::mem::take(&mut sampler.near);
    let steps = NEAR_STEPS.min(sampler.max_steps);
    let ids = l.ids();
    let first = *ids.start();
    // The last marching position of every line's texels.
    let mut last = vec![usize::MAX; (ids.end() - first + 1) as usize];
    for i in 0..n {
        let o = l.offsets[l.dominant_at(i)];
        // Lines with a texel on this row: 0 ≤ c + o < nm.
        let (c0, c1) = (-o, nm as i64 - 1 - o);
        last[(c0 - first) as usize..=(c1 - first) as usize].fill(i);
    }
    for (c, &end) in (first..).zip(&last) {
        if end == usize::MAX {
            continue;
        }
        for s in 0..steps.min(end + 1) {
            let i = end - s;
            let u = l.dominant_at(i);
            let m = c + l.offsets[u];
            if m < 0 || m >= nm as i64 {
                break;
            }
            let m = m as usize;
            let view = View {
                i,
                texel: 0,
                h: sampler.grid[u * nm + m],
                m: m as f64,
                e: 0.0,
                g: 0.0,
                near: 0.0,
            };
            near[u * nm + m] = sampler.near_best(&view, end);
        }
    }
    near
}

/// Bakes one azimuth row by row with a maximum distance of `max_steps` (`K`):
/// the angles, row-major. Rows of the grid are split over `threads`.
pub(crate) fn bake_rows(
    lines: &Lines,
    grid: &[f64],
    inv_two_r: f64,
    max_steps: usize,
    threads: usize,
) -> Vec<f32> {
    let (n, nm) = (lines.n_dominant, lines.n_minor);
    let sampler;
    let (mut acc, shifts) = if lines.exact {
        sampler = None;
        (vec![f64::NEG_INFINITY; n * nm], Vec::new())
    } else {
        let mut s = Sampler::new(lines, grid, inv_two_r, max_steps);
        let near = near_of_views(&mut s);
        let t = lines.slope;
        let shifts: Vec<RowShift> = (0..n)
            .map(|u| {
                let exact = fl(u) * t;
                let floor = exact.floor();
                let w = exact - floor;
                // |c| < 2^29 and |u·t| < 2^29: |x| < 2^30, rounded to within 2^−23,
                // so ⌊x⌋ = c + floor where the weight is 2^−20 from 0 and 1.
                let fast = (1.0 / 1_048_576.0..=1.0 - 1.0 / 1_048_576.0).contains(&w)
                    && nm < 1 << 28
                    && n < 1 << 28;
                RowShift {
                    exact,
                    floor: floor as i64,
                    fast,
                }
            })
            .collect();
        sampler = Some(s);
        (near, shifts)
    };
    let run = |first_row: usize, acc: &mut [f64], out: &mut [f32]| {
        let rows = first_row..first_row + acc.len() / nm;
        match &sampler {
            Some(s) => far_rows(s, &shifts, rows, acc),
            None => exact_rows(lines, grid, inv_two_r, max_steps, rows, acc),
        }
        for (o, &a) in out.iter_mut().zip(acc.iter()) {
            *o = angle_from_tangent(a);
        }
    };
    let mut dominant_major = vec![0.0f32; n * nm];
    let threads = threads.clamp(1, n);
    if threads == 1 {
        run(0, &mut acc, &mut dominant_major);
    } else {
        let rows_per = n.div_ceil(threads);
        std::thread::scope(|scope| {
            for (b, (acc, out)) in acc
                .chunks_mut(rows_per * nm)
                .zip(dominant_major.chunks_mut(rows_per * nm))
                .enumerate()
            {
                let run = &run;
                scope.spawn(move || run(b * rows_per, acc, out));
            }
        });
    }
    if !lines.dominant_is_x {
        return dominant_major;
    }
    // Dominant x: `dominant_major[x · height + y]` to row-major.
    let mut angles = vec![0.0f32; n * nm];
    for (x, column) in dominant_major.chunks(nm).enumerate() {
        for (y, &a) in column.iter().enumerate() {
            angles[y * n + x] = a;
        }
    }
    angles
}
