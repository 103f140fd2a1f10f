// The viewer's window: the frame's display pixels (RGBA8 packed one per u32, R in the
// low byte: the bytes `skyscape render` writes to a PNG) drawn over the window's
// surface, each window pixel the nearest frame pixel. A surface whose format is sRGB
// encodes on write, so the shader decodes first and the window shows the same bytes.

struct WindowPresent {
    // Frame width, height; surface width, height (pixels).
    sizes: vec4<u32>,
    // x: 1 when the surface encodes sRGB on write.
    flags: vec4<u32>,
}

@group(0) @binding(0) var<uniform> window_present: WindowPresent;
@group(0) @binding(1) var<storage, read> pixels: array<u32>;

// One triangle over the whole surface.
@vertex
fn vs_main(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.0, 1.0);
}

fn srgb_to_linear(encoded: vec3<f32>) -> vec3<f32> {
    let low = encoded / 12.92;
    let high = pow((encoded + 0.055) / 1.055, vec3<f32>(2.4));
    return select(high, low, encoded <= vec3<f32>(0.04045));
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let frame = window_present.sizes.xy;
    let surface = max(window_present.sizes.zw, vec2<u32>(1u));
    let pixel = min(
        vec2<u32>(position.xy * vec2<f32>(frame) / vec2<f32>(surface)),
        frame - vec2<u32>(1u),
    );
    let colour = unpack4x8unorm(pixels[pixel.y * frame.x + pixel.x]).rgb;
    if window_present.flags.x == 1u {
        return vec4<f32>(srgb_to_linear(colour), 1.0);
    }
    return vec4<f32>(colour, 1.0);
}
