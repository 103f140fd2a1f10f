// What the rungs' billboard air pass (render::billboard_air_rung) reads and writes
// (group 2), and each particle's segment camera → its centre: the billboards' twin of
// render::cloud_air_io, per particle rather than per pixel. CPU twin: render::billboard_clouds::composite_billboards_cpu
// without tables (SkyQuery::with_max_distance toward the particle's world offset).
#import atmos::frame
#import render::air_segment

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

// A particle's segment (render::air_segment): camera → its centre; `has_air` false past
// the last particle (or at the eye itself).
fn billboard_air_segment(particle: u32, camera: FrameCamera) -> AirSegment {
    var s: AirSegment;
    if particle >= billboard_air_params.count {
        return s;
    }
    let index = 2u * particle;
    let offset = billboard_offsets[particle].xyz;
    let distance = length(offset);
    if !(distance > 0.0) {
        // No air between the eye and a particle at the eye: T = 1, L = 0.
        billboard_air[index] = vec4<f32>(0.0);
        billboard_air[index + 1u] = vec4<f32>(1.0, 1.0, 1.0, 0.0);
        s.index = index;
        s.distance = distance;
        return s;
    }
    return air_segment(index, offset / distance, distance, camera);
}

// Writes the segment's in-scattered radiance and transmittance.
fn billboard_air_store(s: AirSegment, radiance: vec3<f32>, transmittance: vec3<f32>) {
    billboard_air[s.index] = vec4<f32>(radiance, 0.0);
    billboard_air[s.index + 1u] = vec4<f32>(transmittance, 0.0);
}
