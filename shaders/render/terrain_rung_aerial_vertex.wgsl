// The terrain pass of a rung without tables with its aerial perspective per vertex
// (`[terrain] aerial_perspective = "per-vertex"`): render::terrain's vertices, each
// reading its segment camera → vertex from the compute pass over the drawn tiles'
// vertices (render::vertex_air_compute, this light's), interpolated to the fragments by
// the rasteriser (perspective-correct), as render::terrain_aerial_vertex does with the
// precomputed rung's tables. The fragment shades the surface as the per-pixel fragment
// (render::terrain_rung) does, lit by the rung's light, and adds the interpolated
// segment. The segments are bound in group 0 (the
// precomputed rung's tables' group, unbound for these rungs), bindings 4 and 5.
// Twin: render::aerial_vertex::VertexAerial with segment_to without tables.
#import render::terrain_rung
#import render::vertex_air

@group(0) @binding(4) var<uniform> terrain_vertex_air: VertexAirUniform;
@group(0) @binding(5) var<storage, read> terrain_vertex_air_segments: array<vec4<f32>>;

struct TerrainRungAerialVarying {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) transmittance: vec3<f32>,
    @location(2) in_scatter: vec3<f32>,
}

@vertex
fn terrain_rung_aerial_vertex(@builtin(vertex_index) vertex: u32, @builtin(instance_index) tile: u32, @location(0) grid: vec4<u32>, @location(1) tile_origin: vec2<u32>, @location(2) tile_step: u32, @location(3) tile_skirt: f32) -> TerrainRungAerialVarying {
    let world = tile_vertex_world(grid, tile_origin, tile_step, tile_skirt);
    let i = vertex_air_index(terrain_vertex_air, vertex, tile);
    return TerrainRungAerialVarying(terrain.view_projection * vec4<f32>(world, 1.0), world, terrain_vertex_air_segments[i].xyz, terrain_vertex_air_segments[i + 1u].xyz);
}

// The fragment's radiance × the radiance scale: the surface lit by `light_at_point`,
// seen through the interpolated segment (surface × transmittance + in-scatter).
fn terrain_rung_aerial_radiance(in: TerrainRungAerialVarying, light_at_point: vec3<f32>) -> vec4<f32> {
    let surface = terrain_surface(in.world, light_at_point);
    return vec4<f32>((surface * in.transmittance + in.in_scatter) * terrain.radiance_scale, 1.0);
}

@fragment
fn terrain_rung_aerial_fragment(in: TerrainRungAerialVarying) -> @location(0) vec4<f32> {
    return terrain_rung_aerial_radiance(in, rung_light_at(in.world.y));
}
