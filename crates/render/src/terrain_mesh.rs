//! The GPU terrain's level of detail: a quadtree of square tiles over the heightfield
//! (chunked LOD), each tile one instanced grid of [`TILE_CELLS`]² cells whose vertices
//! read the heightfield every `step` texels, with skirts hanging from its border.
//!
//! Why a quadtree of tiles rather than a clipmap: a scene's terrain is a fixed, finite
//! map seen from anywhere (from inside a valley or from orbit), and a tile's geometric
//! error is known exactly ahead of time (the largest height difference between the
//! tile's coarse surface and the full-resolution one), so the selection guarantees a
//! screen-space error in pixels; a clipmap's rings follow the camera's position and
//! bound the error only through the ring spacing. Tiles are one static mesh drawn
//! instanced (no per-frame vertex data); the heights are read in the vertex shader.
//! Skirts — each border vertex repeated lower by the tile's error — hide the cracks
//! where tiles of different levels meet, without stitching.
//!
//! Selection runs on the CPU per frame: O(tiles visited), a few hundred for a 4096²
//! map seen from inside it.

use terrain::Heightfield;

/// Cells per tile side: 64 (a 65 × 65 vertex grid, 8,450 triangles plus skirts).
pub const TILE_CELLS: u32 = 64;

/// One drawn tile: the texel its grid starts at, its step between vertices (texels, a
/// power of two) and how far its skirt hangs (m). Layout of the GPU's per-instance
/// vertex buffer.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Tile {
    /// First texel (x, y) of the tile's grid.
    pub origin: [u32; 2],
    /// Texels between neighbouring vertices.
    pub step: u32,
    /// Skirt depth below the border vertices (m).
    pub skirt: f32,
}

/// The quadtree's per-level geometric errors of a heightfield.
#[derive(Debug, Clone)]
pub struct TerrainLod {
    width: u32,
    height: u32,
    spacing: f64,
    /// Levels: level `l` has tiles of `TILE_CELLS · 2^l` cells.
    levels: u32,
    /// `errors[l][tile]`: the largest height error (m) of the level-`l` tile `tile`
    /// (row-major over that level's tiles), including its descendants'.
    errors: Vec<Vec<f32>>,
    /// `(min, max)` elevation of each level-`l` tile.
    ranges: Vec<Vec<[f32; 2]>>,
}

impl TerrainLod {
    /// Measures every tile's error on `heightfield` (≥ 2 × 2 texels).
    pub fn new(heightfield: &Heightfield) -> Self {
        let (w, h) = (heightfield.width(), heightfield.height());
        let heights: Vec<f32> = heightfield.elevations().iter().map(|&e| e as f32).collect();
        let at = |x: usize, y: usize| heights[y.min(h - 1) * w + x.min(w - 1)];
        let cells = (w.max(h) - 1) as u32;
        let mut levels = 1;
        while TILE_CELLS << (levels - 1) < cells {
            levels += 1;
        }
        let mut errors: Vec<Vec<f32>> = Vec::new();
        let mut ranges: Vec<Vec<[f32; 2]>> = Vec::new();
        for level in 0..levels {
            let step = 1usize << level;
            let span = TILE_CELLS as usize * step;
            let (tiles_x, tiles_y) = ((w - 1).div_ceil(span), (h - 1).div_ceil(span));
            let mut level_errors = vec![0.0f32; tiles_x * tiles_y];
            let mut level_ranges = vec![[f32::INFINITY, f32::NEG_INFINITY]; tiles_x * tiles_y];
            for ty in 0..tiles_y {
                for tx in 0..tiles_x {
                    let (x0, y0) = (tx * span, ty * span);
                    let mut worst = 0.0f32;
                    let mut range = [f32::INFINITY, f32::NEG_INFINITY];
                    for y in y0..=(y0 + span).min(h - 1) {
                        for x in x0..=(x0 + span).min(w - 1) {
                            let value = at(x, y);
                            range = [range[0].min(value), range[1].max(value)];
                            if level == 0 {
                                continue;
                            }
                            // The coarse grid's bilinear surface at this texel.
                            let (cx, cy) =
                                ((x - x0) / step * step + x0, (y - y0) / step * step + y0);
                            let (fx, fy) =
                                ((x - cx) as f32 / step as f32, (y - cy) as f32 / step as f32);
                            let coarse = (1.0 - fy)
                                * ((1.0 - fx) * at(cx, cy) + fx * at(cx + step, cy))
                                + fy * ((1.0 - fx) * at(cx, cy + step)
                                    + fx * at(cx + step, cy + step));
                            worst = worst.max((coarse - value).abs());
                        }
                    }
                    if level > 0 {
                        // A tile is never better than its children.
                        let finer = &errors[level as usize - 1];
                        let finer_x = (w - 1).div_ceil(span / 2);
                        for cy in 2 * ty..(2 * ty + 2) {
                            for cx in 2 * tx..(2 * tx + 2) {
                                if let Some(e) =
                                    finer.get(cy * finer_x + cx).filter(|_| cx < finer_x)
                                {
                                    worst = worst.max(*e);
                                }
                            }
                        }
                    }
                    level_errors[ty * tiles_x + tx] = worst;
                    level_ranges[ty * tiles_x + tx] = range;
                }
            }
            errors.push(level_errors);
            ranges.push(level_ranges);
        }
        Self {
            width: w as u32,
            height: h as u32,
            spacing: heightfield.spacing(),
            levels,
            errors,
            ranges,
        }
    }

    /// Levels of the quadtree (the root level is `levels − 1`).
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// The tiles to draw for a camera at `camera_map` (metres in the map's frame: x
    /// east from texel 0, y south from row 0, z up), whose image maps a length `l` at
    /// distance `d` to `l / d · pixels_per_radian` pixels, keeping every tile's
    /// projected error at or below `max_error_px` (0: the full resolution everywhere),
    /// nearest first (by the horizontal distance to the tile's centre).
    pub fn select(
        &self,
        camera_map: [f64; 3],
        pixels_per_radian: f64,
        max_error_px: f64,
    ) -> Vec<Tile> {
        let mut out = Vec::new();
        let root = self.levels - 1;
        let span = TILE_CELLS << root;
        let tiles_x = (self.width - 1).div_ceil(span);
        let tiles_y = (self.height - 1).div_ceil(span);
        for ty in 0..tiles_y {
            for tx in 0..tiles_x {
                self.visit(
                    root,
                    tx,
                    ty,
                    camera_map,
                    pixels_per_radian,
                    max_error_px,
                    &mut out,
                );
            }
        }
        // Nearest first: the depth test then rejects the fragments of tiles hidden
        // behind nearer ones before they are shaded (early depth testing), instead of
        // shading far ridges that nearer ones overwrite.
        let spacing = self.spacing;
        out.sort_by(|a, b| {
            let distance = |t: &Tile| {
                let half = 0.5 * f64::from(TILE_CELLS * t.step) * spacing;
                let dx = f64::from(t.origin[0]) * spacing + half - camera_map[0];
                let dy = f64::from(t.origin[1]) * spacing + half - camera_map[1];
                dx * dx + dy * dy
            };
            distance(a).total_cmp(&distance(b))
        });
        out
    }

    #[allow(clippy::too_many_arguments)]
    fn visit(
        &self,
        level: u32,
        tx: u32,
        ty: u32,
        camera: [f64; 3],
        pixels_per_radian: f64,
        max_error_px: f64,
        out: &mut Vec<Tile>,
    ) {
        let span = TILE_CELLS << level;
        let tiles_x = (self.width - 1).div_ceil(span);
        let tiles_y = (self.height - 1).div_ceil(span);
        if tx >= tiles_x || ty >= tiles_y {
            return;
        }
        let index = (ty * tiles_x + tx) as usize;
        let error = f64::from(self.errors[level as usize][index]);
        let [low, high] = self.ranges[level as usize][index];
        // Distance from the camera to the tile's bounding box.
        let (x0, y0) = (
            f64::from(tx * span) * self.spacing,
            f64::from(ty * span) * self.spacing,
        );
        let extent = f64::from(span) * self.spacing;
        let gap = |v: f64, lo: f64, hi: f64| (lo - v).max(0.0).max(v - hi);
        let dx = gap(camera[0], x0, x0 + extent);
        let dy = gap(camera[1], y0, y0 + extent);
        let dz = gap(camera[2], f64::from(low), f64::from(high));
        let distance = (dx * dx + dy * dy + dz * dz).sqrt().max(1e-3);
        let projected = error / distance * pixels_per_radian;
        if level == 0 || projected <= max_error_px {
            out.push(Tile {
                origin: [tx * span, ty * span],
                step: 1 << level,
                // Cracks against a finer neighbour are at most this tile's error.
                skirt: (error as f32) + 1.0,
            });
            return;
        }
        for (cx, cy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            self.visit(
                level - 1,
                2 * tx + cx,
                2 * ty + cy,
                camera,
                pixels_per_radian,
                max_error_px,
                out,
            );
        }
    }
}

/// The static tile mesh: `(i, j, skirt)` per vertex — grid vertices `i, j ∈ 0..=64`
/// (skirt 0), then each border vertex again with skirt 1 — and its triangle list.
pub fn tile_mesh() -> (Vec<[u32; 4]>, Vec<u32>) {
    let n = TILE_CELLS + 1;
    let mut vertices: Vec<[u32; 4]> = Vec::new();
    for j in 0..n {
        for i in 0..n {
            vertices.push([i, j, 0, 0]);
        }
    }
    let grid = |i: u32, j: u32| j * n + i;
    let mut indices = Vec::new();
    for j in 0..TILE_CELLS {
        for i in 0..TILE_CELLS {
            let (a, b, c, d) = (
                grid(i, j),
                grid(i + 1, j),
                grid(i, j + 1),
                grid(i + 1, j + 1),
            );
            // Counter-clockwise seen from above (+z up, y south): both winding orders
            // are drawn (no culling), so only the diagonal matters.
            indices.extend([a, c, b, b, c, d]);
        }
    }
    // Skirts: along each edge, a strip from the border vertices down to their copies.
    let edges: [Vec<(u32, u32)>; 4] = [
        (0..n).map(|i| (i, 0)).collect(),
        (0..n).map(|i| (i, TILE_CELLS)).collect(),
        (0..n).map(|j| (0, j)).collect(),
        (0..n).map(|j| (TILE_CELLS, j)).collect(),
    ];
    for edge in edges {
        let first = vertices.len() as u32;
        for &(i, j) in &edge {
            vertices.push([i, j, 1, 0]);
        }
        for k in 0..TILE_CELLS {
            let (top_a, top_b) = (
                grid(edge[k as usize].0, edge[k as usize].1),
                grid(edge[k as usize + 1].0, edge[k as usize + 1].1),
            );
            let (low_a, low_b) = (first + k, first + k + 1);
            indices.extend([top_a, low_a, top_b, top_b, low_a, low_b]);
        }
    }
    (vertices, indices)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ridge(size: usize) -> Heightfield {
        Heightfield::from_fn(size, size, 30.0, |x, y| {
            (200.0 * ((x as f64) * 0.07).sin() * ((y as f64) * 0.05).cos()) as f32
        })
        .unwrap()
    }

    #[test]
    fn errors_grow_with_the_level_and_level_zero_is_exact() {
        let lod = TerrainLod::new(&ridge(257));
        assert_eq!(lod.levels(), 3);
        assert!(lod.errors[0].iter().all(|&e| e == 0.0));
        let worst = |l: usize| lod.errors[l].iter().copied().fold(0.0f32, f32::max);
        assert!(worst(1) > 0.0 && worst(2) >= worst(1));
    }

    #[test]
    fn zero_error_selects_every_finest_tile_and_far_cameras_few() {
        let lod = TerrainLod::new(&ridge(257));
        let full = lod.select([3840.0, 3840.0, 500.0], 1000.0, 0.0);
        assert_eq!(full.len(), 16, "(256 / 64)² finest tiles");
        assert!(full.iter().all(|t| t.step == 1));
        let far = lod.select([3840.0, 3840.0, 5e6], 1000.0, 1.0);
        assert!(far.len() < full.len());
        // The tiles cover the map once.
        let area = |tiles: &[Tile]| -> u64 {
            tiles
                .iter()
                .map(|t| u64::from(TILE_CELLS * t.step).pow(2))
                .sum()
        };
        assert_eq!(area(&full), area(&far));
    }

    #[test]
    fn tiles_come_nearest_first() {
        // Nearest first lets the depth test reject hidden fragments before shading.
        let lod = TerrainLod::new(&ridge(513));
        let camera = [7000.0, 15000.0, 800.0];
        let tiles = lod.select(camera, 1000.0, 0.5);
        assert!(tiles.len() > 4);
        let centre_distance = |t: &Tile| {
            let half = 0.5 * f64::from(TILE_CELLS * t.step) * 30.0;
            let dx = f64::from(t.origin[0]) * 30.0 + half - camera[0];
            let dy = f64::from(t.origin[1]) * 30.0 + half - camera[1];
            (dx * dx + dy * dy).sqrt()
        };
        let distances: Vec<f64> = tiles.iter().map(centre_distance).collect();
        assert!(distances.windows(2).all(|w| w[0] <= w[1]), "{distances:?}");
        assert!(distances[0] < distances[distances.len() - 1]);
    }

    #[test]
    fn the_tile_mesh_has_its_grid_and_skirts() {
        let (vertices, indices) = tile_mesh();
        assert_eq!(vertices.len() as u32, 65 * 65 + 4 * 65);
        assert_eq!(indices.len() as u32, 6 * 64 * 64 + 4 * 6 * 64);
        assert!(indices.iter().all(|&i| (i as usize) < vertices.len()));
    }
}
