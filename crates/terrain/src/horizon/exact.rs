//! The lines of the axes and diagonals, whose samples are texels and so also the
//! viewpoints: brute force and the Timonen–Westerholm sweep.

use super::hull::{can_rise, first_true, not_lower};
use super::{NO_HORIZON, angle_from_tangent, fl};

/// Profile of one line: heights in marching order and the per-line constants.
pub(super) struct Profile<'a> {
    pub(super) h: &'a [f64],
    pub(super) step: f64,
    pub(super) inv_two_r: f64,
}

impl Profile<'_> {
    /// Tangent of the elevation of sample `j` seen from sample `k < j`: the one
    /// formula both algorithms evaluate.
    #[inline]
    pub(super) fn tangent(&self, k: usize, j: usize) -> f64 {
        let d = fl(j - k) * self.step;
        (self.h[j] - self.h[k] - d * d * self.inv_two_r) / d
    }
}

/// Brute force over one line.
pub(super) fn brute_line(p: &Profile<'_>, max_steps: usize, out: &mut [f32]) {
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
pub(super) fn sweep_line(p: &Profile<'_>, max_steps: usize, g: &mut Vec<f64>, out: &mut [f32]) {
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
