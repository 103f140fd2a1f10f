// The compute pass of the terrain's aerial perspective per vertex for a rung without
// tables (render::vertex_air_closed_form, render::vertex_air_single): one invocation per
// vertex of each drawn tile (x: the tile mesh's vertex, y: the tile), its world position
// from render::terrain's tile_vertex_world (what the draw's vertex stage computes), the
// segment camera → vertex in the rung's terms (the CPU's SkyQuery::with_max_distance
// from the camera along the vertex's direction, over its distance), written for the
// draw to interpolate. A compute pass rather than the vertex stage: lavapipe (Mesa
// 22.3) crashes compiling the closed form's path length and the single-scattering march
// into a graphics stage (render::terrain_single, render::cloud_air_closed_form).
// Bindings: render::terrain's group 2 (its uniform and heights are read), and in group 0
// (the tables' group of the precomputed rung, unbound here) bindings 4 to 7; each rung's
// parameters at group 0 binding 8. Twin: render::aerial_vertex's VertexAerial with
// segment_to without tables.
#import render::terrain
#import render::vertex_air

@group(0) @binding(4) var<uniform> vertex_air: VertexAirUniform;
// Two vec4 per vertex (render::vertex_air's vertex_air_index).
@group(0) @binding(5) var<storage, read_write> vertex_air_segments: array<vec4<f32>>;
// The tile mesh's vertices (render::terrain_mesh::tile_mesh, the draw's vertex buffer).
@group(0) @binding(6) var<storage, read> vertex_air_grid: array<vec4<u32>>;
// The drawn tiles (render::terrain_mesh::Tile: origin, step, skirt as its bits).
@group(0) @binding(7) var<storage, read> vertex_air_tiles: array<vec4<u32>>;

// The segment camera → a vertex: the camera's radius, the view's zenith cosine, the
// light's zenith cosine, the view–light cosine and the distance; `valid` is false
// outside the dispatch's vertices.
struct VertexAirSegment {
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    distance: f32,
    valid: bool,
}

fn vertex_air_segment(gid: vec3<u32>) -> VertexAirSegment {
    var out: VertexAirSegment;
    if gid.x >= vertex_air.grid_vertices || gid.y >= vertex_air.tile_count {
        return out;
    }
    let tile = vertex_air_tiles[gid.y];
    let world = tile_vertex_world(vertex_air_grid[gid.x], tile.xy, tile.z, bitcast<f32>(tile.w));
    let offset = world - terrain.camera;
    let r = length(vertex_air.camera_position);
    let up = vertex_air.camera_position / r;
    out.r = r;
    out.distance = length(offset);
    out.mu_s = dot(vertex_air.light, up);
    if out.distance > 0.0 {
        let view = offset / out.distance;
        out.mu = dot(view, up);
        out.nu = dot(view, vertex_air.light);
    }
    out.valid = true;
    return out;
}

// Writes the vertex's segment: `transmittance` and `radiance` (in-scatter); a vertex at
// the camera has none (transmittance 1, no in-scatter), as on the CPU.
fn vertex_air_store(gid: vec3<u32>, s: VertexAirSegment, transmittance: vec3<f32>, radiance: vec3<f32>) {
    let i = vertex_air_index(vertex_air, gid.x, gid.y);
    if s.distance > 0.0 {
        vertex_air_segments[i] = vec4<f32>(transmittance, 0.0);
        vertex_air_segments[i + 1u] = vec4<f32>(radiance, 0.0);
    } else {
        vertex_air_segments[i] = vec4<f32>(1.0, 1.0, 1.0, 0.0);
        vertex_air_segments[i + 1u] = vec4<f32>(0.0);
    }
}
