//! The per-vertex aerial perspective's CPU twin: the tiles a GPU renderer draws, and the
//! segment at each drawn tile vertex interpolated across its triangles.

use std::sync::OnceLock;

use atmos::lut::raymarch::ScatteringSegment;
use glam::{DVec2, DVec3, Vec3};

use crate::RenderError;
use crate::scene::prepare::{PreparedScene, PreparedTerrain};
use crate::terrain_mesh::{TILE_CELLS, TerrainLod, Tile};

/// Vertices per tile (the grid only: skirts are never hit by a ray).
const TILE_VERTICES: usize = ((TILE_CELLS + 1) * (TILE_CELLS + 1)) as usize;

/// The quadtree tiles a GPU renderer (with [`TERRAIN_ERROR_PX`](super::TERRAIN_ERROR_PX)) draws for `scene`'s
/// camera: the same call, with the same arguments, as `SceneRenderer::prepare`.
pub fn selected_tiles(
    scene: &PreparedScene,
    terrain: &PreparedTerrain,
    lod: &TerrainLod,
    max_error_px: f64,
) -> Vec<Tile> {
    let camera = &scene.camera;
    let eye = scene.camera_position - DVec3::new(0.0, scene.atmosphere.planet_radius, 0.0);
    let offset = terrain.map_offset();
    let pixels_per_radian = f64::from(camera.height) / (2.0 * f64::from(camera.tan_half_fov_y));
    lod.select(
        [eye.x + offset[0], eye.z + offset[1], eye.y],
        pixels_per_radian,
        max_error_px,
    )
}

/// The CPU twin of the per-vertex aerial perspective for one frame and one light (see
/// the module documentation): the tiles drawn, which tile covers each 64-texel block,
/// and the segment at each tile vertex, evaluated once when a pixel first needs it.
pub struct VertexAerial {
    tiles: Vec<Tile>,
    /// Per block of `TILE_CELLS`² texels (row-major), the index of the tile covering it.
    blocks: Vec<u32>,
    blocks_x: usize,
    map_size: [u32; 2],
    spacing: f32,
    map_offset: [f32; 2],
    /// The camera's world position, f32 (the terrain uniform's `camera`).
    eye: Vec3,
    /// The camera's world position, f64 (the ray's origin).
    eye64: DVec3,
    /// Heights as the GPU's storage buffer holds them.
    heights: Vec<f32>,
    /// `tiles.len() × 65²` segments, row-major per tile.
    segments: Vec<OnceLock<ScatteringSegment>>,
}

impl std::fmt::Debug for VertexAerial {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("VertexAerial")
            .field("tiles", &self.tiles.len())
            .field(
                "segments_evaluated",
                &self.segments.iter().filter(|s| s.get().is_some()).count(),
            )
            .finish_non_exhaustive()
    }
}

impl VertexAerial {
    /// The tiles `scene`'s camera selects on `terrain` with `max_error_px`.
    pub fn new(scene: &PreparedScene, terrain: &PreparedTerrain, max_error_px: f64) -> Self {
        let hf = &terrain.heightfield;
        let lod = TerrainLod::new(hf);
        let tiles = selected_tiles(scene, terrain, &lod, max_error_px);
        let (width, height) = (hf.width(), hf.height());
        let cells = TILE_CELLS as usize;
        let blocks_x = (width - 1).div_ceil(cells);
        let blocks_y = (height - 1).div_ceil(cells);
        let mut blocks = vec![0u32; blocks_x * blocks_y];
        for (k, tile) in tiles.iter().enumerate() {
            let (bx, by) = (
                tile.origin[0] as usize / cells,
                tile.origin[1] as usize / cells,
            );
            let step = tile.step as usize;
            for y in by..(by + step).min(blocks_y) {
                for x in bx..(bx + step).min(blocks_x) {
                    blocks[y * blocks_x + x] = k as u32;
                }
            }
        }
        let offset = terrain.map_offset();
        let eye64 = scene.camera_position - DVec3::new(0.0, scene.atmosphere.planet_radius, 0.0);
        let segments = (0..tiles.len() * TILE_VERTICES)
            .map(|_| OnceLock::new())
            .collect();
        Self {
            tiles,
            blocks,
            blocks_x,
            map_size: [width as u32, height as u32],
            spacing: hf.spacing() as f32,
            map_offset: [offset[0] as f32, offset[1] as f32],
            eye: eye64.as_vec3(),
            eye64,
            heights: hf.elevations().iter().map(|&e| e as f32).collect(),
            segments,
        }
    }

    /// The tiles drawn.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// The tile whose grid covers the fractional texel position `texel` (column, row).
    pub fn tile_at(&self, texel: [f64; 2]) -> &Tile {
        &self.tiles[self.tile_index(texel)]
    }

    fn tile_index(&self, texel: [f64; 2]) -> usize {
        let cells = f64::from(TILE_CELLS);
        let blocks_y = self.blocks.len() / self.blocks_x;
        let bx = ((texel[0] / cells).floor().max(0.0) as usize).min(self.blocks_x - 1);
        let by = ((texel[1] / cells).floor().max(0.0) as usize).min(blocks_y - 1);
        self.blocks[by * self.blocks_x + bx] as usize
    }

    /// A grid vertex's texel, clamped to the map as the vertex shader clamps it.
    fn vertex_texel(&self, tile: &Tile, i: u32, j: u32) -> [u32; 2] {
        [
            (tile.origin[0] + i * tile.step).min(self.map_size[0] - 1),
            (tile.origin[1] + j * tile.step).min(self.map_size[1] - 1),
        ]
    }

    /// A grid vertex's world position (x east, y up, z south), in f32 as
    /// `terrain_vertex` computes it.
    fn vertex_world(&self, texel: [u32; 2]) -> Vec3 {
        let elevation = self.heights[(texel[0] + self.map_size[0] * texel[1]) as usize];
        let map = [
            texel[0] as f32 * self.spacing,
            texel[1] as f32 * self.spacing,
        ];
        Vec3::new(
            map[0] - self.map_offset[0],
            elevation,
            map[1] - self.map_offset[1],
        )
    }

    /// The segment camera → the terrain seen along the unit world ray `view` whose
    /// bilinear-surface hit is at `texel`: the segments at the three vertices of the
    /// mesh triangle the ray crosses there (see the module documentation; `evaluate`
    /// maps a vertex's offset from the camera, f32 world axes, to its segment),
    /// interpolated at the crossing.
    pub fn segment<E>(
        &self,
        texel: [f64; 2],
        view: DVec3,
        evaluate: E,
    ) -> Result<ScatteringSegment, RenderError>
    where
        E: Fn([f32; 3]) -> Result<ScatteringSegment, RenderError>,
    {
        let index = self.tile_index(texel);
        let tile = &self.tiles[index];
        let step = f64::from(tile.step);
        let last = TILE_CELLS - 1;
        let cell = |axis: usize| -> (u32, f64) {
            let local = (texel[axis] - f64::from(tile.origin[axis])) / step;
            let mut i = (local.floor().max(0.0) as u32).min(last);
            let at = |i: u32| {
                f64::from((tile.origin[axis] + i * tile.step).min(self.map_size[axis] - 1))
            };
            // A cell squashed to nothing by the clamp at the map's edge: the one before.
            if at(i + 1) <= at(i) && i > 0 {
                i -= 1;
            }
            let fraction = ((texel[axis] - at(i)) / (at(i + 1) - at(i))).clamp(0.0, 1.0);
            (i, fraction)
        };
        let ((i, fx), (j, fy)) = (cell(0), cell(1));
        let triangle_world = |corners: Triangle| {
            corners.map(|(i, j)| self.vertex_world(self.vertex_texel(tile, i, j)))
        };
        let crossing = |corners: Triangle| {
            plane_crossing(
                triangle_world(corners).map(|w| w.as_dvec3()),
                self.eye64,
                view,
            )
        };
        // The cell under the hit, its triangle and the hit's own (vertical) weights.
        let under = cell_triangles(i, j)[usize::from(fx + fy > 1.0)];
        let vertical = if fx + fy <= 1.0 {
            [1.0 - fx - fy, fy, fx]
        } else {
            [1.0 - fy, 1.0 - fx, fx + fy - 1.0]
        };
        // The rasteriser shows the nearest triangle the ray crosses: the nearest crossed
        // among the two of the cell under the hit and of the 8 cells around it (this
        // tile's), else the hit's vertical weights in the triangle under it.
        let mut nearest: Option<(f64, Triangle, [f64; 3])> = None;
        for cj in j.saturating_sub(1)..=(j + 1).min(last) {
            for ci in i.saturating_sub(1)..=(i + 1).min(last) {
                for corners in cell_triangles(ci, cj) {
                    if let Some((t, weights)) = crossing(corners)
                        && t > 0.0
                        && nearest.is_none_or(|(best, _, _)| t < best)
                    {
                        nearest = Some((t, corners, weights));
                    }
                }
            }
        }
        let (corners, weights) = nearest.map_or((under, vertical), |(_, corners, weights)| {
            (corners, weights)
        });
        let worlds = triangle_world(corners);
        let mut out = ScatteringSegment {
            radiance: [0.0; 3],
            transmittance: [0.0; 3],
        };
        for ((&(i, j), world), weight) in corners.iter().zip(&worlds).zip(weights) {
            let cell = &self.segments[index * TILE_VERTICES + (j * (TILE_CELLS + 1) + i) as usize];
            let segment = match cell.get() {
                Some(segment) => *segment,
                None => {
                    let segment = evaluate((*world - self.eye).to_array())?;
                    *cell.get_or_init(|| segment)
                }
            };
            let weight = weight as f32;
            for c in 0..3 {
                out.radiance[c] += weight * segment.radiance[c];
                out.transmittance[c] += weight * segment.transmittance[c];
            }
        }
        Ok(out)
    }
}

/// A triangle of a tile's grid: its three vertices `(i, j)`.
type Triangle = [(u32, u32); 3];

/// A tile cell's two triangles as `tile_mesh` draws them: (a, c, b) and (b, c, d) with
/// a = (i, j), b = (i + 1, j), c = (i, j + 1), d = (i + 1, j + 1), split along b–c; the
/// first holds the points with fractions fx + fy ≤ 1.
fn cell_triangles(i: u32, j: u32) -> [Triangle; 2] {
    [
        [(i, j), (i, j + 1), (i + 1, j)],
        [(i + 1, j), (i, j + 1), (i + 1, j + 1)],
    ]
}

/// Barycentric coordinates (of `triangle`'s vertices, in order) of the point where the
/// ray `origin + t·direction` meets the triangle's plane, when it meets it inside the
/// triangle (what a perspective-correct rasteriser interpolates at that pixel); `None`
/// for a ray parallel to the plane or crossing it outside the triangle.
pub fn plane_barycentrics(
    triangle: [DVec3; 3],
    origin: DVec3,
    direction: DVec3,
) -> Option<[f64; 3]> {
    plane_crossing(triangle, origin, direction).map(|(_, weights)| weights)
}

/// [`plane_barycentrics`] and the ray parameter `t` of the crossing.
fn plane_crossing(
    triangle: [DVec3; 3],
    origin: DVec3,
    direction: DVec3,
) -> Option<(f64, [f64; 3])> {
    let [a, b, c] = triangle;
    let normal = (b - a).cross(c - a);
    let denominator = normal.dot(direction);
    if denominator.abs() <= 1e-12 * normal.length() * direction.length() {
        return None;
    }
    let t = normal.dot(a - origin) / denominator;
    let point = origin + direction * t;
    // In the horizontal plane (the terrain is a height field: triangles never stand
    // vertical), where a point of the plane has the same coordinates.
    let flat = |p: DVec3| DVec2::new(p.x, p.z);
    let (a2, b2, c2, p2) = (flat(a), flat(b), flat(c), flat(point));
    let area = (b2 - a2).perp_dot(c2 - a2);
    if area == 0.0 {
        return None;
    }
    let wb = (p2 - a2).perp_dot(c2 - a2) / area;
    let wc = (b2 - a2).perp_dot(p2 - a2) / area;
    let weights = [1.0 - wb - wc, wb, wc];
    // Within a rounding of the triangle's edges.
    weights.iter().all(|&w| w >= -1e-9).then_some((t, weights))
}

/// A surface radiance seen through `segment`: `surface × transmittance + in-scatter`
/// (the per-vertex fragment's arithmetic).
pub fn seen_through(surface: [f32; 3], segment: &ScatteringSegment) -> [f32; 3] {
    std::array::from_fn(|c| surface[c] * segment.transmittance[c] + segment.radiance[c])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial_vertex::AerialPerspective;
    use serde::Deserialize;

    #[test]
    fn plane_barycentrics_reproduce_the_crossing_point() {
        let triangle = [
            DVec3::new(0.0, 10.0, 0.0),
            DVec3::new(100.0, 30.0, 0.0),
            DVec3::new(0.0, 20.0, 100.0),
        ];
        let origin = DVec3::new(-50.0, 500.0, -40.0);
        let target = triangle[0] * 0.2 + triangle[1] * 0.5 + triangle[2] * 0.3;
        let w = plane_barycentrics(triangle, origin, (target - origin).normalize()).unwrap();
        for (got, want) in w.iter().zip([0.2, 0.5, 0.3]) {
            assert!((got - want).abs() < 1e-9, "{w:?}");
        }
        // Outside the triangle, or parallel to its plane: none.
        let outside = triangle[1] * 1.2 - triangle[0] * 0.2;
        assert!(plane_barycentrics(triangle, origin, (outside - origin).normalize()).is_none());
        let flat = [DVec3::ZERO, DVec3::X, DVec3::Z];
        assert!(plane_barycentrics(flat, DVec3::Y, DVec3::X).is_none());
    }

    #[test]
    fn the_scene_key_reads_both_variants() {
        #[derive(Deserialize)]
        struct Key {
            aerial_perspective: AerialPerspective,
        }
        for variant in [AerialPerspective::PerPixel, AerialPerspective::PerVertex] {
            let text = format!("aerial_perspective = \"{}\"", variant.name());
            let key: Key = toml::from_str(&text).unwrap();
            assert_eq!(key.aerial_perspective, variant);
        }
        assert_eq!(AerialPerspective::default(), AerialPerspective::PerPixel);
    }
}
