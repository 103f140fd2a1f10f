// The per-pixel shading of the precomputed rung for the frame camera: the sky-view
// lookup, the aerial-perspective volume, or a LUT march where neither applies (viewer
// above the atmosphere; a finite segment beyond the volume's range). Shared by the
// compute renderer (atmos::lut_render) and the sky pass (atmos::sky_pass). Twin:
// atmos::lut::precomputed_sky.
#import atmos::lut_sampling

// Below the top, within this band (m), the sky-view lookup is blended into the LUT march
// that takes over above the top, so radiance is continuous as a camera crosses the top.
// Twin: atmos::lut::precomputed_sky::TOP_BLEND_BAND.
const TOP_BLEND_BAND: f32 = 1000.0;

// The whole view ray seen from radius r: sky-view lookup inside, march above, blended.
// Twin: atmos::lut::precomputed_sky::unlimited_view_segment.
fn unlimited_view_segment(r: f32, mu: f32, mu_s: f32, nu: f32) -> ScatteringSegment {
    if r > lut_atmosphere.top_radius {
        return march_view_segment(r, mu, mu_s, nu, UNLIMITED_DISTANCE, lut_settings.pixel_samples);
    }
    let lookup = lookup_sky_view(r, mu, view_sun_cos_azimuth(mu, mu_s, nu));
    let blend = (r - (lut_atmosphere.top_radius - TOP_BLEND_BAND)) / TOP_BLEND_BAND;
    if blend <= 0.0 {
        return lookup;
    }
    let marched = march_view_segment(r, mu, mu_s, nu, UNLIMITED_DISTANCE, lut_settings.pixel_samples);
    return ScatteringSegment(
        lookup.radiance + (marched.radiance - lookup.radiance) * blend,
        lookup.transmittance + (marched.transmittance - lookup.transmittance) * blend,
    );
}

fn shade_pixel(pixel: vec2<u32>) -> ScatteringSegment {
    let camera = frame_camera;
    let direction = frame_view_direction(pixel, camera);
    let cosines = view_cosines(camera, direction, lut_atmosphere.planet_radius);
    let r = cosines.x;
    let mu = cosines.y;
    let mu_s = cosines.z;
    let nu = cosines.w;
    if camera.max_distance >= UNLIMITED_DISTANCE {
        return unlimited_view_segment(r, mu, mu_s, nu);
    }
    // The segment ends at the ground if the ray meets it first (the volume's columns go
    // on through the ground, for the lookups' blend between columns).
    let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    var distance = camera.max_distance;
    if segment.z > 0.5 {
        distance = min(camera.max_distance, segment.y);
    }
    if distance <= lut_settings.aerial_perspective_range {
        let uv = vec2<f32>((f32(pixel.x) + 0.5) / f32(camera.width), (f32(pixel.y) + 0.5) / f32(camera.height));
        return lookup_aerial_perspective(uv, distance);
    }
    return march_view_segment(r, mu, mu_s, nu, camera.max_distance, lut_settings.pixel_samples);
}
