// Counter-based random draws, built 32 lanes at a time as bit planes, and the wind
// shift of the cloud automaton. Twin: cloudsim::rng (Rust), same names; integer
// arithmetic wraps in both languages, so the twins are bit-identical.
//
//   key      = hash_combine(hash_combine(hash_u32(seed), step), stream)
//   word_key = hash_combine(key, word)        word = packed word of the cell
//   plane_k  = hash_combine(word_key, k)      bit (15 - k) of all 32 lanes' numbers
//   event  <=>  u < threshold of the lane, base threshold = floor(p * 2^16) in [0, 2^16]
//   (computed on the CPU), scaled per lane by the region-mask level (lane_threshold);
//   thresholds are given as bit planes: LANE_PLANES words per word and stream.

#import common::hash

const STREAM_EXTINCTION: u32 = 0u;
const STREAM_HUMIDITY: u32 = 1u;
const STREAM_ACTIVATION: u32 = 2u;
const UNIFORM_BITS: u32 = 16u;
const THRESHOLD_ONE: u32 = 65536u;
const MASK_BITS: u32 = 8u;
const MASK_FULL: u32 = 256u;
// 16 threshold bit planes (most significant first), then the lanes at 2^16, then the
// lanes above 0.
const LANE_PLANES: u32 = 18u;
const PLANE_ALWAYS: u32 = 16u;
const PLANE_NONZERO: u32 = 17u;

fn stream_key(seed: u32, step: u32, stream: u32) -> u32 {
    return hash_combine(hash_combine(hash_u32(seed), step), stream);
}

fn word_key(key: u32, word: u32) -> u32 {
    return hash_combine(key, word);
}

fn plane_bits(word_key: u32, plane: u32) -> u32 {
    return hash_combine(word_key, plane);
}

// The threshold of a lane at mask level `level` in [0, 256]: floor(t l / 256) for
// supply and activation, floor(t (256 - l) / 256) for extinction (t l <= 2^24).
fn lane_threshold(threshold: u32, level: u32, stream: u32) -> u32 {
    var scale = level;
    if stream == STREAM_EXTINCTION {
        scale = MASK_FULL - level;
    }
    return (threshold * scale) >> MASK_BITS;
}

// The planes of one threshold shared by all 32 lanes (no ellipsoids).
fn uniform_threshold_planes(threshold: u32) -> array<u32, 18> {
    var planes: array<u32, 18>;
    if threshold >= THRESHOLD_ONE {
        planes[PLANE_ALWAYS] = 0xffffffffu;
    } else {
        for (var k = 0u; k < UNIFORM_BITS; k++) {
            planes[k] = 0u - ((threshold >> (UNIFORM_BITS - 1u - k)) & 1u);
        }
    }
    planes[PLANE_NONZERO] = 0u - u32(threshold > 0u);
    return planes;
}

// Lanes of `candidates` whose uniform 16-bit number is below their own threshold
// (`planes`), bit-sliced, most significant plane first; stops once no lane is equal.
fn below_lane_thresholds(key: u32, word: u32, candidates: u32, planes: array<u32, 18>) -> u32 {
    var less = candidates & planes[PLANE_ALWAYS];
    var equal = candidates & planes[PLANE_NONZERO] & ~planes[PLANE_ALWAYS];
    if equal == 0u {
        return less;
    }
    let wk = word_key(key, word);
    for (var k = 0u; k < UNIFORM_BITS; k++) {
        let r = plane_bits(wk, k);
        let t = planes[k];
        less |= equal & t & ~r;
        equal &= ~(t ^ r);
        if equal == 0u {
            break;
        }
    }
    return less;
}

// Cells a slice with 16.16 fixed-point velocity `velocity_q` moves during `step`:
// floor(v (step + 1)) - floor(v step), exact in wrapping 32-bit arithmetic.
fn wind_shift(velocity_q: i32, step: u32) -> i32 {
    let remainder = i32((step * bitcast<u32>(velocity_q)) & 0xffffu);
    return (remainder + velocity_q) >> 16u;
}
