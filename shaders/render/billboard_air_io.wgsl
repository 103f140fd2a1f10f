// What the rungs' billboard air passes (render::billboard_air_closed_form,
// render::billboard_air_single) read and write (group 2), and each particle's segment
// camera → its centre: the billboards' twin of render::cloud_air_io, per particle
// rather than per pixel. CPU twin: render::billboard_clouds::composite_billboards_cpu
// without tables (SkyQuery::with_max_distance toward the particle's world offset).
#import atmos::frame

struct BillboardAirParams {
    // The particles this frame.
    count: u32,
    padding0: u32,
    padding1: u32,
    padding2: u32,
}

@group(2) @binding(0) var<uniform> billboard_air_params: BillboardAirParams;
// Each particle's centre relative to the eye, world frame (x east, y up, z south), m
// (xyz; render::billboard_clouds::world_offset), in the draw's (back-to-front) order.
@group(2) @binding(1) var<storage, read> billboard_offsets: array<vec4<f32>>;
// Two vec4 per particle: the air's in-scattered radiance, then its transmittance.
@group(2) @binding(2) var<storage, read_write> billboard_air: array<vec4<f32>>;

// A particle's segment: the camera's radius, the view's zenith cosine, the distance to
// the particle's centre, the view and the local up; `has_air` false past the last
// particle (or at the eye itself).
struct BillboardAirSegment {
    index: u32,
    r: f32,
    mu: f32,
    distance: f32,
    view: vec3<f32>,
    up: vec3<f32>,
    has_air: bool,
}

fn billboard_air_segment(particle: u32, camera: FrameCamera) -> BillboardAirSegment {
    var s: BillboardAirSegment;
    if particle >= billboard_air_params.count {
        return s;
    }
    s.index = 2u * particle;
    let offset = billboard_offsets[particle].xyz;
    s.distance = length(offset);
    if !(s.distance > 0.0) {
        // No air between the eye and a particle at the eye: T = 1, L = 0.
        billboard_air[s.index] = vec4<f32>(0.0);
        billboard_air[s.index + 1u] = vec4<f32>(1.0, 1.0, 1.0, 0.0);
        return s;
    }
    s.view = offset / s.distance;
    s.r = length(camera.position);
    s.up = camera.position / s.r;
    s.mu = dot(s.view, s.up);
    s.has_air = true;
    return s;
}

// Writes the segment's in-scattered radiance and transmittance.
fn billboard_air_store(s: BillboardAirSegment, radiance: vec3<f32>, transmittance: vec3<f32>) {
    billboard_air[s.index] = vec4<f32>(radiance, 0.0);
    billboard_air[s.index + 1u] = vec4<f32>(transmittance, 0.0);
}
