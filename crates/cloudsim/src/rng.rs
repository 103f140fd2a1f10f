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
//! average). [`below_threshold`] draws the planes in batches of 8 (SIMD-friendly) and
//! stops after the first batch that leaves no lane equal (88% of full words after 8
//! planes); the WGSL twin stops after any plane. Stopping is only an optimisation: the
//! result is exactly the full 16-bit (or 8-bit) comparison that [`uniform16`] spells
//! out one cell at a time for the naive reference.
//!
//! Probabilities are therefore quantised to multiples of 2^-16:
//! `threshold = floor(p * 2^16)` in `[0, 2^16]` ([`probability_threshold`]); `p = 1`
//! gives 2^16, which every `u` is below, `p = 0` gives 0, which none is.
//! Region masks scale a probability through a *second, independent* draw compared with
//! the cell's 8-bit mask level `l` in `[0, 256]` (`u >> 8 < l`, probability `l / 256`),
//! so the event probability is exactly `t / 2^16 * l / 256` (supply, activation) or
//! `t / 2^16 * (1 - l / 256)` (extinction).
//! Because nothing depends on evaluation order, the naive, the bit-packed (any thread
//! count) and the WGSL implementations draw identical numbers.

use skyscape_wgsl::common::{hash_combine, hash_u32};

/// Stream of the cloud-extinction draw (`STREAM_EXTINCTION` in WGSL).
pub const STREAM_EXTINCTION: u32 = 0;
/// Stream of the humidity-supply draw (`STREAM_HUMIDITY` in WGSL).
pub const STREAM_HUMIDITY: u32 = 1;
/// Stream of the activation draw (`STREAM_ACTIVATION` in WGSL).
pub const STREAM_ACTIVATION: u32 = 2;
/// Added to a stream id for its region-mask draw (`STREAM_MASK_OFFSET` in WGSL): the
/// mask draws of the three events are streams 3, 4 and 5.
pub const STREAM_MASK_OFFSET: u32 = 3;

/// Bits of a uniform draw (and of a probability threshold's resolution).
pub const UNIFORM_BITS: u32 = 16;
/// `2^16`: the threshold of probability 1.
pub const THRESHOLD_ONE: u32 = 1 << UNIFORM_BITS;
/// Bits of a mask level's resolution: level `l` in `[0, 256]` means `l / 256`.
pub const MASK_BITS: u32 = 8;
/// The mask level of mask 1 (`MASK_FULL` in WGSL).
pub const MASK_FULL: u16 = 1 << MASK_BITS;

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

/// Planes computed together before the "still equal" mask is tested: independent
/// hashes overlap in the CPU's pipelines (and vectorise), where one data-dependent exit
/// per plane would serialise them behind a mispredicted branch. With 32 candidate lanes
/// the first batch of 8 decides all lanes 88% of the time (`1 - (1 - 2^-8)^32`).
const PLANE_BATCH: u32 = 8;

/// One batch of planes: `plane_bits(wk, first + k)` for `k < PLANE_BATCH`, spelled
/// out step by step over the whole batch (`hash_combine` then `hash_u32` of
/// `skyscape_wgsl::common`, pinned by a test) so that the compiler runs the 8
/// independent hashes in SIMD lanes.
#[inline(always)]
fn plane_batch(wk: u32, first: u32) -> [u32; PLANE_BATCH as usize] {
    let offset = 0x9e37_79b9u32.wrapping_add(wk << 6).wrapping_add(wk >> 2);
    let mut x: [u32; PLANE_BATCH as usize] =
        std::array::from_fn(|k| wk ^ (first + k as u32).wrapping_add(offset));
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

/// The lanes of `candidates` whose uniform number is below `threshold` (in `[0,
/// 2^16]`, shared by the word), compared bit-sliced, most significant plane first
/// (`below_threshold` in WGSL). Lanes outside `candidates` are 0. Planes are drawn in
/// batches of 8 and the comparison stops after a batch once no lane is still equal:
/// the WGSL twin stops after any plane; both equal the full 16-plane comparison.
#[inline]
pub fn below_threshold(key: u32, word: u32, candidates: u32, threshold: u32) -> u32 {
    if candidates == 0 || threshold == 0 {
        return 0;
    }
    if threshold >= THRESHOLD_ONE {
        return candidates;
    }
    let wk = word_key(key, word);
    let mut less = 0u32;
    let mut equal = candidates;
    for first in (0..UNIFORM_BITS).step_by(PLANE_BATCH as usize) {
        for (k, r) in (first..).zip(plane_batch(wk, first)) {
            // threshold bit 1: lanes with bit 0 are below, lanes with 1 stay equal;
            // threshold bit 0: lanes with bit 1 are above, lanes with 0 stay equal
            let t = 0u32.wrapping_sub((threshold >> (UNIFORM_BITS - 1 - k)) & 1);
            less |= equal & t & !r;
            equal &= !(t ^ r);
        }
        if equal == 0 {
            break;
        }
    }
    less
}

/// The lanes of `candidates` whose mask draw `u >> 8` is below their mask level
/// (`below_mask_level` in WGSL). `planes` are the word's mask planes
/// ([`crate::Model::mask_planes`]): `planes[k]` for `k < 8` is bit `7 - k` of every
/// lane's level, `planes[MASK_PLANE_FULL]` the lanes at level 256 (always below),
/// `planes[MASK_PLANE_ALIVE]` the lanes above level 0.
#[inline]
pub fn below_mask_level(key: u32, word: u32, candidates: u32, planes: &[u32]) -> u32 {
    let full = candidates & planes[MASK_PLANE_FULL];
    let mut equal = candidates & !planes[MASK_PLANE_FULL] & planes[MASK_PLANE_ALIVE];
    if equal == 0 {
        return full;
    }
    let wk = word_key(key, word);
    let mut less = 0u32;
    // the 8 mask-draw planes in one batch (see PLANE_BATCH)
    for (&t, r) in planes[..MASK_BITS as usize].iter().zip(plane_batch(wk, 0)) {
        less |= equal & t & !r;
        equal &= !(t ^ r);
    }
    full | less
}

/// Mask planes per packed word: 8 level bits (most significant first), then
/// [`MASK_PLANE_FULL`] and [`MASK_PLANE_ALIVE`].
pub const MASK_PLANES: usize = 10;
/// Index of the "level is 256" plane.
pub const MASK_PLANE_FULL: usize = 8;
/// Index of the "level is above 0" plane (clouds survive there).
pub const MASK_PLANE_ALIVE: usize = 9;

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

    /// The mask planes of 32 lanes' levels.
    fn planes_of(levels: &[u16; 32]) -> [u32; MASK_PLANES] {
        let mut p = [0u32; MASK_PLANES];
        for (lane, &l) in levels.iter().enumerate() {
            for (k, plane) in p.iter_mut().take(8).enumerate() {
                *plane |= u32::from((l & 0xff) >> (7 - k) & 1) << lane;
            }
            p[MASK_PLANE_FULL] |= u32::from(l == MASK_FULL) << lane;
            p[MASK_PLANE_ALIVE] |= u32::from(l > 0) << lane;
        }
        p
    }

    #[test]
    fn plane_batches_are_the_plane_hashes() {
        for wk in [0u32, 1, 0x9e37_79b9, u32::MAX, 0x1234_5678] {
            for first in [0, 8] {
                let batch = plane_batch(wk, first);
                for (k, &p) in batch.iter().enumerate() {
                    assert_eq!(p, plane_bits(wk, first + k as u32));
                }
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
        for word in 0..300u32 {
            let u: Vec<u32> = (0..32).map(|lane| uniform16(key, word, lane)).collect();
            let candidates = hash_u32(word + 77) | hash_u32(word + 78);
            // thresholds around this word's own draws hit the u == t corner
            let thresholds = [0, 1, 65, 6553, 32768, 65535, 65536, u[0], u[0] + 1, u[7]];
            for t in thresholds {
                let got = below_threshold(key, word, candidates, t);
                for (lane, &ul) in u.iter().enumerate() {
                    let want = (candidates >> lane & 1 == 1) && ul < t;
                    assert_eq!(got >> lane & 1 == 1, want, "word {word} lane {lane} t {t}");
                }
            }
            let mut levels = [0u16; 32];
            for (lane, l) in levels.iter_mut().enumerate() {
                *l = match (word as usize + lane) % 5 {
                    0 => 0,
                    1 => MASK_FULL,
                    2 => (u[lane] >> 8) as u16, // equal: not below
                    3 => (u[lane] >> 8) as u16 + 1,
                    _ => (hash_u32(word * 32 + lane as u32) % 257) as u16,
                };
            }
            let planes = planes_of(&levels);
            let got = below_mask_level(key, word, candidates, &planes);
            for (lane, &ul) in u.iter().enumerate() {
                let l = u32::from(levels[lane]);
                let want = (candidates >> lane & 1 == 1) && (ul >> 8) < l;
                assert_eq!(got >> lane & 1 == 1, want, "mask word {word} lane {lane}");
            }
        }
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
        assert_eq!(below_threshold(7, 1, u32::MAX, THRESHOLD_ONE), u32::MAX);
        assert_eq!(below_threshold(7, 1, u32::MAX, 0), 0);
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
