// Single scattering's terrain fragment with the aerial perspective per vertex
// (render::terrain_rung_aerial_vertex): lit as render::terrain_single lights it (the
// light tabulated over the terrain's elevations).
#import render::terrain_single
#import render::terrain_rung_aerial_vertex

@fragment
fn terrain_single_aerial_fragment(in: TerrainRungAerialVarying) -> @location(0) vec4<f32> {
    return terrain_rung_aerial_radiance(in, rung_light_from_table(in.world.y));
}
