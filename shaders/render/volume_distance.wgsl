// The opaque scene's distance along each pixel's ray, from the terrain's reverse-z depth:
// the limit of the volume cloud's march (cloudlight::gpu::MarchPass::prepare_limited),
// so a ridge cuts the cloud where it stands. Twin: the CPU renderer limits its march by
// the terrain hit's distance (render::cpu_renderer; render::volume_clouds::march_pixel).
#import atmos::frame
#import render::scene_distance

struct VolumeDistanceParams {
    camera: FrameCamera,
    // The near plane of the scene's reverse-z projection with an infinite far plane (m).
    near: f32,
    width: u32,
    height: u32,
    padding0: u32,
}

@group(0) @binding(0) var<uniform> params: VolumeDistanceParams;
@group(0) @binding(1) var scene_depth: texture_depth_2d;
// Metres along each pixel's ray, x fastest, row 0 at the top.
@group(0) @binding(2) var<storage, read_write> distances: array<f32>;

@compute @workgroup_size(8, 8)
fn volume_distance_main(@builtin(global_invocation_id) id: vec3<u32>) {
    if id.x >= params.width || id.y >= params.height {
        return;
    }
    let view = frame_view_direction(id.xy, params.camera);
    let depth = textureLoad(scene_depth, id.xy, 0);
    distances[id.y * params.width + id.x] = scene_distance_from_depth(depth, view, params.camera.forward, params.near);
}
