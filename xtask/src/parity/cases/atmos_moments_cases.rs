//! Parity cases of the multiple-scattering LUT's field moments
//! (`atmos::lut::multiple_scattering_moments`, `shaders/atmos/lut_multiple_scattering_moments.wgsl`)
//! and the Legendre moments of the phase function they are scattered with. References:
//! `atmos::lut::reference` and `atmos::reference` (f64, same formulas).
//!
//! Every function here is a handful of products and sums; the tolerances are forward
//! bounds on the sums' cancellation (in units of the terms' magnitudes), plus WGSL's
//! 2.5 ULP division and 4.5 ULP square root where they occur.

use super::*;
use atmos::lut::multiple_scattering_moments as moments32;
use atmos::lut::reference as lut64;

fn anisotropy_grid() -> Vec<Vec<f64>> {
    let mut grid: Vec<Vec<f64>> = linspace(-0.9999, 0.9999, 20_001).map(|g| vec![g]).collect();
    grid.push(vec![0.0]);
    grid
}

/// (μ, μ_s, ν) of consistent view/sun pairs, plus ν slightly outside the possible
/// range (rounded inputs; clamped by the function), and the sun at the zenith.
fn sun_frame_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for view_zenith in linspace(0.0, std::f64::consts::PI, 41) {
        for sun_zenith in linspace(0.0, std::f64::consts::PI, 21) {
            for azimuth in linspace(0.0, std::f64::consts::PI, 13) {
                let (mu, mu_s) = (view_zenith.cos(), sun_zenith.cos());
                let sin_product = view_zenith.sin() * sun_zenith.sin();
                let nu = mu * mu_s + sin_product * azimuth.cos();
                // The "sun at the zenith" branch switches at sin_s = 1e-4; rounding
                // may take either side within 1e-6 of it.
                if (sun_zenith.sin() - 1e-4).abs() < 1e-6 {
                    continue;
                }
                grid.push(vec![mu, mu_s, nu]);
                grid.push(vec![mu, mu_s, (nu + 1e-6).min(1.0)]);
            }
        }
    }
    grid
}

fn sun_frame_bound(x: &[f64]) -> Vec<f64> {
    let (mu, mu_s, nu) = (x[0], x[1], x[2]);
    let [vx, vy, _] = lut64::sun_frame_direction(mu, mu_s, nu);
    let horizontal = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    // horizontal and sin_s: (1 − μ)(1 + μ) (exact factors, 2 roundings) and sqrt.
    let horizontal_error = 8.0 * U * horizontal;
    let x_error = if sin_s > 1e-4 {
        // ν − μμ_s cancels (4u of its terms) over sin_s (relative 8u), then ÷ (2.5 ULP).
        4.0 * U * (nu.abs() + (mu * mu_s).abs()) / sin_s + 16.0 * U * vx.abs() + horizontal_error
    } else {
        0.0
    };
    // y = √((h − x)(h + x)): a perturbation δ of h or x moves y² by ≤ 2h·δ, and y by
    // ≤ √(y² + 2hδ) − y (steep where y → 0); plus the square root's 4.5 ULP.
    let delta = x_error + horizontal_error;
    let y_error = (vy * vy + 2.0 * horizontal * delta + 4.0 * U).sqrt() - vy + 12.0 * U * vy;
    vec![x_error, y_error, 0.0]
}

/// One channel's moments, a sun-frame direction and a phase function's Legendre
/// moments: [Ψ, d_x, d_z, A_xx, A_zz, A_xz, v_x, v_y, v_z, g₁, g₂].
fn scattered_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let phases: Vec<[f64; 2]> = [0.0, 0.3, 0.8, 0.95]
        .iter()
        .map(|&g| f64ref::cornette_shanks_legendre_moments(g))
        .chain([[0.0, 0.1]])
        .collect();
    // Fields from isotropic to strongly anisotropic (|d|, |A| up to Ψ/2; a sky's are
    // ≤ 0.3 Ψ), including ones whose sideways scattering the floor at 0 cuts.
    let fractions = [-0.5, -0.2, 0.0, 0.1, 0.45];
    let mut n = 0u64;
    for (p, legendre) in phases.iter().enumerate() {
        for &dx in &fractions {
            for &dz in &fractions {
                for &axx in &[-0.3, 0.0, 0.2] {
                    for &azz in &[-0.3, 0.0, 0.25] {
                        for &axz in &[-0.1, 0.0, 0.15] {
                            // Directions from a Fibonacci lattice over the y ≥ 0 half.
                            for k in 0..8 {
                                n += 1;
                                let i = (n * 7 + k + p as u64) % 64;
                                let z = 1.0 - 2.0 * (i as f64 + 0.5) / 64.0;
                                let phi = (i as f64 * 2.399_963_229_728_653) % std::f64::consts::PI;
                                let s = (1.0 - z * z).sqrt();
                                let mean = 1e-3 * (1.0 + (n % 5) as f64);
                                grid.push(vec![
                                    mean,
                                    dx * mean,
                                    dz * mean,
                                    axx * mean,
                                    azz * mean,
                                    axz * mean,
                                    s * phi.cos(),
                                    s * phi.sin(),
                                    z,
                                    legendre[0],
                                    legendre[1],
                                ]);
                            }
                        }
                    }
                }
            }
        }
    }
    grid
}

fn scattered_bound(x: &[f64]) -> Vec<f64> {
    let [mean, dx, dz, axx, azz, axz, vx, vy, vz, g1, g2] =
        <[f64; 11]>::try_from(x).expect("arity 11");
    // Σ of the terms' magnitudes: about 6 roundings deep on either side.
    let magnitude = mean.abs()
        + 3.0 * g1.abs() * ((dx * vx).abs() + (dz * vz).abs())
        + 7.5
            * g2.abs()
            * (axx.abs() * (vx * vx + vy * vy)
                + azz.abs() * (vz * vz + vy * vy)
                + 2.0 * (axz * vx * vz).abs());
    vec![8.0 * U * magnitude]
}

fn ground_irradiance_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for mean in logspace(1e-8, 1.0, 25) {
        for dz in linspace(-0.5, 0.5, 21) {
            for azz in linspace(-0.33, 0.66, 21) {
                grid.push(vec![mean, dz * mean, azz * mean]);
            }
        }
    }
    grid
}

fn zenith_sample_grid() -> Vec<Vec<f64>> {
    let mut altitudes: Vec<f64> = vec![-10.0, 0.0, 0.5, 1.0, 10.0];
    altitudes.extend(logspace(100.0, 1e5, 80));
    let mut grid = Vec::new();
    for altitude in altitudes {
        for k in [2u32, 3, 4, 5, 8, 9, 16, 33, 64] {
            for i in 0..k {
                grid.push(vec![
                    R_GROUND + altitude,
                    R_GROUND,
                    f64::from(i),
                    f64::from(k),
                ]);
            }
        }
    }
    grid
}

fn zenith_sample_bound(x: &[f64]) -> Vec<f64> {
    let (r, planet_radius, i, k) = (x[0], x[1], x[2] as u32, x[3] as u32);
    let ratio = (planet_radius / r).min(1.0);
    let mu_h = -((1.0 - ratio) * (1.0 + ratio)).max(0.0).sqrt();
    // ratio: WGSL ÷ (2.5 ULP); (1 − ratio)(1 + ratio) takes its absolute error twice
    // (ill-conditioned as r → R), then √ (steep at 0) and its 4.5 ULP.
    let square = mu_h * mu_h;
    let mu_h_error =
        (square + 2.0 * 4.0 * U + 4.0 * U * square).sqrt() - mu_h.abs() + 10.0 * U * mu_h.abs();
    let [mu, weight] = lut64::direction_zenith_sample(r, planet_radius, i, k);
    // μ = μ_h ± (1 ± μ_h)u² moves with μ_h by ≤ 2δ plus 4 roundings of |terms| ≤ 2;
    // w = (1 ± μ_h)·2u/n by δ·2u/n plus 3 roundings and a division (2.5 ULP).
    let ground = (k / 2).max(1);
    let slope = 2.0 / f64::from(ground.min(k - k / 2));
    vec![
        2.0 * mu_h_error + 8.0 * U * (mu.abs() + 1.0),
        mu_h_error * slope + 12.0 * U * weight,
    ]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::cornette_shanks_legendre_moments",
            imports: &["atmos::phase"],
            arity: (1, 2),
            wgsl: "let m = cornette_shanks_legendre_moments(x0); y0 = m.x; y1 = m.y;",
            grid: anisotropy_grid,
            cpu: |x| atmos::phase::cornette_shanks_legendre_moments(x[0]).to_vec(),
            reference: |x| f64ref::cornette_shanks_legendre_moments(x[0]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 16.0,
                bound: None,
                why: "sums of same-signed terms (no cancellation): ≤ 9 roundings, two of \
                      them WGSL divisions (2.5 ULP each), and constants folded at compile \
                      time (WGSL's abstract floats may round them differently: 0.5 ULP each)",
            },
        },
        Case {
            name: "atmos::sun_frame_direction",
            imports: &["atmos::lut_multiple_scattering_moments"],
            arity: (3, 3),
            wgsl: "let v = sun_frame_direction(x0, x1, x2); y0 = v.x; y1 = v.y; y2 = v.z;",
            grid: sun_frame_grid,
            cpu: |x| atmos::twins::sun_frame_direction(x[0], x[1], x[2]).to_vec(),
            reference: |x| lut64::sun_frame_direction(x[0], x[1], x[2]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(sun_frame_bound),
                why: "v_x: ν − μμ_s cancels (4u of its terms) over sin_s, two square roots \
                      (4.5 ULP) and a division (2.5 ULP); v_y = √((h − v_x)(h + v_x)) is \
                      steep where it vanishes: √(v_y² + 2hδ) − v_y for a δ in h or v_x; \
                      v_z is the input",
            },
        },
        Case {
            name: "atmos::scattered_multiple_scattering",
            imports: &["atmos::lut_multiple_scattering_moments"],
            arity: (11, 1),
            wgsl: "let m = MultipleScatteringMoments(vec3<f32>(x0), vec3<f32>(x1), vec3<f32>(x2), \
                   vec3<f32>(x3), vec3<f32>(x4), vec3<f32>(x5)); \
                   y0 = scattered_multiple_scattering(m, vec3<f32>(x6, x7, x8), vec2<f32>(x9, x10)).x;",
            grid: scattered_grid,
            cpu: |x| {
                let m = moments32::MultipleScatteringMoments::from_layers(std::array::from_fn(
                    |layer| [x[layer]; 3],
                ));
                vec![
                    atmos::twins::scattered_multiple_scattering(
                        &m,
                        [x[6], x[7], x[8]],
                        [x[9], x[10]],
                    )[0],
                ]
            },
            reference: |x| {
                vec![lut64::scattered_multiple_scattering(
                    [x[0], x[1], x[2], x[3], x[4], x[5]],
                    [x[6], x[7], x[8]],
                    [x[9], x[10]],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(scattered_bound),
                why: "Ψ + 3g₁ d·v + 7.5g₂ vᵀAv sums terms of both signs: 8u of the sum of \
                      their magnitudes (≤ 6 roundings deep, WGSL unfused); the floor at 0 is \
                      exact",
            },
        },
        Case {
            name: "atmos::multiple_scattering_ground_irradiance",
            imports: &["atmos::lut_multiple_scattering_moments"],
            arity: (3, 1),
            wgsl: "let m = MultipleScatteringMoments(vec3<f32>(x0), vec3<f32>(0.0), vec3<f32>(x1), \
                   vec3<f32>(0.0), vec3<f32>(x2), vec3<f32>(0.0)); \
                   y0 = multiple_scattering_ground_irradiance(m).x;",
            grid: ground_irradiance_grid,
            cpu: |x| {
                let m = moments32::MultipleScatteringMoments {
                    mean: [x[0]; 3],
                    first_moment_z: [x[1]; 3],
                    anisotropy_zz: [x[2]; 3],
                    ..Default::default()
                };
                vec![atmos::twins::multiple_scattering_ground_irradiance(&m)[0]]
            },
            reference: |x| {
                vec![lut64::multiple_scattering_ground_irradiance(
                    x[0], x[1], x[2],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| {
                    vec![4.0 * U * (x[0].abs() + 2.0 * x[1].abs() + 1.875 * x[2].abs())]
                }),
                why: "Ψ + 2d_z + 1.875A_zz: two exact-or-rounded products and two sums of \
                      both signs, 4u of the terms' magnitudes; the floor at 0 is exact",
            },
        },
        Case {
            name: "atmos::direction_zenith_sample",
            imports: &["atmos::lut_multiple_scattering_moments"],
            arity: (4, 2),
            wgsl: "let s = direction_zenith_sample(x0, x1, u32(x2), u32(x3)); y0 = s.x; y1 = s.y;",
            grid: zenith_sample_grid,
            cpu: |x| {
                atmos::twins::direction_zenith_sample(x[0], x[1], x[2] as u32, x[3] as u32).to_vec()
            },
            reference: |x| {
                lut64::direction_zenith_sample(x[0], x[1], x[2] as u32, x[3] as u32).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(zenith_sample_bound),
                why: "the horizon cosine μ_h = −√((1 − R/r)(1 + R/r)) is ill-conditioned as \
                      r → R (the ratio's 2.5 ULP division enters absolutely under a square \
                      root); μ and w follow μ_h with slopes 2 and 2u/n, plus a few roundings",
            },
        },
    ]
}
