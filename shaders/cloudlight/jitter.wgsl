// Ray-march start offsets (Schneider 2015) from a 4×4 Bayer matrix, to break up the
// layering of fixed-step marching without white-noise grain. Twin: cloudlight::jitter.

// The Bayer threshold of a pixel as a fraction of a step, in {0, 1/16, …, 15/16}:
// the matrix entry is the bit-reversed interleave of (x xor y, y), exact in f32.
fn bayer_jitter_4x4(pixel: vec2<u32>) -> f32 {
    let a = (pixel.x ^ pixel.y) & 3u;
    let y = pixel.y & 3u;
    let index = ((a & 1u) << 3u) | ((y & 1u) << 2u) | (((a >> 1u) & 1u) << 1u) | ((y >> 1u) & 1u);
    return f32(index) * (1.0 / 16.0);
}

// Jimenez's interleaved gradient noise (2014) of a pixel, in [0, 1):
// fract(52.9829189 · fract(0.06711056·x + 0.00583715·y)). Twin:
// cloudlight::jitter::interleaved_gradient_noise.
fn interleaved_gradient_noise(pixel: vec2<u32>) -> f32 {
    let p = vec2<f32>(pixel);
    let inner = fract(0.06711056 * p.x + 0.00583715 * p.y);
    return fract(52.9829189 * inner);
}
