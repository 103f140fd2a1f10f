// The shell and the volume cloud of one scene composited by depth per pixel, one pass
// in place of their two composites (render::gpu::cloud_order): each cloud seen as
// render::volume_clouds sees it alone (where it has opacity nearer than the terrain: its
// light through the air in front of it, the moon's march added at night), then the two
// in the order of their opacity-weighted depths (render::cloud_order's
// clouds_in_depth_order). Twin: render::cloud_order::composite_clouds_by_depth.
//
// The fragment is (S_near + T_near · S_far) × radiance_scale with alpha T_near · T_far;
// the pipeline blends it as src·1 + dst·src_alpha (the colour target holds radiance ×
// exposure, so only the clouds' own light is scaled).
#import atmos::frame
#import render::scene_distance
#import render::volume_composite
#import render::cloud_order

struct CloudOrderComposite {
    camera: FrameCamera,
    // The near plane of the scene's reverse-z projection (m).
    near: f32,
    // Multiplies the clouds' own light (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    // The march images' width (pixels).
    width: u32,
    // 1: add the volume's moonlit march (bindings 4 and 5); 0: the sun's only.
    volume_moonlit: u32,
    // 1: add the shell's moonlit march (bindings 8 and 9); 0: the sun's only.
    shell_moonlit: u32,
    padding0: u32,
    padding1: u32,
    padding2: u32,
}

@group(0) @binding(0) var<uniform> composite: CloudOrderComposite;
@group(0) @binding(1) var scene_depth: texture_depth_2d;
// Each cloud's march (two vec4 per pixel, x fastest: radiance rgb + T_c, then the
// opacity-weighted depth d in x) and render::volume_air's output for it (radiance, then
// transmittance, per pixel); the moonlit march and its air (the sun's again when the
// cloud is not moonlit).
@group(0) @binding(2) var<storage, read> volume_march: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> volume_air: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> volume_moon_march: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> volume_moon_air: array<vec4<f32>>;
@group(0) @binding(6) var<storage, read> shell_march: array<vec4<f32>>;
@group(0) @binding(7) var<storage, read> shell_air: array<vec4<f32>>;
@group(0) @binding(8) var<storage, read> shell_moon_march: array<vec4<f32>>;
@group(0) @binding(9) var<storage, read> shell_moon_air: array<vec4<f32>>;

@vertex
fn cloud_order_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn cloud_order_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    let i = 2u * (pixel.y * composite.width + pixel.x);
    let view = frame_view_direction(pixel, composite.camera);
    let behind = scene_distance_from_depth(textureLoad(scene_depth, pixel, 0), view, composite.camera.forward, composite.near);
    // No cloud: adds nothing, lets everything through.
    var volume = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    let volume_cloud = volume_march[i];
    let volume_depth = volume_march[i + 1u].x;
    // cloud_in_front: some opacity, nearer than the scene.
    if volume_cloud.w < 1.0 && volume_depth < behind {
        var seen = cloud_through_air(volume_cloud, volume_air[i + 1u].xyz, volume_air[i].xyz);
        if composite.volume_moonlit != 0u {
            seen += cloud_through_air(volume_moon_march[i], volume_moon_air[i + 1u].xyz, volume_moon_air[i].xyz);
        }
        volume = vec4<f32>(seen, volume_cloud.w);
    }
    var shell = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    let shell_cloud = shell_march[i];
    let shell_depth = shell_march[i + 1u].x;
    if shell_cloud.w < 1.0 && shell_depth < behind {
        var seen = cloud_through_air(shell_cloud, shell_air[i + 1u].xyz, shell_air[i].xyz);
        if composite.shell_moonlit != 0u {
            seen += cloud_through_air(shell_moon_march[i], shell_moon_air[i + 1u].xyz, shell_moon_air[i].xyz);
        }
        shell = vec4<f32>(seen, shell_cloud.w);
    }
    let both = clouds_in_depth_order(volume, volume_depth, shell, shell_depth);
    return vec4<f32>(both.rgb * composite.radiance_scale, both.w);
}
