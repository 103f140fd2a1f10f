//! Seed 003's ordered ray-march jitter. Twin of `shaders/cloudlight/jitter.wgsl`.

/// The 4×4 Bayer threshold of a pixel as a fraction of a step: `{0, 1/16, …, 15/16}`.
pub fn bayer_jitter_4x4(pixel: [u32; 2]) -> f32 {
    let a = (pixel[0] ^ pixel[1]) & 3;
    let y = pixel[1] & 3;
    let index = ((a & 1) << 3) | ((y & 1) << 2) | (((a >> 1) & 1) << 1) | ((y >> 1) & 1);
    index as f32 * (1.0 / 16.0)
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
