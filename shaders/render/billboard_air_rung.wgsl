// The air in front of each billboard particle with a rung without tables: the rung's
// in-scatter and transmittance (render::rung_sky's segment_air, bound to the rung's
// module) of the segment camera → the particle's centre (render::billboard_air_io), for
// the light whose direction is `billboard_air_camera.sun` and whose atmosphere's
// parameters are bound in group 1 (the groups of render::gpu::cloud_air's RungCloudAir),
// as render::cloud_air_rung evaluates it per pixel. A compute pass before the
// billboards' draw (render::billboard_clouds_rung reads its output per instance). CPU
// twin: render::billboard_clouds::composite_billboards_cpu without tables (the segment
// model, SkyQuery::with_max_distance).
#import atmos::frame
#import render::billboard_air_io
#import render::rung_sky

@group(0) @binding(0) var<uniform> billboard_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> billboard_air_parameters: RungParameters;

@compute @workgroup_size(64)
fn billboard_air_rung(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = billboard_air_segment(id.x, billboard_air_camera);
    if !s.has_air {
        return;
    }
    let air = segment_air(s, billboard_air_camera.sun, billboard_air_parameters);
    billboard_air_store(s, air.radiance, air.transmittance);
}
