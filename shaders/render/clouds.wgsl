// Cloud layers over the opaque scene: celestial's SGSky layers composited farthest
// first, each hidden where the terrain is nearer than the layer. The layer's look is
// celestial::clouds::cloud_layer_radiance; this pass decides, per pixel, which layers
// are in front of the scene (the terrain's distance from its reverse-z depth). Twin:
// render::clouds (Rust): same names, argument order and units.
//
// The fragment writes the composite (the layers, then the in-cloud fog) as c + a·background with c = F(0) and
// a = F(1) − F(0) (F is affine in the background: each layer mixes it with its own
// colour by its opacity), so fixed-function blending (One, OneMinusSrcAlpha) applies it
// over the scene already in the colour target (which holds radiance × exposure: c is
// scaled by it, the background's weight a is not).
#import atmos::frame
#import celestial::clouds
#import common::frames
#import render::in_cloud_fog

struct CloudComposite {
    camera: FrameCamera,
    // The viewer's distance from the planet's centre (m), on celestial's +z axis.
    viewer_radius: f32,
    // The near plane of the scene's reverse-z projection (m).
    near: f32,
    layer_count: u32,
    // Multiplies the layers' own light (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    // The fog of the layers the camera is in or near, over everything drawn so far.
    fog: InCloudFogUniforms,
}

@group(0) @binding(0) var<uniform> composite: CloudComposite;
@group(0) @binding(1) var<storage, read> cloud_layers: array<CloudLayerUniforms>;
@group(0) @binding(2) var scene_depth: texture_depth_2d;

// Distance (m) along `view` (east/north/up) from radius r to the layer's near surface
// (its base seen from below, its top from above), or −1 when the view does not reach it.
fn cloud_hit_distance(view: vec3<f32>, r: f32, layer: CloudLayerUniforms) -> f32 {
    var surface = layer.top_radius;
    if r < layer.base_radius {
        surface = layer.base_radius;
    }
    return cloud_layer_distance(r, view.z, surface, layer.curved);
}

// `background` through the layers along the world direction `view` from radius r, each
// drawn only where it is nearer than the scene (scene_distance, m along the view), then
// through the in-cloud fog around the camera.
fn composite_cloud_layers(view: vec3<f32>, r: f32, scene_distance: f32, background: vec3<f32>) -> vec3<f32> {
    let enu = world_to_enu(view);
    var out = background;
    for (var i = 0u; i < composite.layer_count; i++) {
        let layer = cloud_layers[i];
        let distance = cloud_hit_distance(enu, r, layer);
        if distance >= 0.0 && distance < scene_distance {
            out = cloud_layer_radiance(enu, r, layer, out);
        }
    }
    return in_cloud_fog(enu.z, scene_distance, composite.fog, out);
}

// The scene's distance along `view` from its reverse-z depth with an infinite far
// plane (depth = near / view-space z); the sky (depth 0) is infinitely far.
fn scene_distance_from_depth(depth: f32, view: vec3<f32>) -> f32 {
    if depth <= 0.0 {
        return 3.0e38;
    }
    return composite.near / (depth * dot(view, composite.camera.forward));
}

@vertex
fn clouds_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn clouds_fragment(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let pixel = vec2<u32>(position.xy);
    let view = frame_view_direction(pixel, composite.camera);
    let distance = scene_distance_from_depth(textureLoad(scene_depth, pixel, 0), view);
    let r = composite.viewer_radius;
    let c = composite_cloud_layers(view, r, distance, vec3<f32>(0.0));
    let a = composite_cloud_layers(view, r, distance, vec3<f32>(1.0)) - c;
    return vec4<f32>(c * composite.radiance_scale, 1.0 - a.g);
}
