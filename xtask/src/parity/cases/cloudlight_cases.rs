//! Parity cases of `cloudlight`: slice attenuation and the Bayer jitter.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::slice_attenuation",
            imports: &["cloudlight::slice_attenuation"],
            arity: (3, 1),
            wgsl: "y0 = slice_attenuation(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for light in [1.0, 0.37, 1e-3] {
                    for ratio in linspace(0.0, 1.0, 41) {
                        for density in linspace(0.0, 1.0, 101) {
                            grid.push(vec![light, density, ratio]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![cloudlight::slice::slice_attenuation(x[0], x[1], x[2])],
            reference: |x| vec![x[0] * (1.0 - (1.0 - x[2]) * x[1])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                // 1 − (1 − r)·d cancels as (1 − r)·d → 1: each of its three roundings is
                // at most u relative to 1, so the bound is absolute, times the light.
                bound: Some(|x| vec![3.0 * U * x[0].abs()]),
                why: "four correctly rounded ops; 1 − (1 − r)d cancels for dense, opaque slices: \
                      3u absolute, times the incoming light",
            },
        },
        Case {
            name: "cloudlight::bayer_jitter_4x4",
            imports: &["cloudlight::jitter"],
            arity: (2, 1),
            wgsl: "y0 = bayer_jitter_4x4(vec2<u32>(u32(x0), u32(x1)));",
            grid: || {
                let mut grid = Vec::new();
                for y in 0..101 {
                    for x in 0..101 {
                        grid.push(vec![f64::from(x * 13), f64::from(y * 7)]);
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::jitter::bayer_jitter_4x4([
                    x[0] as u32,
                    x[1] as u32,
                ])]
            },
            reference: |x| {
                const BAYER: [[u32; 4]; 4] =
                    [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
                let (px, py) = (x[0] as usize % 4, x[1] as usize % 4);
                vec![f64::from(BAYER[py][px]) / 16.0]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer bit interleave and an exact power-of-two scale: bit-exact \
                      (reference: the classic matrix by table)",
            },
        },
    ]
}
