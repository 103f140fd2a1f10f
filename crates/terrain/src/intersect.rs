//! Where a ray first meets the terrain surface: the primitive of a CPU ray-cast
//! renderer (`render`'s reference renderer). `f64`, CPU only.
//!
//! # Surface and frame
//!
//! The surface is the same one [`crate::raycast`] uses: the **bilinear interpolation**
//! of the texel heights over `[0, W − 1] × [0, H − 1]` texels. Here positions are in
//! metres in the map frame: `x` east (`x = i · spacing` for column `i`), `y` south
//! (`y = j · spacing` for row `j`), `z` up (the elevation in metres). Outside the map
//! there is no surface.
//!
//! # Exact, not marched
//!
//! Inside one cell the bilinear height along a straight ray is a quadratic in the
//! distance `t`, so `ray_z(t) − h(t)` is a quadratic whose smallest root in the cell's
//! `[t_in, t_out]` is the hit (solved in closed form with the cancellation-free
//! formula). Cells are visited in ray order with a 2D DDA (Amanatides & Woo 1987). To
//! skip empty space, the tracer keeps the maximum height of each block of
//! [`BLOCK_CELLS`]² cells and visits the cells of a block only where the ray
//! descends below that maximum. The answer is therefore the first intersection up to
//! `f64` rounding of one quadratic root (tested against dense sampling), not a march
//! step: no thin ridge is skipped.

use crate::Heightfield;

/// Cells per block side of the empty-space skipping grid: the tracer first walks
/// blocks, then the cells of the blocks the ray may touch.
pub const BLOCK_CELLS: usize = 16;

/// A heightfield prepared for ray intersection (block maxima for empty-space
/// skipping). Borrow it across threads: queries take `&self`.
#[derive(Debug, Clone)]
pub struct HeightfieldTracer<'a> {
    heightfield: &'a Heightfield,
    elevations: Vec<f64>,
    blocks_x: usize,
    blocks_y: usize,
    block_max: Vec<f64>,
    min_elevation: f64,
    max_elevation: f64,
}

/// The first intersection of a ray with the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceHit {
    /// Distance along the (unit) ray, metres.
    pub distance: f64,
    /// The hit point in the map frame (metres: east, south, up).
    pub position: [f64; 3],
    /// The hit point in texel units `(column, row)`, fractional, in
    /// `[0, W − 1] × [0, H − 1]`: where to sample per-texel maps.
    pub texel: [f64; 2],
}

impl<'a> HeightfieldTracer<'a> {
    /// Prepares `heightfield` (one pass over its texels).
    pub fn new(heightfield: &'a Heightfield) -> Self {
        let (w, h) = (heightfield.width(), heightfield.height());
        let elevations = heightfield.elevations();
        let cells_x = w.saturating_sub(1).max(1);
        let cells_y = h.saturating_sub(1).max(1);
        let blocks_x = cells_x.div_ceil(BLOCK_CELLS);
        let blocks_y = cells_y.div_ceil(BLOCK_CELLS);
        let mut block_max = vec![f64::NEG_INFINITY; blocks_x * blocks_y];
        for (bj, row) in block_max.chunks_mut(blocks_x).enumerate() {
            for (bi, max) in row.iter_mut().enumerate() {
                // A block of cells spans texels [b·B, (b+1)·B] inclusive.
                let (x0, y0) = (bi * BLOCK_CELLS, bj * BLOCK_CELLS);
                for y in y0..=(y0 + BLOCK_CELLS).min(h - 1) {
                    for x in x0..=(x0 + BLOCK_CELLS).min(w - 1) {
                        *max = max.max(elevations[y * w + x]);
                    }
                }
            }
        }
        let min_elevation = elevations.iter().copied().fold(f64::INFINITY, f64::min);
        let max_elevation = elevations.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Self {
            heightfield,
            elevations,
            blocks_x,
            blocks_y,
            block_max,
            min_elevation,
            max_elevation,
        }
    }

    /// The heightfield.
    pub fn heightfield(&self) -> &Heightfield {
        self.heightfield
    }

    /// Lowest and highest elevation of the map (m).
    pub fn elevation_range(&self) -> [f64; 2] {
        [self.min_elevation, self.max_elevation]
    }

    /// The bilinear elevation (m) at map position `(x, y)` in metres, clamped to the map.
    pub fn elevation_at(&self, x: f64, y: f64) -> f64 {
        let s = self.heightfield.spacing();
        let (w, h) = (self.heightfield.width(), self.heightfield.height());
        let u = (x / s).clamp(0.0, (w - 1) as f64);
        let v = (y / s).clamp(0.0, (h - 1) as f64);
        let i = (u.floor() as usize).min(w.saturating_sub(2));
        let j = (v.floor() as usize).min(h.saturating_sub(2));
        let (i1, j1) = ((i + 1).min(w - 1), (j + 1).min(h - 1));
        let (fx, fy) = (u - i as f64, v - j as f64);
        let e = |x: usize, y: usize| self.elevations[y * w + x];
        let top = e(i, j) + (e(i1, j) - e(i, j)) * fx;
        let bottom = e(i, j1) + (e(i1, j1) - e(i, j1)) * fx;
        top + (bottom - top) * fy
    }

    /// The first point at distance `t` in `[t_min, t_max]` where the ray
    /// `origin + t · direction` (map frame, metres; `direction` unit) meets the
    /// surface from above, or `None`. A ray starting below the surface hits at the
    /// first point of `[t_min, t_max]` over the map.
    pub fn intersect(
        &self,
        origin: [f64; 3],
        direction: [f64; 3],
        t_min: f64,
        t_max: f64,
    ) -> Option<SurfaceHit> {
        let hf = self.heightfield;
        let (w, h) = (hf.width(), hf.height());
        if w < 2 || h < 2 || t_min.is_nan() || t_max.is_nan() || t_min > t_max {
            return None;
        }
        let s = hf.spacing();
        let extent = [(w - 1) as f64 * s, (h - 1) as f64 * s];
        // Clip to the map's box (slab test), including the elevation range.
        let (mut t0, mut t1) = (t_min.max(0.0), t_max);
        let lo = [0.0, 0.0, self.min_elevation];
        let hi = [extent[0], extent[1], self.max_elevation];
        for k in 0..3 {
            if direction[k] == 0.0 {
                if origin[k] < lo[k] || origin[k] > hi[k] {
                    return None;
                }
            } else {
                let a = (lo[k] - origin[k]) / direction[k];
                let b = (hi[k] - origin[k]) / direction[k];
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        if t0 > t1 {
            return None;
        }
        let block_size = BLOCK_CELLS as f64 * s;
        let hit = walk_grid(
            origin,
            direction,
            [t0, t1],
            block_size,
            [self.blocks_x, self.blocks_y],
            |bi, bj, ta, tb| {
                let z_low = (origin[2] + direction[2] * ta).min(origin[2] + direction[2] * tb);
                if z_low > self.block_max[bj * self.blocks_x + bi] {
                    return None;
                }
                walk_grid(
                    origin,
                    direction,
                    [ta, tb],
                    s,
                    [w - 1, h - 1],
                    |i, j, ca, cb| self.intersect_cell(origin, direction, i, j, ca, cb),
                )
            },
        )?;
        let position: [f64; 3] = std::array::from_fn(|k| origin[k] + direction[k] * hit);
        Some(SurfaceHit {
            distance: hit,
            position,
            texel: [
                (position[0] / s).clamp(0.0, (w - 1) as f64),
                (position[1] / s).clamp(0.0, (h - 1) as f64),
            ],
        })
    }

    /// The smallest `t` in `[ta, tb]` where the ray is at or below the bilinear
    /// surface of cell `(i, j)`.
    fn intersect_cell(
        &self,
        origin: [f64; 3],
        direction: [f64; 3],
        i: usize,
        j: usize,
        ta: f64,
        tb: f64,
    ) -> Option<f64> {
        let w = self.heightfield.width();
        let s = self.heightfield.spacing();
        let e = |x: usize, y: usize| self.elevations[y * w + x];
        let (h00, h10, h01, h11) = (e(i, j), e(i + 1, j), e(i, j + 1), e(i + 1, j + 1));
        let z_low = (origin[2] + direction[2] * ta).min(origin[2] + direction[2] * tb);
        if z_low > h00.max(h10).max(h01).max(h11) {
            return None;
        }
        // Cell-local coordinates along the ray: fx = px + qx·t, fy = py + qy·t.
        let (px, qx) = (origin[0] / s - i as f64, direction[0] / s);
        let (py, qy) = (origin[1] / s - j as f64, direction[1] / s);
        // h = h00 + a·fx + b·fy + c·fx·fy.
        let (a, b, c) = (h10 - h00, h01 - h00, h11 - h10 - h01 + h00);
        // g(t) = z(t) − h(t) = A t² + B t + C.
        let qa = -c * qx * qy;
        let qb = direction[2] - a * qx - b * qy - c * (px * qy + py * qx);
        let qc = origin[2] - h00 - a * px - b * py - c * px * py;
        let g = |t: f64| (qa * t + qb) * t + qc;
        if g(ta) <= 0.0 {
            return Some(ta);
        }
        // First root in (ta, tb] of g, which is positive at ta.
        let mut best: Option<f64> = None;
        let mut consider = |t: f64| {
            if t > ta && t <= tb && best.is_none_or(|b| t < b) {
                best = Some(t);
            }
        };
        if qa == 0.0 {
            if qb != 0.0 {
                consider(-qc / qb);
            }
        } else {
            let discriminant = qb * qb - 4.0 * qa * qc;
            if discriminant >= 0.0 {
                // Cancellation-free pair of roots.
                let q = -0.5 * (qb + discriminant.sqrt().copysign(qb));
                if q != 0.0 {
                    consider(q / qa);
                    consider(qc / q);
                }
            }
        }
        // Rounding can put a grazing root a hair outside; the end point decides.
        best.or_else(|| (g(tb) <= 0.0).then_some(tb))
    }
}

/// Visits the cells of a `cells[0] × cells[1]` grid of square cells (side
/// `cell_size`, origin at 0) that the ray crosses over `[t0, t1]`, in order, with the
/// sub-interval inside each; stops at the first `visit` that returns a value.
fn walk_grid(
    origin: [f64; 3],
    direction: [f64; 3],
    [t0, t1]: [f64; 2],
    cell_size: f64,
    cells: [usize; 2],
    mut visit: impl FnMut(usize, usize, f64, f64) -> Option<f64>,
) -> Option<f64> {
    let cell_of = |k: usize, t: f64| {
        let c = ((origin[k] + direction[k] * t) / cell_size).floor();
        (c.max(0.0) as usize).min(cells[k] - 1)
    };
    let mut index = [cell_of(0, t0), cell_of(1, t0)];
    let mut step = [0i64; 2];
    let mut t_next = [f64::INFINITY; 2];
    let mut t_delta = [f64::INFINITY; 2];
    for k in 0..2 {
        if direction[k] > 0.0 {
            step[k] = 1;
            t_next[k] = ((index[k] + 1) as f64 * cell_size - origin[k]) / direction[k];
            t_delta[k] = cell_size / direction[k];
        } else if direction[k] < 0.0 {
            step[k] = -1;
            t_next[k] = (index[k] as f64 * cell_size - origin[k]) / direction[k];
            t_delta[k] = -cell_size / direction[k];
        }
    }
    let mut t = t0;
    loop {
        let exit = t_next[0].min(t_next[1]).min(t1);
        if let Some(hit) = visit(index[0], index[1], t, exit) {
            return Some(hit);
        }
        if exit >= t1 {
            return None;
        }
        let k = if t_next[0] <= t_next[1] { 0 } else { 1 };
        let next = index[k] as i64 + step[k];
        if next < 0 || next >= cells[k] as i64 {
            return None;
        }
        index[k] = next as usize;
        t = exit;
        t_next[k] += t_delta[k];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tracer_for(hf: &Heightfield) -> HeightfieldTracer<'_> {
        HeightfieldTracer::new(hf)
    }

    #[test]
    fn a_ray_down_onto_a_plane_hits_at_the_plane() {
        let hf = Heightfield::from_fn(40, 30, 10.0, |_, _| 100.0).unwrap();
        let tracer = tracer_for(&hf);
        let hit = tracer
            .intersect([55.0, 77.0, 300.0], [0.0, 0.0, -1.0], 0.0, 1e9)
            .unwrap();
        assert!((hit.distance - 200.0).abs() < 1e-9, "{hit:?}");
        assert!((hit.texel[0] - 5.5).abs() < 1e-12 && (hit.texel[1] - 7.7).abs() < 1e-12);
        // Looking up, or beyond t_max, or off the map: no hit.
        assert!(
            tracer
                .intersect([55.0, 77.0, 300.0], [0.0, 0.0, 1.0], 0.0, 1e9)
                .is_none()
        );
        assert!(
            tracer
                .intersect([55.0, 77.0, 300.0], [0.0, 0.0, -1.0], 0.0, 199.0)
                .is_none()
        );
        assert!(
            tracer
                .intersect([-5.0, 77.0, 300.0], [0.0, 0.0, -1.0], 0.0, 1e9)
                .is_none()
        );
    }

    #[test]
    fn hits_are_on_the_surface_and_nothing_is_crossed_before_them() {
        // A rough surface (many blocks) and oblique rays from above: the hit lies on the
        // bilinear surface, and a dense scan finds no earlier crossing.
        let hf = Heightfield::from_fn(70, 50, 7.0, |x, y| {
            let (x, y) = (x as f64, y as f64);
            (80.0 * (0.31 * x).sin() * (0.23 * y).cos() + 0.9 * x + 60.0) as f32
        })
        .unwrap();
        let tracer = tracer_for(&hf);
        let mut hits = 0;
        for k in 0..200 {
            // From above the map towards a point under it: every ray must hit.
            let o = [10.0 + k as f64, 150.0 + (k % 7) as f64 * 20.0, 260.0];
            let target = [
                5.0 + (k * 37 % 480) as f64 * 0.99,
                3.0 + (k * 53 % 340) as f64,
                -100.0,
            ];
            let d: [f64; 3] = std::array::from_fn(|i| target[i] - o[i]);
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let d = d.map(|c| c / n);
            let Some(hit) = tracer.intersect(o, d, 0.0, 1e9) else {
                continue;
            };
            hits += 1;
            let on_surface = tracer.elevation_at(hit.position[0], hit.position[1]);
            assert!((hit.position[2] - on_surface).abs() < 1e-6, "{hit:?}");
            for m in 0..20_000 {
                let t = hit.distance * m as f64 / 20_000.0;
                let p: [f64; 3] = std::array::from_fn(|i| o[i] + d[i] * t);
                let inside = p[0] >= 0.0 && p[0] <= 69.0 * 7.0 && p[1] >= 0.0 && p[1] <= 49.0 * 7.0;
                if inside {
                    assert!(
                        p[2] > tracer.elevation_at(p[0], p[1]) - 1e-6,
                        "ray {k} crossed at t = {t}"
                    );
                }
            }
        }
        assert_eq!(hits, 200);
    }

    #[test]
    fn a_thin_ridge_is_not_skipped() {
        // One texel column 50 m high on flat ground: a ray skimming at 40 m hits it.
        let hf =
            Heightfield::from_fn(100, 8, 10.0, |x, _| if x == 60 { 50.0 } else { 0.0 }).unwrap();
        let tracer = tracer_for(&hf);
        let hit = tracer
            .intersect([5.0, 35.0, 40.0], [1.0, 0.0, 0.0], 0.0, 1e9)
            .unwrap();
        // The bilinear ramp rises from 0 at x = 590 m to 50 at 600 m: 40 m at 598 m.
        assert!((hit.position[0] - 598.0).abs() < 1e-9, "{hit:?}");
    }
}
