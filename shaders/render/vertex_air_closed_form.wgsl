// The terrain's aerial perspective per vertex with rung 1, the closed form
// (render::vertex_air_compute): atmos::closed_form_sky's in-scatter and transmittance
// of each vertex's segment for one light, by render::air_segment_closed_form (what
// render::air_closed_form calls per pixel).
#import render::vertex_air_compute
#import atmos::closed_form_sky
#import render::air_segment_closed_form

// The closed form's parameters of the light's atmosphere.
@group(0) @binding(8) var<uniform> vertex_air_closed_form_parameters: ClosedFormSkyParameters;

@compute @workgroup_size(64)
fn vertex_air_closed_form(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = vertex_air_segment(gid);
    if !s.has_air {
        return;
    }
    vertex_air_store(s, air_segment_closed_form(s, vertex_air.light, vertex_air_closed_form_parameters));
}
