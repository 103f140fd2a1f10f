//! The hull sweep over one line off the axes and diagonals, unlimited or with a
//! maximum distance (module docs, "A maximum distance").

use super::super::hull::{can_rise, first_true, push_left};
use super::super::{NO_HORIZON, angle_from_tangent, fl};
use super::{LineScratch, NEAR_STEPS, Sampler, View};

impl Sampler<'_> {
    /// The hull sweep over line `c` (after [`Sampler::build`]): the same samples as
    /// [`Sampler::brute`]; the far samples of each window enter upper convex hulls as
    /// the sweep walks back along the line, and each texel's horizon point is its
    /// tangent point on them.
    pub(in crate::horizon) fn sweep(&self, sc: &mut LineScratch) {
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
}
