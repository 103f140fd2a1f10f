//! Parity cases of `cloudlight`'s procedural cloud shell (Schneider 2015): the tileable noise
//! (`shaders/cloudlight/noise.wgsl`) and the shell (`shaders/cloudlight/shell.wgsl`).
//!
//! The integer lattice hash is checked bit for bit against `integer_references`'
//! second spelling of `hash_combine`. The float functions' references are the generic
//! Rust functions' f64 instantiations (one formula, two precisions: the error is the
//! f32 side's rounding), except where a second formulation is short (the fade, the
//! gradient table, smoothstep, the fBm weights), which is then used instead.

use super::*;
use cloudlight::noise;
use cloudlight::shell;

/// A deterministic value in [0, 1) for row `i` and channel `salt`.
fn unit(i: u32, salt: u32) -> f64 {
    f64::from(skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt) >> 8)
        / 16_777_216.0
}

/// A 24-bit seed (exact in f32).
fn seed24(i: u32, salt: u32) -> f64 {
    f64::from(skyscape_wgsl::common::hash_u32(i ^ salt.wrapping_mul(0x85eb_ca6b)) >> 8)
}

const PERIODS: [u32; 9] = [1, 2, 3, 4, 5, 8, 16, 64, 256];

/// 10,000 random points in [−extent, extent]³ with a period and a seed, plus points on
/// the lattice and one period apart.
fn lattice_grid(extent: f64) -> Vec<Vec<f64>> {
    let mut grid: Vec<Vec<f64>> = (0..10_000u32)
        .map(|i| {
            let p = |s| extent * (2.0 * unit(i, s) - 1.0);
            vec![
                p(1),
                p(2),
                p(3),
                f64::from(PERIODS[i as usize % PERIODS.len()]),
                seed24(i, 4),
            ]
        })
        .collect();
    for k in 0..64u32 {
        let c = f64::from(k) - 32.0;
        grid.push(vec![c, -c, 0.5 * c, 4.0, 17.0]);
        grid.push(vec![c + 0.25, 3.75, -c - 0.5, 4.0, 17.0]);
    }
    grid
}

fn p3(x: &[f64]) -> [f64; 3] {
    [x[0], x[1], x[2]]
}

fn p3f(x: &[f32]) -> [f32; 3] {
    [x[0], x[1], x[2]]
}

/// The f32 error of an F1 distance `f1` (see the `worley_noise` case): the squared
/// distance's ≤ 108u, through the square root (≤ 108u/(2·F1), at most √(108u)), plus
/// WGSL's sqrt (4.5 ULP).
fn f1_error(f1: f64) -> f64 {
    let d2 = 108.0 * U;
    (d2 / (2.0 * f1)).min(d2.sqrt()) + 9.0 * U * f1
}

/// The bound of a Worley fBm (`worley_fbm`'s case) at `p` with `period`, `seed`.
fn worley_fbm_error(p: [f64; 3], period: u32, seed: u32) -> f64 {
    let mut bound = 4.0 * U;
    for (k, w) in noise::WORLEY_FBM_WEIGHTS.iter().enumerate() {
        let q = p.map(|c| c * f64::from(1u32 << k));
        let s = noise::noise_octave_seed(seed, k as u32);
        bound += w * (f1_error(noise::worley_noise(q, period << k, s)) + U);
    }
    bound
}

/// The shell of the density cases: Earth's ground, 1.5 km to 4 km.
const INNER: f64 = R_GROUND + 1_500.0;
const OUTER: f64 = R_GROUND + 4_000.0;

/// `shell_density`'s inputs: points at every height through and around the shell over
/// ±40 km horizontally, weather over [0, 1]², the default periods and erosion.
fn shell_density_grid() -> Vec<Vec<f64>> {
    (0..10_000u32)
        .map(|i| {
            let x = 40_000.0 * (2.0 * unit(i, 1) - 1.0);
            let y = 40_000.0 * (2.0 * unit(i, 2) - 1.0);
            let r = INNER - 300.0 + (OUTER - INNER + 600.0) * unit(i, 3);
            let z = (r * r - x * x - y * y).sqrt();
            let coverage = [0.0, 1.0, unit(i, 4)][i as usize % 3];
            vec![
                x,
                y,
                z,
                INNER,
                OUTER,
                coverage,
                unit(i, 5),
                20_000.0,
                2_000.0,
                0.2,
                seed24(i, 6),
            ]
        })
        .collect()
}

fn shell_density_f64(x: &[f64]) -> f64 {
    shell::shell_density(
        p3(x),
        x[3],
        x[4],
        x[5],
        x[6],
        x[7],
        x[8],
        x[9],
        x[10] as u32,
    )
}

/// The local slope of the f64 density over the f32 side's rounding of the radius
/// `r = |p|` (≤ 2u·r: three squares, two sums and a square root): the reference at `p`
/// scaled by 1 ± 3u. Doubled, plus 64u for the arithmetic after `r` (the noise's sums
/// and the remaps' two divisions).
fn shell_density_bound(x: &[f64]) -> Vec<f64> {
    let d = shell_density_f64(x);
    let mut spread: f64 = 0.0;
    for s in [-3.0, 3.0] {
        let mut y = x.to_vec();
        for c in &mut y[..3] {
            *c *= 1.0 + s * U;
        }
        spread = spread.max((shell_density_f64(&y) - d).abs());
    }
    vec![2.0 * spread + 64.0 * U]
}

/// `shell_ray_spans`' f64 roots for one sphere, and a bound on each root's f32 error:
/// `b = r·μ` is the dot product `origin·direction` (≤ 4u|b|), `c = (r − R)(r + R)` with
/// `r` rounded (≤ 2u·r² + 2u|c|), so `|δD| ≤ 8u·b² + 4u·r² + 4u|c|`; the roots inherit
/// `δ√D = min(δD/(2√D), √δD)`, `δb` and a few roundings of themselves.
fn sphere_roots_and_error(r: f64, mu: f64, radius: f64) -> ([f64; 2], f64, f64) {
    let b = r * mu;
    let c = (r - radius) * (r + radius);
    let d = b * b - c;
    let delta_d = 8.0 * U * b * b + 4.0 * U * r * r + 4.0 * U * c.abs();
    let roots = f64ref::ray_sphere_intersect(r, mu, radius);
    let sqrt_error = if d > 0.0 {
        (delta_d / (2.0 * d.sqrt())).min(delta_d.sqrt())
    } else {
        delta_d.sqrt()
    };
    let t = roots[0].abs().max(roots[1].abs());
    (
        roots,
        d,
        2.0 * sqrt_error + 4.0 * U * b.abs() + 12.0 * U * t,
    )
}

fn spans_f64(x: &[f64]) -> cloudlight::RaySpans<f64> {
    shell::shell_ray_spans(p3(x), [x[3], x[4], x[5]], x[6], x[7], x[8])
}

fn r_mu(x: &[f64]) -> (f64, f64) {
    let r = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
    let mu = (x[0] * x[3] + x[1] * x[4] + x[2] * x[5]) / r;
    (r, mu)
}

/// The largest root error over the three spheres (each span end is one of their roots
/// or 0).
fn spans_error(x: &[f64]) -> f64 {
    let (r, mu) = r_mu(x);
    [x[6], x[7], x[8]]
        .iter()
        .map(|&radius| sphere_roots_and_error(r, mu, radius).2)
        .fold(0.0, f64::max)
}

/// Rays from the ground, below, inside and above the shell and from orbit, in directions
/// over the sphere. Rays whose hit or miss of a sphere is undecidable in f32 (|D| within
/// its rounding) and rays whose span count is (a span shorter than twice the error, or
/// two candidate ends closer than that) are excluded: both answers are right there.
fn spans_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let altitudes = [2.0, 800.0, 1_500.5, 2_700.0, 3_999.0, 6_000.0, 5e4, 4e5];
    for (a, &altitude) in altitudes.iter().enumerate() {
        for (k, d) in fibonacci_directions(2_000).into_iter().enumerate() {
            let offset = 20_000.0 * (unit(k as u32, a as u32) - 0.5);
            let z = R_GROUND + altitude;
            let row = vec![offset, -offset, z, d[0], d[1], d[2], R_GROUND, INNER, OUTER];
            let x64: Vec<f64> = row.iter().map(|&v| f64::from(v as f32)).collect();
            let (r, mu) = r_mu(&x64);
            let error = spans_error(&x64);
            let undecidable = [R_GROUND, INNER, OUTER].iter().any(|&radius| {
                let (roots, d, e) = sphere_roots_and_error(r, mu, radius);
                d.abs() < 16.0 * U * (r * r + (r * mu).powi(2))
                    || roots.iter().any(|t| t.abs() < 2.0 * e)
            });
            let spans = spans_f64(&x64);
            let mut ends: Vec<f64> = Vec::new();
            for radius in [R_GROUND, INNER, OUTER] {
                ends.extend(f64ref::ray_sphere_intersect(r, mu, radius));
            }
            ends.retain(|t| *t > 0.0);
            ends.sort_by(f64::total_cmp);
            let close_ends = ends.windows(2).any(|w| w[1] - w[0] < 4.0 * error);
            let short = spans.as_slice().iter().any(|(a, b)| b - a < 4.0 * error);
            if !undecidable && !close_ends && !short {
                grid.push(row);
            }
        }
    }
    grid
}

/// Unit directions spread over the sphere (a Fibonacci lattice).
fn fibonacci_directions(n: u32) -> Vec<[f64; 3]> {
    (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(n);
            let r = (1.0 - z * z).sqrt();
            let phi = f64::from(k) * 2.399_963_229_728_653;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect()
}

fn spans_outputs<F: atmos::real::Real>(s: cloudlight::RaySpans<F>) -> Vec<F> {
    vec![
        F::of(s.count as f64),
        s.spans[0].0,
        s.spans[0].1,
        s.spans[1].0,
        s.spans[1].1,
    ]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::noise_cell_hash",
            imports: &["cloudlight::noise"],
            arity: (4, 2),
            wgsl: "let h = noise_cell_hash(vec3<u32>(u32(x0), u32(x1), u32(x2)), u32(x3)); \
                   y0 = f32(h & 0xffffu); y1 = f32(h >> 16u);",
            grid: || {
                let mut grid: Vec<Vec<f64>> = (0..10_000u32)
                    .map(|i| {
                        let small = |s| f64::from(skyscape_wgsl::common::hash_u32(i ^ s) % 300);
                        if i % 2 == 0 {
                            vec![small(1), small(2), small(3), seed24(i, 4)]
                        } else {
                            vec![seed24(i, 5), seed24(i, 6), seed24(i, 7), seed24(i, 8)]
                        }
                    })
                    .collect();
                grid.push(vec![0.0; 4]);
                grid.push(vec![16_777_215.0; 4]);
                grid
            },
            cpu: |x| {
                let h =
                    noise::noise_cell_hash([x[0] as u32, x[1] as u32, x[2] as u32], x[3] as u32);
                vec![(h & 0xffff) as f32, (h >> 16) as f32]
            },
            reference: |x| {
                use super::integer_references::combine;
                let h = combine(
                    combine(combine(x[3] as u32, x[0] as u32), x[1] as u32),
                    x[2] as u32,
                );
                vec![f64::from(h & 0xffff), f64::from(h >> 16)]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "wrapping u32 arithmetic, bit-identical in both languages; the halves are \
                      exact in f32 (reference: hash_combine spelled again in u64 reduced mod 2^32)",
            },
        },
        Case {
            name: "cloudlight::noise_octave_seed",
            imports: &["cloudlight::noise"],
            arity: (2, 2),
            wgsl: "let h = noise_octave_seed(u32(x0), u32(x1)); y0 = f32(h & 0xffffu); \
                   y1 = f32(h >> 16u);",
            grid: || {
                (0..10_000u32)
                    .map(|i| vec![seed24(i, 1), f64::from(i % 16)])
                    .collect()
            },
            cpu: |x| {
                let h = noise::noise_octave_seed(x[0] as u32, x[1] as u32);
                vec![(h & 0xffff) as f32, (h >> 16) as f32]
            },
            reference: |x| {
                let h = super::integer_references::combine(x[0] as u32, x[1] as u32);
                vec![f64::from(h & 0xffff), f64::from(h >> 16)]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "wrapping u32 arithmetic, bit-identical (reference: hash_combine spelled \
                      again in u64)",
            },
        },
        Case {
            name: "cloudlight::perlin_fade",
            imports: &["cloudlight::noise"],
            arity: (1, 1),
            wgsl: "y0 = perlin_fade(x0);",
            grid: || linspace(0.0, 1.0, 10_001).map(|t| vec![t]).collect(),
            cpu: |x| vec![noise::perlin_fade(x[0])],
            // Independent form: the expanded polynomial.
            reference: |x| {
                let t = x[0];
                vec![6.0 * t.powi(5) - 15.0 * t.powi(4) + 10.0 * t.powi(3)]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // t ∈ [0, 1]: t(6t − 15) + 10 ∈ [1, 10] (no cancellation below 1), each of the
                // seven roundings is u of a term ≤ 10·t³ ≤ 10: ≤ 8u of t³·10 absolute.
                bound: Some(|x| vec![8.0 * U * 10.0 * x[0].powi(3) + U]),
                why: "t³(t(6t − 15) + 10) on [0, 1]: 7 roundings of terms ≤ 10t³ \
                      (reference: the expanded quintic in f64)",
            },
        },
        Case {
            name: "cloudlight::perlin_gradient_dot",
            imports: &["cloudlight::noise"],
            arity: (4, 1),
            wgsl: "y0 = perlin_gradient_dot(u32(x0) << 28u, x1, x2, x3);",
            grid: || {
                (0..10_000u32)
                    .map(|i| {
                        let c = |s| ((unit(i, s) * 2048.0).floor() - 1024.0) / 1024.0;
                        vec![f64::from(i % 16), c(1), c(2), c(3)]
                    })
                    .collect()
            },
            cpu: |x| {
                vec![noise::perlin_gradient_dot(
                    (x[0] as u32) << 28,
                    x[1],
                    x[2],
                    x[3],
                )]
            },
            // Independent form: Perlin's (2002) gradient table.
            reference: |x| {
                const G: [[f64; 3]; 16] = [
                    [1.0, 1.0, 0.0],
                    [-1.0, 1.0, 0.0],
                    [1.0, -1.0, 0.0],
                    [-1.0, -1.0, 0.0],
                    [1.0, 0.0, 1.0],
                    [-1.0, 0.0, 1.0],
                    [1.0, 0.0, -1.0],
                    [-1.0, 0.0, -1.0],
                    [0.0, 1.0, 1.0],
                    [0.0, -1.0, 1.0],
                    [0.0, 1.0, -1.0],
                    [0.0, -1.0, -1.0],
                    [1.0, 1.0, 0.0],
                    [0.0, -1.0, 1.0],
                    [-1.0, 1.0, 0.0],
                    [0.0, -1.0, -1.0],
                ];
                let g = G[x[0] as usize];
                vec![g[0] * x[1] + g[1] * x[2] + g[2] * x[3]]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "inputs are multiples of 2⁻¹⁰ in [−1, 1], so ±a ± b is exact in f32: \
                      bit-exact, a wrong sign or component shows (reference: Perlin's \
                      16-gradient table, dot product in f64)",
            },
        },
        Case {
            name: "cloudlight::perlin_noise",
            imports: &["cloudlight::noise"],
            arity: (5, 1),
            wgsl: "y0 = perlin_noise(vec3<f32>(x0, x1, x2), u32(x3), u32(x4));",
            grid: || lattice_grid(50.0),
            cpu: |x| vec![noise::perlin_noise(p3f(x), x[3] as u32, x[4] as u32)],
            reference: |x| vec![noise::perlin_noise(p3(x), x[3] as u32, x[4] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // The fraction p − floor(p) is exact; the corner dots (|·| ≤ 2, one rounding
                // each), the fades (≤ 8u·10) and seven lerps (three levels, each ≤ 3u of
                // values ≤ 2) add up to ≤ 2u·2 + 3·3u·2 + 80u·2 ≈ 200u absolute.
                bound: Some(|_| vec![200.0 * U]),
                why: "exact fractions; corner dots, quintic fades and three lerp levels of \
                      values ≤ 2: ≤ 200u absolute (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::worley_noise",
            imports: &["cloudlight::noise"],
            arity: (5, 1),
            wgsl: "y0 = worley_noise(vec3<f32>(x0, x1, x2), u32(x3), u32(x4));",
            grid: || lattice_grid(50.0),
            cpu: |x| vec![noise::worley_noise(p3f(x), x[3] as u32, x[4] as u32)],
            reference: |x| vec![noise::worley_noise(p3(x), x[3] as u32, x[4] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Offsets d + u − f with |·| ≤ 2 (two roundings, ≤ 4u each), squared and
                // summed (≤ 12 total, 5 roundings): |δF1²| ≤ 3·2·2·4u + 5u·12 ≈ 108u; the
                // square root halves it relative to F1 and adds 4.5 ULP (WGSL sqrt):
                // ≤ 108u/(2F1) capped at √(108u), plus 9u·F1.
                bound: Some(|x| {
                    vec![f1_error(noise::worley_noise(
                        p3(x),
                        x[3] as u32,
                        x[4] as u32,
                    ))]
                }),
                why: "exact fractions; three offsets of ≤ 2 cells, their squares' sum (≤ 108u of \
                      F1²) and the square root (4.5 ULP in WGSL) (reference: the generic \
                      function at f64)",
            },
        },
        Case {
            name: "cloudlight::worley_fbm",
            imports: &["cloudlight::noise"],
            arity: (5, 1),
            wgsl: "y0 = worley_fbm(vec3<f32>(x0, x1, x2), u32(x3), u32(x4));",
            grid: || lattice_grid(20.0),
            cpu: |x| vec![noise::worley_fbm(p3f(x), x[3] as u32, x[4] as u32)],
            reference: |x| vec![noise::worley_fbm(p3(x), x[3] as u32, x[4] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Three Worley octaves (p·2ᵏ exact) whose F1 error is ≤ √(108u) near a
                // feature point and ≤ 60u elsewhere, weighted by ≤ 0.625 and summed.
                bound: Some(|x| vec![worley_fbm_error(p3(x), x[3] as u32, x[4] as u32)]),
                why: "each octave's F1 bound (see worley_noise) times its weight, plus the \
                      weighted sum's roundings (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::perlin_fbm",
            imports: &["cloudlight::noise"],
            arity: (5, 1),
            wgsl: "y0 = perlin_fbm(vec3<f32>(x0, x1, x2), u32(x3), u32(x4));",
            grid: || lattice_grid(20.0),
            cpu: |x| vec![noise::perlin_fbm(p3f(x), x[3] as u32, x[4] as u32)],
            reference: |x| vec![noise::perlin_fbm(p3(x), x[3] as u32, x[4] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // Three Perlin octaves (≤ 200u each, weights 1, ½, ¼), the sum and the map
                // ½ + ½·n/1.75: ≤ ½·(1.75·200u + 4u)/1.75 + 2u ≈ 104u.
                bound: Some(|_| vec![104.0 * U]),
                why: "three Perlin octaves (200u each, see perlin_noise), weights ≤ 1, the map \
                      ½ + ½n/1.75 halves it (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::perlin_worley",
            imports: &["cloudlight::noise"],
            arity: (5, 1),
            wgsl: "y0 = perlin_worley(vec3<f32>(x0, x1, x2), u32(x3), u32(x4));",
            grid: || lattice_grid(20.0),
            cpu: |x| vec![noise::perlin_worley(p3f(x), x[3] as u32, x[4] as u32)],
            reference: |x| vec![noise::perlin_worley(p3(x), x[3] as u32, x[4] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // w + p(1 − w) with p, w ∈ [0, 1]: ∂/∂w = 1 − p ≤ 1, ∂/∂p = 1 − w ≤ 1, so the
                // error is at most the Worley fBm's (√(108u)-sized near a feature point)
                // plus Perlin fBm's 104u plus 3u.
                bound: Some(|x| {
                    let seed = noise::noise_octave_seed(x[4] as u32, 1);
                    vec![111.0 * U + worley_fbm_error(p3(x), x[3] as u32, seed)]
                }),
                why: "w + p(1 − w) has unit sensitivities: the Worley fBm's bound plus the \
                      Perlin fBm's plus 3u (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::cloud_shape_noise",
            imports: &["cloudlight::noise"],
            arity: (4, 4),
            wgsl: "let v = cloud_shape_noise(vec3<f32>(x0, x1, x2), u32(x3)); \
                   y0 = v.x; y1 = v.y; y2 = v.z; y3 = v.w;",
            grid: || {
                (0..10_000u32)
                    .map(|i| {
                        let c = |s| 3.0 * (2.0 * unit(i, s) - 1.0);
                        vec![c(1), c(2), c(3), seed24(i, 4)]
                    })
                    .collect()
            },
            cpu: |x| noise::cloud_shape_noise(p3f(x), x[3] as u32).to_vec(),
            reference: |x| noise::cloud_shape_noise(p3(x), x[3] as u32).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // u·4·2ᵏ is exact (powers of two); each channel's own bound: the
                // Perlin–Worley's (111u + its Worley fBm's) and each Worley octave's F1.
                bound: Some(|x| {
                    let seed = x[3] as u32;
                    let p = p3(x).map(|c| c * 4.0);
                    let pw_seed = noise::noise_octave_seed(seed, 0);
                    let mut bound = vec![
                        111.0 * U + worley_fbm_error(p, 4, noise::noise_octave_seed(pw_seed, 1)),
                    ];
                    for k in 0..3u32 {
                        let q = p.map(|c| c * f64::from(1u32 << k));
                        let s = noise::noise_octave_seed(seed, 1 + k);
                        bound.push(f1_error(noise::worley_noise(q, 4 << k, s)) + U);
                    }
                    bound
                }),
                why: "u·cells·2ᵏ is exact (powers of two); channel 0 has the Perlin–Worley \
                      bound, channels 1–3 each octave's F1 bound (reference: the generic \
                      function at f64)",
            },
        },
        Case {
            name: "cloudlight::cloud_detail_noise",
            imports: &["cloudlight::noise"],
            arity: (4, 3),
            wgsl: "let v = cloud_detail_noise(vec3<f32>(x0, x1, x2), u32(x3)); \
                   y0 = v.x; y1 = v.y; y2 = v.z;",
            grid: || {
                (0..10_000u32)
                    .map(|i| {
                        let c = |s| 3.0 * (2.0 * unit(i, s) - 1.0);
                        vec![c(1), c(2), c(3), seed24(i, 4)]
                    })
                    .collect()
            },
            cpu: |x| noise::cloud_detail_noise(p3f(x), x[3] as u32).to_vec(),
            reference: |x| noise::cloud_detail_noise(p3(x), x[3] as u32).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    let p = p3(x).map(|c| c * 2.0);
                    (0..3u32)
                        .map(|k| {
                            let q = p.map(|c| c * f64::from(1u32 << k));
                            let s = noise::noise_octave_seed(x[3] as u32, 4 + k);
                            f1_error(noise::worley_noise(q, 2 << k, s)) + U
                        })
                        .collect()
                }),
                why: "u·cells·2ᵏ is exact (powers of two); each channel has its octave's F1 \
                      bound (see worley_noise) (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::worley_channels_fbm",
            imports: &["cloudlight::noise"],
            arity: (3, 1),
            wgsl: "y0 = worley_channels_fbm(vec3<f32>(x0, x1, x2));",
            grid: || {
                (0..10_000u32)
                    .map(|i| vec![unit(i, 1), unit(i, 2), unit(i, 3)])
                    .collect()
            },
            cpu: |x| vec![noise::worley_channels_fbm(p3f(x))],
            reference: |x| vec![(5.0 * x[0] + 2.0 * x[1] + x[2]) / 8.0],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![3.0 * U * (0.625 * x[0] + 0.25 * x[1] + 0.125 * x[2])]),
                why: "power-of-two-exact weights 5/8, 1/4, 1/8: three roundings of non-negative \
                      terms, 3u of the sum (reference: (5a + 2b + c)/8 in f64)",
            },
        },
        Case {
            name: "cloudlight::noise_texel_lerp",
            imports: &["cloudlight::noise"],
            arity: (2, 3),
            wgsl: "let l = noise_texel_lerp(x0, u32(x1)); y0 = l.x; y1 = l.y; y2 = l.z;",
            grid: || {
                let mut grid: Vec<Vec<f64>> = (0..10_000u32)
                    .map(|i| {
                        let size = [128u32, 32, 20, 7, 1][i as usize % 5];
                        vec![60.0 * (unit(i, 1) - 0.5), f64::from(size)]
                    })
                    .collect();
                for k in 0..=64 {
                    // Texel centres and edges of a 32-texel tile.
                    grid.push(vec![f64::from(k) / 64.0, 32.0]);
                }
                grid
            },
            cpu: |x| {
                let (i0, i1, t) = noise::noise_texel_lerp(x[0], x[1] as u32);
                vec![i0 as f32, i1 as f32, t]
            },
            // Independent form: Euclidean remainders of the floor in f64.
            reference: |x| {
                let n = x[1];
                let g = x[0] * n - 0.5;
                let i = g.floor();
                vec![i.rem_euclid(n), (i + 1.0).rem_euclid(n), g - i]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // u·size − ½ rounds twice (≤ u·|g| each) before the exact floor and
                // fraction; a rounding across an integer changes the texels, which the
                // grid's values do not (checked: the case passes with texels exact).
                bound: Some(|x| {
                    let g = (x[0] * x[1] - 0.5).abs();
                    vec![0.0, 0.0, 2.0 * U * (g + 1.0)]
                }),
                why: "texels exact (the grid has no g within rounding of an integer); the \
                      weight inherits the two roundings of g = u·size − ½ (reference: floor and \
                      rem_euclid in f64)",
            },
        },
        Case {
            name: "cloudlight::shell_smoothstep",
            imports: &["cloudlight::shell"],
            arity: (3, 1),
            wgsl: "y0 = shell_smoothstep(x0, x1, x2);",
            grid: || {
                (0..10_000u32)
                    .map(|i| {
                        let lo = unit(i, 1) * 0.5;
                        let hi = lo + 0.01 + unit(i, 2) * 0.5;
                        vec![lo, hi, 1.2 * unit(i, 3) - 0.1]
                    })
                    .collect()
            },
            cpu: |x| vec![shell::shell_smoothstep(x[0], x[1], x[2])],
            // Independent form: 3t² − 2t³.
            reference: |x| {
                let t = ((x[2] - x[0]) / (x[1] - x[0])).clamp(0.0, 1.0);
                vec![3.0 * t * t - 2.0 * t * t * t]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // t = (x − lo)/(hi − lo): two subtractions and WGSL's division (2.5 ULP):
                // ≤ 5u·t (+ the subtractions' u|x|, u|lo| over hi − lo); the slope 6t(1 − t)
                // ≤ 1.5; then t²(3 − 2t) adds 4u.
                bound: Some(|x| {
                    let w = x[1] - x[0];
                    let t = ((x[2] - x[0]) / w).clamp(0.0, 1.0);
                    let dt =
                        5.0 * U * t + U * (x[2].abs() + x[0].abs()) / w + U * x[1].abs() / w * t;
                    vec![1.5 * dt + 4.0 * U]
                }),
                why: "t's two subtractions and division (2.5 ULP in WGSL), times the slope ≤ 1.5, \
                      plus t²(3 − 2t)'s four roundings (reference: 3t² − 2t³ in f64)",
            },
        },
        Case {
            name: "cloudlight::height_gradient",
            imports: &["cloudlight::shell"],
            arity: (2, 1),
            wgsl: "y0 = height_gradient(x0, x1);",
            grid: || {
                let mut grid = Vec::new();
                for t in linspace(0.0, 1.0, 41) {
                    for h in linspace(-0.05, 1.05, 251) {
                        grid.push(vec![h, t]);
                    }
                }
                grid
            },
            cpu: |x| vec![shell::height_gradient(x[0], x[1])],
            reference: |x| vec![shell::height_gradient(x[0], x[1])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // The blended corners (three products and sums of numbers ≤ 1: ≤ 5u) move
                // each smoothstep by ≤ 1.5·5u/width, widths ≥ 0.1 (stratus) … 0.0875
                // (cumulus's upper ramp): ≤ 90u each; two smoothsteps and a subtraction.
                bound: Some(|_| vec![200.0 * U]),
                why: "corner blends (≤ 5u) over ramps ≥ 0.0875 wide (slope ≤ 1.5/width) in two \
                      smoothsteps: ≤ 200u (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::shell_density_from_noise",
            imports: &["cloudlight::shell"],
            arity: (10, 1),
            wgsl: "y0 = shell_density_from_noise(x0, x1, x2, vec4<f32>(x3, x4, x5, x6), \
                   vec3<f32>(x7, x8, x9), 0.2);",
            grid: || {
                (0..10_000u32)
                    .map(|i| (1..=10).map(|s| unit(i, s)).collect::<Vec<f64>>())
                    .collect()
            },
            cpu: |x| {
                vec![shell::shell_density_from_noise(
                    x[0],
                    x[1],
                    x[2],
                    [x[3], x[4], x[5], x[6]],
                    [x[7], x[8], x[9]],
                    0.2,
                )]
            },
            reference: |x| {
                vec![shell::shell_density_from_noise(
                    x[0],
                    x[1],
                    x[2],
                    [x[3], x[4], x[5], x[6]],
                    [x[7], x[8], x[9]],
                    0.2,
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // The height profile (≤ 200u, see height_gradient) times base ≤ 1, the base's
                // division (2.5 ULP) and the erosion remap's division by 1 − e ≥ 0.8: the
                // chain amplifies by ≤ 1.25, ≤ 320u in all.
                bound: Some(|_| vec![320.0 * U]),
                why: "the height profile's 200u plus the base and erosion remaps' divisions \
                      (2.5 ULP each in WGSL), amplified by 1/(1 − e) ≤ 1.25 (reference: the \
                      generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::shell_density",
            imports: &["cloudlight::shell"],
            arity: (11, 1),
            wgsl: "y0 = shell_density(vec3<f32>(x0, x1, x2), x3, x4, x5, x6, x7, x8, x9, u32(x10));",
            grid: shell_density_grid,
            cpu: |x| {
                vec![shell::shell_density(
                    p3f(x),
                    x[3],
                    x[4],
                    x[5],
                    x[6],
                    x[7],
                    x[8],
                    x[9],
                    x[10] as u32,
                )]
            },
            reference: |x| vec![shell_density_f64(x)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(shell_density_bound),
                why: "at Earth scale |p| rounds to ~0.4 m in f32, which moves the height \
                      fraction and the noise's vertical coordinate: the bound is the f64 \
                      density's own change over r·(1 ± 3u), doubled, plus 64u for the rest \
                      (reference: the generic function at f64)",
            },
        },
        Case {
            name: "cloudlight::horizon_fade",
            imports: &["cloudlight::shell"],
            arity: (3, 1),
            wgsl: "y0 = horizon_fade(x0, x1, x2);",
            grid: || {
                (0..10_000u32)
                    .map(|i| {
                        let start = 1e5 * unit(i, 1);
                        let end = start + 1e3 + 1e5 * unit(i, 2);
                        vec![2.5e5 * unit(i, 3), start, end]
                    })
                    .collect()
            },
            cpu: |x| vec![shell::horizon_fade(x[0], x[1], x[2])],
            // Independent form: 1 − (3t² − 2t³).
            reference: |x| {
                let t = ((x[0] - x[1]) / (x[2] - x[1])).clamp(0.0, 1.0);
                vec![1.0 - (3.0 * t * t - 2.0 * t * t * t)]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    let w = x[2] - x[1];
                    let t = ((x[0] - x[1]) / w).clamp(0.0, 1.0);
                    let dt =
                        5.0 * U * t + U * (x[0].abs() + x[1].abs()) / w + U * x[2].abs() / w * t;
                    vec![1.5 * dt + 5.0 * U]
                }),
                why: "shell_smoothstep's bound plus the final 1 − s (u) (reference: \
                      1 − (3t² − 2t³) in f64)",
            },
        },
        Case {
            name: "cloudlight::procedural_weather",
            imports: &["cloudlight::shell"],
            arity: (9, 2),
            wgsl: "let w = procedural_weather(vec2<f32>(x0, x1), x2, u32(x3), u32(x4), x5, x6, \
                   x7, x8); y0 = w.x; y1 = w.y;",
            grid: || {
                (0..10_000u32)
                    .map(|i| {
                        vec![
                            2e5 * (unit(i, 1) - 0.5),
                            2e5 * (unit(i, 2) - 0.5),
                            50_000.0,
                            f64::from([1u32, 4, 8][i as usize % 3]),
                            seed24(i, 3),
                            unit(i, 4),
                            2.0 * unit(i, 5),
                            unit(i, 6),
                            unit(i, 7),
                        ]
                    })
                    .collect()
            },
            cpu: |x| {
                shell::procedural_weather(
                    [x[0], x[1]],
                    x[2],
                    x[3] as u32,
                    x[4] as u32,
                    x[5],
                    x[6],
                    x[7],
                    x[8],
                )
                .to_vec()
            },
            reference: |x| {
                shell::procedural_weather(
                    [x[0], x[1]],
                    x[2],
                    x[3] as u32,
                    x[4] as u32,
                    x[5],
                    x[6],
                    x[7],
                    x[8],
                )
                .to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // cells/period (WGSL division, 2.5 ULP) and x·scale round: ≤ 4u of the
                // coordinate (≤ 16 cells at the top octave: 64u cells, Perlin slope ≤ 3):
                // ≤ 200u, plus the fBm's 104u, times 2·contrast ≤ 4, plus 3u.
                bound: Some(|x| {
                    let contrast = [x[6], x[8]];
                    contrast
                        .iter()
                        .map(|c| 2.0 * c * 304.0 * U + 3.0 * U)
                        .collect()
                }),
                why: "the coordinate's scale and product (≤ 4u of ≤ 16 cells, Perlin slope ≤ 3) \
                      and the fBm's 104u, times 2·contrast (reference: the generic function \
                      at f64)",
            },
        },
        Case {
            name: "cloudlight::shell_ray_spans",
            imports: &["cloudlight::shell"],
            arity: (9, 5),
            wgsl: "let s = shell_ray_spans(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), x6, x7, \
                   x8); y0 = f32(s.count); y1 = s.spans[0].x; y2 = s.spans[0].y; \
                   y3 = s.spans[1].x; y4 = s.spans[1].y;",
            grid: spans_grid,
            cpu: |x| {
                spans_outputs(shell::shell_ray_spans(
                    p3f(x),
                    [x[3], x[4], x[5]],
                    x[6],
                    x[7],
                    x[8],
                ))
            },
            reference: |x| spans_outputs(spans_f64(x)),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    let e = spans_error(x);
                    vec![0.0, e, e, e, e]
                }),
                why: "the count is exact (rays whose count is undecidable in f32 are excluded \
                      from the grid); each end is a root of one of the three spheres: the \
                      discriminant's error from b = origin·direction and c = (r − R)(r + R) with \
                      r rounded, through √D, plus a few roundings of t (reference: the generic \
                      function at f64)",
            },
        },
    ]
}
