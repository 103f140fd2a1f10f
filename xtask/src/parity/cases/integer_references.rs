//! Independent references for the integer cases: the published hash and the
//! counter-based draws written a second time, in 64-bit arithmetic reduced modulo 2^32
//! by hand (no `wrapping_*`, no call into the crates under test), and the bit-sliced
//! comparison replaced by the plain per-lane one. A changed constant, shift or
//! operation order in the Rust twin or the WGSL makes these cases fail, which calling
//! the twin itself as the reference could not.

/// 2^32 − 1: every product and sum below is reduced with it.
const MASK32: u64 = 0xffff_ffff;

/// Chris Wellons' "lowbias32" integer hash (hash-prospector; constants 0x7feb352d and
/// 0x846ca68b, shifts 16, 15, 16), in u64 reduced modulo 2^32 after each product.
pub fn lowbias32(value: u32) -> u32 {
    let mut x = u64::from(value);
    x ^= x >> 16;
    x = (x * 0x7feb_352d) & MASK32;
    x ^= x >> 15;
    x = (x * 0x846c_a68b) & MASK32;
    x ^= x >> 16;
    x as u32
}

/// Boost's `hash_combine` step, `seed ^ (value + 0x9e3779b9 + (seed << 6) + (seed >> 2))`
/// (each term modulo 2^32), finished by [`lowbias32`].
pub fn combine(seed: u32, value: u32) -> u32 {
    let seed64 = u64::from(seed);
    let sum = (u64::from(value) + 0x9e37_79b9 + ((seed64 << 6) & MASK32) + (seed64 >> 2)) & MASK32;
    lowbias32(seed ^ sum as u32)
}

/// `cloudsim`'s per-step, per-stream key: the seed hashed, then combined with the step
/// and the stream.
pub fn stream_key(seed: u32, step: u32, stream: u32) -> u32 {
    combine(combine(lowbias32(seed), step), stream)
}

/// Bit plane `plane` of a word's 32 draws: the word key combined with the plane.
pub fn plane_bits(word_key: u32, plane: u32) -> u32 {
    combine(word_key, plane)
}

/// The 16-bit draw of one lane: plane `k` gives bit `15 − k`.
pub fn uniform16(key: u32, word: u32, lane: u32) -> u32 {
    let word_key = combine(key, word);
    (0..16).fold(0, |u, k| {
        u | ((plane_bits(word_key, k) >> lane) & 1) << (15 - k)
    })
}

/// The lanes of `candidates` whose draw is below `threshold` (in [0, 2^16]), one lane
/// at a time: the comparison `below_lane_thresholds` performs bit-sliced.
pub fn below_threshold(key: u32, word: u32, candidates: u32, threshold: u32) -> u32 {
    (0..32)
        .filter(|&lane| candidates >> lane & 1 == 1 && uniform16(key, word, lane) < threshold)
        .fold(0, |less, lane| less | 1 << lane)
}

/// A lane's threshold at mask level `level` of 256: `floor(t·l/256)`, or
/// `floor(t·(256 − l)/256)` for the extinction stream (0), in exact f64 arithmetic.
pub fn lane_threshold(threshold: u32, level: u32, stream: u32) -> u32 {
    let scale = if stream == 0 {
        256.0 - f64::from(level)
    } else {
        f64::from(level)
    };
    (f64::from(threshold) * scale / 256.0).floor() as u32
}

/// Cells a slice of 16.16 velocity `q` moves during `step`: `floor(v(step + 1)) −
/// floor(v·step)` with `v = q / 2^16`, in exact 128-bit arithmetic.
pub fn wind_shift(velocity_q: i32, step: u32) -> i32 {
    let q = i128::from(velocity_q);
    let s = i128::from(step);
    ((q * (s + 1)).div_euclid(65_536) - (q * s).div_euclid(65_536)) as i32
}

/// `render`'s dither offset in (−1, 1): the pixel hashed with the seed, then the sum of
/// two 23-bit uniforms (a triangular distribution), in f64.
pub fn dither_offset(pixel: [u32; 2], seed: u32) -> f64 {
    let h = combine(combine(seed, pixel[0]), pixel[1]);
    let second = lowbias32(h ^ 0x5bd1_e995);
    f64::from((h >> 9) + (second >> 9)) / 8_388_608.0 - 1.0
}

#[cfg(test)]
mod tests {
    use super::*;

    // These agree with the twins over the parity grids (that is the parity run); here
    // only spot checks that the second spellings are wired to the right arguments.

    #[test]
    fn hash_and_combine_agree_with_the_twins_at_the_edges() {
        for v in [0, 1, 0x9e37_79b9, u32::MAX] {
            assert_eq!(lowbias32(v), skyscape_wgsl::common::hash_u32(v));
            assert_eq!(combine(v, 7), skyscape_wgsl::common::hash_combine(v, 7));
        }
    }

    #[test]
    fn draws_agree_with_the_bit_sliced_twin() {
        let key = stream_key(42, 3, 1);
        assert_eq!(key, cloudsim::rng::stream_key(42, 3, 1));
        for threshold in [0, 1, 30_000, 65_535, 65_536] {
            let planes = cloudsim::rng::uniform_threshold_planes(threshold);
            assert_eq!(
                below_threshold(key, 5, 0xffff_0f0f, threshold),
                cloudsim::twins::below_lane_thresholds(key, 5, 0xffff_0f0f, &planes)
            );
        }
        assert_eq!(uniform16(key, 9, 31), cloudsim::rng::uniform16(key, 9, 31));
    }

    #[test]
    fn wind_shift_and_dither_agree_with_the_twins() {
        for (q, step) in [(98_304, 5), (-98_304, 5), (-1, 0), (16 * 65_536, u32::MAX)] {
            assert_eq!(wind_shift(q, step), cloudsim::rng::wind_shift(q, step));
        }
        let twin = render::tonemap::dither_offset([3, 4], 7);
        assert_eq!(dither_offset([3, 4], 7), f64::from(twin));
    }
}
