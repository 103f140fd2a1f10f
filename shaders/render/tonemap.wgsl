// Display encoding: exposure tone map (O'Neil 2005), sRGB transfer, dithered 8-bit
// quantisation. Twin: render::tonemap (Rust). Same names and arguments.
#import common::hash
#import atmos::transmittance

// O'Neil 2005's tone map, 1 − exp(−radiance·exposure) per channel, using the accurate
// 1 − e^{−x} so that dim radiance keeps its digits.
fn tonemap_exposure(radiance: vec3<f32>, exposure: f32) -> vec3<f32> {
    let x = radiance * exposure;
    return vec3<f32>(one_minus_exp_neg(x.x), one_minus_exp_neg(x.y), one_minus_exp_neg(x.z));
}

// The sRGB transfer function (IEC 61966-2-1) for one channel in [0, 1].
fn linear_to_srgb(linear: f32) -> f32 {
    if linear <= 0.0031308 {
        return 12.92 * linear;
    }
    return 1.055 * pow(linear, 1.0 / 2.4) - 0.055;
}

// Triangular-PDF dither in (−1, 1) LSB for a pixel: the sum of two independent
// 23-bit uniform draws from the shared hash, formed in integers and converted once
// (exactly: |sum − 2²³| < 2²⁴), so CPU and GPU add the bit-identical offset. (Float
// additions here were measured to differ by 2⁻²⁴ on lavapipe.)
fn dither_offset(pixel: vec2<u32>, seed: u32) -> f32 {
    let h = hash_combine(hash_combine(seed, pixel.x), pixel.y);
    let sum = (h >> 9u) + (hash_u32(h ^ 0x5bd1e995u) >> 9u);
    return f32(i32(sum) - 8388608) * (1.0 / 8388608.0);
}

// sRGB-encodes a display value in [0, 1]³, adds the pixel's dither and quantises
// to 8 bits; returns the code values 0…255 (as f32, exact).
fn quantize_srgb8(display: vec3<f32>, pixel: vec2<u32>, seed: u32) -> vec3<f32> {
    let offset = dither_offset(pixel, seed);
    let encoded = vec3<f32>(linear_to_srgb(display.x), linear_to_srgb(display.y), linear_to_srgb(display.z));
    return clamp(floor(encoded * 255.0 + offset + 0.5), vec3<f32>(0.0), vec3<f32>(255.0));
}

// Packs code values into RGBA8 (alpha 255), little-endian: R in the low byte.
fn pack_rgba8(code: vec3<f32>) -> u32 {
    let c = vec3<u32>(code);
    return c.x | (c.y << 8u) | (c.z << 16u) | (255u << 24u);
}
