//! The lines off the axes and diagonals: each texel's near field on its own ray, the
//! far field on its line's samples (module docs, "Which samples").

use super::hull::first_true;
use super::lines::{Lines, lerp_row};
use super::{angle_from_tangent, fl};

mod sweep;

/// Neighbouring lines built, swept and written together (off the axes and diagonals).
pub(super) const LINE_BATCH: usize = 8;

/// Steps along each texel's own exact ray before the shared line takes over (off the
/// axes and diagonals): the near field, where a lateral offset of half a texel matters
/// most, is sampled exactly; beyond it every texel of a line reads the line's samples.
pub const NEAR_STEPS: usize = 4;

/// One texel (viewpoint) of a line off the axes and diagonals.
#[derive(Debug, Clone, Copy)]
pub(super) struct View {
    /// Marching position of the texel's dominant coordinate.
    pub(super) i: usize,
    /// Row-major texel index.
    pub(super) texel: usize,
    /// Height, metres.
    pub(super) h: f64,
    /// Minor coordinate of the texel.
    pub(super) m: f64,
    /// Where the texel's foot lies along the line, relative to the line's sample at the
    /// same marching position, metres (`s_P = i · L + e`).
    pub(super) e: f64,
    /// Curvature-corrected height of the viewpoint, `h − s_P² / (2R)`.
    pub(super) g: f64,
    /// The near field's largest tangent ([`Sampler::near_best`]).
    pub(super) near: f64,
}

/// Scratch buffers of one worker for the lines off the axes and diagonals.
#[derive(Debug, Default)]
pub(super) struct LineScratch {
    /// Line samples in marching order (NaN where the line is outside the map).
    pub(super) h: Vec<f64>,
    /// `h − s² / (2R)`, `s = i · L`.
    pub(super) g: Vec<f64>,
    pub(super) views: Vec<View>,
    pub(super) hull: Vec<usize>,
    pub(super) prefix: Vec<usize>,
    /// (sample, added, popped count) per sample offered to the prefix hull.
    pub(super) undo_log: Vec<(usize, bool, usize)>,
    pub(super) popped: Vec<usize>,
    /// Per view: its largest tangent where the unlimited sweep found it, else NaN
    /// ([`Sampler::sweep_by_unlimited`]).
    pub(super) known: Vec<f64>,
    /// Per view whose `known` is NaN: where its window's maximum starts (the near
    /// field, or a larger tangent of a window sample) and the last sample up to which
    /// that is the window's maximum (none: `0`).
    pub(super) lower: Vec<(f64, usize)>,
    /// The running maximum of `g` over the next block, from its first sample: the
    /// bound that lets a window skip its part-B search.
    pub(super) prefix_max: Vec<f64>,
    pub(super) out: Vec<f32>,
}

/// One azimuth's sampling off the axes and diagonals (module docs, "Which samples").
pub(super) struct Sampler<'a> {
    pub(super) lines: &'a Lines,
    /// [`Lines::dominant_major`].
    pub(super) grid: &'a [f64],
    pub(super) inv_two_r: f64,
    pub(super) max_steps: usize,
    /// Every texel's near field, dominant-major ([`Sampler::near_field`]).
    pub(super) near: Vec<f64>,
    /// A maximum distance runs through the unlimited sweep
    /// ([`Sampler::sweep_by_unlimited`]) rather than the windowed one.
    pub(super) by_unlimited: bool,
}

impl<'a> Sampler<'a> {
    pub(super) fn new(lines: &'a Lines, grid: &'a [f64], inv_two_r: f64, max_steps: usize) -> Self {
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
    pub(super) fn near_field(&self) -> Vec<f64> {
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
    pub(super) fn build(&self, c: i64, sc: &mut LineScratch) {
        self.build_batch(&[c], std::slice::from_mut(sc));
    }

    /// [`Sampler::build`] for consecutive lines `cs` at once (`scs[k]` for `cs[k]`),
    /// each row of the grid visited once for all of them: neighbouring lines read
    /// neighbouring texels, so a batch touches each row's memory once instead of once
    /// per line. Every line's values are computed as on its own.
    pub(super) fn build_batch(&self, cs: &[i64], scs: &mut [LineScratch]) {
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
    pub(super) fn near_best(&self, v: &View, last: usize) -> f64 {
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
    pub(super) fn distance(&self, v: &View, j: usize) -> f64 {
        fl(j - v.i) * self.lines.step - v.e
    }

    /// Tangent of the elevation of line sample `j` seen from `v`: the formula both
    /// algorithms evaluate.
    #[inline]
    pub(super) fn tangent(&self, sc: &LineScratch, v: &View, j: usize) -> f64 {
        let d = self.distance(v, j);
        (sc.h[j] - v.h - d * d * self.inv_two_r) / d
    }

    /// `true` when, seen from `v`, sample `b` is not above sample `a` (curvature-
    /// corrected frame; both ahead of `v`).
    #[inline]
    pub(super) fn not_above(&self, g: &[f64], v: &View, a: usize, b: usize) -> bool {
        (g[b] - v.g) * self.distance(v, a) <= (g[a] - v.g) * self.distance(v, b)
    }

    /// The position `k < len` of the tangent point from `v` on an upper hull given
    /// left to right by `at(k)`, searched from position `guess` (the neighbouring
    /// texel's tangent point, usually the same or next to it; [`first_true`]).
    pub(super) fn tangent_point(
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
    pub(super) fn brute(&self, sc: &mut LineScratch) {
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

    #[inline]
    pub(super) fn tangent_h(&self, h: &[f64], v: &View, j: usize) -> f64 {
        let d = self.distance(v, j);
        (h[j] - v.h - d * d * self.inv_two_r) / d
    }
}
