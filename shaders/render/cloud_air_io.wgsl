// What every cloud air pass (render::volume_air with the precomputed tables,
// render::cloud_air_rung with a rung without tables) reads and writes: its
// group 2 (the uniform, cloudlight's march output, the air per pixel: one layout,
// `air_layout` of crates/render/src/gpu/cloud_composite.rs, whose air buffer the
// composite reads) and each pixel's segment camera → the cloud's transmittance-weighted
// depth.
#import atmos::frame
#import render::air_segment

struct CloudAirParams {
    width: u32,
    height: u32,
    padding0: u32,
    padding1: u32,
}

@group(2) @binding(0) var<uniform> cloud_air_params: CloudAirParams;
// cloudlight's march output: two vec4 per pixel, x fastest (radiance rgb + T_c, then the
// transmittance-weighted depth d in x).
@group(2) @binding(1) var<storage, read> cloud_march: array<vec4<f32>>;
// Two vec4 per pixel: the air's in-scattered radiance, then its transmittance (written
// where the cloud has opacity, T_c < 1).
@group(2) @binding(2) var<storage, read_write> cloud_air: array<vec4<f32>>;

// A pixel's segment (render::air_segment): camera → the cloud's depth; `has_air` false
// outside the image or where the cloud has no opacity.
fn cloud_air_segment(pixel: vec2<u32>, camera: FrameCamera) -> AirSegment {
    var s: AirSegment;
    if pixel.x >= cloud_air_params.width || pixel.y >= cloud_air_params.height {
        return s;
    }
    let index = 2u * (pixel.y * cloud_air_params.width + pixel.x);
    if !(cloud_march[index].w < 1.0) {
        s.index = index;
        return s;
    }
    let view = frame_view_direction(pixel, camera);
    return air_segment(index, view, cloud_march[index + 1u].x, camera);
}

// Writes the segment's in-scattered radiance and transmittance.
fn cloud_air_store(s: AirSegment, radiance: vec3<f32>, transmittance: vec3<f32>) {
    cloud_air[s.index] = vec4<f32>(radiance, 0.0);
    cloud_air[s.index + 1u] = vec4<f32>(transmittance, 0.0);
}
