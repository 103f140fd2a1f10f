//! Parity cases of `cloudlight`: slice attenuation, the slice propagation's per-texel
//! arithmetic and the Bayer jitter. The propagation's references are the generic
//! functions' f64 instantiations (one formula, two precisions: the error is rounding).

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
            name: "cloudlight::slice_optical_depth",
            imports: &["cloudlight::slice_propagation"],
            arity: (4, 1),
            wgsl: "y0 = slice_optical_depth(x0, x1, x2, x3);",
            grid: || {
                let mut grid = Vec::new();
                for tau in [0.0, 1e-3, 0.37, 2.5, 40.0] {
                    for sigma_ds in [0.0, 1e-4, 0.05, 0.9, 7.0] {
                        for a in linspace(0.0, 1.5, 16) {
                            for b in linspace(0.0, 1.0, 11) {
                                grid.push(vec![tau, a, b, sigma_ds]);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::propagate::slice_optical_depth(
                    x[0], x[1], x[2], x[3],
                )]
            },
            reference: |x| {
                vec![cloudlight::propagate::slice_optical_depth(
                    x[0], x[1], x[2], x[3],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Four correctly rounded ops on non-negative terms (no cancellation): the
                // sum's rounding is u·|result|, the product chain's 3u of its own size.
                bound: Some(|x| {
                    let step = 0.5 * x[3] * (x[1] + x[2]);
                    vec![U * (x[0] + step) + 3.0 * U * step]
                }),
                why: "τ + (½σΔs)(ρ_prev + ρ): four correctly rounded ops on non-negative terms, \
                      u of the sum + 3u of the step (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::catmull_rom",
            imports: &["cloudlight::slice_propagation"],
            arity: (5, 1),
            wgsl: "y0 = catmull_rom(x0, x1, x2, x3, x4);",
            grid: || {
                let mut grid = Vec::new();
                for i in 0..6000u32 {
                    let h = |salt: u32| {
                        f64::from(
                            skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt)
                                & 0xffff,
                        ) / 65_535.0
                    };
                    let scale = [1.0, 12.0, 1e-2][i as usize % 3];
                    grid.push(vec![
                        scale * h(1),
                        scale * h(2),
                        scale * h(3),
                        scale * h(4),
                        h(5),
                    ]);
                }
                for t in [0.0, 1.0] {
                    grid.push(vec![0.1, 0.5, 2.0, 0.3, t]);
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::propagate::catmull_rom(
                    x[0], x[1], x[2], x[3], x[4],
                )]
            },
            reference: |x| {
                // Independent form: the cardinal basis weights.
                let t = x[4];
                let (t2, t3) = (t * t, t * t * t);
                vec![
                    0.5 * ((-t3 + 2.0 * t2 - t) * x[0]
                        + (3.0 * t3 - 5.0 * t2 + 2.0) * x[1]
                        + (-3.0 * t3 + 4.0 * t2 + t) * x[2]
                        + (t3 - t2) * x[3]),
                ]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Horner with t ∈ [0, 1]: the inner sums of ±p (coefficients ≤ 5) cancel, so
                // each level's rounding is u of Σ|coeff·p| ≤ 16·max|p|; four levels, t ≤ 1.
                bound: Some(|x| {
                    let m = x[0].abs().max(x[1].abs()).max(x[2].abs()).max(x[3].abs());
                    vec![40.0 * U * m]
                }),
                why: "Horner form with t in [0, 1]: inner sums of ±p with coefficients ≤ 5 \
                      cancel; ≤ 40u of the largest |p| over the 16 roundings (reference: the \
                      cardinal basis weights in f64)",
            },
        },
        Case {
            name: "cloudlight::cross_smooth",
            imports: &["cloudlight::slice_propagation"],
            arity: (5, 1),
            wgsl: "y0 = cross_smooth(x0, x1, x2, x3, x4);",
            grid: || {
                let mut grid = Vec::new();
                for i in 0..6000u32 {
                    let h = |salt: u32| {
                        f64::from(
                            skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt)
                                & 0xffff,
                        ) / 65_535.0
                    };
                    grid.push(vec![h(1), h(2), h(3), h(4), h(5)]);
                }
                grid.push(vec![0.0; 5]);
                grid.push(vec![1.0; 5]);
                grid
            },
            cpu: |x| {
                vec![cloudlight::propagate::cross_smooth(
                    x[0], x[1], x[2], x[3], x[4],
                )]
            },
            reference: |x| vec![(x[0] + x[1] + x[2] + x[3] + x[4]) / 5.0],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Four additions of non-negative terms (4u of the sum), then WGSL's division
                // (2.5 ULP): ≤ 4u·Σ/5 + 2.5 ulp; written as 6.5u of the result + its ulp.
                bound: Some(|x| {
                    let mean = (x[0] + x[1] + x[2] + x[3] + x[4]) / 5.0;
                    vec![4.0 * U * mean + 2.5 * super::super::compare::ulp_f32(mean)]
                }),
                why: "four additions of densities ≥ 0 (4u relative) and WGSL's f32 division \
                      (2.5 ULP); reference: the f64 mean",
            },
        },
        Case {
            name: "cloudlight::bilinear",
            imports: &["cloudlight::slice_propagation"],
            arity: (6, 1),
            wgsl: "y0 = bilinear(x0, x1, x2, x3, x4, x5);",
            grid: || {
                let mut grid = Vec::new();
                for i in 0..6000u32 {
                    let h = |salt: u32| {
                        f64::from(
                            skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt)
                                & 0xffff,
                        ) / 65_535.0
                    };
                    let scale = [1.0, 30.0, 1e-3][i as usize % 3];
                    grid.push(vec![
                        scale * h(1),
                        scale * h(2),
                        scale * h(3),
                        scale * h(4),
                        h(5),
                        h(6),
                    ]);
                }
                for f in [0.0, 1.0] {
                    grid.push(vec![0.2, 0.4, 0.6, 0.8, f, 1.0 - f]);
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::propagate::bilinear(
                    x[0], x[1], x[2], x[3], x[4], x[5],
                )]
            },
            reference: |x| {
                // Independent form: the weights first.
                let (fu, fv) = (x[4], x[5]);
                vec![
                    (1.0 - fu) * (1.0 - fv) * x[0]
                        + fu * (1.0 - fv) * x[1]
                        + (1.0 - fu) * fv * x[2]
                        + fu * fv * x[3],
                ]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Non-negative texels and weights in [0, 1]: each of the 11 roundings
                // (1 − f exact for f in [½, 1], else u) is at most u of a term bounded by the
                // largest texel; 8u of max texel covers the depth-3 expression tree.
                bound: Some(|x| vec![8.0 * U * x[0].max(x[1]).max(x[2]).max(x[3])]),
                why: "weights in [0, 1] and texels ≥ 0: an 11-op tree of depth 4, ≤ 8u of the \
                      largest texel (reference: the weights-first form in f64)",
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
