// The compute pass of the terrain's aerial perspective per vertex for a rung without
// tables (render::rung_sky's segment_air, bound to the rung's module, as
// render::rung_air calls it per pixel): one invocation per vertex of each drawn tile (x: the tile mesh's vertex, y: the tile), its world position
// from render::terrain's tile_vertex_world (what the draw's vertex stage computes), the
// segment camera → vertex (render::air_segment; the CPU's SkyQuery::with_max_distance
// from the camera along the vertex's direction, over its distance), written for the
// draw to interpolate. A compute pass rather than the vertex stage: lavapipe (Mesa
// 22.3) crashes compiling the closed form's path length and the single-scattering march
// into a graphics stage (render::rung_single, render::cloud_air_rung).
// Bindings: render::terrain's group 2 (its uniform and heights are read), and in group 0
// (the tables' group of the precomputed rung, unbound here) bindings 4 to 7 and the
// rung's parameters of the light's atmosphere at binding 8. Twin: render::aerial_vertex's VertexAerial with
// segment_to without tables.
#import render::terrain
#import render::vertex_air
#import render::air_segment
#import render::rung_sky

@group(0) @binding(4) var<uniform> vertex_air: VertexAirUniform;
// Two vec4 per vertex (render::vertex_air's vertex_air_index).
@group(0) @binding(5) var<storage, read_write> vertex_air_segments: array<vec4<f32>>;
// The tile mesh's vertices (render::terrain_mesh::tile_mesh, the draw's vertex buffer).
@group(0) @binding(6) var<storage, read> vertex_air_grid: array<vec4<u32>>;
// The drawn tiles (render::terrain_mesh::Tile: origin, step, skirt as its bits).
@group(0) @binding(7) var<storage, read> vertex_air_tiles: array<vec4<u32>>;
// The rung's parameters of the light's atmosphere.
@group(0) @binding(8) var<uniform> vertex_air_parameters: RungParameters;

// The segment camera → a vertex (render::air_segment), its `index` the vertex's two
// vec4 in the segments array (render::vertex_air's vertex_air_index); `has_air` is false
// outside the dispatch's vertices. A vertex at the camera has a segment of no length
// (view and zenith cosine 0).
fn vertex_air_segment(gid: vec3<u32>) -> AirSegment {
    var s: AirSegment;
    if gid.x >= vertex_air.grid_vertices || gid.y >= vertex_air.tile_count {
        return s;
    }
    let tile = vertex_air_tiles[gid.y];
    let world = tile_vertex_world(vertex_air_grid[gid.x], tile.xy, tile.z, bitcast<f32>(tile.w));
    let offset = world - terrain.camera;
    s.index = vertex_air_index(vertex_air, gid.x, gid.y);
    s.r = length(vertex_air.camera_position);
    s.up = vertex_air.camera_position / s.r;
    s.distance = length(offset);
    if s.distance > 0.0 {
        s.view = offset / s.distance;
        s.mu = dot(s.view, s.up);
    }
    s.has_air = true;
    return s;
}

// Writes the vertex's segment: its transmittance and in-scatter (`air`, the rung's);
// a vertex at the camera has none (transmittance 1, no in-scatter), as on the CPU.
fn vertex_air_store(s: AirSegment, air: SegmentAir) {
    if s.distance > 0.0 {
        vertex_air_segments[s.index] = vec4<f32>(air.transmittance, 0.0);
        vertex_air_segments[s.index + 1u] = vec4<f32>(air.radiance, 0.0);
    } else {
        vertex_air_segments[s.index] = vec4<f32>(1.0, 1.0, 1.0, 0.0);
        vertex_air_segments[s.index + 1u] = vec4<f32>(0.0);
    }
}

@compute @workgroup_size(64)
fn vertex_air_compute(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = vertex_air_segment(gid);
    if !s.has_air {
        return;
    }
    vertex_air_store(s, segment_air(s, vertex_air.light, vertex_air_parameters));
}
