//! Parity cases of `cloudlight::march` (the view march after Schneider 2015): the energy-conserving step,
//! the multiple-scattering octaves, the pinhole camera's pixel direction, and the
//! interleaved-gradient-noise jitter. References are f64 textbook forms (expm1, powi,
//! glam's normalize), independent of the generic twins.

use super::super::compare::ulp_f32;
use super::*;

/// `dt·(1 − e^{−x})/x` in f64 (`x = σ·dt`), `dt` at `x = 0`.
fn step_integral_f64(sigma: f64, dt: f64) -> f64 {
    let x = sigma * dt;
    if x == 0.0 {
        dt
    } else {
        dt * (-(-x).exp_m1() / x)
    }
}

/// Forward bound of the f32 `step_integral`: `x = σ·dt` rounded (u, which moves the
/// result by at most u of itself: |d ln g/d ln x| ≤ 1), `one_minus_exp_neg` (atmos' Horner
/// series below 0.5: a few u; above, `1 − exp(−x)` with WGSL's exp error (3 + 2x ULP of
/// e^{−x}, + 1 for libm) kept absolute by the subtraction), the division (2.5 ULP) and
/// the product (u): 12u of the result plus the exp term.
fn step_integral_bound(sigma: f64, dt: f64) -> f64 {
    let x = sigma * dt;
    let r = step_integral_f64(sigma, dt);
    let exp_term = if x >= 0.5 {
        dt * (4.0 + 2.0 * x) * ulp_f32((-x).exp()) / x
    } else {
        0.0
    };
    12.0 * U * r.abs() + exp_term
}

/// Henyey–Greenstein in f64 and its derivative in g.
fn hg(mu: f64, g: f64) -> (f64, f64) {
    let d = 1.0 + g * g - 2.0 * g * mu;
    let four_pi = 4.0 * std::f64::consts::PI;
    let value = (1.0 - g * g) / (four_pi * d.powf(1.5));
    let derivative = (-2.0 * g * d - 3.0 * (1.0 - g * g) * (g - mu)) / (four_pi * d.powf(2.5));
    (value, derivative)
}

/// The octave sum in f64 (inputs: τ, cos θ, g_f, g_b, w, octaves, a, b, c) with, per term,
/// its forward error bound; returns (sum, bound).
fn octaves_f64(x: &[f64]) -> (f64, f64) {
    let (tau, mu, gf, gb, w) = (x[0], x[1], x[2], x[3], x[4]);
    let count = x[5] as i32;
    let (a, b, c) = (x[6], x[7], x[8]);
    let mut sum = 0.0;
    let mut bound = 0.0;
    let mut magnitude = 0.0;
    for n in 0..count {
        let (an, bn, cn) = (a.powi(n), b.powi(n), c.powi(n));
        let nf = f64::from(n);
        let arg = an * tau;
        let e = (-arg).exp();
        let (f, df) = hg(mu, cn * gf);
        let (k, dk) = hg(mu, cn * gb);
        let (f, k) = ((1.0 - w) * f, w * k);
        let phase = f + k;
        let term = bn * e * phase;
        sum += term;
        magnitude += term.abs();
        // exp: WGSL's 3 + 2|arg| ULP (+1 libm) and the argument's (n + 1)u relative error
        // (aⁿ a product chain of n roundings, times τ).
        let e_err = (4.0 + 2.0 * arg) * ulp_f32(e) + e * arg * (nf + 1.0) * U;
        // The phase: atmos' lobes (16 ULP each, their parity case) mixed (3u), and the
        // lobes' g = cⁿ·g rounded (n + 1)u relative, through ∂HG/∂g.
        let dg_f = (nf + 1.0) * U * (cn * gf).abs();
        let dg_b = (nf + 1.0) * U * (cn * gb).abs();
        let p_err = 16.0 * (ulp_f32(f) + ulp_f32(k))
            + 3.0 * U * phase
            + (1.0 - w) * df.abs() * dg_f
            + w * dk.abs() * dg_b;
        // bⁿ's n roundings and the two products.
        bound += bn * (e_err * phase + e * p_err) + (nf + 3.0) * U * term.abs();
    }
    // The running sum: one rounding per octave of at most the partial sum.
    bound += f64::from(count.max(1)) * U * magnitude;
    (sum, bound)
}

/// The pixel direction in f64 (inputs: x, y, w, h, forward, right, up, tan_half) with
/// glam's normalize, and its forward bound per component.
fn pixel_direction_f64(x: &[f64]) -> ([f64; 3], [f64; 3]) {
    use glam::DVec3;
    let (px, py, w, h) = (x[0], x[1], x[2], x[3]);
    let f = DVec3::new(x[4], x[5], x[6]);
    let r = DVec3::new(x[7], x[8], x[9]);
    let u = DVec3::new(x[10], x[11], x[12]);
    let (tx, ty) = (x[13], x[14]);
    let sx = (2.0 * (px + 0.5) / w - 1.0) * tx;
    let sy = (1.0 - 2.0 * (py + 0.5) / h) * ty;
    let v = f + sx * r + sy * u;
    let d = v.normalize();
    // sx, sy: the division (u) and the cancelling − 1 (u of 2) and the product: 4u·2·tan.
    let (dsx, dsy) = (8.0 * U * tx.abs(), 8.0 * U * ty.abs());
    // v: the products and two sums, 3u of the summands' magnitudes, + δs·|basis|.
    let magnitude = f.abs() + (sx * r).abs() + (sy * u).abs();
    let dv = 3.0 * U * magnitude.max_element()
        + dsx * r.abs().max_element()
        + dsy * u.abs().max_element();
    // The direction: δv/|v| twice (the component and the norm), + sqrt (4.5 ULP as
    // 1/inverseSqrt), the sums of squares (3u) and the division (2.5 ULP): 12u.
    let len = v.length();
    let bound = d.to_array().map(|c| 2.0 * dv / len + 12.0 * U * c.abs());
    (d.to_array(), bound)
}

/// The interleaved-gradient-noise constants as the f32 twins hold them.
const IGN_A: f32 = 0.067_110_56;
const IGN_B: f32 = 0.005_837_15;
const IGN_C: f32 = 52.982_918;

/// `fract(c·fract(a·x + b·y))` in f64 with the f32 constants, the inner value, and the
/// forward bound: the inner sum's three roundings (u of each product and of the sum;
/// fract is exact in f32), scaled by c, + u of c·inner.
fn ign_f64(x: f64, y: f64) -> (f64, f64, f64) {
    let (a, b, c) = (f64::from(IGN_A), f64::from(IGN_B), f64::from(IGN_C));
    let v = a * x + b * y;
    let inner = v - v.floor();
    let outer = c * inner;
    let bound_inner = U * ((a * x).abs() + (b * y).abs() + v.abs());
    let bound = c * bound_inner + U * outer.abs() + U;
    (outer - outer.floor(), inner, bound)
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::step_integral",
            imports: &["cloudlight::march"],
            arity: (2, 1),
            wgsl: "y0 = step_integral(x0, x1);",
            grid: || {
                let mut grid = Vec::new();
                let sigmas: Vec<f64> = std::iter::once(0.0)
                    .chain(logspace(1e-9, 1.0, 100))
                    .collect();
                for sigma in sigmas {
                    for dt in logspace(1e-2, 2e4, 100) {
                        grid.push(vec![sigma, dt]);
                    }
                }
                grid
            },
            cpu: |x| vec![cloudlight::march::step_integral(x[0], x[1])],
            reference: |x| vec![step_integral_f64(x[0], x[1])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![step_integral_bound(x[0], x[1])]),
                why: "dt·(1 − e^{−x})/x: x's rounding (u of the result), atmos' \
                      one_minus_exp_neg (Horner below 0.5; above, WGSL exp's 3 + 2x ULP of \
                      e^{−x} + 1 for libm, absolute through the subtraction), division 2.5 \
                      ULP, product: 12u + the exp term (reference: dt·(−expm1(−x))/x in f64)",
            },
        },
        Case {
            name: "cloudlight::scatter_step",
            imports: &["cloudlight::march"],
            arity: (4, 2),
            wgsl: "let s = scatter_step(x0, x1, x2, x3); y0 = s.x; y1 = s.y;",
            grid: || {
                let mut grid = Vec::new();
                let sigmas: Vec<f64> = std::iter::once(0.0)
                    .chain(logspace(1e-6, 1.0, 28))
                    .collect();
                for t in [1.0, 0.37, 1e-3] {
                    for source in [0.0, 1e-5, 0.02, 3.0] {
                        for &sigma in &sigmas {
                            for dt in logspace(0.1, 5000.0, 30) {
                                grid.push(vec![t, source, sigma, dt]);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                let s = cloudlight::march::scatter_step(x[0], x[1], x[2], x[3]);
                vec![s[0], s[1]]
            },
            reference: |x| {
                vec![
                    x[0] * x[1] * step_integral_f64(x[2], x[3]),
                    x[0] * (-x[2] * x[3]).exp(),
                ]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                // exp(−σΔ)·T below 2^−126 is subnormal: WGSL may flush it to 0 (lavapipe
                // does), f32 keeps it with an absolute rounding of the smallest subnormal.
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    let (t, s, sigma, dt) = (x[0], x[1], x[2], x[3]);
                    let arg = sigma * dt;
                    let e = (-arg).exp();
                    let gain = t * s * step_integral_f64(sigma, dt);
                    vec![
                        t * s.abs() * step_integral_bound(sigma, dt) + 2.0 * U * gain.abs(),
                        t * ((4.0 + 2.0 * arg) * ulp_f32(e) + e * arg * U) + U * t * e,
                    ]
                }),
                why: "gain: T·S times step_integral's bound, + 2u for the products; \
                      transmittance: T·exp(−σΔ) with WGSL exp's 3 + 2x ULP (+1 libm), the \
                      argument's rounding (u·x of e^{−x}) and the product; results below \
                      f32::MIN_POSITIVE may be flushed (reference: f64 expm1 and exp)",
            },
        },
        Case {
            name: "cloudlight::octave_scattering",
            imports: &["cloudlight::march"],
            arity: (9, 1),
            wgsl: "y0 = octave_scattering(x0, x1, x2, x3, x4, u32(x5), x6, x7, x8);",
            grid: || {
                let mut grid = Vec::new();
                let lobes = [
                    [0.8, -0.3, 0.2],
                    [0.6, 0.0, 0.0],
                    [0.95, -0.5, 0.5],
                    [0.0, 0.0, 0.0],
                ];
                let factors = [[0.5, 0.5, 0.5], [0.25, 0.5, 0.9], [0.8, 0.3, 0.1]];
                for tau in [0.0, 0.01, 0.5, 2.0, 10.0, 40.0] {
                    for mu in linspace(-1.0, 1.0, 41) {
                        for l in lobes {
                            for octaves in [1.0, 2.0, 4.0, 8.0] {
                                for f in factors {
                                    grid.push(vec![
                                        tau, mu, l[0], l[1], l[2], octaves, f[0], f[1], f[2],
                                    ]);
                                }
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::march::octave_scattering(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                    x[6],
                    x[7],
                    x[8],
                )]
            },
            reference: |x| vec![octaves_f64(x).0],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![octaves_f64(x).1]),
                why: "per octave: WGSL exp's 3 + 2|aⁿτ| ULP (+1 libm) and the argument's \
                      (n + 1)u, atmos' two HG lobes (16 ULP each) mixed (3u) and their \
                      g = cⁿg rounded (n + 1)u through ∂HG/∂g, bⁿ's n roundings; the running \
                      sum's u per octave (reference: powi, exp and the textbook HG in f64)",
            },
        },
        Case {
            name: "cloudlight::pixel_direction",
            imports: &["cloudlight::march"],
            arity: (15, 3),
            wgsl: "let d = pixel_direction(vec2<u32>(u32(x0), u32(x1)), vec2<u32>(u32(x2), \
                   u32(x3)), vec3<f32>(x4, x5, x6), vec3<f32>(x7, x8, x9), vec3<f32>(x10, x11, \
                   x12), vec2<f32>(x13, x14)); y0 = d.x; y1 = d.y; y2 = d.z;",
            grid: || {
                use glam::DVec3;
                let mut grid = Vec::new();
                let sizes = [[32.0, 32.0], [1280.0, 720.0], [7.0, 3.0]];
                for (k, f) in fibonacci(120).into_iter().enumerate() {
                    let forward = DVec3::from_array(f);
                    let hint = if forward.z.abs() < 0.9 {
                        DVec3::Z
                    } else {
                        DVec3::X
                    };
                    let right = forward.cross(hint).normalize();
                    let up = right.cross(forward);
                    let size = sizes[k % 3];
                    let tan_x = [0.1, 0.6, 2.5][k % 3];
                    let tan_y = tan_x * size[1] / size[0];
                    for i in 0..9 {
                        for j in 0..10 {
                            let px = ((size[0] - 1.0) * f64::from(i) / 8.0).round();
                            let py = ((size[1] - 1.0) * f64::from(j) / 9.0).round();
                            let mut row = vec![px, py, size[0], size[1]];
                            row.extend(forward.to_array());
                            row.extend(right.to_array());
                            row.extend(up.to_array());
                            row.extend([tan_x, tan_y]);
                            grid.push(row);
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                let v = |k: usize| [x[k], x[k + 1], x[k + 2]];
                cloudlight::march::pixel_direction(
                    [x[0] as u32, x[1] as u32],
                    [x[2] as u32, x[3] as u32],
                    v(4),
                    v(7),
                    v(10),
                    [x[13], x[14]],
                )
                .to_vec()
            },
            reference: |x| pixel_direction_f64(x).0.to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| pixel_direction_f64(x).1.to_vec()),
                why: "screen offsets 8u·tan (division, cancelling − 1, product), the unnormalised \
                      vector 3u of its summands + the offsets' error; normalising doubles the \
                      vector's relative error and adds sqrt (4.5 ULP), division (2.5 ULP) and \
                      the sum of squares: 12u (reference: glam's f64 normalize)",
            },
        },
        Case {
            name: "cloudlight::interleaved_gradient_noise",
            imports: &["cloudlight::jitter"],
            arity: (2, 1),
            wgsl: "y0 = interleaved_gradient_noise(vec2<u32>(u32(x0), u32(x1)));",
            grid: || {
                let mut grid = Vec::new();
                for j in 0..105u32 {
                    for i in 0..105u32 {
                        let (x, y) = (f64::from(i * 37), f64::from(j * 23));
                        // Within rounding of a wrap of either fract, both 0 and 1 are right:
                        // such pixels are left out.
                        let (_, inner, bound) = ign_f64(x, y);
                        let outer = f64::from(IGN_C) * inner;
                        let near = |v: f64, e: f64| (v - v.round()).abs() <= e;
                        if near(inner, bound / f64::from(IGN_C)) || near(outer, bound) {
                            continue;
                        }
                        grid.push(vec![x, y]);
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::jitter::interleaved_gradient_noise([
                    x[0] as u32,
                    x[1] as u32,
                ])]
            },
            reference: |x| vec![ign_f64(x[0], x[1]).0],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![ign_f64(x[0], x[1]).2]),
                why: "the inner a·x + b·y's three roundings (u each, of up to 250), scaled by \
                      52.98, + u of the outer product; fract exact in f32; pixels within that \
                      of a wrap left out (reference: f64 with the f32 constants)",
            },
        },
    ]
}

/// Unit directions spread over the sphere (a Fibonacci lattice).
fn fibonacci(n: u32) -> Vec<[f64; 3]> {
    (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(n);
            let r = (1.0 - z * z).sqrt();
            let phi = f64::from(k) * 2.399_963_229_728_653;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect()
}
