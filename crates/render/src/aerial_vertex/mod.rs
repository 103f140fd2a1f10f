//! The terrain's aerial perspective per vertex (Hoffman and Preetham 2002) or per pixel, and the CPU twin
//! of the per-vertex variant.
//!
//! `[terrain] aerial_perspective = "per-pixel"` (the default) evaluates the segment
//! camera → point (transmittance and in-scatter, atmos' `aerial_perspective`) for every
//! terrain fragment at its position. `"per-vertex"` evaluates it, as Hoffman and Preetham's vertex
//! shader does, at the vertices of the GPU's terrain mesh (the quadtree tiles of
//! [`crate::terrain_mesh`]) and lets the rasteriser interpolate it to the fragments
//! (perspective-correct). With the precomputed rung the vertex stage evaluates it
//! (`shaders/render/terrain_aerial_vertex.wgsl`, atmos' `aerial_perspective`, the same
//! WGSL function by `#import`); with the closed form and single scattering a compute
//! pass over the drawn tiles' vertices evaluates the rung's own functions (those its
//! per-pixel pass evaluates) and the vertex stage reads them (`render::gpu::vertex_air`,
//! `shaders/render/terrain_rung_aerial_vertex.wgsl`). A fragment then pays a multiply-add
//! instead of a lookup in the aerial-perspective volume or a march (the tables beyond
//! the volume's 32 km range, the rung's segment otherwise); the price is the
//! interpolation error over a triangle, which grows with the tile's step (far, coarse
//! tiles).
//!
//! The CPU reference renderer ray casts the bilinear heightfield, so it has no triangles
//! of its own. Its twin of the per-vertex variant ([`VertexAerial`]) selects the tiles
//! the GPU draws (the same [`TerrainLod::select`](crate::terrain_mesh::TerrainLod::select) with the camera the GPU renderer
//! passes and its default error, [`TERRAIN_ERROR_PX`]), finds the tile under the
//! ray's hit and the triangle the ray crosses there, evaluates the segment at that triangle's three vertices (world
//! positions computed in f32 as the vertex shader computes them) and interpolates it
//! with the barycentric coordinates of the point where the pixel's ray meets the
//! triangle's plane: what a perspective-correct rasteriser interpolates at that pixel.
//! Where the two differ:
//! - the triangle is the nearest one the ray crosses among the two of the cell under the
//!   bilinear surface's hit and those of the 8 cells around it (the tile's own), not
//!   the first along the whole ray; where none of them is crossed — coarse tiles of a
//!   small image stand up to a pixel's geometric error off the bilinear surface — the
//!   hit's own (vertical) barycentric coordinates in the triangle under it are used (12
//!   of 2,989 terrain pixels of the default scene at 96×54, none on smooth hills;
//!   `tests/aerial_vertex.rs`);
//! - skirts (the vertical strips hiding cracks between tiles of different steps) are
//!   never hit by the ray caster; a GPU pixel showing a skirt interpolates between its
//!   border vertex and the lowered copy;
//! - a GPU renderer built with another `terrain_error_px` than [`TERRAIN_ERROR_PX`] draws
//!   other tiles than the twin assumes.

mod mesh;

use serde::Deserialize;

pub use mesh::{VertexAerial, plane_barycentrics, seen_through, selected_tiles};

/// Where the terrain's aerial perspective is evaluated (`[terrain] aerial_perspective`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum AerialPerspective {
    /// At every terrain pixel (fragment), at its own position.
    #[default]
    PerPixel,
    /// At the terrain mesh's vertices (Hoffman and Preetham 2002), interpolated across each triangle.
    PerVertex,
}

impl AerialPerspective {
    /// The name as written in a scene file.
    pub fn name(self) -> &'static str {
        match self {
            Self::PerPixel => "per-pixel",
            Self::PerVertex => "per-vertex",
        }
    }

    /// The WGSL `override aerial_per_vertex` value of the terrain pipeline.
    pub fn per_vertex(self) -> bool {
        self == Self::PerVertex
    }
}

/// The terrain pipeline of a variant: the WGSL module and its vertex and fragment entry
/// points (`render::terrain` per pixel, `render::terrain_aerial_vertex` per vertex).
pub fn terrain_shader(variant: AerialPerspective) -> (&'static str, &'static str, &'static str) {
    match variant {
        AerialPerspective::PerPixel => ("render::terrain", "terrain_vertex", "terrain_fragment"),
        AerialPerspective::PerVertex => (
            "render::terrain_aerial_vertex",
            "terrain_aerial_vertex",
            "terrain_aerial_fragment",
        ),
    }
}

/// What `skyscape explain` says of a variant.
pub fn plan(variant: AerialPerspective) -> &'static str {
    match variant {
        AerialPerspective::PerPixel => {
            "aerial perspective per pixel (atmos' aerial_perspective per fragment: the \
             table within its range on screen, a march of the tables elsewhere)"
        }
        AerialPerspective::PerVertex => {
            "aerial perspective per vertex (Hoffman and Preetham 2002: atmos' aerial_perspective at each tile \
             vertex, interpolated across the triangles; [terrain] aerial_perspective = \
             \"per-vertex\")"
        }
    }
}

/// What `skyscape explain` says of the terrain's aerial perspective with a rung without
/// tables, whose model (e.g. "the closed form") evaluates it.
pub fn rung_plan(variant: AerialPerspective, model: &str) -> String {
    match variant {
        AerialPerspective::PerPixel => format!(
            "{model}'s in-scatter and transmittance of each terrain pixel's segment from the \
             camera (compute, reading the depth), copied back"
        ),
        AerialPerspective::PerVertex => format!(
            "per vertex (Hoffman and Preetham 2002; [terrain] aerial_perspective = \"per-vertex\"): {model}'s \
             in-scatter and transmittance of the segment to each drawn tile vertex (compute \
             over the vertices, per light), interpolated across the triangles by the terrain \
             draw"
        ),
    }
}

/// The GPU renderer's default largest projected geometric error of the terrain (pixels):
/// `SceneRendererSettings::default().terrain_error_px`, and the error with which the
/// CPU twin of the per-vertex aerial perspective selects its tiles.
pub const TERRAIN_ERROR_PX: f64 = 1.0;
