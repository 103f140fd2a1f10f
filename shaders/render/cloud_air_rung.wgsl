// The air in front of a marched cloud (the volume's, the shell's) with a rung without
// tables: per pixel, the rung's in-scatter and transmittance (render::rung_sky's
// segment_air, bound to the rung's module) of the segment camera → the cloud's
// transmittance-weighted depth, for the light whose direction is `cloud_air_camera.sun`
// and whose atmosphere's parameters are bound in group 1 (the sun's, or at night the
// moon's). The twin of render::volume_air for a rung without tables, with its group 2
// (render::cloud_air_io); the formulas are those of the terrain's aerial perspective
// (render::rung_air) and of the billboards' air (render::billboard_air_rung). A compute
// pass, as render::volume_air is (lavapipe crashes compiling the closed form's path
// length into a fragment stage). CPU twin: render::volume_clouds::air_in_front without
// tables (the light's segment model, SkyQuery::with_max_distance).
#import atmos::frame
#import render::cloud_air_io
#import render::rung_sky

@group(0) @binding(0) var<uniform> cloud_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> cloud_air_parameters: RungParameters;

@compute @workgroup_size(8, 8)
fn cloud_air_rung(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = cloud_air_segment(id.xy, cloud_air_camera);
    if !s.has_air {
        return;
    }
    let air = segment_air(s, cloud_air_camera.sun, cloud_air_parameters);
    cloud_air_store(s, air.radiance, air.transmittance);
}
