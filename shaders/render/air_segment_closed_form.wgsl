// Rung 1, the closed form, over a segment (render::air_segment): atmos::closed_form_sky's
// in-scatter and transmittance of the segment for one light. No bindings: the clouds'
// air pass (render::cloud_air_closed_form, per pixel), the billboards'
// (render::billboard_air_closed_form, per particle) and the terrain's
// (render::air_closed_form per pixel, render::vertex_air_closed_form per vertex) import
// it with their own groups.
#import render::air_segment
#import atmos::closed_form_sky

// The in-scatter of segment `s` lit from the unit `light` direction and its
// transmittance, `params` the closed form's parameters of the light's atmosphere.
fn air_segment_closed_form(s: AirSegment, light: vec3<f32>, params: ClosedFormSkyParameters) -> SegmentAir {
    let mu_s = dot(light, s.up);
    let sunlight = closed_form_sunlight(s.r, mu_s, params);
    let radiance = closed_form_sky_radiance(s.r, s.mu, mu_s, dot(s.view, light), s.distance, sunlight, params);
    let transmittance = closed_form_sky_transmittance(s.r, s.mu, s.distance, params);
    return SegmentAir(radiance, transmittance);
}
