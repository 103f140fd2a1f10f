// The volumetric cloud over the opaque scene: reads cloudlight's march output (two
// vec4 per pixel, x fastest: radiance rgb + transmittance T_c, then the
// transmittance-weighted depth d) and the terrain's reverse-z depth, and draws the cloud
// where d is nearer than the terrain, seen through the air in front of it (the
// aerial-perspective volume, as the terrain's). Twin: render::cpu_renderer's
// composite_volume_cloud (render::volume_clouds).
//
// The fragment is (L_c·T_air + L_air·(1 − T_c)) × radiance_scale with alpha T_c; the
// pipeline blends it as src·1 + dst·src_alpha, i.e. + T_c · L_behind (the colour target
// holds radiance × exposure, so only the cloud's own light is scaled).
//
// Bindings: the LUTs in groups 0 and 1 (atmos::lut_bindings), the composite in group 2.
#import atmos::aerial_perspective
#import atmos::frame
#import render::scene_distance

struct VolumeComposite {
    camera: FrameCamera,
    // The near plane of the scene's reverse-z projection (m).
    near: f32,
    // Multiplies the cloud's own light (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    // The march image's width (pixels).
    width: u32,
    padding0: u32,
}

@group(2) @binding(0) var<uniform> composite: VolumeComposite;
@group(2) @binding(1) var<storage, read> march: array<vec4<f32>>;
@group(2) @binding(2) var scene_depth: texture_depth_2d;


@vertex
fn volume_clouds_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn volume_clouds_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    let i = 2u * (pixel.y * composite.width + pixel.x);
    let cloud = march[i];
    let depth = march[i + 1u].x;
    let view = frame_view_direction(pixel, composite.camera);
    let behind = scene_distance_from_depth(textureLoad(scene_depth, pixel, 0), view, composite.camera.forward, composite.near);
    // The air in front of the cloud from the aerial-perspective volume: the cloud's
    // point is on this pixel's ray, so always on screen, which is the branch atmos'
    // aerial_perspective (and the CPU twin's drop_in) takes within the volume's range
    // (32 km by default); beyond it this clamps to the last slice where they march.
    // (Calling aerial_perspective itself, whose off-screen branch marches the LUTs,
    // from this full-screen fragment crashes lavapipe: SIGSEGV in llvmpipe, Mesa 22.3.6.)
    let screen = frame_screen_position(frame_camera, view);
    let air = lookup_aerial_perspective(screen.xy, max(depth, 1.0));
    let seen = cloud.rgb * air.transmittance + air.radiance * (1.0 - cloud.w);
    // cloud_in_front: some opacity, nearer than the scene.
    if !(cloud.w < 1.0 && depth < behind) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return vec4<f32>(seen * composite.radiance_scale, cloud.w);
}
