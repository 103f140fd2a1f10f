//! Ordered ray-march jitter (Schneider 2015). Twin of `shaders/cloudlight/jitter.wgsl`.

/// The 4×4 Bayer threshold of a pixel as a fraction of a step: `{0, 1/16, …, 15/16}`.
pub fn bayer_jitter_4x4(pixel: [u32; 2]) -> f32 {
    let a = (pixel[0] ^ pixel[1]) & 3;
    let y = pixel[1] & 3;
    let index = ((a & 1) << 3) | ((y & 1) << 2) | (((a >> 1) & 1) << 1) | ((y >> 1) & 1);
    index as f32 * (1.0 / 16.0)
}

/// Jimenez's interleaved gradient noise (2014) of a pixel, in `[0, 1)`:
/// `fract(52.9829189 · fract(0.06711056·x + 0.00583715·y))`, a blue-ish start offset with
/// no tile. f32 operation for operation like the WGSL twin `interleaved_gradient_noise`.
pub fn interleaved_gradient_noise(pixel: [u32; 2]) -> f32 {
    let fract = |v: f32| v - v.floor();
    let inner = fract(0.067_110_56 * pixel[0] as f32 + 0.005_837_15 * pixel[1] as f32);
    fract(52.982_918 * inner)
}

#[cfg(test)]
mod tests {
    use super::bayer_jitter_4x4;

    #[test]
    fn matches_the_classic_matrix_and_tiles() {
        const BAYER: [[u32; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
        for y in 0..8u32 {
            for x in 0..8u32 {
                let expected = BAYER[(y % 4) as usize][(x % 4) as usize] as f32 / 16.0;
                assert_eq!(bayer_jitter_4x4([x, y]), expected, "({x}, {y})");
            }
        }
    }
}
