// The air in front of each billboard particle with rung 2, single scattering:
// atmos::single_scattering's in-scatter and transmittance of the segment camera → the
// particle's centre (render::billboard_air_io), for the light whose direction is
// `billboard_air_camera.sun` and whose atmosphere is bound in group 1 (the groups of
// render::gpu::cloud_air's RungCloudAir), by render::air_segment_single, which
// render::cloud_air_single calls per pixel, with the CPU's SingleScatteringSky's sample
// counts (override constants).
// A compute pass before the billboards' draw (render::billboard_clouds_rung reads its
// output per instance). CPU twin: render::billboard_clouds::composite_billboards_cpu
// without tables (the segment model, SkyQuery::with_max_distance).
#import atmos::frame
#import atmos::single_scattering
#import render::billboard_air_io
#import render::air_segment_single

@group(0) @binding(0) var<uniform> billboard_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> billboard_air_atmosphere: AtmosphereParameters;

override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

@compute @workgroup_size(64)
fn billboard_air_single(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = billboard_air_segment(id.x, billboard_air_camera);
    if !s.has_air {
        return;
    }
    let air = air_segment_single(s, billboard_air_camera.sun, billboard_air_atmosphere, view_samples, light_samples);
    billboard_air_store(s, air.radiance, air.transmittance);
}
