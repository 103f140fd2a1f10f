//! Counter-based random draws, built 32 lanes at a time as bit planes, and the wind
//! shift: Rust twins of `shaders/cloudsim/rng.wgsl` (same names, same argument order,
//! bit-identical).
//!
//! Every cell's draw is a pure function of `(seed, step, stream, word, lane)`, where
//! `word = wx + words_per_row * (y + ny * z)` is the packed word holding the cell and
//! `lane = x mod 32` its bit:
//!
//! ```text
//! key      = hash_combine(hash_combine(hash_u32(seed), step), stream)   // per step and stream
//! word_key = hash_combine(key, word)                                    // per word
//! plane_k  = hash_combine(word_key, k)        k = 0..15                 // 32 lanes, one bit each
//! u(lane)  = Σ_k ((plane_k >> lane) & 1) << (15 - k)                    // a uniform 16-bit number
//! ```
//!
//! Plane `k` holds bit `15 - k` of all 32 lanes' numbers, so a word's 32 comparisons
//! `u < t` run *bit-sliced*, most significant plane first, with a running
//! "still equal" mask that usually empties after ~6 planes (`log2(lanes) + 1.3` on
//! average). Each lane compares with its own threshold, also given as bit planes
//! ([`below_lane_thresholds`]); the CPU compares 16 words at once in SIMD lanes and stops
//! once no lane of the 8 is equal, the WGSL twin stops per word. Stopping is only an
//! optimisation: the result is exactly the full 16-bit comparison that [`uniform16`]
//! spells out one cell at a time for the naive reference.
//!
//! Probabilities are therefore quantised to multiples of 2^-16:
//! `threshold = floor(p * 2^16)` in `[0, 2^16]` ([`probability_threshold`]); `p = 1`
//! gives 2^16, which every `u` is below, `p = 0` gives 0, which none is.
//! Region masks scale the threshold of each lane: a cell at mask level `l` in `[0, 256]`
//! compares its one draw with [`lane_threshold`] (`floor(t l / 256)` for supply and
//! activation, `floor(t (256 - l) / 256)` for extinction), so every event keeps a
//! single draw per cell and the bit-sliced comparison reads per-lane threshold planes
//! ([`lane_threshold_planes`], built once per model) instead of one shared threshold.
//! Because nothing depends on evaluation order, the naive, the bit-packed (any thread
//! count) and the WGSL implementations draw identical numbers.

use skyscape_wgsl::common::{hash_combine, hash_u32};

/// Stream of the cloud-extinction draw (`STREAM_EXTINCTION` in WGSL).
pub const STREAM_EXTINCTION: u32 = 0;
/// Stream of the humidity-supply draw (`STREAM_HUMIDITY` in WGSL).
pub const STREAM_HUMIDITY: u32 = 1;
/// Stream of the activation draw (`STREAM_ACTIVATION` in WGSL).
pub const STREAM_ACTIVATION: u32 = 2;

/// Bits of a uniform draw (and of a probability threshold's resolution).
pub const UNIFORM_BITS: u32 = 16;
/// `2^16`: the threshold of probability 1.
pub const THRESHOLD_ONE: u32 = 1 << UNIFORM_BITS;
/// Bits of a mask level's resolution: level `l` in `[0, 256]` means `l / 256`.
pub const MASK_BITS: u32 = 8;
/// The mask level of mask 1 (`MASK_FULL` in WGSL).
pub const MASK_FULL: u16 = 1 << MASK_BITS;

/// Planes of a word's per-lane thresholds ([`lane_threshold_planes`]): 16 bit planes
/// (most significant first), then [`PLANE_ALWAYS`] and [`PLANE_NONZERO`]
/// (`LANE_PLANES` in WGSL).
pub const LANE_PLANES: usize = 18;
/// Index of the plane of lanes whose threshold is 2^16 (the event always happens).
pub const PLANE_ALWAYS: usize = 16;
/// Index of the plane of lanes whose threshold is above 0 (the event can happen).
pub const PLANE_NONZERO: usize = 17;

/// Fixed-point scale of wind velocities: 16.16, i.e. `velocity_q = round(v * 65536)`.
pub const WIND_FIXED_ONE: f64 = 65_536.0;

/// The per-step, per-stream key (`stream_key` in WGSL).
pub fn stream_key(seed: u32, step: u32, stream: u32) -> u32 {
    hash_combine(hash_combine(hash_u32(seed), step), stream)
}

/// The per-word key of a stream (`word_key` in WGSL).
#[inline(always)]
pub fn word_key(key: u32, word: u32) -> u32 {
    hash_combine(key, word)
}

/// Bit plane `plane` (0 = most significant) of the 32 lanes' uniform numbers of a word
/// (`plane_bits` in WGSL).
#[doc(hidden)]
#[inline(always)]
pub fn plane_bits(word_key: u32, plane: u32) -> u32 {
    hash_combine(word_key, plane)
}

/// The uniform 16-bit number of one cell (lane `lane` of packed word `word`), assembled
/// bit by bit from the planes. The naive reference's spelling of the draw: 16 hashes
/// per call, written for clarity.
pub fn uniform16(key: u32, word: u32, lane: u32) -> u32 {
    let wk = word_key(key, word);
    (0..UNIFORM_BITS).fold(0, |u, k| {
        let bit = (plane_bits(wk, k) >> lane) & 1;
        u | bit << (UNIFORM_BITS - 1 - k)
    })
}

/// The threshold of a lane at region-mask level `level` in `[0, 256]` for event stream
/// `stream`, from the base threshold `threshold` in `[0, 2^16]` (`lane_threshold` in
/// WGSL): supply and activation grow toward the ellipsoid centres, `floor(t l / 256)`;
/// extinction grows away from them, `floor(t (256 - l) / 256)`. Exact integer
/// arithmetic (`t l ≤ 2^24`); without ellipsoids the base threshold applies unscaled.
pub fn lane_threshold(threshold: u32, level: u32, stream: u32) -> u32 {
    let scale = if stream == STREAM_EXTINCTION {
        u32::from(MASK_FULL) - level
    } else {
        level
    };
    (threshold * scale) >> MASK_BITS
}

/// The [`LANE_PLANES`] planes of 32 lanes' thresholds (each in `[0, 2^16]`): plane `k <
/// 16` holds bit `15 - k` of every lane's threshold, [`PLANE_ALWAYS`] the lanes at
/// 2^16, [`PLANE_NONZERO`] the lanes above 0. CPU only: the model builds them once and
/// the GPU reads them from a buffer.
pub fn lane_threshold_planes(thresholds: &[u32; 32]) -> [u32; LANE_PLANES] {
    let mut planes = [0u32; LANE_PLANES];
    for (lane, &t) in thresholds.iter().enumerate() {
        if t >= THRESHOLD_ONE {
            planes[PLANE_ALWAYS] |= 1 << lane;
        } else {
            for (k, plane) in planes[..UNIFORM_BITS as usize].iter_mut().enumerate() {
                *plane |= (t >> (UNIFORM_BITS as usize - 1 - k) & 1) << lane;
            }
        }
        planes[PLANE_NONZERO] |= u32::from(t > 0) << lane;
    }
    planes
}

/// The planes of one threshold shared by all 32 lanes (`uniform_threshold_planes` in
/// WGSL): the model without ellipsoids.
pub fn uniform_threshold_planes(threshold: u32) -> [u32; LANE_PLANES] {
    let mut planes = [0u32; LANE_PLANES];
    if threshold >= THRESHOLD_ONE {
        planes[PLANE_ALWAYS] = u32::MAX;
    } else {
        for (k, plane) in planes[..UNIFORM_BITS as usize].iter_mut().enumerate() {
            *plane = 0u32.wrapping_sub(threshold >> (UNIFORM_BITS as usize - 1 - k) & 1);
        }
    }
    planes[PLANE_NONZERO] = 0u32.wrapping_sub(u32::from(threshold > 0));
    planes
}

/// The lanes of `candidates` whose uniform number is below their own threshold, given
/// as planes ([`lane_threshold_planes`]), compared bit-sliced, most significant plane
/// first, stopping once no lane is still equal (`below_lane_thresholds` in WGSL).
/// Lanes outside `candidates` are 0. Equal to comparing [`uniform16`] with each lane's
/// threshold one cell at a time.
#[doc(hidden)]
pub fn below_lane_thresholds(
    key: u32,
    word: u32,
    candidates: u32,
    planes: &[u32; LANE_PLANES],
) -> u32 {
    let mut less = candidates & planes[PLANE_ALWAYS];
    let mut equal = candidates & planes[PLANE_NONZERO] & !planes[PLANE_ALWAYS];
    if equal == 0 {
        return less;
    }
    let wk = word_key(key, word);
    for (k, &t) in (0..UNIFORM_BITS).zip(planes) {
        // threshold bit 1: lanes with bit 0 are below, lanes with 1 stay equal;
        // threshold bit 0: lanes with bit 1 are above, lanes with 0 stay equal
        let r = plane_bits(wk, k);
        less |= equal & t & !r;
        equal &= !(t ^ r);
        if equal == 0 {
            break;
        }
    }
    less
}

/// Words per batch of the CPU's fast path: each draw of a step runs over 16 words.
pub(crate) const WORD_BATCH: usize = 16;

/// Sixteen words' lanes: one AVX-512 register, two AVX2 registers, four SSE2 ones.
pub(crate) type Lanes = [u32; WORD_BATCH];

/// `plane_bits` of a batch of word keys for plane `k`, spelled out step by step over
/// the batch (`hash_combine` then `hash_u32` of `skyscape_wgsl::common`, pinned by a
/// test) so that the compiler keeps it in SIMD registers; `offset` is the per-key part
/// of `hash_combine` (`0x9e3779b9 + (wk << 6) + (wk >> 2)`).
#[inline(always)]
fn plane_bits_batch(word_keys: &Lanes, offset: &Lanes, k: u32) -> Lanes {
    let mut x = [0u32; WORD_BATCH];
    for i in 0..WORD_BATCH {
        x[i] = word_keys[i] ^ k.wrapping_add(offset[i]);
    }
    for v in &mut x {
        *v ^= *v >> 16;
    }
    for v in &mut x {
        *v = v.wrapping_mul(0x7feb_352d);
    }
    for v in &mut x {
        *v ^= *v >> 15;
    }
    for v in &mut x {
        *v = v.wrapping_mul(0x846c_a68b);
    }
    for v in &mut x {
        *v ^= *v >> 16;
    }
    x
}

/// [`below_lane_thresholds`] for `S` draws of 16 words each at once (the CPU's fast
/// path: the three streams of 16 words, `S = 3`), given their word keys
/// ([`word_key`]); `planes(k)` gives plane `k` of every word. Each draw's 16 words sit
/// in SIMD registers, and one exit test serves all of them: the comparison stops
/// once no lane of any word is still equal. The result is the full comparison's.
#[inline(always)]
pub(crate) fn below_lane_thresholds_batch<const S: usize>(
    word_keys: &[Lanes; S],
    candidates: &[Lanes; S],
    planes: impl Fn(usize) -> [Lanes; S],
) -> [Lanes; S] {
    let always = planes(PLANE_ALWAYS);
    let nonzero = planes(PLANE_NONZERO);
    let mut less = [[0u32; WORD_BATCH]; S];
    let mut equal = [[0u32; WORD_BATCH]; S];
    let mut offset = [[0u32; WORD_BATCH]; S];
    let mut any_equal = 0;
    for s in 0..S {
        for i in 0..WORD_BATCH {
            less[s][i] = candidates[s][i] & always[s][i];
            equal[s][i] = candidates[s][i] & nonzero[s][i] & !always[s][i];
            any_equal |= equal[s][i];
            let w = word_keys[s][i];
            offset[s][i] = 0x9e37_79b9u32.wrapping_add(w << 6).wrapping_add(w >> 2);
        }
    }
    if any_equal == 0 {
        return less;
    }
    for k in 0..UNIFORM_BITS {
        let t = planes(k as usize);
        // OR the draws' lanes together first: one horizontal reduction per plane
        let mut any_equal = [0u32; WORD_BATCH];
        for s in 0..S {
            let r = plane_bits_batch(&word_keys[s], &offset[s], k);
            for i in 0..WORD_BATCH {
                less[s][i] |= equal[s][i] & t[s][i] & !r[i];
                equal[s][i] &= !(t[s][i] ^ r[i]);
                any_equal[i] |= equal[s][i];
            }
        }
        if any_equal.iter().fold(0, |a, &e| a | e) == 0 {
            break;
        }
    }
    less
}

/// `floor(p * 2^16)`, the integer threshold of probability `p` in `[0, 1]` (exact in
/// f64). CPU only: the shader receives the result. `None` for NaN or values outside
/// `[0, 1]`, which [`crate::Model::new`] rejects with a typed error.
pub fn probability_threshold(probability: f64) -> Option<u32> {
    (0.0..=1.0)
        .contains(&probability)
        .then(|| (probability * f64::from(THRESHOLD_ONE)).floor() as u32)
}

/// A wind velocity in cells per step as 16.16 fixed point. CPU only.
pub fn wind_velocity_fixed(velocity: f32) -> i32 {
    (f64::from(velocity) * WIND_FIXED_ONE).round() as i32
}

/// How many cells a slice with fixed-point velocity `velocity_q` moves during `step`
/// (`wind_shift` in WGSL): `floor(v (step + 1)) - floor(v step)` with `v =
/// velocity_q / 2^16`, computed exactly in wrapping 32-bit arithmetic, so the shifts of
/// steps `0..t` add up to `floor(v t)` (while `v t` stays within 2^15 cells).
pub fn wind_shift(velocity_q: i32, step: u32) -> i32 {
    // (step * v) mod 2^16: exact under wrapping because 2^16 divides 2^32.
    let remainder = (step.wrapping_mul(velocity_q as u32) & 0xffff) as i32;
    (remainder + velocity_q) >> 16
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Per-lane thresholds of a word: the ends, values next to the lanes' own draws
    /// (the `u == t` corner) and hashed values.
    fn lane_thresholds(u: &[u32], word: u32) -> [u32; 32] {
        std::array::from_fn(|lane| match (word as usize + lane) % 6 {
            0 => 0,
            1 => THRESHOLD_ONE,
            2 => u[lane], // equal: not below
            3 => u[lane] + 1,
            4 => hash_u32(word * 32 + lane as u32) % (THRESHOLD_ONE + 1),
            _ => hash_u32(word * 32 + lane as u32) % 200, // small: long equal runs
        })
    }

    #[test]
    fn batched_hashes_are_the_plane_hashes() {
        // below_lane_thresholds_batch spells out hash_combine + hash_u32; with every
        // lane at threshold 2^15 the first plane decides, so the result is !plane 0.
        let half = uniform_threshold_planes(1 << 15);
        for key in [0u32, 1, 0x9e37_79b9, u32::MAX] {
            let words: [u32; WORD_BATCH] =
                std::array::from_fn(|i| (i as u32 * 977).wrapping_add(key));
            let keys = [words.map(|w| word_key(key, w))];
            let got = below_lane_thresholds_batch(&keys, &[[u32::MAX; WORD_BATCH]], |k| {
                [[half[k]; WORD_BATCH]]
            });
            for (i, &w) in words.iter().enumerate() {
                assert_eq!(got[0][i], !plane_bits(word_key(key, w), 0));
            }
        }
    }

    #[test]
    fn draw_is_the_documented_formula() {
        let (seed, step, word) = (0xdead_beef, 17, 123_456);
        let key = hash_combine(hash_combine(hash_u32(seed), step), STREAM_HUMIDITY);
        assert_eq!(stream_key(seed, step, STREAM_HUMIDITY), key);
        let wk = hash_combine(key, word);
        for lane in [0, 5, 31] {
            let mut u = 0;
            for k in 0..16 {
                u = u << 1 | (hash_combine(wk, k) >> lane & 1);
            }
            assert_eq!(uniform16(key, word, lane), u);
        }
    }

    #[test]
    fn bit_sliced_comparisons_equal_the_per_cell_ones() {
        let key = stream_key(3, 4, STREAM_ACTIVATION);
        let mut batch = Vec::new();
        for word in 0..304u32 {
            let u: Vec<u32> = (0..32).map(|lane| uniform16(key, word, lane)).collect();
            let candidates = hash_u32(word + 77) | hash_u32(word + 78);
            // one threshold for all lanes, around this word's own draws
            let shared = [0, 1, 65, 6553, 32768, 65535, 65536, u[0], u[0] + 1, u[7]];
            for t in shared {
                let got =
                    below_lane_thresholds(key, word, candidates, &uniform_threshold_planes(t));
                for (lane, &ul) in u.iter().enumerate() {
                    let want = (candidates >> lane & 1 == 1) && ul < t;
                    assert_eq!(got >> lane & 1 == 1, want, "word {word} lane {lane} t {t}");
                }
            }
            // a threshold per lane
            let thresholds = lane_thresholds(&u, word);
            let planes = lane_threshold_planes(&thresholds);
            let got = below_lane_thresholds(key, word, candidates, &planes);
            for (lane, &ul) in u.iter().enumerate() {
                let want = (candidates >> lane & 1 == 1) && ul < thresholds[lane];
                assert_eq!(got >> lane & 1 == 1, want, "lanes word {word} lane {lane}");
            }
            batch.push((word, candidates, planes, got));
        }
        // the batched fast path gives the same lanes
        for group in batch.chunks_exact(WORD_BATCH) {
            // two draws side by side: the group's words, and the same words with all
            // candidates (checked against the single-word comparison too)
            let keys = [std::array::from_fn(|i| word_key(key, group[i].0)); 2];
            let candidates = [std::array::from_fn(|i| group[i].1), [u32::MAX; WORD_BATCH]];
            let got = below_lane_thresholds_batch(&keys, &candidates, |k| {
                [std::array::from_fn(|i| group[i].2[k]); 2]
            });
            for (i, entry) in group.iter().enumerate() {
                assert_eq!(got[0][i], entry.3, "batched word {}", entry.0);
                let all = below_lane_thresholds(key, entry.0, u32::MAX, &entry.2);
                assert_eq!(got[1][i], all, "batched word {}, all lanes", entry.0);
            }
        }
    }

    #[test]
    fn lane_thresholds_scale_with_the_mask() {
        let t = 6553;
        assert_eq!(lane_threshold(t, 256, STREAM_HUMIDITY), t);
        assert_eq!(lane_threshold(t, 256, STREAM_ACTIVATION), t);
        assert_eq!(lane_threshold(t, 256, STREAM_EXTINCTION), 0);
        assert_eq!(lane_threshold(t, 0, STREAM_HUMIDITY), 0);
        assert_eq!(lane_threshold(t, 0, STREAM_EXTINCTION), t);
        assert_eq!(lane_threshold(t, 64, STREAM_HUMIDITY), t / 4);
        assert_eq!(lane_threshold(t, 64, STREAM_EXTINCTION), 6553 * 192 / 256);
        assert_eq!(
            lane_threshold(THRESHOLD_ONE, 256, STREAM_ACTIVATION),
            THRESHOLD_ONE
        );
        // planes of a lane at 2^16 and at 0
        let mut ts = [0u32; 32];
        ts[3] = THRESHOLD_ONE;
        ts[4] = 0x8001;
        let p = lane_threshold_planes(&ts);
        assert_eq!(p[PLANE_ALWAYS], 1 << 3);
        assert_eq!(p[PLANE_NONZERO], 1 << 3 | 1 << 4);
        assert_eq!(p[0], 1 << 4);
        assert_eq!(p[15], 1 << 4);
        assert!(p[1..15].iter().all(|&x| x == 0));
    }

    #[test]
    fn thresholds_are_exact_at_the_ends() {
        assert_eq!(probability_threshold(0.0), Some(0));
        assert_eq!(probability_threshold(1.0), Some(THRESHOLD_ONE));
        assert_eq!(probability_threshold(0.5), Some(1 << 15));
        // floor, not round
        assert_eq!(probability_threshold(1.0 / 3.0), Some(21_845));
        assert_eq!(probability_threshold(f64::NAN), None);
        assert_eq!(probability_threshold(1.0 + 1e-9), None);
        let always = uniform_threshold_planes(THRESHOLD_ONE);
        assert_eq!(below_lane_thresholds(7, 1, u32::MAX, &always), u32::MAX);
        let never = uniform_threshold_planes(0);
        assert_eq!(below_lane_thresholds(7, 1, u32::MAX, &never), 0);
    }

    #[test]
    fn wind_shifts_add_up_to_floor_of_distance() {
        for v in [
            0.0f32, 0.25, 0.5, 0.3, 1.0, 1.75, -0.5, -0.3, -2.6, 16.0, -16.0,
        ] {
            let q = wind_velocity_fixed(v);
            let mut total = 0i64;
            for step in 0..5000u32 {
                total += i64::from(wind_shift(q, step));
                let exact = (i64::from(q) * i64::from(step + 1)).div_euclid(1 << 16);
                assert_eq!(total, exact, "v={v} step={step}");
                assert!(wind_shift(q, step).abs() <= 16);
            }
        }
    }
}
