// The terrain of a scene drawn with rung 2, single scattering: the terrain pass of
// render::terrain lit by the light through atmos' single scattering, tabulated per frame
// over the terrain's elevations (render::terrain_rung's rung_light_from_table: the
// table render::cpu_renderer builds with SingleScatteringSky's transmittance from each
// elevation to the top of the atmosphere, the values its own terrain reads; lavapipe
// (Mesa 22.3) crashes compiling the single-scattering march into a fragment stage, so
// the light is not marched per fragment). It writes the surface's own radiance, and
// render::air_single then applies the aerial perspective per pixel (compute). Groups 0
// and 1 (the tables) are declared by render::terrain but not read by these entry
// points; group 3 holds the light (render::terrain_rung).
// Twin: render::cpu_renderer's shade_terrain for rungs without tables, with
// SingleScatteringSky as the segment model.
#import render::terrain_rung

@fragment
fn terrain_single_fragment(in: TerrainVarying) -> @location(0) vec4<f32> {
    return vec4<f32>(terrain_surface(in.world, rung_light_from_table(in.world.y)) * terrain.radiance_scale, 1.0);
}
