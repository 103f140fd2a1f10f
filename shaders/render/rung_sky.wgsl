// The sky of a rung without tables, as the passes written once for every such rung
// read it: the slot their entries import (the terrain's air per pixel,
// render::rung_air, and per vertex, render::vertex_air_compute; the air in front of a
// marched cloud, render::cloud_air_rung, and of a billboard particle,
// render::billboard_air_rung; the terrain's light, render::terrain_rung), which the
// Rust side binds to the rung's own module at composition
// (Composer::compose_module_bound; render::gpu::rung_kind maps a Rung to its module):
// render::rung_closed_form (rung 1) or render::rung_single (rung 2). A rung's module
// defines
//   alias RungParameters               the uniform of one light's atmosphere that the
//                                      passes bind, each at its own group
//   segment_air(s, light, params)      the in-scatter and transmittance of the segment
//     -> SegmentAir                    s (render::air_segment) lit from the unit
//                                      direction light
//   terrain_light_irradiance(path,     the light's irradiance at a terrain point whose
//     tabulated, params) -> vec3<f32>  path toward the light is path (RungLightPath);
//                                      tabulated is that irradiance as the frame's
//                                      table over the terrain's elevations gives it
//                                      (render::terrain_rung), for a rung whose
//                                      transmittance is a march that a fragment stage
//                                      does not run
// and any override constants its functions read (render::gpu::rung_kind's
// air_constants). This module is the trivial rung, which every entry composes and
// validates with on its own: no air (no in-scatter, transmittance 1) and no light.
#import render::air_segment

alias RungParameters = vec4<f32>;

fn segment_air(s: AirSegment, light: vec3<f32>, params: RungParameters) -> SegmentAir {
    return SegmentAir(vec3<f32>(0.0), vec3<f32>(1.0));
}

fn terrain_light_irradiance(path: RungLightPath, tabulated: vec3<f32>, params: RungParameters) -> vec3<f32> {
    return vec3<f32>(0.0);
}
