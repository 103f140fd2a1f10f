//! Parity cases of `cloudlight`'s cloud shadow map (`shaders/cloudlight/shadow_map.wgsl`):
//! the texel's ground point, the sun ray's span through the box, the march's sample point,
//! a span's optical depth, and the whole per-texel march through an analytic cloud (an
//! ellipsoidal paraboloid written inline in the kernel and as a `DensityField` here). The
//! references are the slab method in f64 (the span) or the generic functions' f64
//! instantiations (one formula, two precisions: the error is rounding).

use super::*;
use cloudlight::shadow_map as sm;

/// The analytic cloud's box (metres) and ellipsoid (centre, radii); σ_t 0.004 /m.
const LO: [f64; 3] = [-1000.0, -800.0, 1000.0];
const HI: [f64; 3] = [1000.0, 800.0, 1800.0];
const CENTRE: [f64; 3] = [0.0, 0.0, 1400.0];
const RADII: [f64; 3] = [900.0, 700.0, 380.0];
const SIGMA_T: f64 = 0.004;
/// The texel grid of the per-texel case: minimum corner and edge, metres.
const GRID_ORIGIN: [f64; 2] = [-3000.0, -3000.0];
const GRID_CELL: f64 = 75.0;

/// `max(1 − |(q − c)/r|², 0)` inside the box, written op for op as the kernel writes it,
/// its spans the box's ([`sm::shadow_box_span`]).
struct Paraboloid;

impl<F: atmos::real::Real> cloudlight::DensityField<F> for Paraboloid {
    fn density(&self, q: [F; 3]) -> F {
        let d = [0, 1, 2].map(|a| (q[a] - F::of(CENTRE[a])) / F::of(RADII[a]));
        (F::one() - (d[0] * d[0] + d[1] * d[1] + d[2] * d[2])).max(F::zero())
    }

    fn extinction_per_density(&self) -> F {
        F::of(SIGMA_T)
    }

    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> cloudlight::RaySpans<F> {
        let [enter, exit] = sm::shadow_box_span(origin, direction, LO.map(F::of), HI.map(F::of));
        if enter <= exit {
            cloudlight::RaySpans::one(enter, exit)
        } else {
            cloudlight::RaySpans::none()
        }
    }
}

/// Suns: elevations from the zenith through grazing to below the horizon, 7 azimuths.
fn suns() -> Vec<[f64; 3]> {
    let mut v = Vec::new();
    for e in [
        90.0f64, 75.0, 60.0, 40.0, 25.0, 12.0, 6.0, 2.0, 0.5, 0.0, -3.0, -30.0,
    ] {
        for az in [0.0f64, 17.0, 90.0, 133.0, 200.0, 271.0, 330.0] {
            let (e, a) = (e.to_radians(), az.to_radians());
            v.push([e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]);
            if e == std::f64::consts::FRAC_PI_2 {
                break;
            }
        }
    }
    v
}

/// The slab method's per-axis parameters `(t_lo, t_hi)` for the non-zero components.
fn axis_ts(x: &[f64]) -> Vec<(f64, f64)> {
    (0..3)
        .filter(|&a| x[3 + a] != 0.0)
        .map(|a| ((LO[a] - x[a]) / x[3 + a], (HI[a] - x[a]) / x[3 + a]))
        .collect()
}

/// Bound of the march's f32 error at inputs `(i, j, ground, l, n)` (see the case's `why`).
fn texel_bound(x: &[f64]) -> f64 {
    let p =
        sm::shadow_texel_centre::<f64>([x[0] as u32, x[1] as u32], GRID_ORIGIN, GRID_CELL, x[2]);
    let l = [x[3], x[4], x[5]];
    let n = x[6] as u32;
    let [s0, s1] = sm::shadow_box_span(p, l, LO, HI);
    let transmittance = sm::shadow_texel::<f64, _>(&Paraboloid, p, l, n);
    let tau = -transmittance.ln();
    let exp_error = (5.0 + 2.0 * tau) * super::super::compare::ulp_f32(transmittance);
    // A grazing ray: f32 may find a span where f64 finds none (or the reverse); its
    // length is within the span's rounding, 8u·(|p| + the box's far corner distance).
    let p_norm = p.iter().map(|c| c.abs()).fold(0.0, f64::max);
    let reach = 8.0 * U * (p_norm + 4000.0);
    if s0 > s1 {
        return transmittance * SIGMA_T * reach * 2.0 + exp_error;
    }
    let (t_max, h) = (s1.abs().max(s0.abs()), (s1 - s0) / f64::from(n));
    // Sample points: p + t·l with t from span ends carrying ≤ 8u|t| each (subtraction,
    // WGSL division 2.5 ULP), then 3 more roundings: δq ≤ 12u(|p| + |t|) per component.
    let dq = 12.0 * U * (p_norm + t_max);
    // ρ = 1 − |d|², |d| ≤ 1 where ρ > 0: δρ ≤ 2·Σ|δd| + 4u with δd ≤ δq/r + 3u.
    let r_min = RADII.iter().copied().fold(f64::INFINITY, f64::min);
    let d_rho = 2.0 * 3.0 * (dq / r_min + 3.0 * U) + 4.0 * U;
    let sum: f64 = (0..n)
        .map(|k| {
            cloudlight::DensityField::<f64>::density(
                &Paraboloid,
                sm::shadow_march_point(p, l, [s0, s1], k, n),
            )
        })
        .sum();
    let d_sum = f64::from(n) * d_rho + f64::from(n) * U * sum;
    let d_h = (16.0 * U * t_max + U * (s1 - s0)) / f64::from(n) + 5.0 * U * h;
    let d_tau = SIGMA_T * (d_sum * h + sum * d_h) + 3.0 * U * tau;
    2.0 * (transmittance * d_tau + reach * SIGMA_T * transmittance) + exp_error
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::shadow_texel_centre",
            imports: &["cloudlight::shadow_map"],
            arity: (6, 3),
            wgsl: "let p = shadow_texel_centre(vec2<u32>(u32(x0), u32(x1)), vec2<f32>(x2, x3), x4, x5); \
                   y0 = p.x; y1 = p.y; y2 = p.z;",
            grid: || {
                let mut grid = Vec::new();
                for i in [
                    0.0, 1.0, 2.0, 7.0, 63.0, 100.0, 255.0, 256.0, 1023.0, 2900.0, 4095.0, 16383.0,
                ] {
                    for j in [
                        0.0, 3.0, 5.0, 31.0, 128.0, 511.0, 777.0, 2047.0, 5000.0, 8191.0,
                    ] {
                        for origin in [[0.0, 0.0], [-3000.0, -2500.0], [123_456.7, -98_765.4]] {
                            for cell in [0.5, 1.0, 10.0, 30.0, 75.0, 250.0] {
                                for ground in [0.0, 1234.5, -400.0, 8000.0, 0.001] {
                                    grid.push(vec![i, j, origin[0], origin[1], cell, ground]);
                                }
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                sm::shadow_texel_centre([x[0] as u32, x[1] as u32], [x[2], x[3]], x[4], x[5])
                    .to_vec()
            },
            reference: |x| vec![x[2] + (x[0] + 0.5) * x[4], x[3] + (x[1] + 0.5) * x[4], x[5]],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // f32(i) and i + ½ exact below 2²³; ·cell and + origin: 2 roundings of
                // terms ≤ |origin| + (i + 1)·cell.
                bound: Some(|x| {
                    let e = |o: f64, i: f64| 2.0 * U * (o.abs() + (i + 1.0) * x[4]);
                    vec![e(x[2], x[0]), e(x[3], x[1]), 0.0]
                }),
                why: "f32(i) + ½ exact below 2²³; the product and the sum round once each, of \
                      terms ≤ |origin| + (i + 1)·cell (reference: the formula in f64)",
            },
        },
        Case {
            name: "cloudlight::shadow_box_span",
            imports: &["cloudlight::shadow_map"],
            arity: (6, 2),
            wgsl: "let s = shadow_box_span(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), \
                   vec3<f32>(-1000.0, -800.0, 1000.0), vec3<f32>(1000.0, 800.0, 1800.0)); \
                   y0 = s.x; y1 = s.y;",
            grid: || {
                let mut grid = Vec::new();
                let mut points = Vec::new();
                for x in [-2500.0, -1000.0, -999.0, 0.0, 37.5, 1000.0, 4200.0] {
                    for y in [-3000.0, -800.0, 12.0, 650.0, 1500.0] {
                        for z in [0.0, 1000.0, 1400.0, 2500.0] {
                            points.push([x, y, z]);
                        }
                    }
                }
                let mut directions = suns();
                directions.extend([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]]);
                for p in &points {
                    for l in &directions {
                        grid.push(vec![p[0], p[1], p[2], l[0], l[1], l[2]]);
                    }
                }
                grid
            },
            cpu: |x| {
                sm::shadow_box_span(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    to_f32(LO),
                    to_f32(HI),
                )
                .to_vec()
            },
            reference: |x| {
                // Independent form: miss on a parallel axis outside its slab, else the
                // largest near and smallest far slab parameter (enter clamped at 0).
                for a in 0..3 {
                    if x[3 + a] == 0.0 && (x[a] < LO[a] || x[a] > HI[a]) {
                        return vec![1.0, 0.0];
                    }
                }
                let ts = axis_ts(x);
                let enter = ts.iter().map(|(a, b)| a.min(*b)).fold(0.0, f64::max);
                let exit = ts
                    .iter()
                    .map(|(a, b)| a.max(*b))
                    .fold(f64::from(f32::MAX), f64::min);
                vec![enter, exit]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // (face − p)/l: the subtraction rounds once (u of |face − p|), WGSL's
                // division 2.5 ULP: ≤ 7u·|t| per slab parameter; min and max are exact.
                bound: Some(|x| {
                    let e = axis_ts(x)
                        .iter()
                        .map(|(a, b)| 7.0 * U * a.abs().max(b.abs()))
                        .fold(0.0, f64::max);
                    vec![e, e]
                }),
                why: "(face − p)/l per axis: u of |face − p| then WGSL division 2.5 ULP, ≤ 7u of \
                      the largest slab parameter; min/max exact (reference: the slab method in \
                      f64)",
            },
        },
        Case {
            name: "cloudlight::shadow_march_point",
            imports: &["cloudlight::shadow_map"],
            arity: (10, 3),
            wgsl: "let q = shadow_march_point(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), \
                   vec2<f32>(x6, x7), u32(x8), u32(x9)); y0 = q.x; y1 = q.y; y2 = q.z;",
            grid: || {
                let mut grid = Vec::new();
                let points = [
                    [0.0, 0.0, 0.0],
                    [-2962.5, 1837.5, 350.0],
                    [812.5, -87.5, 1200.0],
                    [37.5, 2962.5, 0.0],
                    [-1012.5, -412.5, 1799.0],
                ];
                for p in points {
                    for l in suns().into_iter().step_by(2) {
                        for span in [
                            [0.0, 800.0],
                            [1000.0, 1017.0],
                            [0.0, 0.0],
                            [3500.0, 41000.0],
                            [120.0, 2321.5],
                            [0.0, 0.75],
                        ] {
                            for n in [1u32, 8, 64] {
                                for k in [0, n / 2, n - 1] {
                                    grid.push(vec![
                                        p[0],
                                        p[1],
                                        p[2],
                                        l[0],
                                        l[1],
                                        l[2],
                                        span[0],
                                        span[1],
                                        f64::from(k),
                                        f64::from(n),
                                    ]);
                                }
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                sm::shadow_march_point(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    [x[6], x[7]],
                    x[8] as u32,
                    x[9] as u32,
                )
                .to_vec()
            },
            reference: |x| {
                let h = (x[7] - x[6]) / x[9];
                let t = x[6] + (x[8] + 0.5) * h;
                vec![x[0] + t * x[3], x[1] + t * x[4], x[2] + t * x[5]]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // h: u of the difference + WGSL division 2.5 ULP; t = s0 + (k + ½)h: 2 more
                // roundings of terms ≤ |s0| + |s1|; q = p + t·l: 2 of |p| + |t|.
                bound: Some(|x| {
                    let t = x[6].abs() + x[7].abs();
                    (0..3).map(|a| 10.0 * U * (x[a].abs() + t)).collect()
                }),
                why: "h = (s1 − s0)/n (u + WGSL's 2.5 ULP), t = s0 + (k + ½)h and p + t·l two \
                      roundings each of terms ≤ |p| + |s0| + |s1|: 10u of that (reference: the \
                      formula in f64)",
            },
        },
        Case {
            name: "cloudlight::shadow_span_optical_depth",
            imports: &["cloudlight::shadow_map"],
            arity: (5, 1),
            wgsl: "y0 = shadow_span_optical_depth(x0, vec2<f32>(x1, x2), u32(x3), x4);",
            grid: || {
                let mut grid = Vec::new();
                for sum in [0.0, 0.37, 1.0, 3.0, 7.9, 51.2, 133.0, 640.0, 2048.5, 1e4] {
                    for span in [
                        [0.0, 800.0],
                        [1000.0, 1017.0],
                        [0.0, 0.0],
                        [3500.0, 41000.0],
                        [12.5, 12.75],
                        [250.0, 1900.0],
                    ] {
                        for n in [1.0, 3.0, 8.0, 32.0, 64.0, 4096.0] {
                            for sigma in logspace(1e-5, 1.0, 30) {
                                grid.push(vec![sum, span[0], span[1], n, sigma]);
                            }
                        }
                    }
                }
                grid.extend([[0.0, 0.0, 1.0, 1.0, 0.0]].map(|r| r.to_vec()));
                grid
            },
            cpu: |x| {
                vec![sm::shadow_span_optical_depth(
                    x[0],
                    [x[1], x[2]],
                    x[3] as u32,
                    x[4],
                )]
            },
            reference: |x| {
                let depth = (x[0] * ((x[2] - x[1]) / x[3])).min(1e30);
                vec![(x[4].min(1e30) * depth).min(1e30)]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // s1 − s0 rounds u of max(|s0|, |s1|) (cancels for a short far span), the
                // division 2.5 ULP, two products: σ·sum·(u·|s1| + 7u·h) over n.
                bound: Some(|x| {
                    let h = (x[2] - x[1]) / x[3];
                    vec![x[4] * x[0] * (U * x[2].abs().max(x[1].abs()) / x[3] + 8.0 * U * h)]
                }),
                why: "s1 − s0 rounds u of the larger end (a short span far away cancels), WGSL's \
                      division 2.5 ULP and two products: σ·Σρ·(u·max|s|/n + 8u·h) (reference: the \
                      formula in f64)",
            },
        },
        Case {
            name: "cloudlight::shadow_texel",
            imports: &["cloudlight::shadow_map", "cloudlight::cone"],
            arity: (7, 1),
            wgsl: "let p = shadow_texel_centre(vec2<u32>(u32(x0), u32(x1)), \
                   vec2<f32>(-3000.0, -3000.0), 75.0, x2); \
                   let l = vec3<f32>(x3, x4, x5); let n = u32(x6); \
                   let span = shadow_box_span(p, l, vec3<f32>(-1000.0, -800.0, 1000.0), \
                   vec3<f32>(1000.0, 800.0, 1800.0)); \
                   var tau = 0.0; \
                   if span.x <= span.y { \
                       var sum = 0.0; \
                       for (var k = 0u; k < n; k++) { \
                           let q = shadow_march_point(p, l, span, k, n); \
                           let dx = (q.x - 0.0) / 900.0; let dy = (q.y - 0.0) / 700.0; \
                           let dz = (q.z - 1400.0) / 380.0; \
                           sum = shadow_accumulate(sum, max(1.0 - (dx * dx + dy * dy + dz * dz), 0.0)); \
                       } \
                       tau = min(0.0 + shadow_span_optical_depth(sum, span, n, 0.004), 1e30); \
                   } \
                   y0 = beer_lambert(tau);",
            grid: || {
                let mut grid = Vec::new();
                let texels = [
                    0.0, 9.0, 17.0, 26.0, 33.0, 38.0, 41.0, 47.0, 55.0, 66.0, 79.0,
                ];
                for &i in &texels {
                    for &j in texels.iter().step_by(1) {
                        for ground in [0.0, 1250.0] {
                            for (k, l) in suns().into_iter().enumerate() {
                                let n = [1.0, 8.0, 64.0][(k + i as usize + j as usize) % 3];
                                grid.push(vec![i, j, ground, l[0], l[1], l[2], n]);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                let p = sm::shadow_texel_centre(
                    [x[0] as u32, x[1] as u32],
                    [GRID_ORIGIN[0] as f32, GRID_ORIGIN[1] as f32],
                    GRID_CELL as f32,
                    x[2],
                );
                vec![sm::shadow_texel::<f32, _>(
                    &Paraboloid,
                    p,
                    [x[3], x[4], x[5]],
                    x[6] as u32,
                )]
            },
            reference: |x| {
                let p = sm::shadow_texel_centre(
                    [x[0] as u32, x[1] as u32],
                    GRID_ORIGIN,
                    GRID_CELL,
                    x[2],
                );
                vec![sm::shadow_texel::<f64, _>(
                    &Paraboloid,
                    p,
                    [x[3], x[4], x[5]],
                    x[6] as u32,
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![texel_bound(x)]),
                why: "the march's forward error, doubled: sample points 12u(|p| + |t|) move \
                      ρ = 1 − |d|² by ≤ 6(δq/r + 3u) + 4u each, n of them summed (+ n·u·Σρ), h \
                      from the span's ends (16u·max|t|/n + 5u·h), σ·Σρ·h (3u·τ), exp 5 + 2τ ULP \
                      of T; a grazing span found by one precision only is 8u·(|p| + 4 km) long \
                      (reference: the generic march at f64 on the same analytic field)",
            },
        },
        Case {
            name: "cloudlight::shadow_depth_above",
            imports: &["cloudlight::shadow_map"],
            arity: (4, 1),
            wgsl: "y0 = shadow_depth_above(x0, x1, x2, x3);",
            grid: || {
                let mut grid = Vec::new();
                // Transmittances from opaque (below the 1e-30 floor) to clear; heights
                // below, inside and above two clouds (the deck's, a cumulus's altitudes).
                let transmittances = [
                    0.0, 1e-38, 1e-30, 1e-12, 1e-3, 0.05, 0.37, 0.5, 0.9, 0.999, 1.0,
                ];
                for t in transmittances.into_iter().chain(logspace(1e-6, 0.99, 40)) {
                    for [base, top] in [[1000.0, 1800.0], [1400.0, 2000.0], [300.0, 900.0]] {
                        for h in [0.0, 299.0, 999.5, 1000.0, 1013.7, 1250.0, 1400.0, 1600.0]
                            .into_iter()
                            .chain([1799.0, 1800.0, 1950.0, 2000.0, 2600.0])
                            .chain(linspace(0.0, 2600.0, 66))
                        {
                            grid.push(vec![t, h, base, top]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![sm::shadow_depth_above(x[0], x[1], x[2], x[3])],
            reference: |x| {
                let f = ((x[3] - x[1]) / (x[3] - x[2])).clamp(0.0, 1.0);
                vec![-(x[0].max(1e-30)).ln() * f * f]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // f: top − h and top − base one rounding each, the division u (WGSL 2.5
                // ULP), f² doubles it and adds u: 10u of f²; −ln T: 3 ULP (WGSL's log)
                // and 2^-21 absolute near T = 1; the product one more u.
                bound: Some(|x| {
                    let f = ((x[3] - x[1]) / (x[3] - x[2])).clamp(0.0, 1.0);
                    let depth = -(x[0].max(1e-30)).ln();
                    vec![f * f * (depth * 14.0 * U + 2f64.powi(-21) + 1e-30)]
                }),
                why: "f = clamp((top − h)/(top − base)) two subtractions and a division (u, \
                      WGSL 2.5 ULP), f² doubling it plus u: 10u of f²; −ln max(T, 1e-30) 3 ULP \
                      and 2^-21 absolute (WGSL's log), the product u (reference: the formula \
                      in f64)",
            },
        },
        Case {
            name: "cloudlight::shadow_map_taps",
            imports: &["cloudlight::shadow_map"],
            arity: (8, 7),
            // The lookup as its callers write it (render's terrain `shadow_map_at`,
            // cloudlight's `outside_depth`): the taps, each tap's value (1 outside the
            // map; here from the inputs, there from a binding), shadow_map_bilinear.
            wgsl: "let t = shadow_map_taps(vec2<f32>(x0, x1), vec2<u32>(u32(x2), u32(x3))); \
                   let c = vec4<f32>(x4, x5, x6, x7); var v = vec4<f32>(1.0); \
                   for (var k = 0; k < 4; k++) { if t.index[k] >= 0 { v[k] = c[k]; } } \
                   y0 = f32(t.index.x); y1 = f32(t.index.y); y2 = f32(t.index.z); \
                   y3 = f32(t.index.w); y4 = t.fraction.x; y5 = t.fraction.y; \
                   y6 = shadow_map_bilinear(v, t.fraction);",
            grid: || {
                let mut grid = Vec::new();
                // Texel coordinates (f32-exact) before, inside, on and past both edges of
                // maps from one texel to 256 a side; 12 sets of four texel values.
                let at = |n: f64| {
                    [-3.0, -1.0, -0.75, -0.5, 0.0, 0.375, 1.0, 1.5]
                        .into_iter()
                        .chain([
                            0.5 * n + 0.125,
                            n - 2.0,
                            n - 1.5,
                            n - 1.0,
                            n - 0.25,
                            n + 0.5,
                        ])
                };
                let values = [
                    [0.0, 0.0, 0.0, 0.0],
                    [1.0, 1.0, 1.0, 1.0],
                    [0.0, 1.0, 0.0, 1.0],
                    [0.25, 0.5, 0.75, 1.0],
                    [1.0, 0.0, 0.0, 1.0],
                    [0.9, 0.1, 0.3, 0.7],
                    [1e-30, 0.5, 1.0, 0.999],
                    [0.123, 0.456, 0.789, 0.0125],
                    [0.6, 0.6, 0.2, 0.2],
                    [0.05, 0.95, 0.35, 0.65],
                    [1e-6, 1e-3, 0.01, 0.1],
                    [0.333, 0.667, 0.111, 0.889],
                ];
                for [w, h] in [
                    [1.0, 1.0],
                    [2.0, 3.0],
                    [30.0, 29.0],
                    [56.0, 55.0],
                    [256.0, 256.0],
                ] {
                    for x in at(w) {
                        for y in at(h) {
                            for c in values {
                                grid.push(vec![x, y, w, h, c[0], c[1], c[2], c[3]]);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                let t = sm::shadow_map_taps([x[0], x[1]], [x[2] as u32, x[3] as u32]);
                let v = [0, 1, 2, 3].map(|k| if t.index[k] >= 0 { x[4 + k] } else { 1.0 });
                let mut out: Vec<f32> = t.index.iter().map(|&i| i as f32).collect();
                out.extend(t.fraction);
                out.push(sm::shadow_map_bilinear(v, t.fraction));
                out
            },
            reference: |x| {
                let (i, j, w, h) = (x[0].floor(), x[1].floor(), x[2], x[3]);
                let inside = |a: f64, b: f64| a >= 0.0 && b >= 0.0 && a < w && b < h;
                let taps = [(i, j), (i + 1.0, j), (i, j + 1.0), (i + 1.0, j + 1.0)];
                let index = taps.map(|(a, b)| if inside(a, b) { a + w * b } else { -1.0 });
                let v = [0, 1, 2, 3].map(|k| if index[k] >= 0.0 { x[4 + k] } else { 1.0 });
                let (u, t) = (x[0] - i, x[1] - j);
                let blend = v[0] * (1.0 - u) * (1.0 - t)
                    + v[1] * u * (1.0 - t)
                    + v[2] * (1.0 - u) * t
                    + v[3] * u * t;
                let mut out = index.to_vec();
                out.extend([u, t, blend]);
                out
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Indices exact (integers below 2^24); x − ⌊x⌋ exact in f32 (the inputs
                // are f32-exact); the bilinear blend: 1 − f exact for these fractions,
                // four products and three sums of terms ≤ max |c|: 8u of it.
                bound: Some(|x| {
                    let m = x[4..8].iter().fold(1.0f64, |a, c| a.max(c.abs()));
                    vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 8.0 * U * m]
                }),
                why: "indices are integers below 2^24 and x − ⌊x⌋ is exact for the f32-exact \
                      inputs (0 error); the blend (1 − f)·((1 − u)·c00 + u·c10) + f·(…): \
                      1 − u and 1 − f exact for these fractions, 4 products and 3 sums of \
                      terms ≤ max(1, |c|): 8u of it (reference: the four weights' sum in f64)",
            },
        },
    ]
}
