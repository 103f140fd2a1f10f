//! Parity cases of `cloudsim::rng`: the counter-based draws and the wind shift. All
//! integer arithmetic: every case is bit-exact. Inputs and outputs travel as f32, so
//! 32-bit values are split into 16-bit halves (exact in f32). The references are the
//! draws written a second time (`integer_references`): 64-bit arithmetic reduced by
//! hand, the plain per-lane comparison instead of the bit-sliced one, exact floors.

use super::integer_references as second;
use super::*;

const EXACT: Tolerance = Tolerance {
    abs: 0.0,
    rel: 0.0,
    ulp: 0.0,
    bound: None,
    why: "integer arithmetic wraps identically in WGSL and Rust: bit-exact against a second \
          formulation (u64 reduced modulo 2^32 by hand; per-lane comparison; exact floors)",
};

/// `[low 16 bits, high 16 bits]` of `v` as f32 outputs.
fn halves(v: u32) -> [f32; 2] {
    [(v & 0xffff) as f32, (v >> 16) as f32]
}

/// The same as f64 reference outputs.
fn halves64(v: u32) -> [f64; 2] {
    [f64::from(v & 0xffff), f64::from(v >> 16)]
}

/// A 32-bit value from two 16-bit halves given as inputs.
fn join(low: f64, high: f64) -> u32 {
    low as u32 | (high as u32) << 16
}

/// Hashed 16-bit halves: spread inputs with no structure the hash could hide.
fn hashed_half(i: u32, salt: u32) -> f64 {
    f64::from(skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt) & 0xffff)
}

fn stream_key_case() -> Case {
    Case {
        name: "cloudsim::stream_key",
        imports: &["cloudsim::rng"],
        arity: (4, 2),
        wgsl: "let k = stream_key(u32(x0) | (u32(x1) << 16u), u32(x2), u32(x3)); \
               y0 = f32(k & 0xffffu); y1 = f32(k >> 16u);",
        grid: || {
            let mut v = Vec::new();
            for i in 0..10_000u32 {
                let step = [0, 1, 999, 65_535, 16_777_215][i as usize % 5];
                v.push(vec![
                    hashed_half(i, 1),
                    hashed_half(i, 2),
                    f64::from(step),
                    f64::from(i % 3),
                ]);
            }
            v
        },
        cpu: |x| {
            let seed = join(f64::from(x[0]), f64::from(x[1]));
            halves(cloudsim::rng::stream_key(seed, x[2] as u32, x[3] as u32)).to_vec()
        },
        reference: |x| {
            halves64(second::stream_key(
                join(x[0], x[1]),
                x[2] as u32,
                x[3] as u32,
            ))
            .to_vec()
        },
        audit: Audit::INDEPENDENT,
        tolerance: EXACT,
    }
}

fn plane_bits_case() -> Case {
    Case {
        name: "cloudsim::plane_bits",
        imports: &["cloudsim::rng"],
        arity: (4, 2),
        wgsl: "let wk = word_key(u32(x0) | (u32(x1) << 16u), u32(x2)); \
               let p = plane_bits(wk, u32(x3)); y0 = f32(p & 0xffffu); y1 = f32(p >> 16u);",
        grid: || {
            let mut v = Vec::new();
            for i in 0..10_000u32 {
                let word = [0, 1, 31, 131_071, 16_777_215][i as usize % 5];
                v.push(vec![
                    hashed_half(i, 3),
                    hashed_half(i, 4),
                    f64::from(word),
                    f64::from(i % 16),
                ]);
            }
            v
        },
        cpu: |x| {
            let wk = cloudsim::rng::word_key(join(f64::from(x[0]), f64::from(x[1])), x[2] as u32);
            halves(cloudsim::twins::plane_bits(wk, x[3] as u32)).to_vec()
        },
        reference: |x| {
            let wk = second::combine(join(x[0], x[1]), x[2] as u32);
            halves64(second::plane_bits(wk, x[3] as u32)).to_vec()
        },
        audit: Audit::INDEPENDENT,
        tolerance: EXACT,
    }
}

fn lane_threshold_case() -> Case {
    Case {
        name: "cloudsim::lane_threshold",
        imports: &["cloudsim::rng"],
        arity: (3, 1),
        wgsl: "y0 = f32(lane_threshold(u32(x0), u32(x1), u32(x2)));",
        grid: || {
            let mut v = Vec::new();
            let thresholds = [
                0u32, 1, 2, 65, 255, 256, 257, 6_553, 32_767, 32_768, 65_280, 65_535, 65_536,
            ];
            for t in thresholds {
                for level in 0..=256u32 {
                    for stream in 0..3u32 {
                        v.push(vec![f64::from(t), f64::from(level), f64::from(stream)]);
                    }
                }
            }
            v
        },
        cpu: |x| vec![cloudsim::rng::lane_threshold(x[0] as u32, x[1] as u32, x[2] as u32) as f32],
        reference: |x| {
            vec![f64::from(second::lane_threshold(
                x[0] as u32,
                x[1] as u32,
                x[2] as u32,
            ))]
        },
        audit: Audit::INDEPENDENT,
        tolerance: EXACT,
    }
}

/// `below_lane_thresholds` with `uniform_threshold_planes`: one threshold for the 32
/// lanes (the per-lane planes are checked bit for bit by the step pass, whose region
/// table feeds them).
fn below_lane_thresholds_case() -> Case {
    Case {
        name: "cloudsim::below_lane_thresholds",
        imports: &["cloudsim::rng"],
        arity: (6, 2),
        wgsl: "let less = below_lane_thresholds(u32(x0) | (u32(x1) << 16u), u32(x2), \
               u32(x3) | (u32(x4) << 16u), uniform_threshold_planes(u32(x5))); \
               y0 = f32(less & 0xffffu); y1 = f32(less >> 16u);",
        grid: || {
            let mut v = Vec::new();
            for i in 0..12_000u32 {
                let threshold = match i % 8 {
                    0 => 0,
                    1 => 65_536,
                    2 => 1,
                    3 => 65_535,
                    _ => u32::from(hashed_half(i, 5) as u16) + (i & 1),
                };
                let (low, high) = if i % 5 == 0 {
                    (65_535.0, 65_535.0)
                } else {
                    (hashed_half(i, 6), hashed_half(i, 7))
                };
                v.push(vec![
                    hashed_half(i, 8),
                    hashed_half(i, 9),
                    f64::from(i * 977 % 16_777_216),
                    low,
                    high,
                    f64::from(threshold),
                ]);
            }
            v
        },
        cpu: |x| {
            let x: Vec<f64> = x.iter().map(|&v| f64::from(v)).collect();
            halves(below(&x)).to_vec()
        },
        reference: |x| {
            halves64(second::below_threshold(
                join(x[0], x[1]),
                x[2] as u32,
                join(x[3], x[4]),
                x[5] as u32,
            ))
            .to_vec()
        },
        audit: Audit::INDEPENDENT,
        tolerance: EXACT,
    }
}

fn below(x: &[f64]) -> u32 {
    let planes = cloudsim::rng::uniform_threshold_planes(x[5] as u32);
    cloudsim::twins::below_lane_thresholds(join(x[0], x[1]), x[2] as u32, join(x[3], x[4]), &planes)
}

fn wind_shift_case() -> Case {
    Case {
        name: "cloudsim::wind_shift",
        imports: &["cloudsim::rng"],
        arity: (3, 1),
        // the velocity travels as a signed 16.16 value split into sign and magnitude
        wgsl: "var v = i32(x1); if x0 < 0.0 { v = -v; } y0 = f32(wind_shift(v, u32(x2)));",
        grid: || {
            let mut v = Vec::new();
            for velocity in [0.0f32, 0.25, 0.3, 1.0, 1.75, 2.6, 15.9, 16.0] {
                let q = cloudsim::rng::wind_velocity_fixed(velocity);
                for sign in [-1.0, 1.0] {
                    for step in (0..5_000u32).step_by(7).chain([65_535, 65_536, 16_777_215]) {
                        v.push(vec![sign, f64::from(q), f64::from(step)]);
                    }
                }
            }
            v
        },
        cpu: |x| {
            let q = if x[0] < 0.0 {
                -(x[1] as i32)
            } else {
                x[1] as i32
            };
            vec![cloudsim::rng::wind_shift(q, x[2] as u32) as f32]
        },
        reference: |x| {
            let q = if x[0] < 0.0 {
                -(x[1] as i32)
            } else {
                x[1] as i32
            };
            vec![f64::from(second::wind_shift(q, x[2] as u32))]
        },
        audit: Audit::INDEPENDENT,
        tolerance: EXACT,
    }
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        stream_key_case(),
        plane_bits_case(),
        lane_threshold_case(),
        below_lane_thresholds_case(),
        wind_shift_case(),
    ]
}
