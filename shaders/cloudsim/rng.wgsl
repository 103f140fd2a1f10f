// Counter-based random draws, built 32 lanes at a time as bit planes, and the wind
// shift of the cloud automaton. Twin: cloudsim::rng (Rust), same names; integer
// arithmetic wraps in both languages, so the twins are bit-identical.
//
//   key      = hash_combine(hash_combine(hash_u32(seed), step), stream)
//   word_key = hash_combine(key, word)        word = packed word of the cell
//   plane_k  = hash_combine(word_key, k)      bit (15 - k) of all 32 lanes' numbers
//   event  <=>  u < threshold,  threshold = floor(p * 2^16) in [0, 2^16], computed on the CPU
//   mask draw: (u >> 8) < level,  level in [0, 256]

#import common::hash

const STREAM_EXTINCTION: u32 = 0u;
const STREAM_HUMIDITY: u32 = 1u;
const STREAM_ACTIVATION: u32 = 2u;
const STREAM_MASK_OFFSET: u32 = 3u;
const UNIFORM_BITS: u32 = 16u;
const THRESHOLD_ONE: u32 = 65536u;
const MASK_BITS: u32 = 8u;
const MASK_PLANES: u32 = 10u;
const MASK_PLANE_FULL: u32 = 8u;
const MASK_PLANE_ALIVE: u32 = 9u;

fn stream_key(seed: u32, step: u32, stream: u32) -> u32 {
    return hash_combine(hash_combine(hash_u32(seed), step), stream);
}

fn word_key(key: u32, word: u32) -> u32 {
    return hash_combine(key, word);
}

fn plane_bits(word_key: u32, plane: u32) -> u32 {
    return hash_combine(word_key, plane);
}

// Lanes of `candidates` whose uniform 16-bit number is below `threshold` (shared by
// the word), bit-sliced, most significant plane first; stops once no lane is equal.
fn below_threshold(key: u32, word: u32, candidates: u32, threshold: u32) -> u32 {
    if candidates == 0u || threshold == 0u {
        return 0u;
    }
    if threshold >= THRESHOLD_ONE {
        return candidates;
    }
    let wk = word_key(key, word);
    var less = 0u;
    var equal = candidates;
    for (var k = 0u; k < UNIFORM_BITS; k++) {
        let r = plane_bits(wk, k);
        if ((threshold >> (UNIFORM_BITS - 1u - k)) & 1u) == 1u {
            less |= equal & ~r;
            equal &= r;
        } else {
            equal &= ~r;
        }
        if equal == 0u {
            break;
        }
    }
    return less;
}

// Lanes of `candidates` whose mask draw (u >> 8) is below their mask level; `planes`
// are the word's mask planes (level bits 7..0, then full, then alive).
fn below_mask_level(key: u32, word: u32, candidates: u32, planes: array<u32, 10>) -> u32 {
    let full = candidates & planes[MASK_PLANE_FULL];
    var equal = candidates & ~planes[MASK_PLANE_FULL] & planes[MASK_PLANE_ALIVE];
    if equal == 0u {
        return full;
    }
    let wk = word_key(key, word);
    var less = 0u;
    for (var k = 0u; k < MASK_BITS; k++) {
        let r = plane_bits(wk, k);
        let t = planes[k];
        less |= equal & t & ~r;
        equal &= ~(t ^ r);
        if equal == 0u {
            break;
        }
    }
    return full | less;
}

// Cells a slice with 16.16 fixed-point velocity `velocity_q` moves during `step`:
// floor(v (step + 1)) - floor(v step), exact in wrapping 32-bit arithmetic.
fn wind_shift(velocity_q: i32, step: u32) -> i32 {
    let remainder = i32((step * bitcast<u32>(velocity_q)) & 0xffffu);
    return (remainder + velocity_q) >> 16u;
}
