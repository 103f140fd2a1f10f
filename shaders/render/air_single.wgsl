// The terrain's aerial perspective with rung 2, single scattering (render::rung_air):
// atmos::single_scattering's in-scatter and transmittance of each terrain pixel's
// segment, by render::air_segment_single (what the clouds' and the billboards' air
// passes call too), with the CPU's SingleScatteringSky's sample counts (override
// constants).
#import render::rung_air
#import atmos::single_scattering
#import render::air_segment_single

@group(1) @binding(0) var<uniform> air_sun: AtmosphereParameters;
@group(1) @binding(1) var<uniform> air_moon: AtmosphereParameters;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

@compute @workgroup_size(8, 8)
fn air_single(@builtin(global_invocation_id) gid: vec3<u32>) {
    let p = air_pixel(gid);
    if !p.segment.has_air {
        return;
    }
    let sun = air_segment_single(p.segment, air.camera.sun, air_sun, view_samples, light_samples);
    var radiance = sun.radiance;
    if air.moon != 0u {
        radiance += air_segment_single(p.segment, air.moon_direction, air_moon, view_samples, light_samples).radiance;
    }
    air_store(gid, p, sun.transmittance, radiance);
}
