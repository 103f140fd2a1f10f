// The terrain pass with its aerial perspective per vertex (`[terrain] aerial_perspective
// = "per-vertex"`, as Hoffman & Preetham 2002): render::terrain's vertices, bindings and shading, with the
// segment camera → vertex (atmos::aerial_perspective, the function render::terrain's
// fragments call per pixel) evaluated in the vertex stage and interpolated to the
// fragments by the rasteriser (perspective-correct). A fragment shades its surface as
// render::terrain does and adds the interpolated segment: `surface × transmittance +
// in-scatter`. Twin: render::aerial_vertex::VertexAerial (the same vertices, the
// segments interpolated at the ray's crossing of the triangle).
#import render::terrain

struct TerrainAerialVarying {
    @builtin(position) @invariant clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) transmittance: vec3<f32>,
    @location(2) in_scatter: vec3<f32>,
}

@vertex
fn terrain_aerial_vertex(@location(0) grid: vec4<u32>, @location(1) tile_origin: vec2<u32>, @location(2) tile_step: u32, @location(3) tile_skirt: f32) -> TerrainAerialVarying {
    let world = tile_vertex_world(grid, tile_origin, tile_step, tile_skirt);
    let segment = aerial_perspective(world - terrain.camera);
    return TerrainAerialVarying(terrain.view_projection * vec4<f32>(world, 1.0), world, segment.transmittance, segment.radiance);
}

@fragment
fn terrain_aerial_fragment(in: TerrainAerialVarying) -> @location(0) vec4<f32> {
    let surface = terrain_surface(in.world, sunlight_at(in.world - terrain.camera));
    return vec4<f32>((surface * in.transmittance + in.in_scatter) * terrain.radiance_scale, 1.0);
}
