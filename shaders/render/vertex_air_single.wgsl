// The terrain's aerial perspective per vertex with rung 2, single scattering
// (render::vertex_air_compute): atmos::single_scattering's in-scatter and transmittance
// of each vertex's segment for one light, by render::air_segment_single (what
// render::air_single calls per pixel), with the CPU's SingleScatteringSky's sample
// counts (override constants).
#import render::vertex_air_compute
#import atmos::single_scattering
#import render::air_segment_single

// The light's atmosphere.
@group(0) @binding(8) var<uniform> vertex_air_atmosphere: AtmosphereParameters;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

@compute @workgroup_size(64)
fn vertex_air_single(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = vertex_air_segment(gid);
    if !s.has_air {
        return;
    }
    vertex_air_store(s, air_segment_single(s, vertex_air.light, vertex_air_atmosphere, view_samples, light_samples));
}
