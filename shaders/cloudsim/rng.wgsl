// Counter-based random draws and the wind shift of the cloud automaton.
// Twin: cloudsim::rng (Rust), same names; integer arithmetic wraps in both languages,
// so the twins are bit-identical.
//
//   key  = hash_combine(hash_combine(hash_u32(seed), step), stream)
//   bits = hash_combine(key, cell)          cell = x + nx * (y + ny * z)
//   event  <=>  (bits >> 8) < threshold,    threshold = floor(p * 2^24), computed on the CPU

#import common::hash

const STREAM_EXTINCTION: u32 = 0u;
const STREAM_HUMIDITY: u32 = 1u;
const STREAM_ACTIVATION: u32 = 2u;
const THRESHOLD_ONE: u32 = 16777216u;

fn stream_key(seed: u32, step: u32, stream: u32) -> u32 {
    return hash_combine(hash_combine(hash_u32(seed), step), stream);
}

fn draw_bits(key: u32, cell: u32) -> u32 {
    return hash_combine(key, cell);
}

fn draw_event(key: u32, cell: u32, threshold: u32) -> bool {
    return (draw_bits(key, cell) >> 8u) < threshold;
}

// Cells a slice with 16.16 fixed-point velocity `velocity_q` moves during `step`:
// floor(v (step + 1)) - floor(v step), exact in wrapping 32-bit arithmetic.
fn wind_shift(velocity_q: i32, step: u32) -> i32 {
    let remainder = i32((step * bitcast<u32>(velocity_q)) & 0xffffu);
    return (remainder + velocity_q) >> 16u;
}
