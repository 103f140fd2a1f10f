// The segments whose air a rung without tables evaluates (render::rung_sky): the
// segment camera → a point that every air pass in front of something evaluates (per
// pixel in render::cloud_air_io and the terrain's render::rung_air, per particle in
// render::billboard_air_io, per terrain vertex in render::vertex_air_compute), and the
// light's path from a terrain point (render::terrain_rung). No bindings of its own, so
// each of those passes, with its own groups, imports it, and so does each rung's module
// (render::rung_closed_form, render::rung_single) whose functions take them.
#import atmos::frame

// A segment: the index of its two vec4 in the pass's air output (unused where that is
// a texture, render::rung_air's), the camera's radius, the view's zenith cosine, the
// distance to the point, the view and the local up; `has_air` false where the pass
// writes nothing for it (outside the image, no cloud opacity, the sky behind the
// terrain, past the last particle or the last vertex, a particle at the eye).
struct AirSegment {
    index: u32,
    r: f32,
    mu: f32,
    distance: f32,
    view: vec3<f32>,
    up: vec3<f32>,
    has_air: bool,
}

// What a rung gives for a segment and one light (render::rung_sky's segment_air): the
// in-scattered radiance and the transmittance.
struct SegmentAir {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

// The segment of length `distance` along the unit `view` from the camera, its air
// output at `index`.
fn air_segment(index: u32, view: vec3<f32>, distance: f32, camera: FrameCamera) -> AirSegment {
    var s: AirSegment;
    s.index = index;
    s.view = view;
    s.r = length(camera.position);
    s.up = camera.position / s.r;
    s.mu = dot(s.view, s.up);
    s.distance = distance;
    s.has_air = true;
    return s;
}

// The light's path from a terrain point: its radius and zenith cosine, the distance to
// the top of the atmosphere, and whether the planet hides the light
// (render::terrain_rung's rung_light_path builds it; render::rung_sky's
// terrain_light_irradiance reads it).
struct RungLightPath {
    r: f32,
    mu_s: f32,
    top: f32,
    hidden: bool,
}
