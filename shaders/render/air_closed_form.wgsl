// The terrain's aerial perspective with rung 1, the closed form (render::rung_air):
// atmos::closed_form_sky's in-scatter and transmittance of each terrain pixel's segment,
// by render::air_segment_closed_form (what the clouds' and the billboards' air passes
// call too).
#import render::rung_air
#import atmos::closed_form_sky
#import render::air_segment_closed_form

@group(1) @binding(0) var<uniform> air_sun: ClosedFormSkyParameters;
@group(1) @binding(1) var<uniform> air_moon: ClosedFormSkyParameters;

@compute @workgroup_size(8, 8)
fn air_closed_form(@builtin(global_invocation_id) gid: vec3<u32>) {
    let p = air_pixel(gid);
    if !p.segment.has_air {
        return;
    }
    let sun = air_segment_closed_form(p.segment, air.camera.sun, air_sun);
    var radiance = sun.radiance;
    if air.moon != 0u {
        radiance += air_segment_closed_form(p.segment, air.moon_direction, air_moon).radiance;
    }
    air_store(gid, p, sun.transmittance, radiance);
}
