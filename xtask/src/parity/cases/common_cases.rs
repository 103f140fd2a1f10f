//! Parity cases of `skyscape-wgsl` common modules: the shared hash.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "common::hash_u32",
        imports: &["common::hash"],
        arity: (2, 2),
        wgsl: "let h = hash_u32(u32(x0) | (u32(x1) << 16u)); y0 = f32(h >> 8u); y1 = f32(h & 0xffu);",
        grid: || {
            let mut v = Vec::new();
            for hi in (0..65_536u32).step_by(4099) {
                for lo in (0..65_536u32).step_by(97) {
                    v.push(vec![f64::from(lo), f64::from(hi)]);
                }
            }
            v.push(vec![65_535.0, 65_535.0]);
            v
        },
        cpu: |x| {
            let h = skyscape_wgsl::common::hash_u32(x[0] as u32 | ((x[1] as u32) << 16));
            vec![(h >> 8) as f32, (h & 0xff) as f32]
        },
        reference: |x| {
            let h = super::integer_references::lowbias32(x[0] as u32 | ((x[1] as u32) << 16));
            vec![f64::from(h >> 8), f64::from(h & 0xff)]
        },
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: None,
            why: "integer arithmetic wraps identically in WGSL and Rust: bit-exact against the \
                  published lowbias32 written a second time (u64 reduced modulo 2^32 by hand)",
        },
    }]
}
