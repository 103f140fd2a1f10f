// Rung 1, the closed form (Hoffman & Preetham 2002; atmos::closed_form_sky), as the
// passes of the rungs without tables read a rung's sky: the module bound to
// render::rung_sky for `closed-form` and `closed-form-vertex` (whose sky differs, per
// pixel or per dome vertex, but whose air and terrain light are per pixel, as on the
// CPU). No bindings: each pass binds the closed form's parameters of its light's
// atmosphere at its own group.
#import render::air_segment
#import atmos::closed_form_sky

// The closed form's parameters of one light's atmosphere.
alias RungParameters = ClosedFormSkyParameters;

// The in-scatter of segment `s` lit from the unit `light` direction and its
// transmittance, `params` the closed form's parameters of the light's atmosphere.
// Twin: atmos::closed_form_sky's ClosedFormSky over SkyQuery::with_max_distance.
fn segment_air(s: AirSegment, light: vec3<f32>, params: RungParameters) -> SegmentAir {
    let mu_s = dot(light, s.up);
    let sunlight = closed_form_sunlight(s.r, mu_s, params);
    let radiance = closed_form_sky_radiance(s.r, s.mu, mu_s, dot(s.view, light), s.distance, sunlight, params);
    let transmittance = closed_form_sky_transmittance(s.r, s.mu, s.distance, params);
    return SegmentAir(radiance, transmittance);
}

// The light's irradiance at a terrain point whose path toward the light is `path`:
// none where the planet hides the light, else the closed form's transmittance over the
// path to the top of the atmosphere × the light's irradiance there, evaluated per
// fragment (`tabulated` unused). Twin: render::passes::terrain::lighting's
// light_irradiance_at with ClosedFormSky.
fn terrain_light_irradiance(path: RungLightPath, tabulated: vec3<f32>, params: RungParameters) -> vec3<f32> {
    if path.hidden {
        return vec3<f32>(0.0);
    }
    return closed_form_sky_transmittance(path.r, path.mu_s, path.top, params) * params.sun_irradiance;
}
