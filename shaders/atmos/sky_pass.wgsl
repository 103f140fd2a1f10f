// The sky drawn into a caller's colour target (a render pipeline: one full-screen
// triangle, normally drawn first with depth writes off, as Hoffman & Preetham 2002
// draw their sky hemisphere): each pixel of the frame view (frame_view: the caller's view and
// projection matrices and viewport, so a viewport anywhere in the target and any
// perspective projection draw the right sky) gets the whole view ray's in-scatter
// (atmos::lut_shading's unlimited_view_segment) and, where the ray sees the sun's disc
// and not the ground, the disc through the ray's transmittance. Bindings: the LUT
// groups 0 and 1 (atmos::lut_bindings) and this pass's parameters in group 2. Twin:
// atmos::lut::drop_in::sky_pass_radiance.
#import atmos::lut_shading

struct SkyPassParameters {
    // Radiance of the sun's disc above the atmosphere (Atmosphere::sun_disc_radiance;
    // zero: no disc).
    sun_disc_radiance: vec3<f32>,
    // cos(the sun's angular radius).
    cos_sun_radius: f32,
    // Multiplies the output (e.g. an exposure, or watts to the target's unit).
    radiance_scale: f32,
    // The clip-space depth the triangle is drawn at (1: the far plane; 0 with reverse z).
    depth: f32,
    padding: vec2<f32>,
}

@group(2) @binding(0) var<uniform> sky_pass: SkyPassParameters;

@vertex
fn sky_pass_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, sky_pass.depth, 1.0);
}

// The radiance the pass writes at the target position `position` (pixels, pixel
// centres at +0.5) of the frame view (before radiance_scale).
fn sky_pass_radiance(position: vec2<f32>, parameters: SkyPassParameters) -> vec3<f32> {
    let camera = frame_camera;
    let direction = frame_view_direction_at(position, frame_view);
    let cosines = view_cosines(camera, direction, lut_atmosphere.planet_radius);
    let segment = unlimited_view_segment(cosines.x, cosines.y, cosines.z, cosines.w);
    let mu = cosines.y;
    // Rays at the ground: only mu < 0 can meet it (docs/architecture.md).
    let sees_ground = mu < 0.0 && ray_sphere_intersect(cosines.x, mu, lut_atmosphere.planet_radius).x >= 0.0;
    if !sees_ground && cosines.w >= parameters.cos_sun_radius {
        return segment.radiance + segment.transmittance * parameters.sun_disc_radiance;
    }
    return segment.radiance;
}

// The largest finite f16. A colour brighter than it (the sun's disc times an exposure)
// is scaled down as a whole to fit an Rgba16Float target: a target clamps (or
// overflows) each channel alone, which would turn a reddened sun's hue to yellow and
// white.
const SKY_PASS_LARGEST: f32 = 65504.0;

@fragment
fn sky_pass_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let radiance = sky_pass_radiance(position.xy, sky_pass) * sky_pass.radiance_scale;
    let peak = max(max(radiance.x, radiance.y), radiance.z);
    return vec4<f32>(radiance * select(1.0, SKY_PASS_LARGEST / peak, peak > SKY_PASS_LARGEST), 1.0);
}
