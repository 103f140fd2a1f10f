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
                        for a in linspace(0.0, 1.5, 37) {
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
                    vec![2.0 * U * (x[0] + step) + 3.0 * U * step]
                }),
                why: "τ + (½σΔs·ρ_prev + ½σΔs·ρ): correctly rounded ops on non-negative terms, 3u of \
                      the step; the sum into τ may be evaluated in another order (lavapipe: 1 ULP \
                      of τ = 40 plus a tiny step): 2u of the result (reference: the generic \
                      function at f64)",
            },
        },
        Case {
            name: "cloudlight::catmull_rom",
            imports: &["cloudlight::slice_propagation"],
            arity: (5, 1),
            wgsl: "y0 = catmull_rom(x0, x1, x2, x3, x4);",
            grid: || {
                let mut grid = Vec::new();
                for i in 0..10000u32 {
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
                for i in 0..10000u32 {
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
                for i in 0..10000u32 {
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

/// Unit directions spread over the sphere (a Fibonacci lattice) plus the six axes.
fn directions(n: u32) -> Vec<[f64; 3]> {
    let mut v: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(n);
            let r = (1.0 - z * z).sqrt();
            let phi = f64::from(k) * 2.399_963_229_728_653;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect();
    for a in 0..3 {
        for s in [1.0, -1.0] {
            let mut d = [0.0; 3];
            d[a] = s;
            v.push(d);
        }
    }
    v
}

const BOX_LO: [f64; 3] = [0.0, 0.0, 1000.0];
const BOX_HI: [f64; 3] = [1000.0, 800.0, 1600.0];

/// Cone-sampling cases (Schneider 2015): the sample layout, Beer–Lambert, powder, the dual
/// lobe, the exit distance.
pub fn cone_cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::cone_sample",
            imports: &["cloudlight::cone"],
            arity: (8, 4),
            wgsl: "let s = cone_sample(u32(x0), vec3<f32>(x1, x2, x3), x4, x5, x6, x7 > 0.5); \
                   y0 = s.x; y1 = s.y; y2 = s.z; y3 = s.w;",
            grid: || {
                let mut grid = Vec::new();
                for (k, d) in directions(60).into_iter().enumerate() {
                    for step in [1.0, 40.0, 333.3] {
                        for exit in [0.0, 25.0, 280.0, 4000.0] {
                            for i in 0..7 {
                                let spread = [0.0, 0.2, 1.0][(k + i) % 3];
                                for mode in [0.0, 1.0] {
                                    grid.push(vec![
                                        i as f64, d[0], d[1], d[2], step, exit, spread, mode,
                                    ]);
                                }
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                let weights = if x[7] > 0.5 {
                    cloudlight::cone::ConeWeights::Partitioned
                } else {
                    cloudlight::cone::ConeWeights::Raw
                };
                cloudlight::cone::cone_sample(
                    x[0] as u32,
                    [x[1], x[2], x[3]],
                    x[4],
                    x[5],
                    x[6],
                    weights,
                )
                .to_vec()
            },
            reference: |x| {
                let weights = if x[7] > 0.5 {
                    cloudlight::cone::ConeWeights::Partitioned
                } else {
                    cloudlight::cone::ConeWeights::Raw
                };
                cloudlight::cone::cone_sample(
                    x[0] as u32,
                    [x[1], x[2], x[3]],
                    x[4],
                    x[5],
                    x[6],
                    weights,
                )
                .to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Distances ≤ max(9·step, exit) from ≤ 3 roundings (WGSL's exit/7: 2.5 ULP);
                // offsets l·d + spread·d·k: 3 more of terms ≤ (1 + spread)·d; the far weight
                // exit − 6Δ cancels: ≤ u·exit + 6Δ·4u.
                bound: Some(|x| {
                    let d = (9.0 * x[4]).max(x[5]);
                    let e = 10.0 * U * d * (1.0 + x[6]);
                    vec![e, e, e, 10.0 * U * d]
                }),
                why: "distances ≤ max(9·step, exit) carry ≤ 3 roundings (WGSL's exit/7 2.5 ULP), \
                      offsets l·d + spread·d·k 3 more of (1 + spread)·d, the far weight exit − 6Δ \
                      cancels: 10u of the largest distance (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::beer_lambert",
            imports: &["cloudlight::cone"],
            arity: (1, 1),
            wgsl: "y0 = beer_lambert(x0);",
            grid: || {
                let mut g: Vec<Vec<f64>> = logspace(1e-7, 80.0, 10001).map(|t| vec![t]).collect();
                g.push(vec![0.0]);
                g
            },
            cpu: |x| vec![cloudlight::cone::beer_lambert(x[0])],
            reference: |x| vec![(-x[0]).exp()],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    let t = (-x[0]).exp();
                    vec![(4.0 + 2.0 * x[0]) * super::super::compare::ulp_f32(t)]
                }),
                why: "WGSL exp: 3 + 2|x| ULP (the spec's bound), + 1 for Rust's libm",
            },
        },
        Case {
            name: "cloudlight::powder",
            imports: &["cloudlight::cone"],
            arity: (1, 1),
            wgsl: "y0 = powder(x0);",
            grid: || {
                let mut g: Vec<Vec<f64>> = logspace(1e-5, 40.0, 10001).map(|t| vec![t]).collect();
                g.push(vec![0.0]);
                g
            },
            cpu: |x| vec![cloudlight::cone::powder(x[0])],
            reference: |x| vec![-(-2.0 * x[0]).exp_m1()],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 1.0,
                // 1 − e: e = exp(−2τ) carries (4 + 4τ) ULP of itself (WGSL exp), which the
                // subtraction keeps as an absolute error (cancels for small τ).
                bound: Some(|x| {
                    let e = (-2.0 * x[0]).exp();
                    vec![(4.0 + 4.0 * x[0]) * super::super::compare::ulp_f32(e)]
                }),
                why: "1 − exp(−2τ): WGSL exp's 3 + 2·2τ ULP of exp(−2τ) (+1 for libm) kept as an \
                      absolute error by the cancelling subtraction, + 1 ULP of the result \
                      (reference: −expm1(−2τ))",
            },
        },
        Case {
            name: "cloudlight::dual_lobe_henyey_greenstein",
            imports: &["cloudlight::cone"],
            arity: (4, 1),
            wgsl: "y0 = dual_lobe_henyey_greenstein(x0, x1, x2, x3);",
            grid: || {
                let mut grid = Vec::new();
                for mu in linspace(-1.0, 1.0, 141) {
                    for g in [0.0, 0.3, 0.6, 0.85, 0.95, 0.99] {
                        for b in [-0.5, -0.2, 0.0] {
                            for w in [0.0, 0.1, 0.5, 1.0] {
                                grid.push(vec![mu, g, b, w]);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::cone::dual_lobe_henyey_greenstein(
                    x[0], x[1], x[2], x[3],
                )]
            },
            reference: |x| {
                let hg = |g: f64| {
                    (1.0 - g * g)
                        / (4.0 * std::f64::consts::PI * (1.0 + g * g - 2.0 * g * x[0]).powf(1.5))
                };
                vec![(1.0 - x[3]) * hg(x[1]) + x[3] * hg(x[2])]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Each lobe within atmos' 16 ULP (its parity case), the weights and sum 3u.
                bound: Some(|x| {
                    let hg = |g: f64| {
                        (1.0 - g * g)
                            / (4.0
                                * std::f64::consts::PI
                                * (1.0 + g * g - 2.0 * g * x[0]).powf(1.5))
                    };
                    let (f, b) = ((1.0 - x[3]) * hg(x[1]), x[3] * hg(x[2]));
                    vec![
                        16.0 * (super::super::compare::ulp_f32(f)
                            + super::super::compare::ulp_f32(b))
                            + 3.0 * U * (f + b),
                    ]
                }),
                why: "two of atmos' Henyey–Greenstein lobes (16 ULP each, its parity case) mixed \
                      by non-negative weights (3u); reference: the textbook formula in f64",
            },
        },
        Case {
            name: "cloudlight::box_exit_distance",
            imports: &["cloudlight::cone"],
            arity: (6, 1),
            wgsl: "y0 = box_exit_distance(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), \
                   vec3<f32>(0.0, 0.0, 1000.0), vec3<f32>(1000.0, 800.0, 1600.0));",
            grid: || {
                let mut grid = Vec::new();
                let points = [
                    [500.0, 400.0, 1300.0],
                    [1.0, 799.0, 1000.5],
                    [0.0, 0.0, 1000.0],
                    [999.9, 3.0, 1599.0],
                    [-200.0, 400.0, 1300.0],
                    [500.0, 400.0, 2000.0],
                    [137.5, 612.25, 1111.0],
                ];
                for p in points {
                    for d in directions(1500) {
                        grid.push(vec![p[0], p[1], p[2], d[0], d[1], d[2]]);
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::cone::box_exit_distance(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    to_f32(BOX_LO),
                    to_f32(BOX_HI),
                )]
            },
            reference: |x| {
                // Independent form: the slab method's far intersections.
                let mut far = f64::INFINITY;
                for a in 0..3 {
                    if x[3 + a] != 0.0 {
                        let t0 = (BOX_LO[a] - x[a]) / x[3 + a];
                        let t1 = (BOX_HI[a] - x[a]) / x[3 + a];
                        far = far.min(t0.max(t1));
                    }
                }
                vec![far.max(0.0)]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // (face − p)/d: the subtraction is exact or u of the larger of the two
                // (≤ 1600 m), WGSL's division 2.5 ULP; min/max are exact.
                bound: Some(|x| {
                    let mut e = 0.0f64;
                    for a in 0..3 {
                        if x[3 + a] != 0.0 {
                            let t = (BOX_HI[a] - x[a]).abs().max((BOX_LO[a] - x[a]).abs())
                                / x[3 + a].abs();
                            e = e.max(
                                U * 3200.0 / x[3 + a].abs()
                                    + 3.0 * super::super::compare::ulp_f32(t),
                            );
                        }
                    }
                    vec![e]
                }),
                why: "(face − p)/d per axis: u of operands ≤ 1600 m over |d|, WGSL division \
                      2.5 ULP; min and max exact (reference: the slab method in f64)",
            },
        },
    ]
}
