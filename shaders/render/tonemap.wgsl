// Display encoding: the display transforms (O'Neil 2005's per-channel tone map, a
// hue-preserving neutral one), sRGB transfer, dithered 8-bit quantisation.
// Twin: render::tonemap (Rust). Same names and arguments.
#import common::hash
#import atmos::transmittance

// O'Neil 2005's tone map, 1 − exp(−radiance·exposure) per channel, using the accurate
// 1 − e^{−x} so that dim radiance keeps its digits.
fn tonemap_exposure(radiance: vec3<f32>, exposure: f32) -> vec3<f32> {
    let x = radiance * exposure;
    return vec3<f32>(one_minus_exp_neg(x.x), one_minus_exp_neg(x.y), one_minus_exp_neg(x.z));
}

// The scene's display transform (render::tonemap::DisplayTransform::code).
const DISPLAY_NEUTRAL: u32 = 0u;
const DISPLAY_PER_CHANNEL: u32 = 1u;
// The largest finite f16, the HDR target's (render::tonemap::HDR_LARGEST).
const HDR_LARGEST: f32 = 65504.0;
// Khronos PBR Neutral's startCompression (0.8 − 0.04) and desaturation.
const NEUTRAL_COMPRESSION_START: f32 = 0.76;
const NEUTRAL_DESATURATION: f32 = 0.15;
// The most white mixed into an infinitely bright colour (a bright light keeps three
// quarters of its saturation).
const NEUTRAL_WHITE_MIX_LIMIT: f32 = 0.25;

// Hue-preserving display transform after Khronos PBR Neutral (2024): the peak channel
// follows the identity to 0.76, then 1 − 0.24² / (p − 0.52); the colour is scaled with
// it (hue and saturation kept), then mixed a bounded fraction towards white at the new
// peak. No toe (it turns dark saturated colours' hue). A colour brighter than
// HDR_LARGEST is scaled down to it as a whole first (an infinite channel counts as the
// largest f32). Twin: render::tonemap::tonemap_neutral.
fn tonemap_neutral(radiance: vec3<f32>, exposure: f32) -> vec3<f32> {
    let unfitted = clamp(radiance * exposure, vec3<f32>(0.0), vec3<f32>(3.40282347e38));
    let brightest = max(max(unfitted.x, unfitted.y), unfitted.z);
    let exposed = unfitted * select(1.0, HDR_LARGEST / brightest, brightest > HDR_LARGEST);
    let peak = max(max(exposed.x, exposed.y), exposed.z);
    if peak < NEUTRAL_COMPRESSION_START {
        return exposed;
    }
    let new_peak = 1.0 - 0.0576 / (peak - 0.52);
    let scale = new_peak / peak;
    let white_mix = NEUTRAL_WHITE_MIX_LIMIT * (1.0 - 1.0 / (NEUTRAL_DESATURATION * (peak - new_peak) + 1.0));
    return exposed * scale * (1.0 - white_mix) + vec3<f32>(new_peak * white_mix);
}

// The scene's display transform: DISPLAY_PER_CHANNEL is tonemap_exposure, any other
// code tonemap_neutral. Twin: render::tonemap::display_transform.
fn display_transform(radiance: vec3<f32>, exposure: f32, transform: u32) -> vec3<f32> {
    if transform == DISPLAY_PER_CHANNEL {
        return tonemap_exposure(radiance, exposure);
    }
    return tonemap_neutral(radiance, exposure);
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
