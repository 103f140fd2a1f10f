//! Parity cases of rung 1 in spherical geometry (`atmos::closed_form_sky`) and of the
//! shared frame camera (`atmos::frame`). The f64 references are composed here from
//! `atmos::reference`'s f64 twins, following the Rust functions line by line.

use super::*;

/// The Earth shell of `ClosedFormSkyParameters::from_atmosphere` with literals that
/// round identically in WGSL and Rust (Mie 3.996e-6 × 1200/8000 = 5.994e-7).
macro_rules! params_wgsl {
    () => {
        "ClosedFormSkyParameters(vec3<f32>(5.802e-6, 13.558e-6, 33.1e-6), 0.8, \
         vec3<f32>(5.994e-7), 6360000.0, vec3<f32>(1.0), 6368000.0)"
    };
}
const SHELL: f64 = 6_368_000.0;

fn params() -> atmos::closed_form_sky::ClosedFormSkyParameters {
    atmos::closed_form_sky::ClosedFormSkyParameters {
        beta_rayleigh: [5.802e-6, 13.558e-6, 33.1e-6],
        mie_g: 0.8,
        beta_mie: [5.994e-7; 3],
        planet_radius: 6_360_000.0,
        sun_irradiance: [1.0; 3],
        shell_radius: 6_368_000.0,
    }
}

fn extinction64() -> [f64; 3] {
    let p = params();
    std::array::from_fn(|i| f64::from(p.beta_rayleigh[i]) + f64::from(p.beta_mie[i]))
}

/// Hit-or-miss of a sphere is undecidable in f32 within the discriminant's rounding:
/// such rays are left out of the grids (both answers are right).
fn decidable(r: f64, mu: f64, radius: f64) -> bool {
    let (d, error) = discriminant_and_error(r, f64::from(mu as f32), radius);
    d.abs() >= 2.0 * error
}

/// Intersections that the f32 code may put on either side of 0 are undecidable too.
fn sign_decidable(r: f64, mu: f64, radius: f64) -> bool {
    let t = f64ref::ray_sphere_intersect(r, mu, radius);
    let bound = ray_sphere_bound(&[r, mu, radius]);
    t.iter().zip(&bound).all(|(t, b)| t.abs() > 2.0 * b + 1e-3)
}

const SCALE_HEIGHT: f64 = SHELL - R_GROUND;
/// The top of the equivalent path's layer (`CLOSED_FORM_TOP_SCALE_HEIGHTS` up).
const PATH_TOP: f64 = R_GROUND + 50.0 * SCALE_HEIGHT;
/// An unbounded `max_distance` (Rust `f32::MAX`, WGSL `F32_MAX_FINITE`).
const UNBOUNDED: f64 = f32::MAX as f64;

/// Where the f32 path ends: `(r, end distance)`, `r` clamped to the ground.
fn path_end64(r: f64, mu: f64, max_distance: f64) -> Option<(f64, f64)> {
    let r = r.max(R_GROUND);
    let exit = f64ref::ray_sphere_intersect(r, mu, PATH_TOP);
    if exit[1] < 0.0 {
        return None;
    }
    let ground = f64ref::ray_sphere_intersect(r, mu, R_GROUND);
    let mut end = exit[1].min(max_distance);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu < 0.0 && ground[0] >= 0.0 {
        end = end.min(ground[0]);
    }
    Some((r, end.max(0.0)))
}

fn path_length64(r: f64, mu: f64, max_distance: f64) -> f64 {
    path_end64(r, mu, max_distance).map_or(0.0, |(r, end)| {
        atmos::closed_form_sky::closed_form_segment_path::<f64>(r, mu, end, R_GROUND, SCALE_HEIGHT)
    })
}

/// Absolute error bound of the f32 equivalent path. Each path-to-space term
/// `H e^{−h/H} Ch` carries: the altitude's rounding `δh` (the end point's from
/// `(r − R)(r + R) + t(2rμ + t)`, ≈ 4u of its terms over 2R) as a relative `δh/H`;
/// the cosine's rounding (2u, through `∂ln erfcx/∂y ≤ 2y + 2/√π` with `y = μ√(x/2)`);
/// 64u of arithmetic (exp 3 + 2|h/H| ULP, sqrt, the rational erfcx). They add over the
/// terms without cancelling. Plus the end distance's error (the intersections'
/// forward bounds) times the density there (≤ 1), + 1 mm.
fn path_length_bound(r: f64, mu: f64, max_distance: f64) -> f64 {
    let Some((r, end)) = path_end64(r, mu, max_distance) else {
        return 0.0;
    };
    let u = U;
    let x = r / SCALE_HEIGHT;
    let term_bound = |t: f64, cosine: f64| {
        let radius_excess = (r - R_GROUND) * (r + R_GROUND);
        let along = t * (2.0 * r * mu + t);
        let r_t = (r * r + along).max(0.0).sqrt();
        let altitude = (radius_excess + along) / (r_t + R_GROUND);
        let altitude_error = 4.0 * u * (radius_excess.abs() + (t * (2.0 * r * mu.abs() + t)).abs())
            / (2.0 * R_GROUND)
            + 2.0 * u * altitude.abs();
        let y = cosine.abs() * (0.5 * x).sqrt();
        let cosine_error = 2.0 * u * (0.5 * x).sqrt() * (2.0 * y + 2.0);
        let value = atmos::closed_form_sky::closed_form_path_to_space::<f64>(
            altitude,
            r_t,
            cosine.abs(),
            SCALE_HEIGHT,
        );
        value * (altitude_error / SCALE_HEIGHT + cosine_error + 64.0 * u)
            + value * (2.0 * (3.0 + 2.0 * altitude.abs() / SCALE_HEIGHT) * u)
    };
    let r_end = (r * r + end * (2.0 * r * mu + end)).max(0.0).sqrt();
    let mu_end = ((r * mu + end) / r_end).clamp(-1.0, 1.0);
    let mut bound = term_bound(0.0, mu) + term_bound(end, mu_end);
    if mu < 0.0 && end > -r * mu {
        bound += 2.0 * term_bound(-r * mu, 0.0);
    }
    let exit = ray_sphere_bound(&[r, mu, PATH_TOP]);
    let ground = ray_sphere_bound(&[r, mu, R_GROUND]);
    let end_altitude = f64ref::altitude_along_ray(r, mu, end, R_GROUND);
    bound + (exit[1] + ground[0]) * (-end_altitude / SCALE_HEIGHT).exp().min(1.0) + 1e-3
}

fn sunlight64(r: f64, mu_s: f64) -> [f64; 3] {
    let ground = f64ref::ray_sphere_intersect(r, mu_s, R_GROUND);
    if mu_s < 0.0 && ground[0] >= 0.0 {
        return [0.0; 3];
    }
    let path = path_length64(r, mu_s, UNBOUNDED);
    extinction64().map(|beta| {
        let tau = beta * path;
        if tau > 0.0 {
            f64ref::one_minus_exp_neg(tau) / tau
        } else {
            1.0
        }
    })
}

/// The shadow interval in f64 by an independent construction: the ray and the shadow's
/// axis projected on the plane normal to the sun, a 2D ray–circle intersection
/// (`f64ref::ray_sphere_intersect` of the projected start radius, cosine and the planet
/// radius), rescaled to the 3D distance and cut to the half-space behind the planet.
/// The far end `f32::MAX` where the ray stays in the shadow, as the f32 side.
fn shadow_interval64(r: f64, mu: f64, mu_s: f64, nu: f64) -> [f64; 2] {
    let far = f64::from(f32::MAX);
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    let projected_start = r * sin_s;
    let speed2 = (1.0 - nu * nu).max(0.0);
    let (lo, hi) = if speed2 < f64::from(atmos::closed_form_sky::CLOSED_FORM_SHADOW_PARALLEL) {
        if projected_start < R_GROUND {
            (0.0, far)
        } else {
            (0.0, 0.0)
        }
    } else {
        let speed = speed2.sqrt();
        // p⊥·v⊥ = r (μ − μ_s ν); at a start on the axis every direction is radial.
        let cosine = if projected_start > 0.0 {
            (r * (mu - mu_s * nu) / (projected_start * speed)).clamp(-1.0, 1.0)
        } else {
            1.0
        };
        let hit = f64ref::ray_sphere_intersect(projected_start, cosine, R_GROUND);
        if hit[1] <= hit[0] {
            (0.0, 0.0)
        } else {
            (hit[0] / speed, hit[1] / speed)
        }
    };
    let (behind_lo, behind_hi) = if nu > 0.0 {
        (0.0, -r * mu_s / nu)
    } else if nu < 0.0 {
        (-r * mu_s / nu, far)
    } else if mu_s < 0.0 {
        (0.0, far)
    } else {
        (0.0, 0.0)
    };
    let start = lo.max(behind_lo).max(0.0);
    let end = hi.min(behind_hi).min(far);
    if end <= start {
        [0.0, 0.0]
    } else {
        [start, end]
    }
}

/// Absolute error bound (m) of each end of the f32 shadow interval: the roundings of
/// a = 1 − ν², b = μ − μ_s ν, c = (sin θ_s − R/r)(sin θ_s + R/r) and of the
/// discriminant, through the roots (the square root's error at most √δD), ×4.
fn shadow_interval_bound(r: f64, mu: f64, mu_s: f64, nu: f64) -> f64 {
    let u = U;
    let k = R_GROUND / r;
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    let (a, b, c) = (1.0 - nu * nu, mu - mu_s * nu, (sin_s - k) * (sin_s + k));
    let (da, db, dc) = (
        3.0 * u,
        3.0 * u * (mu.abs() + (mu_s * nu).abs()),
        4.0 * u * (sin_s + k) * (1.0 + sin_s + k) + 2.0 * u * k,
    );
    let d = b * b - a * c;
    let dd = 2.0 * b.abs() * db + c.abs() * da + a * dc + 3.0 * u * (b * b + (a * c).abs());
    let d_root = if d > 0.0 {
        (dd / (2.0 * d.sqrt())).min(dd.sqrt())
    } else {
        dd.sqrt()
    };
    let root = d.max(0.0).sqrt();
    let q = b.abs() + root;
    let mut tau_error = 0.0f64;
    if a > 0.0 {
        let x = q / a;
        tau_error = tau_error.max((db + d_root) / a + x * (da / a + 2.0 * u));
    }
    if q > 0.0 {
        let y = c.abs() / q;
        tau_error = tau_error.max(dc / q + y * (db + d_root) / q + 2.0 * u * y);
    }
    if nu != 0.0 {
        tau_error = tau_error.max(3.0 * u * (mu_s / nu).abs() + u * (mu_s / (nu * nu)).abs());
    }
    let [_, t_out] = shadow_interval64(r, mu, mu_s, nu);
    let t_scale = if t_out < 1e37 { t_out } else { 0.0 };
    4.0 * (r * tau_error + 2.0 * u * t_scale) + 1e-3
}

/// The shadow interval's ends are decidable in f32: the ray is not within the
/// interval's error of touching the shadow's cylinder, of the terminator plane, or of
/// the parallel threshold.
fn shadow_decidable(r: f64, mu: f64, mu_s: f64, nu: f64) -> bool {
    let k = R_GROUND / r;
    let sin_s = (1.0 - mu_s * mu_s).max(0.0).sqrt();
    let (a, b, c) = (1.0 - nu * nu, mu - mu_s * nu, (sin_s - k) * (sin_s + k));
    let d = b * b - a * c;
    let scale = b * b + (a * c).abs() + 1e-12;
    let threshold = f64::from(atmos::closed_form_sky::CLOSED_FORM_SHADOW_PARALLEL);
    let interval = shadow_interval64(r, mu, mu_s, nu);
    let bound = shadow_interval_bound(r, mu, mu_s, nu);
    let length = interval[1] - interval[0];
    d.abs() > 1e-4 * scale
        && c.abs() > 1e-5
        && (a - threshold).abs() > 1e-3 * threshold
        && (mu_s + nu).abs() > 1e-5
        && (length == 0.0 || length > 4.0 * bound)
}

fn radiance64(r: f64, mu: f64, mu_s: f64, nu: f64, max_distance: f64) -> Vec<f64> {
    let p = params();
    let inscatter = |path: f64| {
        f64ref::closed_form_inscatter(
            p.beta_rayleigh.map(f64::from),
            p.beta_mie.map(f64::from),
            nu,
            0.8,
            path,
        )
    };
    let path = path_length64(r, mu, max_distance);
    let shadow = shadow_interval64(r.max(R_GROUND), mu, mu_s, nu);
    if shadow[1] <= shadow[0] {
        return inscatter(path).to_vec();
    }
    let path_in = path_length64(r, mu, shadow[0].min(max_distance));
    let path_out = path_length64(r, mu, shadow[1].min(max_distance));
    let (before, after) = (inscatter(path_in), inscatter((path - path_out).max(0.0)));
    let through = extinction64().map(|beta| (-beta * path_out).exp());
    (0..3).map(|i| before[i] + through[i] * after[i]).collect()
}

fn geometry_grid(with_distance: bool, cosine_count: usize) -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let distances: &[f64] = if with_distance {
        &[1e30, 1_000.0, 50_000.0]
    } else {
        &[1e30]
    };
    for altitude in altitudes() {
        let r = f64::from((R_GROUND + altitude) as f32);
        let mut mus = cosines(cosine_count);
        for radius in [R_GROUND, PATH_TOP] {
            if r > radius {
                let tangent = -(1.0 - (radius / r).powi(2)).sqrt();
                for k in 0..12 {
                    let d = 1e-6 * 2f64.powi(k);
                    mus.extend([tangent - d, tangent + d]);
                }
            }
        }
        for mu in mus {
            let mu = f64::from(mu as f32);
            let decided = decidable(r, mu, R_GROUND)
                && decidable(r, mu, PATH_TOP)
                && sign_decidable(r, mu, R_GROUND)
                && sign_decidable(r, mu, PATH_TOP);
            if !decided {
                continue;
            }
            for &max_distance in distances {
                grid.push(vec![r, mu, max_distance]);
            }
        }
    }
    // Rays from the ground along, just above and just below the tangent plane (±0.01°):
    // the ground test is decided by the sign of mu alone, exactly in both precisions.
    for mu in [0.0, 0.01f64.to_radians().sin(), -0.01f64.to_radians().sin()] {
        let mu = f64::from(mu as f32);
        for &max_distance in distances {
            grid.push(vec![R_GROUND, mu, max_distance]);
        }
    }
    grid
}

/// Rows (r, mu, mu_s, nu, max_distance): the sun overhead, on the horizon and 12°
/// below it, and azimuths that send the view towards, across and away from the sun
/// (through the planet's shadow); rows whose shadow ends are undecidable in f32 left
/// out.
fn radiance_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for row in geometry_grid(true, 121) {
        let (r, mu) = (row[0], row[1]);
        for mu_s in [1.0f64, 0.0, -0.2] {
            let sines = ((1.0 - mu * mu) * (1.0 - mu_s * mu_s)).max(0.0).sqrt();
            for cos_azimuth in [-1.0, -0.3, 0.2, 0.7, 0.95, 0.999, 1.0] {
                let nu = f64::from((mu * mu_s + sines * cos_azimuth).clamp(-1.0, 1.0) as f32);
                if shadow_decidable(r.max(R_GROUND), mu, mu_s, nu) {
                    grid.push(vec![r, mu, mu_s, nu, row[2]]);
                }
            }
        }
    }
    grid
}

/// Rows (r, mu, mu_s, nu) for the shadow interval: the radiance grid's geometry.
fn shadow_grid() -> Vec<Vec<f64>> {
    let mut rows: Vec<Vec<f64>> = radiance_grid()
        .into_iter()
        .filter(|row| row[4] > 1e29)
        .map(|row| vec![row[0].max(R_GROUND), row[1], row[2], row[3]])
        .collect();
    rows.dedup();
    rows
}

fn frame_camera_wgsl_and_rust() -> atmos::frame::FrameCamera {
    atmos::frame::FrameCamera {
        position: [0.0, 0.0, 6_361_000.0],
        width: 1280,
        right: [0.0, -1.0, 0.0],
        height: 720,
        up: [0.0, 0.0, 1.0],
        tan_half_fov_y: 0.75,
        forward: [1.0, 0.0, 0.0],
        max_distance: 1e30,
        sun: [0.0, 0.6, 0.8],
        padding: 0,
    }
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::closed_form_path_length",
            imports: &["atmos::closed_form_sky"],
            arity: (3, 1),
            wgsl: concat!(
                "y0 = closed_form_path_length(x0, x1, x2, ",
                params_wgsl!(),
                ");"
            ),
            grid: || geometry_grid(true, 241),
            cpu: |x| {
                vec![atmos::closed_form_sky::closed_form_path_length(
                    x[0],
                    x[1],
                    x[2],
                    &params(),
                )]
            },
            reference: |x| vec![path_length64(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| vec![path_length_bound(x[0], x[1], x[2])]),
                why: "a sum of Chapman path-to-space terms: each term's altitude rounding \
                      (δh/H), cosine rounding (through erfcx's slope) and 64u of arithmetic, \
                      plus the end distance's intersection bound times the density there, \
                      + 1 mm, + 4 ULP (see path_length_bound)",
            },
        },
        Case {
            name: "atmos::closed_form_sunlight",
            imports: &["atmos::closed_form_sky"],
            arity: (2, 3),
            wgsl: concat!(
                "let s = closed_form_sunlight(x0, x1, ",
                params_wgsl!(),
                "); y0 = s.x; y1 = s.y; y2 = s.z;"
            ),
            grid: || {
                geometry_grid(false, 801)
                    .into_iter()
                    .map(|row| vec![row[0], row[1]])
                    .collect()
            },
            cpu: |x| atmos::closed_form_sky::closed_form_sunlight(x[0], x[1], &params()).to_vec(),
            reference: |x| sunlight64(x[0], x[1]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 16.0,
                bound: Some(|x| {
                    // d/dτ (1 − e^{−τ})/τ ∈ [−1/2, 0]: the path error times β / 2.
                    let path_error = path_length_bound(x[0], x[1], UNBOUNDED);
                    extinction64().map(|beta| 0.5 * beta * path_error).to_vec()
                }),
                why: "(1 − e^{−τ})/τ (one_minus_exp_neg 4 ULP or exp's bound, the division \
                      2.5, τ = βs 1.5): 16 ULP, plus the sun path's intersection error times \
                      β/2 (the average's slope is at most 1/2)",
            },
        },
        Case {
            name: "atmos::closed_form_shadow_interval",
            imports: &["atmos::closed_form_sky"],
            arity: (4, 2),
            wgsl: "let t = closed_form_shadow_interval(x0, x1, x2, x3, 6360000.0); \
                   y0 = t.x; y1 = t.y;",
            grid: shadow_grid,
            cpu: |x| {
                atmos::closed_form_sky::closed_form_shadow_interval(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    R_GROUND as f32,
                )
                .to_vec()
            },
            reference: |x| shadow_interval64(x[0], x[1], x[2], x[3]).to_vec(),
            audit: Audit::INDEPENDENT.loose(
                "a forward bound through the quadratic's roots, written for the worst \
                 conditioning of the family (near-tangent rays); most rows are far better",
            ),
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| {
                    let b = shadow_interval_bound(x[0], x[1], x[2], x[3]);
                    vec![b, b]
                }),
                why: "the roundings of a = 1 − ν², b = μ − μ_s ν, c = (sin θ_s − R/r)(sin θ_s + \
                      R/r) and the discriminant through the stable roots (the square root's \
                      error at most √δD), ×4, scaled by r; the reference is an independent \
                      2D ray–circle intersection in the plane normal to the sun",
            },
        },
        Case {
            name: "atmos::closed_form_sky_radiance",
            imports: &["atmos::closed_form_sky"],
            arity: (5, 3),
            wgsl: concat!(
                "let l = closed_form_sky_radiance(x0, x1, x2, x3, x4, vec3<f32>(1.0), ",
                params_wgsl!(),
                "); y0 = l.x; y1 = l.y; y2 = l.z;"
            ),
            grid: radiance_grid,
            cpu: |x| {
                atmos::closed_form_sky::closed_form_sky_radiance(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    [1.0; 3],
                    &params(),
                )
                .to_vec()
            },
            reference: |x| radiance64(x[0], x[1], x[2], x[3], x[4]),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 40.0,
                bound: Some(|x| {
                    // dL/ds = (βR·P_R + βM·P_HG)·e^{−βs} ≤ the angular coefficient, and
                    // ds/dt = e^{−h/H} ≤ 1 at the shadow's ends.
                    let p = params();
                    let (r, mu, mu_s, nu, max_distance) = (x[0], x[1], x[2], x[3], x[4]);
                    let p_r = f64ref::rayleigh_phase(nu);
                    let p_m = f64ref::henyey_greenstein_phase(nu, 0.8);
                    let path = path_length64(r, mu, max_distance);
                    let shadow = shadow_interval64(r.max(R_GROUND), mu, mu_s, nu);
                    let mut path_error = path_length_bound(r, mu, max_distance);
                    if shadow[1] > shadow[0] {
                        let ends = shadow.map(|t| t.min(max_distance));
                        path_error = 2.0 * path_error
                            + ends
                                .iter()
                                .map(|&t| path_length_bound(r, mu, t))
                                .sum::<f64>()
                            + 2.0 * shadow_interval_bound(r.max(R_GROUND), mu, mu_s, nu);
                    }
                    (0..3)
                        .map(|i| {
                            let angular = f64::from(p.beta_rayleigh[i]) * p_r
                                + f64::from(p.beta_mie[i]) * p_m;
                            let tau = extinction64()[i] * path;
                            angular * path_error
                                + angular * (one_minus_exp_bound(tau) + exp_relative_error(tau))
                                    / extinction64()[i]
                        })
                        .collect()
                }),
                why: "closed_form_inscatter (32 ULP + its exp bound) of each lit part, the \
                      extinction to the shadow's far end (exp's bound), times the unit \
                      sunlight, plus the path-length errors and the shadow ends' errors \
                      (shadow_interval_bound) times dL/ds ≤ βR·P_R + βM·P_HG",
            },
        },
        Case {
            name: "atmos::closed_form_sky_transmittance",
            imports: &["atmos::closed_form_sky"],
            arity: (3, 3),
            wgsl: concat!(
                "let t = closed_form_sky_transmittance(x0, x1, x2, ",
                params_wgsl!(),
                "); y0 = t.x; y1 = t.y; y2 = t.z;"
            ),
            grid: || geometry_grid(true, 241),
            cpu: |x| {
                atmos::closed_form_sky::closed_form_sky_transmittance(x[0], x[1], x[2], &params())
                    .to_vec()
            },
            reference: |x| {
                let path = path_length64(x[0], x[1], x[2]);
                extinction64().map(|beta| (-beta * path).exp()).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-38,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| {
                    let path = path_length64(x[0], x[1], x[2]);
                    let path_error = path_length_bound(x[0], x[1], x[2]);
                    extinction64()
                        .map(|beta| {
                            let t = (-beta * path).exp();
                            t * (exp_relative_error(beta * path) + beta * path_error)
                        })
                        .to_vec()
                }),
                why: "exp(−βs): WGSL exp's 3 + 2|x| ULP, τ = βs (1.5 ULP), plus the path \
                      error times β·T",
            },
        },
        Case {
            name: "atmos::frame_view_direction",
            imports: &["atmos::frame"],
            arity: (2, 3),
            wgsl: "let c = FrameCamera(vec3<f32>(0.0, 0.0, 6361000.0), 1280u, vec3<f32>(0.0, -1.0, 0.0), \
                   720u, vec3<f32>(0.0, 0.0, 1.0), 0.75, vec3<f32>(1.0, 0.0, 0.0), 1e30, \
                   vec3<f32>(0.0, 0.6, 0.8), 0u); \
                   let d = frame_view_direction(vec2<u32>(u32(x0), u32(x1)), c); y0 = d.x; y1 = d.y; y2 = d.z;",
            grid: || {
                let mut grid = Vec::new();
                for y in (0..720).step_by(7).chain([719]) {
                    for x in (0..1280).step_by(13).chain([1279]) {
                        grid.push(vec![f64::from(x), f64::from(y)]);
                    }
                }
                grid
            },
            cpu: |x| {
                atmos::frame::frame_view_direction(
                    [x[0] as u32, x[1] as u32],
                    &frame_camera_wgsl_and_rust(),
                )
                .to_vec()
            },
            reference: |x| {
                let aspect = 1280.0 / 720.0;
                let ndc_x = (2.0 * (x[0] + 0.5) / 1280.0 - 1.0) * 0.75 * aspect;
                let ndc_y = (1.0 - 2.0 * (x[1] + 0.5) / 720.0) * 0.75;
                let d = [1.0, -ndc_x, ndc_y];
                let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|c| c / length).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 4e-7,
                rel: 0.0,
                ulp: 8.0,
                bound: None,
                why: "pixel-centre NDC (4 roundings, ≤ 3u relative), the basis combination and \
                      WGSL's normalize (inverseSqrt 2 ULP): 8 ULP of each component, and 4e-7 \
                      absolute for components that cancel to ~0 (|d| = 1, so 3.4u)",
            },
        },
        Case {
            name: "atmos::local_to_planet_direction",
            imports: &["atmos::aerial_perspective"],
            arity: (3, 3),
            wgsl: "let d = local_to_planet_direction(vec3<f32>(x0, x1, x2)); y0 = d.x; y1 = d.y; y2 = d.z;",
            grid: || {
                let values: Vec<f64> = linspace(-1e5, 1e5, 21)
                    .chain([0.0, -0.0, 1e-30, 3.5, -7.25])
                    .collect();
                let mut grid = Vec::new();
                for &x in &values {
                    for &y in &values {
                        for &z in &values {
                            grid.push(vec![x, y, z]);
                        }
                    }
                }
                grid
            },
            cpu: |x| atmos::frame::local_to_planet_direction([x[0], x[1], x[2]]).to_vec(),
            reference: |x| {
                // The rotation (x, y, z) → (x, −z, y) as a matrix product in f64.
                let m = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]];
                (0..3)
                    .map(|i| (0..3).map(|j| m[i][j] * x[j]).sum())
                    .collect()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "a permutation and a sign change: exact on every side",
            },
        },
        Case {
            name: "atmos::frame_screen_position",
            imports: &["atmos::aerial_perspective"],
            arity: (2, 3),
            wgsl: "let c = FrameCamera(vec3<f32>(0.0, 0.0, 6361000.0), 1280u, vec3<f32>(0.0, -1.0, 0.0), \
                   720u, vec3<f32>(0.0, 0.0, 1.0), 0.75, vec3<f32>(1.0, 0.0, 0.0), 1e30, \
                   vec3<f32>(0.0, 0.6, 0.8), 0u); \
                   let d = frame_view_direction(vec2<u32>(u32(x0), u32(x1)), c); \
                   let p = frame_screen_position(c, d); y0 = p.x; y1 = p.y; y2 = p.z;",
            grid: || {
                let mut grid = Vec::new();
                for y in (0..720).step_by(7).chain([719]) {
                    for x in (0..1280).step_by(13).chain([1279]) {
                        grid.push(vec![f64::from(x), f64::from(y)]);
                    }
                }
                grid
            },
            cpu: |x| {
                let camera = frame_camera_wgsl_and_rust();
                let d = atmos::frame::frame_view_direction([x[0] as u32, x[1] as u32], &camera);
                atmos::lut::drop_in::frame_screen_position(&camera, d).to_vec()
            },
            reference: |x| {
                // The pixel's centre in [0, 1]², and its direction's cosine to forward.
                let aspect = 1280.0 / 720.0;
                let ndc_x = (2.0 * (x[0] + 0.5) / 1280.0 - 1.0) * 0.75 * aspect;
                let ndc_y = (1.0 - 2.0 * (x[1] + 0.5) / 720.0) * 0.75;
                let depth = 1.0 / (1.0 + ndc_x * ndc_x + ndc_y * ndc_y).sqrt();
                vec![(x[0] + 0.5) / 1280.0, (x[1] + 0.5) / 720.0, depth]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 2e-6,
                rel: 0.0,
                ulp: 8.0,
                bound: None,
                why: "the direction's 8 ULP (frame_view_direction) through two dot products \
                      and a division by depth·tan·aspect ≤ 1.6 in [0.5, 1]: ≈ 3e-6 of the NDC \
                      coordinate, halved to [0, 1]; 2e-6 absolute (a 1/400 of a pixel)",
            },
        },
    ]
}
