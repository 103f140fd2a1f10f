// Rung 2, single scattering (atmos::single_scattering, after Bruneton & Neyret 2008
// without the multiple orders), as the passes of the rungs without tables read a
// rung's sky: the module bound to render::rung_sky for `single`, with the CPU's
// SingleScatteringSky's sample counts (override constants, render::gpu::rung_kind's
// air_constants). No bindings: each pass binds the light's atmosphere at its own group.
#import render::air_segment
#import atmos::single_scattering

// One light's atmosphere.
alias RungParameters = AtmosphereParameters;

// Samples along a segment, and toward the light at each.
override view_samples: u32 = 32u;
override light_samples: u32 = 8u;

// The in-scatter of segment `s` lit from the unit `light` direction and its
// transmittance, `atmosphere` the light's, with `view_samples` along the segment and
// `light_samples` toward the light at each. Twin: atmos::single_scattering's
// SingleScatteringSky over SkyQuery::with_max_distance.
fn segment_air(s: AirSegment, light: vec3<f32>, atmosphere: RungParameters) -> SegmentAir {
    let air = single_scattering(atmosphere, s.r, s.mu, dot(light, s.up), dot(s.view, light), s.distance, view_samples, light_samples);
    return SegmentAir(air.radiance, air.transmittance);
}

// The light's irradiance at a terrain point: `tabulated`, the frame's table over the
// terrain's elevations (render::terrain_rung), which render::passes::terrain::lighting's
// light_irradiance_at fills with SingleScatteringSky, the values the CPU's terrain
// reads. The march toward the light is not run per fragment: lavapipe (Mesa 22.3)
// crashes compiling the single-scattering march into a fragment stage. `path` and
// `atmosphere` unused.
fn terrain_light_irradiance(path: RungLightPath, tabulated: vec3<f32>, atmosphere: RungParameters) -> vec3<f32> {
    return tabulated;
}
