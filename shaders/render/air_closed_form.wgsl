// The terrain's aerial perspective with rung 1, the closed form (render::rung_air):
// atmos::closed_form_sky's in-scatter and transmittance of each terrain pixel's segment.
#import render::rung_air
#import atmos::closed_form_sky

@group(1) @binding(0) var<uniform> air_sun: ClosedFormSkyParameters;
@group(1) @binding(1) var<uniform> air_moon: ClosedFormSkyParameters;

// In-scatter of the segment lit from `light` with `params`' irradiance.
fn closed_form_air_radiance(s: AirSegment, light: vec3<f32>, params: ClosedFormSkyParameters) -> vec3<f32> {
    let mu_s = dot(light, s.up);
    let sunlight = closed_form_sunlight(s.r, mu_s, params);
    return closed_form_sky_radiance(s.r, s.mu, mu_s, dot(s.view, light), s.distance, sunlight, params);
}

@compute @workgroup_size(8, 8)
fn air_closed_form(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= air.camera.width || gid.y >= air.camera.height {
        return;
    }
    let surface = textureLoad(air_surface, gid.xy, 0);
    let s = air_segment(gid.xy);
    if s.distance <= 0.0 {
        textureStore(air_out, gid.xy, surface);
        return;
    }
    var radiance = closed_form_air_radiance(s, air.camera.sun, air_sun);
    if air.moon != 0u {
        radiance += closed_form_air_radiance(s, air.moon_direction, air_moon);
    }
    let transmittance = closed_form_sky_transmittance(s.r, s.mu, s.distance, air_sun);
    textureStore(air_out, gid.xy, vec4<f32>(surface.xyz * transmittance + radiance * air.radiance_scale, 1.0));
}
