// The volumetric cloud over the opaque scene: reads cloudlight's march output (two
// vec4 per pixel, x fastest: radiance rgb + transmittance T_c, then the
// transmittance-weighted depth d), the air in front of it (render::volume_air: atmos'
// aerial_perspective to d, per light) and the terrain's reverse-z depth, and draws the
// cloud where d is nearer than the terrain. At night (moonlit = 1) the cloud's moonlit
// march is added, seen through the moonlit air. Twin: render::cpu_renderer's
// composite_volume_cloud (render::volume_clouds).
//
// The fragment is Σ_lights (L_c·T_air + L_air·(1 − T_c)) × radiance_scale with alpha
// T_c; the pipeline blends it as src·1 + dst·src_alpha, i.e. + T_c · L_behind (the
// colour target holds radiance × exposure, so only the cloud's own light is scaled).
#import atmos::frame
#import render::scene_distance
#import render::volume_composite

struct VolumeComposite {
    camera: FrameCamera,
    // The near plane of the scene's reverse-z projection (m).
    near: f32,
    // Multiplies the cloud's own light (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    // The march image's width (pixels).
    width: u32,
    // 1: add the moonlit march (bindings 4 and 5); 0: the sun's only.
    moonlit: u32,
}

@group(0) @binding(0) var<uniform> composite: VolumeComposite;
@group(0) @binding(1) var<storage, read> march: array<vec4<f32>>;
@group(0) @binding(2) var scene_depth: texture_depth_2d;
// render::volume_air's output for the sun: radiance, then transmittance, per pixel.
@group(0) @binding(3) var<storage, read> air: array<vec4<f32>>;
// The march lit by the moon and its air (the sun's buffers again when moonlit = 0).
@group(0) @binding(4) var<storage, read> moon_march: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read> moon_air: array<vec4<f32>>;

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
    // cloud_in_front: some opacity, nearer than the scene.
    if !(cloud.w < 1.0 && depth < behind) {
        return vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    var seen = cloud_through_air(cloud, air[i + 1u].xyz, air[i].xyz);
    if composite.moonlit != 0u {
        seen += cloud_through_air(moon_march[i], moon_air[i + 1u].xyz, moon_air[i].xyz);
    }
    return vec4<f32>(seen * composite.radiance_scale, cloud.w);
}
