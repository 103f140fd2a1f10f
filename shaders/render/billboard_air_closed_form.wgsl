// The air in front of each billboard particle with rung 1, the closed form:
// atmos::closed_form_sky's in-scatter and transmittance of the segment camera → the
// particle's centre (render::billboard_air_io), for the light whose direction is
// `billboard_air_camera.sun` and whose parameters are bound in group 1 (the groups of
// render::gpu::cloud_air's RungCloudAir), by render::air_segment_closed_form, which
// render::cloud_air_closed_form calls per pixel. A compute pass before the billboards' draw
// (render::billboard_clouds_rung reads its output per instance). CPU twin:
// render::billboard_clouds::composite_billboards_cpu without tables (the segment model,
// SkyQuery::with_max_distance).
#import atmos::frame
#import atmos::closed_form_sky
#import render::billboard_air_io
#import render::air_segment_closed_form

@group(0) @binding(0) var<uniform> billboard_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> billboard_air_rung: ClosedFormSkyParameters;

@compute @workgroup_size(64)
fn billboard_air_closed_form(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = billboard_air_segment(id.x, billboard_air_camera);
    if !s.has_air {
        return;
    }
    let air = air_segment_closed_form(s, billboard_air_camera.sun, billboard_air_rung);
    billboard_air_store(s, air.radiance, air.transmittance);
}
