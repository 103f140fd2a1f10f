// The terrain's aerial perspective per vertex with rung 2, single scattering
// (render::vertex_air_compute): atmos::single_scattering's in-scatter and transmittance
// of each vertex's segment for one light, with the CPU's SingleScatteringSky's sample
// counts (override constants), as render::air_single evaluates them per pixel.
#import render::vertex_air_compute
#import atmos::single_scattering

// The light's atmosphere.
@group(0) @binding(8) var<uniform> vertex_air_atmosphere: AtmosphereParameters;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

@compute @workgroup_size(64)
fn vertex_air_single(@builtin(global_invocation_id) gid: vec3<u32>) {
    let s = vertex_air_segment(gid);
    if !s.valid {
        return;
    }
    let sample = single_scattering(vertex_air_atmosphere, s.r, s.mu, s.mu_s, s.nu, s.distance, view_samples, light_samples);
    vertex_air_store(gid, s, sample.transmittance, sample.radiance);
}
