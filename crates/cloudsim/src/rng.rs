//! Counter-based random draws and the wind shift: Rust twins of
//! `shaders/cloudsim/rng.wgsl` (same names, same argument order, bit-identical).
//!
//! A draw is a pure function of `(seed, step, stream, cell)`:
//!
//! ```text
//! key  = hash_combine(hash_combine(hash_u32(seed), step), stream)   // once per step and stream
//! bits = hash_combine(key, cell)                                    // cell = x + nx * (y + ny * z)
//! event  <=>  (bits >> 8) < threshold,   threshold = floor(p * 2^24) in [0, 2^24]
//! ```
//!
//! The comparison uses the top 24 bits of the hash, i.e. it is exactly
//! `unit_float_from_bits(bits) < threshold / 2^24`: the probability is quantised *down*
//! to a multiple of 2^-24 (`p = 1` gives `2^24`, which every draw is below; `p = 0`
//! gives 0, which none is). Thresholds are computed once on the CPU
//! ([`probability_threshold`]) and handed to the shader as `u32`, so both sides compare
//! the same integers. Because nothing depends on evaluation order, the naive, the
//! bit-packed (any thread count) and the WGSL implementations draw identical numbers.

use skyscape_wgsl::common::{hash_combine, hash_u32};

/// Stream id of the cloud-extinction draw (`STREAM_EXTINCTION` in WGSL).
pub const STREAM_EXTINCTION: u32 = 0;
/// Stream id of the humidity-supply draw (`STREAM_HUMIDITY` in WGSL).
pub const STREAM_HUMIDITY: u32 = 1;
/// Stream id of the activation draw (`STREAM_ACTIVATION` in WGSL).
pub const STREAM_ACTIVATION: u32 = 2;

/// `2^24`: the threshold of probability 1.
pub const THRESHOLD_ONE: u32 = 1 << 24;

/// Fixed-point scale of wind velocities: 16.16, i.e. `velocity_q = round(v * 65536)`.
pub const WIND_FIXED_ONE: f64 = 65_536.0;

/// The per-step, per-stream key (`stream_key` in WGSL).
pub fn stream_key(seed: u32, step: u32, stream: u32) -> u32 {
    hash_combine(hash_combine(hash_u32(seed), step), stream)
}

/// The 32 random bits of one cell's draw (`draw_bits` in WGSL).
pub fn draw_bits(key: u32, cell: u32) -> u32 {
    hash_combine(key, cell)
}

/// Whether the event with `threshold` (see [`probability_threshold`]) happens for this
/// cell (`draw_event` in WGSL).
pub fn draw_event(key: u32, cell: u32, threshold: u32) -> bool {
    (draw_bits(key, cell) >> 8) < threshold
}

/// `floor(p * 2^24)`, the integer threshold of probability `p` in [0, 1]. CPU only: the
/// shader receives the result. Values outside [0, 1] are the caller's bug; they are
/// rejected by [`crate::Model::new`] before they get here.
pub fn probability_threshold(probability: f64) -> u32 {
    (probability.clamp(0.0, 1.0) * f64::from(THRESHOLD_ONE)).floor() as u32
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

    #[test]
    fn draw_is_the_documented_formula() {
        let (seed, step, cell) = (0xdead_beef, 17, 123_456);
        let key = hash_combine(hash_combine(hash_u32(seed), step), STREAM_HUMIDITY);
        assert_eq!(stream_key(seed, step, STREAM_HUMIDITY), key);
        assert_eq!(draw_bits(key, cell), hash_combine(key, cell));
        let top = draw_bits(key, cell) >> 8;
        assert!(draw_event(key, cell, top + 1));
        assert!(!draw_event(key, cell, top));
    }

    #[test]
    fn thresholds_are_exact_at_the_ends() {
        assert_eq!(probability_threshold(0.0), 0);
        assert_eq!(probability_threshold(1.0), THRESHOLD_ONE);
        assert_eq!(probability_threshold(0.5), 1 << 23);
        // floor, not round
        assert_eq!(probability_threshold(1.0 / 3.0), 5_592_405);
        // every draw is below 2^24, none below 0
        for cell in 0..1000 {
            assert!(draw_event(7, cell, THRESHOLD_ONE));
            assert!(!draw_event(7, cell, 0));
        }
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
