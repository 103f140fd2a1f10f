// The terrain of a scene drawn with rung 1, the closed form (`closed-form`, and
// `closed-form-vertex`, whose terrain segments are per pixel as on the CPU): the
// terrain pass of render::terrain (its vertices, shading and bindings in group 2) lit
// by the light through atmos::closed_form_sky's transmittance instead of the
// precomputed tables; it writes the surface's own radiance, and render::air_closed_form
// then applies the aerial perspective per pixel. Groups 0 and 1 (the tables) are
// declared by render::terrain but not read by these entry points; group 3 holds the
// light (render::terrain_rung) and the closed form's parameters for its atmosphere.
// Twin: render::cpu_renderer's shade_terrain for rungs without tables, with
// ClosedFormSky as the segment model.
#import render::terrain_rung
#import atmos::closed_form_sky

@group(3) @binding(1) var<uniform> rung_closed_form: ClosedFormSkyParameters;

// The light's irradiance at a terrain point `elevation` metres above the camera's
// ground point. Twin: render::cpu_renderer::light_irradiance_at with ClosedFormSky.
fn closed_form_light_at(elevation: f32) -> vec3<f32> {
    let path = rung_light_path(elevation);
    if path.hidden {
        return vec3<f32>(0.0);
    }
    return closed_form_sky_transmittance(path.r, path.mu_s, path.top, rung_closed_form) * rung_closed_form.sun_irradiance;
}

@fragment
fn terrain_closed_form_fragment(in: TerrainVarying) -> @location(0) vec4<f32> {
    return vec4<f32>(terrain_surface(in.world, closed_form_light_at(in.world.y)) * terrain.radiance_scale, 1.0);
}
