// The closed form's terrain fragment with the aerial perspective per vertex
// (render::terrain_rung_aerial_vertex): lit as render::terrain_closed_form lights it.
#import render::terrain_closed_form
#import render::terrain_rung_aerial_vertex

@fragment
fn terrain_closed_form_aerial_fragment(in: TerrainRungAerialVarying) -> @location(0) vec4<f32> {
    return terrain_rung_aerial_radiance(in, closed_form_light_at(in.world.y));
}
