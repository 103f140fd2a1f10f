//! Parity cases of `atmos::lut` (the precomputed rung): the LUT parameterisations and
//! their inverses, the azimuth and ray-segment geometry, and the log-linear optical
//! depth step. References: `atmos::lut::reference` (f64, same stable forms).
//!
//! Tolerances are absolute in texture coordinates where the output is one: what
//! matters is the fraction of a texel an error moves a lookup, and 1e-3 of a texel at
//! the default sizes is invisible. Inverse mappings get forward bounds from the
//! conditioning of each step, with WGSL's accuracy rules for the transcendentals.

use super::*;
use atmos::lut::parameterization as lut32;
use atmos::lut::reference as lut64;

const W_T: u32 = 256;
const H_T: u32 = 64;
const W_S: u32 = 192;
const H_S: u32 = 108;

/// Altitudes with the extremes of the sweep: below ground (clamped to the
/// ground), the ground, the top ± 1 m, far above (clamped to the top).
fn lut_altitudes() -> Vec<f64> {
    let mut v = vec![
        -10.0, 0.0, 0.5, 1.0, 10.0, 100.0, 1e3, 5e3, 1e4, 2.5e4, 5e4, 8e4, 99_000.0, 99_999.0,
        100_000.0, 100_001.0, 1e6, 1e7,
    ];
    v.sort_by(f64::total_cmp);
    v
}

/// Cosines plus rays grazing the ground horizon of radius r.
fn lut_cosines(r: f64) -> Vec<f64> {
    let mut mus = cosines(521);
    if r > R_GROUND {
        let tangent = -(1.0 - (R_GROUND / r).powi(2)).sqrt();
        for k in 0..12 {
            let d = 1e-6 * 2f64.powi(k);
            mus.extend([tangent - d, tangent + d]);
        }
    }
    mus
}

fn r_mu_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in lut_altitudes() {
        let r = f64::from((R_GROUND + altitude) as f32);
        for mu in lut_cosines(r) {
            grid.push(vec![r, mu]);
        }
    }
    grid
}

/// Unit-square coordinates: a dense grid, the texel centres of the edges, and
/// out-of-range values (clamped).
fn uv_grid() -> Vec<Vec<f64>> {
    let mut axis: Vec<f64> = linspace(0.0, 1.0, 101).collect();
    axis.extend([-0.1, 1.1, 1e-7, 1.0 - 1e-7, 0.5 / 64.0, 1.0 - 0.5 / 64.0]);
    let mut grid = Vec::new();
    for &v in &axis {
        for &u in &axis {
            grid.push(vec![u, v]);
        }
    }
    grid
}

/// |δ| of the far root of a ray–sphere intersection from its forward bound.
fn far_root_error(r: f64, mu: f64, radius: f64) -> f64 {
    ray_sphere_bound(&[r, mu, radius])[1]
}

fn transmittance_uv_bound(x: &[f64]) -> Vec<f64> {
    let r = x[0].clamp(R_GROUND, R_TOP);
    let mu = x[1];
    let top_horizon = lut64::horizon_distance(R_TOP, R_GROUND);
    let rho = lut64::horizon_distance(r, R_GROUND);
    let d = f64ref::ray_sphere_intersect(r, mu, R_TOP)[1].max(0.0);
    let span = rho + top_horizon - (R_TOP - r);
    // d from the intersection bound, then d − d_min, d_max (a sum) and the division;
    // ρ through WGSL's sqrt (1/inverseSqrt, ≤ 4.5 ULP) and the product under it.
    let du = (far_root_error(r, mu, R_TOP) + 8.0 * U * (d + rho + top_horizon)) / span + 8.0 * U;
    let dv = 16.0 * U;
    vec![du, dv]
}

fn transmittance_r_mu_bound(x: &[f64]) -> Vec<f64> {
    transmittance_r_mu_error([x[0], x[1]], W_T, H_T).to_vec()
}

/// Forward error (δr, δμ) of `transmittance_lut_r_mu` at texture coordinate `uv` of a
/// `width`×`height` transmittance LUT on the Earth's radii (also the transmittance
/// bake's texel coordinates, `passes::atmos_passes`).
pub(crate) fn transmittance_r_mu_error(uv: [f64; 2], width: u32, height: u32) -> [f64; 2] {
    let x = uv;
    let [r, mu] = lut64::transmittance_lut_r_mu(uv, R_GROUND, R_TOP, width, height);
    let top_horizon = lut64::horizon_distance(R_TOP, R_GROUND);
    let rho = lut64::horizon_distance(r, R_GROUND);
    let d_min = R_TOP - r;
    let d_max = rho + top_horizon;
    let x_mu = lut64::texel_uv_to_unit_range(x[0], width).clamp(0.0, 1.0);
    let d = d_min + x_mu * (d_max - d_min);
    // r = √(ρ² + R²): 8u relative; d inherits r's absolute error through d_min.
    let dr = 8.0 * U * r;
    let dd = dr + 6.0 * U * (d_min + d_max);
    let numerator = ((top_horizon - rho) * (top_horizon + rho)).abs() + d * d;
    let dmu = if d > 0.0 {
        (8.0 * U * numerator + 2.0 * d * dd + 4.0 * U * rho * rho) / (2.0 * r * d)
            + mu.abs() * (dd / d + dr / r + 8.0 * U)
    } else {
        0.0
    };
    [dr, dmu.min(2.0)]
}

/// The sky-view row coordinate's error from zenith-angle errors δθ (θ and the
/// horizon's θ_h, both atan2: 512 ULP allowed, ≈ 300 measured on lavapipe), through
/// the square roots of the mapping, whose slope is unbounded at the horizon.
fn sky_view_v_error(zenith_angle: f64, horizon: f64) -> f64 {
    let d_angle = |a: f64| 512.0 * super::super::compare::ulp_f32(a) + 8.0 * U * a;
    let d_theta = d_angle(zenith_angle) + d_angle(horizon);
    let sqrt_spread = |x: f64, dx: f64| (x + dx).max(0.0).sqrt() - (x - dx).max(0.0).sqrt();
    let above = 0.5 * sqrt_spread(1.0 - zenith_angle / horizon, 2.0 * d_theta / horizon);
    let below = 0.5
        * sqrt_spread(
            (zenith_angle - horizon) / (std::f64::consts::PI - horizon),
            2.0 * d_theta / (std::f64::consts::PI - horizon),
        );
    let near_horizon = (zenith_angle - horizon).abs() <= 2.0 * d_theta;
    let error = if near_horizon {
        // Either branch may be taken: both lie within their spread of ½.
        above.max(below)
    } else if zenith_angle < horizon {
        above
    } else {
        below
    };
    error + 8.0 * U
}

fn sky_view_uv_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in [-10.0, 0.0, 1.0, 1e3, 1e4, 5e4, 99_999.0, 100_000.0] {
        let r = f64::from((R_GROUND + altitude) as f32);
        for mu in lut_cosines(r).into_iter().step_by(3) {
            for cos_azimuth in [-1.0, -0.999_999, -0.5, 0.0, 0.3, 0.9, 0.999_999, 1.0] {
                grid.push(vec![r, mu, cos_azimuth]);
            }
        }
    }
    grid
}

fn sky_view_uv_bound(x: &[f64]) -> Vec<f64> {
    let (r, mu, c) = (x[0], x[1], x[2]);
    let horizon = lut64::horizon_zenith_angle(r, R_GROUND);
    let zenith_angle = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt().atan2(mu);
    // sin(φ/2) = √(½ − ½cos φ): the square root's slope is unbounded at cos φ = 1.
    let y = (0.5 - 0.5 * c).max(0.0);
    let dy = 4.0 * U;
    let du = (y + dy).sqrt() - (y - dy).max(0.0).sqrt() + 8.0 * U;
    vec![du, sky_view_v_error(zenith_angle, horizon)]
}

fn sky_view_direction_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in [-10.0, 0.0, 1.0, 1e3, 1e4, 99_999.0, 100_000.0] {
        let r = f64::from((R_GROUND + altitude) as f32);
        for v in linspace(0.0, 1.0, 61).chain([0.5, 0.5 - 1e-6, 0.5 + 1e-6]) {
            for u in linspace(0.0, 1.0, 25) {
                grid.push(vec![u, v, r]);
            }
        }
    }
    grid
}

/// Lavapipe's cos/sin were measured near 1 ULP of π-sized arguments; WGSL allows an
/// absolute 2^-11 for cos on [−π, π], which would make this case unable to fail, so
/// the tolerance is the measured behaviour with margin: the zenith-angle error (the
/// horizon's atan2, 512 ULP, times the mapping's slope ≤ 1) plus 64 ULP of π for cos.
fn sky_view_direction_bound(x: &[f64]) -> Vec<f64> {
    let horizon = lut64::horizon_zenith_angle(x[2], R_GROUND);
    let d_theta = 512.0 * super::super::compare::ulp_f32(horizon)
        + 64.0 * super::super::compare::ulp_f32(std::f64::consts::PI);
    vec![d_theta + 8.0 * U, 8.0 * U]
}

fn azimuth_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for view_zenith in linspace(0.0, std::f64::consts::PI, 41) {
        for sun_zenith in linspace(0.0, std::f64::consts::PI, 21) {
            for azimuth in linspace(0.0, std::f64::consts::PI, 13) {
                let (mu, mu_s) = (view_zenith.cos(), sun_zenith.cos());
                let nu = mu * mu_s + view_zenith.sin() * sun_zenith.sin() * azimuth.cos();
                // Vertical directions switch to the "azimuth moot" branch at a
                // denominator of 1e-6; rounding may take either side within 1e-5.
                let denominator = view_zenith.sin() * sun_zenith.sin();
                if denominator > 1e-12 && (denominator - 1e-6).abs() < 1e-5 {
                    continue;
                }
                grid.push(vec![mu, mu_s, nu]);
            }
        }
    }
    grid
}

fn azimuth_bound(x: &[f64]) -> Vec<f64> {
    let (mu, mu_s, nu) = (x[0], x[1], x[2]);
    let denominator = ((1.0 - mu) * (1.0 + mu) * (1.0 - mu_s) * (1.0 + mu_s))
        .max(0.0)
        .sqrt();
    if denominator < 1e-6 {
        return vec![0.0];
    }
    // nu − mu·mu_s cancels; the denominator's product and sqrt (≤ 4.5 ULP) are relative.
    let c = lut64::view_sun_cos_azimuth(mu, mu_s, nu);
    vec![4.0 * U * (nu.abs() + (mu * mu_s).abs()) / denominator + 16.0 * U * c.abs()]
}

fn segment_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for row in r_mu_grid() {
        let (r, mu) = (row[0], row[1]);
        let mu32 = f64::from(mu as f32);
        // Hit or miss of either sphere is undecidable within rounding of D = 0.
        let undecidable = [R_GROUND, R_TOP].iter().any(|&radius| {
            let b = r.max(R_GROUND) * mu32;
            let c = (r.max(R_GROUND) - radius) * (r.max(R_GROUND) + radius);
            (b * b - c).abs() < 8.0 * U * (b * b + c.abs())
        });
        if !undecidable {
            grid.push(vec![r, mu]);
        }
    }
    // Rays from the ground along, just above and just below the tangent plane (±0.01°):
    // the ground test is decided by the sign of mu alone, exactly in both precisions.
    for mu in [0.0, 0.01f64.to_radians().sin(), -0.01f64.to_radians().sin()] {
        grid.push(vec![R_GROUND, f64::from(mu as f32)]);
    }
    grid
}

fn segment_bound(x: &[f64]) -> Vec<f64> {
    let r = x[0].max(R_GROUND);
    let top = ray_sphere_bound(&[r, x[1], R_TOP]);
    let ground = ray_sphere_bound(&[r, x[1], R_GROUND]);
    vec![top[0], top[1].max(ground[0]), 0.0]
}

fn radius_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in [-10.0, 0.0, 1.0, 100.0, 1e4, 1e5, 1e6, 1e7] {
        let r = R_GROUND + altitude;
        for mu in linspace(-1.0, 1.0, 41) {
            for t in std::iter::once(0.0).chain(logspace(1e-2, 2e7, 32)) {
                grid.push(vec![r, mu, t]);
            }
        }
    }
    grid
}

fn radius_bound(x: &[f64]) -> Vec<f64> {
    let (r, mu, t) = (x[0], x[1], x[2]);
    let r_t = lut64::radius_along_ray(r, mu, t);
    // r² + t(2rμ + t) may cancel (ray towards the centre): absolute 4u of its terms,
    // through the square root (derivative 1/(2 r_t)), plus sqrt's own 4.5 ULP.
    let squared_error = 4.0 * U * (r * r + t * (2.0 * (r * mu).abs() + t));
    let through_sqrt = if r_t > 0.0 {
        (squared_error / (2.0 * r_t)).min(squared_error.sqrt())
    } else {
        squared_error.sqrt()
    };
    vec![through_sqrt + 10.0 * U * r_t]
}

/// (r, μ, t) of [`radius_grid`] with a sun cosine and a view–sun cosine from a
/// low-discrepancy walk over [−1, 1], plus the exact ends.
fn point_along_ray_grid() -> Vec<Vec<f64>> {
    radius_grid()
        .into_iter()
        .enumerate()
        .map(|(i, rmt)| {
            let walk = |a: f64| match i % 97 {
                0 => 1.0,
                1 => -1.0,
                2 => 0.0,
                _ => 2.0 * ((i as f64 * a).fract()) - 1.0,
            };
            vec![
                rmt[0],
                rmt[1],
                walk(0.618_033_988_7),
                walk(0.414_213_562_4),
                rmt[2],
            ]
        })
        .collect()
}

/// r_t: [`radius_bound`]. Each cosine `(r·c + t·d)/r_t`: the numerator's two products
/// and sum carry 2u of its terms' magnitudes absolutely (it cancels where the ray
/// passes its lowest point), r_t's relative error and the division's 2.5 ULP scale
/// the quotient; the clamp to [−1, 1] never widens an error.
fn point_along_ray_bound(x: &[f64]) -> Vec<f64> {
    let (r, mu, mu_s, nu, t) = (x[0], x[1], x[2], x[3], x[4]);
    let r_bound = radius_bound(&[r, mu, t])[0];
    let [r_t, mu_t, mu_s_t] = lut64::point_along_ray(r, mu, mu_s, nu, t);
    let cosine_bound = |numerator_terms: f64, quotient: f64| {
        if r_t <= 0.0 {
            return 2.0;
        }
        (2.0 * U * numerator_terms / r_t + quotient.abs() * (r_bound / r_t + 3.0 * U)).min(2.0)
    };
    vec![
        r_bound,
        cosine_bound((r * mu).abs() + t.abs(), mu_t),
        cosine_bound((r * mu_s).abs() + (t * nu).abs(), mu_s_t),
    ]
}

/// Marches so far, sources, extinctions and steps spanning the rung's bakes: thin air
/// (1e-7 /m) to thick haze (1e-2 /m), steps of 0.1 m to 100 km, extinction 0 (the
/// σ = 0 branch) and optical depths across the series/exp switch at 0.5.
fn integrate_step_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let extinctions: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-7, 1e-2, 21))
        .collect();
    let steps: Vec<f64> = logspace(0.1, 1e5, 25)
        .chain([5.0e4 / 1e-1, 0.5 / 1e-3])
        .collect();
    let mut i = 0usize;
    for &sigma in &extinctions {
        for &dt in &steps {
            for k in 0..18 {
                i += 1;
                let f = |a: f64| (i as f64 * a + k as f64 * 0.137).fract();
                let radiance = [1e-3 * f(0.31), 2e-3 * f(0.47), 4e-3 * f(0.59)];
                let transmittance = [
                    f(0.71),
                    1.0 - 0.5 * f(0.23),
                    if k == 0 { 1.0 } else { f(0.83) },
                ];
                let source = [1e-6 + 1e-4 * f(0.13), 1e-5 * f(0.29), 3e-4 * f(0.37)];
                let extinction = [sigma, 2.3 * sigma, 0.5 * sigma];
                let mut row = Vec::with_capacity(13);
                row.extend(radiance);
                row.extend(transmittance);
                row.extend(source);
                row.extend(extinction);
                row.push(dt);
                grid.push(row);
            }
        }
    }
    grid
}

fn segment64(
    x: &[f64],
) -> (
    atmos::lut::raymarch::ScatteringSegment<f64>,
    [f64; 3],
    [f64; 3],
    f64,
) {
    (
        atmos::lut::raymarch::ScatteringSegment {
            radiance: [x[0], x[1], x[2]],
            transmittance: [x[3], x[4], x[5]],
        },
        [x[6], x[7], x[8]],
        [x[9], x[10], x[11]],
        x[12],
    )
}

/// Per channel: the weight (1 − e^{−σdt})/σ carries σ·dt's rounding (u, through the
/// slope ≤ 1 of the series), one_minus_exp_neg's 4 ULP or exp bound and the division's
/// 2.5 ULP; T·s·w two roundings and the sum one (all terms ≥ 0, no cancellation). The
/// new transmittance: σ·dt rounds by u·σdt in the exponent, WGSL's exp 3 + 2|x| ULP,
/// one product.
fn integrate_step_bound(x: &[f64]) -> Vec<f64> {
    let (march, source, extinction, dt) = segment64(x);
    let mut bound = vec![0.0; 6];
    for c in 0..3 {
        let optical_depth = extinction[c] * dt;
        let weight = lut64::scattering_step_fraction(extinction[c], dt);
        let weight_relative = if extinction[c] > 0.0 {
            U + 8.0 * U
                + one_minus_exp_bound(optical_depth)
                    / (1.0 - (-optical_depth).exp()).max(f64::MIN_POSITIVE)
                + 2.5 * 2.0 * U
        } else {
            0.0
        };
        let added = march.transmittance[c] * source[c] * weight;
        bound[c] = U * march.radiance[c]
            + added * (weight_relative + 3.0 * U)
            + U * (march.radiance[c] + added);
        let transmittance = march.transmittance[c] * (-optical_depth).exp();
        bound[3 + c] = transmittance * (U * optical_depth + exp_relative_error(optical_depth) + U);
    }
    bound
}

fn step_integral_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for x0 in linspace(0.0, 100.0, 51).chain([1e-3, 0.01, 0.1]) {
        for delta in linspace(-3.0, 3.0, 49).chain([1e-7, -1e-7, 1e-4, -1e-4, 0.49, 0.51]) {
            for dt in [1.0, 2500.0, 28_000.0, 1e5] {
                grid.push(vec![x0, (x0 + delta).max(0.0), dt]);
            }
        }
    }
    grid
}

fn step_integral_bound(x: &[f64]) -> Vec<f64> {
    let (x0, x1) = (x[0], x[1]);
    let delta = x1 - x0;
    let value = lut64::exponential_step_integral(x0, x1, x[2]);
    // Δ = x1 − x0 rounds absolutely (u·max|x|), which moves (1 − e^{−Δ})/Δ by at most
    // that much relative; exp(−x0) is WGSL's 3 + 2|x| ULP; the quotient and products
    // a few ULP; for |Δ| ≥ 0.5 the 1 − e^{−Δ} form adds its own exp error.
    let delta_error = U * x0.abs().max(x1.abs());
    let one_minus = if delta.abs() < 0.5 {
        2.0 * U
    } else {
        2.0 * U * (3.0 + 2.0 * delta.abs()) * (-delta).exp() / (1.0 - (-delta).exp()).abs()
    };
    // WGSL exp flushes results below f32::MIN_POSITIVE (x0 > 87.3) to 0: the rest of
    // the product, dt·(1 − e^{−Δ})/Δ, times that floor.
    let factor = if delta == 0.0 {
        1.0
    } else {
        -(-delta).exp_m1() / delta
    };
    let flushed = x[2] * f64::from(f32::MIN_POSITIVE) * factor;
    vec![value.abs() * (delta_error + exp_relative_error(x0) + one_minus + 8.0 * U) + flushed]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::transmittance_lut_uv",
            imports: &["atmos::lut_parameterization"],
            arity: (2, 2),
            wgsl: "let uv = transmittance_lut_uv(x0, x1, 6360000.0, 6460000.0, 256u, 64u); \
                   y0 = uv.x; y1 = uv.y;",
            grid: r_mu_grid,
            cpu: |x| {
                lut32::transmittance_lut_uv(x[0], x[1], R_GROUND as f32, R_TOP as f32, W_T, H_T)
                    .to_vec()
            },
            reference: |x| {
                lut64::transmittance_lut_uv(x[0], x[1], R_GROUND, R_TOP, W_T, H_T).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(transmittance_uv_bound),
                why: "u: the far root's forward bound (ray_sphere_intersect) and the sums \
                      d − d_min, ρ + H over the span d_max − d_min ≥ 1e6 m; v: ρ/H through \
                      WGSL sqrt (4.5 ULP) and a division: 16u",
            },
        },
        Case {
            name: "atmos::transmittance_lut_r_mu",
            imports: &["atmos::lut_parameterization"],
            arity: (2, 2),
            wgsl: "let rm = transmittance_lut_r_mu(vec2<f32>(x0, x1), 6360000.0, 6460000.0, \
                   256u, 64u); y0 = rm.x; y1 = rm.y;",
            grid: uv_grid,
            cpu: |x| {
                lut32::transmittance_lut_r_mu([x[0], x[1]], R_GROUND as f32, R_TOP as f32, W_T, H_T)
                    .to_vec()
            },
            reference: |x| {
                lut64::transmittance_lut_r_mu([x[0], x[1]], R_GROUND, R_TOP, W_T, H_T).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(transmittance_r_mu_bound),
                why: "r = √(ρ² + R²): 8u; μ by the law of cosines: the numerator \
                      (H − ρ)(H + ρ) − d² cancels and d inherits r's absolute error \
                      (8u·r ≈ 3 m) through d_min = top − r, divided by 2rd",
            },
        },
        Case {
            name: "atmos::multiple_scattering_lut_uv",
            imports: &["atmos::lut_parameterization"],
            arity: (2, 2),
            wgsl: "let uv = multiple_scattering_lut_uv(x0, x1, 6360000.0, 6460000.0, 32u, 32u); \
                   y0 = uv.x; y1 = uv.y;",
            grid: r_mu_grid,
            cpu: |x| {
                lut32::multiple_scattering_lut_uv(x[0], x[1], R_GROUND as f32, R_TOP as f32, 32, 32)
                    .to_vec()
            },
            reference: |x| {
                lut64::multiple_scattering_lut_uv(x[0], x[1], R_GROUND, R_TOP, 32, 32).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 8.0 * U,
                rel: 0.0,
                ulp: 2.0,
                bound: None,
                why: "linear maps: (r − R) exact (Sterbenz) or 1 rounding, a division \
                      (2.5 ULP) and the texel-centre affine map: ≤ 8u absolute on [0, 1]",
            },
        },
        Case {
            name: "atmos::multiple_scattering_lut_r_mu_s",
            imports: &["atmos::lut_parameterization"],
            arity: (2, 2),
            wgsl: "let rm = multiple_scattering_lut_r_mu_s(vec2<f32>(x0, x1), 6360000.0, \
                   6460000.0, 32u, 32u); y0 = rm.x; y1 = rm.y;",
            grid: uv_grid,
            cpu: |x| {
                lut32::multiple_scattering_lut_r_mu_s(
                    [x[0], x[1]],
                    R_GROUND as f32,
                    R_TOP as f32,
                    32,
                    32,
                )
                .to_vec()
            },
            reference: |x| {
                lut64::multiple_scattering_lut_r_mu_s([x[0], x[1]], R_GROUND, R_TOP, 32, 32)
                    .to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 16.0 * U,
                rel: 0.0,
                ulp: 4.0,
                bound: None,
                why: "the inverse affine maps (a division, ≤ 2.5 ULP) then R + x·(top − R): \
                      ≤ 4 ULP of r; μ_s = 2x − 1 absolute ≤ 16u",
            },
        },
        Case {
            name: "atmos::sky_view_lut_uv",
            imports: &["atmos::lut_parameterization"],
            arity: (3, 2),
            wgsl: "let uv = sky_view_lut_uv(x0, x1, x2, 6360000.0, 192u, 108u); \
                   y0 = uv.x; y1 = uv.y;",
            grid: sky_view_uv_grid,
            cpu: |x| lut32::sky_view_lut_uv(x[0], x[1], x[2], R_GROUND as f32, W_S, H_S).to_vec(),
            reference: |x| lut64::sky_view_lut_uv(x[0], x[1], x[2], R_GROUND, W_S, H_S).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(sky_view_uv_bound),
                why: "zenith angles by atan2 (512 ULP allowed, ≈ 300 measured) through \
                      Hillaire's square-root mapping, whose slope is unbounded at the horizon \
                      and at the sun's azimuth: the bound propagates δθ through √ exactly \
                      (lookups clamp to the horizon rows there anyway)",
            },
        },
        Case {
            name: "atmos::sky_view_lut_direction",
            imports: &["atmos::lut_parameterization"],
            arity: (3, 2),
            wgsl: "let d = sky_view_lut_direction(vec2<f32>(x0, x1), x2, 6360000.0, 192u, 108u); \
                   y0 = d.x; y1 = d.y;",
            grid: sky_view_direction_grid,
            cpu: |x| {
                lut32::sky_view_lut_direction([x[0], x[1]], x[2], R_GROUND as f32, W_S, H_S)
                    .to_vec()
            },
            reference: |x| {
                lut64::sky_view_lut_direction([x[0], x[1]], x[2], R_GROUND, W_S, H_S).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(sky_view_direction_bound),
                why: "the horizon angle's atan2 (512 ULP) scaled by the mapping (≤ 1), then \
                      cos: WGSL allows 2^-11 absolute, lavapipe measured ≈ 1 ULP of π, \
                      64 ULP of π allowed; cos φ = 1 − 2x² ≤ 8u",
            },
        },
        Case {
            name: "atmos::view_sun_cos_azimuth",
            imports: &["atmos::lut_parameterization"],
            arity: (3, 1),
            wgsl: "y0 = view_sun_cos_azimuth(x0, x1, x2);",
            grid: azimuth_grid,
            cpu: |x| vec![lut32::view_sun_cos_azimuth(x[0], x[1], x[2])],
            reference: |x| vec![lut64::view_sun_cos_azimuth(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(azimuth_bound),
                why: "ν − μμ_s cancels (4u of its terms, over the denominator); the \
                      denominator's products and WGSL sqrt (4.5 ULP) are relative: 16u",
            },
        },
        Case {
            name: "atmos::ray_segment_in_atmosphere",
            imports: &["atmos::lut_parameterization"],
            arity: (2, 3),
            wgsl: "let s = ray_segment_in_atmosphere(x0, x1, 6360000.0, 6460000.0); \
                   y0 = s.x; y1 = s.y; y2 = s.z;",
            grid: segment_grid,
            cpu: |x| {
                atmos::twins::ray_segment_in_atmosphere(x[0], x[1], R_GROUND as f32, R_TOP as f32)
                    .to_vec()
            },
            reference: |x| lut64::ray_segment_in_atmosphere(x[0], x[1], R_GROUND, R_TOP).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(segment_bound),
                why: "the roots' forward bounds of ray_sphere_intersect (both spheres); the \
                      hit flag is exact once near-tangent rays (hit undecidable within \
                      rounding of the discriminant) are excluded",
            },
        },
        Case {
            name: "atmos::radius_along_ray",
            imports: &["atmos::lut_parameterization"],
            arity: (3, 1),
            wgsl: "y0 = radius_along_ray(x0, x1, x2);",
            grid: radius_grid,
            cpu: |x| vec![atmos::twins::radius_along_ray(x[0], x[1], x[2])],
            reference: |x| vec![lut64::radius_along_ray(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(radius_bound),
                why: "r² + t(2rμ + t) cancels towards the centre: 4u of its terms through \
                      the square root's slope 1/(2 r_t); plus sqrt (4.5 ULP)",
            },
        },
        Case {
            name: "atmos::point_along_ray",
            imports: &["atmos::lut_parameterization"],
            arity: (5, 3),
            wgsl: "let p = point_along_ray(x0, x1, x2, x3, x4); y0 = p.x; y1 = p.y; y2 = p.z;",
            grid: point_along_ray_grid,
            cpu: |x| atmos::twins::point_along_ray(x[0], x[1], x[2], x[3], x[4]).to_vec(),
            reference: |x| lut64::point_along_ray(x[0], x[1], x[2], x[3], x[4]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(point_along_ray_bound),
                why: "r_t as atmos::radius_along_ray; each cosine (r·c + t·d)/r_t: 2u of the \
                      numerator's terms absolutely (it cancels at the ray's lowest point), \
                      r_t's relative error and the division's 2.5 ULP on the quotient",
            },
        },
        Case {
            name: "atmos::integrate_scattering_step",
            imports: &["atmos::lut_parameterization"],
            arity: (13, 6),
            wgsl: "let m = integrate_scattering_step(ScatteringSegment(vec3<f32>(x0, x1, x2), \
                   vec3<f32>(x3, x4, x5)), vec3<f32>(x6, x7, x8), vec3<f32>(x9, x10, x11), x12); \
                   y0 = m.radiance.x; y1 = m.radiance.y; y2 = m.radiance.z; \
                   y3 = m.transmittance.x; y4 = m.transmittance.y; y5 = m.transmittance.z;",
            grid: integrate_step_grid,
            cpu: |x| {
                let march = atmos::lut::raymarch::ScatteringSegment {
                    radiance: [x[0], x[1], x[2]],
                    transmittance: [x[3], x[4], x[5]],
                };
                let m = atmos::twins::integrate_scattering_step(
                    march,
                    [x[6], x[7], x[8]],
                    [x[9], x[10], x[11]],
                    x[12],
                );
                m.radiance.iter().chain(&m.transmittance).copied().collect()
            },
            reference: |x| {
                let (march, source, extinction, dt) = segment64(x);
                let m = lut64::integrate_scattering_step(march, source, extinction, dt);
                m.radiance.iter().chain(&m.transmittance).copied().collect()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(integrate_step_bound),
                why: "weight (1 − e^{−σdt})/σ: σdt's rounding, one_minus_exp_neg's series \
                      (4 ULP) or exp bound, the division (2.5 ULP); T·s·w and the sum of \
                      non-negative terms 3 roundings; the transmittance: u·σdt in the \
                      exponent, WGSL exp's 3 + 2|x| ULP and a product; flushed subnormals",
            },
        },
        Case {
            name: "atmos::exponential_step_integral",
            imports: &["atmos::lut_parameterization"],
            arity: (3, 1),
            wgsl: "y0 = exponential_step_integral(x0, x1, x2);",
            grid: step_integral_grid,
            cpu: |x| vec![atmos::twins::exponential_step_integral(x[0], x[1], x[2])],
            reference: |x| vec![lut64::exponential_step_integral(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(step_integral_bound),
                why: "Δ = x1 − x0 rounds absolutely (u·max|x|, relative in the result), \
                      exp(−x0) WGSL's 3 + 2|x| ULP, one_minus_exp_neg's series or exp form, \
                      and a quotient and two products; exp's flushed subnormals (x0 > 87.3, \
                      above the LUT's 104 km for Mie) allowed, scaled by dt·(1 − e^{−Δ})/Δ",
            },
        },
    ]
}
