// The air in front of each billboard particle with rung 1, the closed form:
// atmos::closed_form_sky's in-scatter and transmittance of the segment camera → the
// particle's centre (render::billboard_air_io), for the light whose direction is
// `billboard_air_camera.sun` and whose parameters are bound in group 1 (the groups of
// render::gpu::cloud_air's RungCloudAir: the formulas of render::cloud_air_closed_form,
// per particle). A compute pass before the billboards' draw
// (render::billboard_clouds_rung reads its output per instance). CPU twin:
// render::billboard_clouds::composite_billboards_cpu without tables (the segment model,
// SkyQuery::with_max_distance).
#import atmos::frame
#import atmos::closed_form_sky
#import render::billboard_air_io

@group(0) @binding(0) var<uniform> billboard_air_camera: FrameCamera;
@group(1) @binding(0) var<uniform> billboard_air_rung: ClosedFormSkyParameters;

@compute @workgroup_size(64)
fn billboard_air_closed_form(@builtin(global_invocation_id) id: vec3<u32>) {
    let s = billboard_air_segment(id.x, billboard_air_camera);
    if !s.has_air {
        return;
    }
    let light = billboard_air_camera.sun;
    let mu_s = dot(light, s.up);
    let sunlight = closed_form_sunlight(s.r, mu_s, billboard_air_rung);
    let radiance = closed_form_sky_radiance(s.r, s.mu, mu_s, dot(s.view, light), s.distance, sunlight, billboard_air_rung);
    let transmittance = closed_form_sky_transmittance(s.r, s.mu, s.distance, billboard_air_rung);
    billboard_air_store(s, radiance, transmittance);
}
