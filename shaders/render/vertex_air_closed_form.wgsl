// The terrain's aerial perspective per vertex with rung 1, the closed form
// (render::vertex_air_compute): atmos::closed_form_sky's in-scatter and transmittance
// of each vertex's segment for one light, as render::air_closed_form evaluates them per
// pixel.
#import render::vertex_air_compute
#import atmos::closed_form_sky

// The closed form's parameters of the light's atmosphere.
@group(0) @binding(8) var<uniform> vertex_air_closed_form_parameters: ClosedFormSkyParameters;

@compute @workgroup_size(64)
fn vertex_air_closed_form(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = vertex_air_segment(gid);
    if !s.valid {
        return;
    }
    let params = vertex_air_closed_form_parameters;
    let sunlight = closed_form_sunlight(s.r, s.mu_s, params);
    let radiance = closed_form_sky_radiance(s.r, s.mu, s.mu_s, s.nu, s.distance, sunlight, params);
    vertex_air_store(gid, s, closed_form_sky_transmittance(s.r, s.mu, s.distance, params), radiance);
}
