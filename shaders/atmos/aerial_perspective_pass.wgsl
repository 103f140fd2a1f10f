// Aerial perspective applied to a caller's colour target from its depth buffer: a
// full-screen triangle whose two fragment entry points are drawn one after the other,
// the first multiplying the target by the transmittance between the camera and the
// surface the depth buffer holds (blend: destination × source), the second adding the
// in-scatter (blend: one + one), so no dual-source blending is needed. Pixels where the
// depth buffer holds the far plane's depth (the sky) are left alone. Bindings: the LUT
// groups 0 and 1 (atmos::lut_bindings; frame_view gives each pixel's ray and distance)
// and this pass's parameters and the depth texture in group 2. Twin:
// atmos::lut::drop_in::depth_aerial_perspective.
#import atmos::aerial_perspective

struct AerialPerspectivePassParameters {
    // The depth the caller's buffer holds where nothing was drawn (1: standard depth,
    // 0: reversed z).
    sky_depth: f32,
    // Multiplies the in-scatter (the unit of the colour target, as the sky pass's).
    radiance_scale: f32,
    padding: vec2<f32>,
}

@group(2) @binding(0) var<uniform> aerial_perspective_pass: AerialPerspectivePassParameters;
@group(2) @binding(1) var scene_depth: texture_depth_2d;

@vertex
fn aerial_perspective_pass_vertex(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.5, 1.0);
}

// In-scatter and transmittance between the frame view's camera and the surface at
// depth `depth` (the caller's depth buffer) seen through the target position
// `position` (pixels, pixel centres at +0.5).
fn depth_aerial_perspective(position: vec2<f32>, depth: f32) -> ScatteringSegment {
    let distance = frame_view_distance(position, depth, frame_view);
    let direction = frame_view_direction_at(position, frame_view);
    return aerial_perspective(direction * distance);
}

fn scene_depth_at(position: vec2<f32>) -> f32 {
    return textureLoad(scene_depth, vec2<i32>(position), 0);
}

@fragment
fn aerial_perspective_pass_transmittance(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let depth = scene_depth_at(position.xy);
    if depth == aerial_perspective_pass.sky_depth {
        discard;
    }
    return vec4<f32>(depth_aerial_perspective(position.xy, depth).transmittance, 1.0);
}

@fragment
fn aerial_perspective_pass_inscatter(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let depth = scene_depth_at(position.xy);
    if depth == aerial_perspective_pass.sky_depth {
        discard;
    }
    let radiance = depth_aerial_perspective(position.xy, depth).radiance;
    return vec4<f32>(radiance * aerial_perspective_pass.radiance_scale, 0.0);
}
