// The air in front of a marched cloud (the volume's, the shell's) with rung 1, the
// closed form: per pixel, atmos::closed_form_sky's in-scatter and transmittance of the
// segment camera → the cloud's transmittance-weighted depth, for the light whose
// direction is `cloud_air_camera.sun` and whose parameters are bound in group 1 (the
// sun's, or at night the moon's). The twin of render::volume_air for a rung without
// tables, with its group 2 (render::cloud_air_io), by render::air_segment_closed_form
// (which render::billboard_air_closed_form calls per particle; the formulas are
// render::air_closed_form's, the terrain's aerial perspective). A compute pass, as
// render::volume_air is (lavapipe crashes compiling the closed form's path length into
// a fragment stage). CPU twin: render::volume_clouds::air_in_front without tables (the
// light's segment model, SkyQuery::with_max_distance).
#import atmos::frame
#import atmos::closed_form_sky
#import render::cloud_air_io
#import render::air_segment_closed_form

@group(0) @binding(0) var<uniform> cloud_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> cloud_air_rung: ClosedFormSkyParameters;

@compute @workgroup_size(8, 8)
fn cloud_air_closed_form(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = cloud_air_segment(id.xy, cloud_air_camera);
    if !s.has_air {
        return;
    }
    let air = air_segment_closed_form(s, cloud_air_camera.sun, cloud_air_rung);
    cloud_air_store(s, air.radiance, air.transmittance);
}
