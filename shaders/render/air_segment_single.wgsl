// Rung 2, single scattering, over a segment (render::air_segment):
// atmos::single_scattering's in-scatter and transmittance of the segment for one light.
// No bindings and no override constants: the clouds' air pass
// (render::cloud_air_single, per pixel), the billboards' (render::billboard_air_single,
// per particle) and the terrain's (render::air_single per pixel,
// render::vertex_air_single per vertex) import it with their own groups and pass their
// sample counts.
#import render::air_segment
#import atmos::single_scattering

// The in-scatter of segment `s` lit from the unit `light` direction and its
// transmittance, `atmosphere` the light's, with `view_samples` along the segment and
// `light_samples` toward the light at each.
fn air_segment_single(s: AirSegment, light: vec3<f32>, atmosphere: AtmosphereParameters, view_samples: u32, light_samples: u32) -> SegmentAir {
    let air = single_scattering(atmosphere, s.r, s.mu, dot(light, s.up), dot(s.view, light), s.distance, view_samples, light_samples);
    return SegmentAir(air.radiance, air.transmittance);
}
