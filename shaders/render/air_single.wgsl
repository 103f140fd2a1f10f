// The terrain's aerial perspective with rung 2, single scattering (render::rung_air):
// atmos::single_scattering's in-scatter and transmittance of each terrain pixel's
// segment, with the CPU's SingleScatteringSky's sample counts (override constants).
#import render::rung_air
#import atmos::single_scattering

@group(1) @binding(0) var<uniform> air_sun: AtmosphereParameters;
@group(1) @binding(1) var<uniform> air_moon: AtmosphereParameters;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

fn single_air(s: AirSegment, light: vec3<f32>, atmosphere: AtmosphereParameters) -> SingleScatteringSample {
    return single_scattering(atmosphere, s.r, s.mu, dot(light, s.up), dot(s.view, light), s.distance, view_samples, light_samples);
}

@compute @workgroup_size(8, 8)
fn air_single(@builtin(global_invocation_id) gid: vec3<u32>) {
    let p = air_pixel(gid);
    if !p.has_air {
        return;
    }
    let sun = single_air(p.segment, air.camera.sun, air_sun);
    var radiance = sun.radiance;
    if air.moon != 0u {
        radiance += single_air(p.segment, air.moon_direction, air_moon).radiance;
    }
    air_store(gid, p, sun.transmittance, radiance);
}
