// The last pass of a scene: the HDR radiance image to display pixels — exposure,
// the scene's display transform, sRGB, triangular dither, packed RGBA8 (R in the low byte). Twin: the
// CPU renderer's render::cpu_renderer::render_cpu (the same render::tonemap functions).
#import render::tonemap

struct DisplayParameters {
    width: u32,
    height: u32,
    exposure: f32,
    dither_seed: u32,
    // render::tonemap::DisplayTransform::code.
    display_transform: u32,
    padding_a: u32,
    padding_b: u32,
    padding_c: u32,
}

@group(0) @binding(0) var<uniform> display: DisplayParameters;
@group(0) @binding(1) var radiance_image: texture_2d<f32>;
@group(0) @binding(2) var<storage, read_write> display_pixels: array<u32>;

@compute @workgroup_size(8, 8)
fn display_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= display.width || gid.y >= display.height {
        return;
    }
    let radiance = textureLoad(radiance_image, gid.xy, 0).xyz;
    let encoded = display_transform(radiance, display.exposure, display.display_transform);
    display_pixels[gid.x + display.width * gid.y] = pack_rgba8(quantize_srgb8(encoded, gid.xy, display.dither_seed));
}
