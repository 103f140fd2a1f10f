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
    let p = air_pixel(gid);
    if !p.has_air {
        return;
    }
    var radiance = closed_form_air_radiance(p.segment, air.camera.sun, air_sun);
    if air.moon != 0u {
        radiance += closed_form_air_radiance(p.segment, air.moon_direction, air_moon);
    }
    let s = p.segment;
    air_store(gid, p, closed_form_sky_transmittance(s.r, s.mu, s.distance, air_sun), radiance);
}
