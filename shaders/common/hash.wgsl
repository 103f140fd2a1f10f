// Integer hashing shared by every stochastic pass (dithering, cloud automaton draws).
// Twin: skyscape_wgsl::common::{hash_u32, hash_combine, unit_float_from_bits}.
// Integer arithmetic wraps in both languages, so the twins are bit-identical.

// Chris Wellons' "lowbias32" integer hash: a bijection on u32 with low bias.
fn hash_u32(value: u32) -> u32 {
    var x = value;
    x ^= x >> 16u;
    x *= 0x7feb352du;
    x ^= x >> 15u;
    x *= 0x846ca68bu;
    x ^= x >> 16u;
    return x;
}

// Order-dependent combination of a running hash with one more word.
fn hash_combine(seed: u32, value: u32) -> u32 {
    return hash_u32(seed ^ (value + 0x9e3779b9u + (seed << 6u) + (seed >> 2u)));
}

// The top 24 bits of a hash as a float in [0, 1): exact in f32 on both sides.
fn unit_float_from_bits(bits: u32) -> f32 {
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}
