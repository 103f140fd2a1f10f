//! Upper convex hulls of line samples and the searches on them, shared by both
//! sweeps (curvature-corrected frame `g`, module docs "Algorithms").

use super::fl;

/// `true` when, seen from `q` (left of both), `b` is at least as high in slope as
/// `a`, in the curvature-corrected frame `g` (indices are positions along the line).
#[inline]
pub(super) fn not_lower(g: &[f64], q: usize, a: usize, b: usize) -> bool {
    (g[b] - g[q]) * fl(a - q) >= (g[a] - g[q]) * fl(b - q)
}

/// Adds sample `p`, left of every point, to the upper hull `hull` (indices along the
/// line, leftmost last) in the curvature-corrected frame `g`.
#[inline]
pub(super) fn push_left(g: &[f64], hull: &mut Vec<usize>, p: usize) {
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

/// The first `i < len` with `pred(i)`, `pred` monotone (false, then true) on
/// `0..len − 1` and taken as true at `len − 1`: galloping from `guess` (1, 2, 4, …
/// positions towards the answer), then bisecting the bracket. The same answer as a
/// bisection of the whole range, in O(1) when the guess is at or next to it.
#[inline]
pub(super) fn first_true(len: usize, guess: usize, pred: impl Fn(usize) -> bool) -> usize {
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
pub(super) fn can_rise(
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
