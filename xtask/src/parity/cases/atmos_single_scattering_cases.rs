//! Parity cases of rung 2 (`atmos::single_scattering`): densities, optical lengths, sun
//! transmittance, the segment weight and the single-scattering integral itself.

use super::*;

/// Earth's parameters as the f32 uniforms hold them (the WGSL literal of the struct).
macro_rules! earth_wgsl {
    () => {
        "let earth = AtmosphereParameters(vec3<f32>(5.802e-6, 13.558e-6, 33.1e-6), 8000.0, \
         vec3<f32>(3.996e-6), 1200.0, vec3<f32>(4.40e-6), 0.8, \
         vec3<f32>(0.650e-6, 1.881e-6, 0.085e-6), 25000.0, vec3<f32>(0.1), 15000.0, \
         vec3<f32>(1.0), 0.004675, 6360000.0, 6460000.0, vec2<f32>(0.0)); "
    };
}

/// The stability sweep's extreme atmospheres, through the WGSL side: every Earth density
/// ×100 with g = 0.9999 (optical depths of thousands on grazing paths, a needle-sharp
/// forward lobe), and every density ×0 (vacuum). Literals, so both sides round alike.
macro_rules! dense_wgsl {
    () => {
        "let earth = AtmosphereParameters(vec3<f32>(5.802e-4, 13.558e-4, 33.1e-4), 8000.0, \
         vec3<f32>(3.996e-4), 1200.0, vec3<f32>(4.40e-4), 0.9999, \
         vec3<f32>(0.650e-4, 1.881e-4, 0.085e-4), 25000.0, vec3<f32>(0.1), 15000.0, \
         vec3<f32>(1.0), 0.004675, 6360000.0, 6460000.0, vec2<f32>(0.0)); "
    };
}

macro_rules! vacuum_wgsl {
    () => {
        "let earth = AtmosphereParameters(vec3<f32>(0.0), 8000.0, vec3<f32>(0.0), 1200.0, \
         vec3<f32>(0.0), 0.8, vec3<f32>(0.0), 25000.0, vec3<f32>(0.1), 15000.0, \
         vec3<f32>(1.0), 0.004675, 6360000.0, 6460000.0, vec2<f32>(0.0)); "
    };
}

fn dense_atmosphere() -> atmos::Atmosphere {
    atmos::Atmosphere {
        rayleigh_scattering: [5.802e-4, 13.558e-4, 33.1e-4],
        mie_scattering: [3.996e-4; 3],
        mie_extinction: [4.40e-4; 3],
        mie_g: 0.9999,
        ozone_absorption: [0.650e-4, 1.881e-4, 0.085e-4],
        ..atmos::Atmosphere::earth()
    }
}

fn vacuum_atmosphere() -> atmos::Atmosphere {
    atmos::Atmosphere {
        rayleigh_scattering: [0.0; 3],
        mie_scattering: [0.0; 3],
        mie_extinction: [0.0; 3],
        ozone_absorption: [0.0; 3],
        ..atmos::Atmosphere::earth()
    }
}

fn single_scattering_in(atmosphere: &atmos::Atmosphere, x: &[f32]) -> Vec<f32> {
    let s = atmos::single_scattering::single_scattering(
        &atmosphere.to_uniforms().expect("valid"),
        x[0],
        x[1],
        x[2],
        x[3],
        x[4],
        x[5] as u32,
        x[6] as u32,
    );
    s.radiance.iter().chain(&s.transmittance).copied().collect()
}

fn earth32() -> atmos::AtmosphereParameters {
    atmos::Atmosphere::earth()
        .to_uniforms()
        .expect("Earth is valid")
}

/// Rung 2's default sample counts (the parity cases run what users run).
const VIEW_SAMPLES: f64 = 32.0;
const LIGHT_SAMPLES: f64 = 8.0;
/// "Unlimited" segment length as the frame camera passes it.
const UNLIMITED: f64 = 1e30;

fn sweep_altitudes() -> [f64; 14] {
    [
        -10.0, 0.0, 1.0, 10.0, 100.0, 1e3, 1e4, 5e4, 99_999.0, 100_000.0, 100_001.0, 2e5, 1e6, 1e7,
    ]
}

/// View cosines from `altitude`: a dense grid, the poles and horizon, and the ground's
/// and the top's tangents (± a little: the limb seen from space).
fn sweep_view_cosines(altitude: f64, n: usize) -> Vec<f64> {
    let mut v: Vec<f64> = linspace(-1.0, 1.0, n).collect();
    let r = R_GROUND + altitude.max(0.0);
    for radius in [R_GROUND, R_TOP] {
        if r > radius {
            let tangent = -(1.0 - (radius / r).powi(2)).sqrt();
            v.extend([tangent * 1.0001, tangent * 0.9999, tangent * 0.99]);
        }
    }
    v.extend([0.0, -1e-4, 1e-4]);
    v
}

/// Rows (r, mu, mu_s, nu, max_distance, view, light) over the sweep: sun elevations from
/// −30° (night) to the zenith, four azimuths; every third row limited to 50 km
/// (aerial perspective).
fn single_scattering_grid(max_altitude: f64, view_cosines: usize) -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in sweep_altitudes() {
        if altitude > max_altitude {
            continue;
        }
        let r = if altitude == 100_000.0 {
            R_TOP
        } else {
            R_GROUND + altitude
        };
        for mu in sweep_view_cosines(altitude, view_cosines) {
            for elevation in [-30.0f64, -6.0, -0.5, 0.0, 2.0, 10.0, 45.0, 90.0] {
                let mu_s = elevation.to_radians().sin();
                for azimuth in [0.0, 1.0, 2.0, std::f64::consts::PI] {
                    let nu = mu * mu_s
                        + azimuth.cos() * ((1.0 - mu * mu) * (1.0 - mu_s * mu_s)).max(0.0).sqrt();
                    // A horizontal view from the ground away from a sun exactly on the
                    // horizon puts every sample exactly on the terminator (mu_s(t) equals
                    // the horizon's −t/r_t): lit or shadowed is undecidable, as for
                    // tangent rays in ray_sphere_intersect. Excluded.
                    if altitude <= 0.0 && mu == 0.0 && mu_s == 0.0 && nu < 0.0 {
                        continue;
                    }
                    let max_distance = if grid.len() % 3 == 0 { 5e4 } else { UNLIMITED };
                    grid.push(vec![
                        r,
                        mu,
                        mu_s,
                        nu.clamp(-1.0, 1.0),
                        max_distance,
                        VIEW_SAMPLES,
                        LIGHT_SAMPLES,
                    ]);
                }
            }
        }
    }
    grid
}

type SingleScatteringFn = fn(
    &atmos::Atmosphere,
    f64,
    f64,
    f64,
    f64,
    f64,
    u32,
    u32,
) -> atmos::single_scattering::SingleScatteringSample<f64>;

fn evaluate_f64(f: SingleScatteringFn, x: &[f64]) -> Vec<f64> {
    evaluate_f64_in(&earth_f32_as_f64(), f, x)
}

fn evaluate_f64_in(atmosphere: &atmos::Atmosphere, f: SingleScatteringFn, x: &[f64]) -> Vec<f64> {
    let s = f(
        atmosphere,
        x[0],
        x[1],
        x[2],
        x[3],
        x[4],
        x[5] as u32,
        x[6] as u32,
    );
    s.radiance.iter().chain(&s.transmittance).copied().collect()
}

/// Forward allowance of the single-scattering integral (per output):
///
/// * conditioning: the f32 side rounds every intermediate geometric quantity (sample
///   altitudes, the sun cosine at each sample, the entry point of an outside ray) with
///   errors equivalent to a small change of the inputs, so the allowance includes the
///   largest change of the f64 result when r moves by 32 of its ULPs and the cosines by
///   32 ULPs of 1 (≈ 4e−6 absolute), in four sign patterns. This covers samples that
///   switch between lit and shadowed at the terminator, and the steep sun transmittance
///   of grazing light paths;
/// * arithmetic: each of the n_view·(n_light + 1) density evaluations carries WGSL's exp
///   bound (3 + 2|x| ULP) and the running sums add n·u each; the view transmittance
///   multiplies relative errors by (1 + τ): (n_view + n_light + 64)·u·(1 + τ)·|value|.
fn single_scattering_bound(f: SingleScatteringFn, x: &[f64]) -> Vec<f64> {
    single_scattering_bound_in(&earth_f32_as_f64(), f, x)
}

fn single_scattering_bound_in(
    atmosphere: &atmos::Atmosphere,
    f: SingleScatteringFn,
    x: &[f64],
) -> Vec<f64> {
    let base = evaluate_f64_in(atmosphere, f, x);
    let ulp = |v: f64| super::super::compare::ulp_f32(v);
    let mut allowance = vec![0.0f64; 6];
    for pattern in [
        [1.0, 1.0, 1.0, 1.0],
        [-1.0, -1.0, -1.0, -1.0],
        [1.0, -1.0, 1.0, -1.0],
        [-1.0, 1.0, -1.0, 1.0],
    ] {
        let mut y = x.to_vec();
        // r: 32 of its own ULPs; cosines: 32 ULPs of 1, since the cosines the f32 side
        // forms at each sample ((r·mu_s + t·nu)/r_t, the entry point's −√D/R) are sums
        // of terms of size ~1 and carry absolute, not relative, rounding.
        y[0] = x[0] + pattern[0] * 32.0 * ulp(x[0]);
        for (a, cosine) in y.iter_mut().enumerate().take(4).skip(1) {
            *cosine = (x[a] + pattern[a] * 32.0 * ulp(1.0)).clamp(-1.0, 1.0);
        }
        let perturbed = evaluate_f64_in(atmosphere, f, &y);
        for k in 0..6 {
            allowance[k] = allowance[k].max((perturbed[k] - base[k]).abs());
        }
    }
    let n = x[5] + x[6] + 64.0;
    for k in 0..3 {
        let tau = -base[3 + k].max(1e-300).ln();
        allowance[k] += n * U * (1.0 + tau) * base[k].abs();
        allowance[3 + k] += n * U * (1.0 + tau) * base[3 + k].abs();
    }
    allowance
}

/// Bound of the optical lengths along (r, mu) over `length` with n samples, per
/// (Rayleigh, Mie, ozone): each sample's exp bound and altitude error, the tent's 5u and
/// slope 1/w, the sum of n positive terms; plus a relative δlength/length from the
/// length's own error (the samples' positions scale with it).
fn optical_lengths_bound(x: &[f64], length_error: f64) -> Vec<f64> {
    let a = earth_f32_as_f64();
    let (r, mu, length) = (x[0], x[1], x[2]);
    if length <= 0.0 {
        return vec![0.0; 3];
    }
    let n = (x[3] as u32).max(1);
    let t_split = f64ref::lowest_point_distance(r, mu, length);
    let mut bound = [0.0f64; 3];
    let mut total = [0.0f64; 3];
    let mut t_start = 0.0;
    for i in 0..n {
        let t_end = f64ref::ray_sample_distance(f64::from(i + 1) / f64::from(n), t_split, length);
        let t = f64ref::ray_sample_distance((f64::from(i) + 0.5) / f64::from(n), t_split, length);
        let dt = t_end - t_start;
        // The layout's distances carry ~16u·length absolute (ray_sample_distance's
        // bound); the segment length twice that.
        let dt_error = 32.0 * U * length;
        let dh = altitude_error(r, mu, t, a.planet_radius)
            + 16.0 * U * length * (r * mu + t).abs()
                / (r * r + t * (2.0 * r * mu + t)).max(1.0).sqrt();
        let h = f64ref::altitude_along_ray(r, mu, t, a.planet_radius);
        for (k, scale_height) in [a.rayleigh_scale_height, a.mie_scale_height]
            .into_iter()
            .enumerate()
        {
            let xk = h / scale_height;
            let density = (-xk).exp();
            bound[k] += density
                * dt
                * (2.0 * U * (3.0 + 2.0 * xk.abs()) + 5.0 * U * xk.abs() + dh / scale_height)
                + density * dt_error;
            total[k] += density * dt;
        }
        let tent = f64ref::tent_density(h, a.ozone_center_altitude, a.ozone_half_width);
        bound[2] += dt * (TENT_ERROR + dh / a.ozone_half_width) + tent * dt_error;
        total[2] += tent * dt;
        t_start = t_end;
    }
    let relative_length = length_error / length;
    (0..3)
        .map(|k| bound[k] + (f64::from(n) + 4.0) * U * total[k] + relative_length * total[k])
        .collect()
}

fn light_path_transmittance_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let mut altitudes: Vec<f64> = vec![-10.0, 0.0, 1.0, 10.0, 100.0, 99_999.0, 100_000.0];
    altitudes.extend(logspace(300.0, 90_000.0, 24));
    for altitude in altitudes {
        let r = R_GROUND + altitude;
        let mut mus = cosines(301);
        if r > R_GROUND {
            let tangent = -(1.0 - (R_GROUND / r).powi(2)).sqrt();
            for k in 0..12 {
                let d = 1e-5 * 1.8f64.powi(k);
                mus.extend([tangent - d, tangent + d]);
            }
        }
        for mu_s in mus {
            // Sun paths within rounding of tangency to the ground are undecidable in f32
            // (lit or shadowed): excluded, as for ray_sphere_intersect. The shadow test
            // is mu_s²·r² > h·(r + R), with r = R + h rounded (½ ULP of R).
            let (h, mu) = (f64::from(altitude as f32), f64::from(mu_s as f32));
            let r32 = f64::from((R_GROUND as f32) + (h as f32));
            let margin = mu * mu * r32 * r32 - h * (r32 + R_GROUND);
            let error = 8.0 * U * (mu * mu * r32 * r32 + (h * (r32 + R_GROUND)).abs());
            if margin.abs() < error {
                continue;
            }
            grid.push(vec![altitude, mu_s, LIGHT_SAMPLES]);
        }
    }
    grid
}

fn light_path_transmittance_bound(x: &[f64]) -> Vec<f64> {
    let a = earth_f32_as_f64();
    let t = f64ref::light_path_transmittance(&a, x[0], x[1], x[2] as u32);
    if t.iter().all(|&v| v == 0.0) {
        return vec![0.0; 3];
    }
    // The f32 side starts from r = R + h rounded to f32: its ½-ULP error moves the path.
    let r = a.planet_radius + x[0];
    let r32 = f64::from((a.planet_radius as f32) + (x[0] as f32));
    let top = f64ref::ray_sphere_intersect(r, x[1], a.top_radius);
    let length = top[1].max(0.0);
    let length_error = ray_sphere_bound(&[r32, x[1], a.top_radius])[1];
    let lengths = f64ref::optical_lengths(&a, r, x[1], length, x[2] as u32);
    let mut errors = optical_lengths_bound(&[r32, x[1], length, x[2]], length_error);
    // The rounding of r shifts every sample's altitude by |r32 − r|: density × δh/H.
    let dr = (r32 - r).abs();
    errors[0] += lengths[0] * dr / a.rayleigh_scale_height;
    errors[1] += lengths[1] * dr / a.mie_scale_height;
    errors[2] += length * dr / a.ozone_half_width;
    (0..3)
        .map(|k| {
            let tau = a.rayleigh_scattering[k] * lengths[0]
                + a.mie_extinction[k] * lengths[1]
                + a.ozone_absorption[k] * lengths[2];
            let dtau = a.rayleigh_scattering[k] * errors[0]
                + a.mie_extinction[k] * errors[1]
                + a.ozone_absorption[k] * errors[2]
                + 4.0 * U * tau;
            t[k] * (dtau + exp_relative_error(tau))
        })
        .collect()
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::ray_sample_distance",
            imports: &["atmos::single_scattering"],
            arity: (3, 1),
            wgsl: "y0 = ray_sample_distance(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for length in logspace(1.0, 2e7, 13) {
                    for split in [0.0, 1e-3, 0.1, 0.3, 0.5, 0.9, 0.999, 1.0] {
                        for s in linspace(0.0, 1.0, 101) {
                            grid.push(vec![s, split * length, length]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![atmos::twins::ray_sample_distance(x[0], x[1], x[2])],
            reference: |x| vec![f64ref::ray_sample_distance(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| vec![16.0 * U * x[2]]),
                why: "every intermediate is ≤ the ray length L in magnitude (x ∈ [0, 1]) and                       passes through ~8 roundings (two divisions at 2.5 ULP); the cancellations                       (s_split − s, t_split − t_split·x²) make the bound absolute: 16u·L",
            },
        },
        Case {
            name: "atmos::lowest_point_distance",
            imports: &["atmos::single_scattering"],
            arity: (3, 1),
            wgsl: "y0 = lowest_point_distance(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for altitude in sweep_altitudes() {
                    for mu in cosines(401) {
                        for length in [1e3, 1e5, 1e6, UNLIMITED] {
                            grid.push(vec![R_GROUND + altitude, mu, length]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![atmos::twins::lowest_point_distance(x[0], x[1], x[2])],
            reference: |x| vec![f64ref::lowest_point_distance(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 1.0,
                bound: None,
                why: "one correctly rounded product, then a clamp: ≤ 0.5 ULP plus the \
                      reference's rounding to f32",
            },
        },
        Case {
            name: "atmos::density_profile",
            imports: &["atmos::single_scattering"],
            arity: (1, 3),
            wgsl: concat!(
                earth_wgsl!(),
                "let d = density_profile(earth, x0); y0 = d.x; y1 = d.y; y2 = d.z;"
            ),
            grid: || profile_altitudes().into_iter().map(|h| vec![h]).collect(),
            cpu: |x| atmos::twins::density_profile(&earth32(), x[0]).to_vec(),
            reference: |x| f64ref::density_profile(&earth_f32_as_f64(), x[0]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 1.0,
                bound: Some(|x| {
                    let a = earth_f32_as_f64();
                    vec![
                        exponential_density_error(x[0], a.rayleigh_scale_height),
                        exponential_density_error(x[0], a.mie_scale_height),
                        TENT_ERROR,
                    ]
                }),
                why: "the exponential_density and tent_density bounds per component (h/H \
                      2.5 ULP, WGSL exp 3 + 2|x| ULP; tent 5u absolute); flushed subnormals",
            },
        },
        Case {
            name: "atmos::extinction_from_densities",
            imports: &["atmos::single_scattering"],
            arity: (3, 3),
            wgsl: concat!(
                earth_wgsl!(),
                "let e = extinction_from_densities(earth, vec3<f32>(x0, x1, x2)); \
                 y0 = e.x; y1 = e.y; y2 = e.z;"
            ),
            grid: || {
                let values: Vec<f64> = std::iter::once(0.0)
                    .chain(logspace(1e-6, 100.0, 21))
                    .collect();
                let mut grid = Vec::new();
                for &a in &values {
                    for &b in &values {
                        for &c in &values {
                            grid.push(vec![a, b, c]);
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                atmos::twins::extinction_from_densities(&earth32(), [x[0], x[1], x[2]]).to_vec()
            },
            reference: |x| {
                f64ref::extinction_from_densities(&earth_f32_as_f64(), [x[0], x[1], x[2]]).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 3.0,
                bound: None,
                why: "three products and two sums of non-negative terms, each correctly \
                      rounded (WGSL fma unfused): ≤ 2.5 ULP",
            },
        },
        Case {
            name: "atmos::optical_lengths",
            imports: &["atmos::single_scattering"],
            arity: (4, 3),
            wgsl: concat!(
                earth_wgsl!(),
                "let l = optical_lengths(earth, x0, x1, x2, u32(x3)); y0 = l.x; y1 = l.y; y2 = l.z;"
            ),
            grid: || {
                optical_length_grid()
                    .into_iter()
                    .filter(|row| row[4] == 8000.0)
                    .map(|row| vec![row[0], row[1], row[2], LIGHT_SAMPLES])
                    .chain(
                        optical_length_grid()
                            .into_iter()
                            .filter(|row| row[4] == 1200.0)
                            .map(|row| vec![row[0], row[1], row[2], VIEW_SAMPLES]),
                    )
                    .collect()
            },
            cpu: |x| {
                atmos::twins::optical_lengths(&earth32(), x[0], x[1], x[2], x[3] as u32).to_vec()
            },
            reference: |x| {
                f64ref::optical_lengths(&earth_f32_as_f64(), x[0], x[1], x[2], x[3] as u32).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| optical_lengths_bound(x, 0.0)),
                why: "per sample: WGSL exp (3 + 2|x| ULP), h/H (2.5 ULP), the altitude's \
                      forward bound and 4u·t from t = (i + ½)dt, the tent's 5u and slope 1/w; \
                      then n + 4 roundings of the positive sum",
            },
        },
        Case {
            name: "atmos::light_path_transmittance",
            imports: &["atmos::single_scattering"],
            arity: (3, 3),
            wgsl: concat!(
                earth_wgsl!(),
                "let t = light_path_transmittance(earth, x0, x1, u32(x2)); y0 = t.x; y1 = t.y; y2 = t.z;"
            ),
            grid: light_path_transmittance_grid,
            cpu: |x| {
                atmos::twins::light_path_transmittance(&earth32(), x[0], x[1], x[2] as u32).to_vec()
            },
            reference: |x| {
                f64ref::light_path_transmittance(&earth_f32_as_f64(), x[0], x[1], x[2] as u32)
                    .to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(light_path_transmittance_bound),
                why: "e^{−τ}·(δτ + exp bound): δτ from the optical-length bound along the \
                      sun path (whose length carries ray_sphere_intersect's bound), the \
                      altitude shift of r = R + h rounded to f32, and 4u·τ for the \
                      coefficient products; paths within rounding of ground tangency are \
                      excluded as undecidable (lit or shadowed)",
            },
        },
        Case {
            name: "atmos::mean_transmittance_over_segment",
            imports: &["atmos::single_scattering"],
            arity: (3, 3),
            wgsl: "let m = mean_transmittance_over_segment(vec3<f32>(x0, x1, x2)); \
                   y0 = m.x; y1 = m.y; y2 = m.z;",
            grid: || {
                optical_depths()
                    .into_iter()
                    .map(|x| vec![x, 0.5 * x, 2.0 * x])
                    .collect()
            },
            cpu: |x| atmos::twins::mean_transmittance_over_segment([x[0], x[1], x[2]]).to_vec(),
            reference: |x| f64ref::mean_transmittance_over_segment([x[0], x[1], x[2]]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| {
                    x.iter()
                        .map(|&v| {
                            if v > 0.0 {
                                one_minus_exp_bound(v) / v
                            } else {
                                0.0
                            }
                        })
                        .collect()
                }),
                why: "one_minus_exp_neg's bound (series ≤ 2 ULP below 0.5, then the exp \
                      bound) divided by x, plus the division's 2.5 ULP",
            },
        },
        Case {
            name: "atmos::single_scattering_inside",
            imports: &["atmos::single_scattering"],
            arity: (7, 6),
            wgsl: concat!(
                earth_wgsl!(),
                "let s = single_scattering_inside(earth, x0, x1, x2, x3, x4, u32(x5), u32(x6)); \
                 y0 = s.radiance.x; y1 = s.radiance.y; y2 = s.radiance.z; \
                 y3 = s.transmittance.x; y4 = s.transmittance.y; y5 = s.transmittance.z;"
            ),
            grid: || single_scattering_grid(100_000.0, 41),
            cpu: |x| {
                let s = atmos::twins::single_scattering_inside(
                    &earth32(),
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                    x[6] as u32,
                );
                s.radiance.iter().chain(&s.transmittance).copied().collect()
            },
            reference: |x| evaluate_f64(f64ref::single_scattering_inside, x),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-8,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| single_scattering_bound(f64ref::single_scattering_inside, x)),
                why: "conditioning (the f64 result's change when r moves 32 ULPs and the \
                      cosines 32 ULPs of 1: covers rounded sample altitudes, sun cosines and \
                      terminator crossings) + (n_view + n_light + 64)·u·(1 + τ) relative for \
                      the exp bounds and running sums; abs 1e-8 (1e-6 of the daylight sky) \
                      for twilight light paths through optical depths of 10–40, where f32 \
                      exp and rounding move values of ~1e-5 by ~1e-4 relative",
            },
        },
        Case {
            name: "atmos::single_scattering",
            imports: &["atmos::single_scattering"],
            arity: (7, 6),
            wgsl: concat!(
                earth_wgsl!(),
                "let s = single_scattering(earth, x0, x1, x2, x3, x4, u32(x5), u32(x6)); \
                 y0 = s.radiance.x; y1 = s.radiance.y; y2 = s.radiance.z; \
                 y3 = s.transmittance.x; y4 = s.transmittance.y; y5 = s.transmittance.z;"
            ),
            grid: || single_scattering_grid(f64::INFINITY, 17),
            cpu: |x| {
                let s = atmos::single_scattering::single_scattering(
                    &earth32(),
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                    x[6] as u32,
                );
                s.radiance.iter().chain(&s.transmittance).copied().collect()
            },
            reference: |x| evaluate_f64(f64ref::single_scattering, x),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-8,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| single_scattering_bound(f64ref::single_scattering, x)),
                why: "as single_scattering_inside; outside the shell the entry point (√D, \
                      r·mu_s + t·nu) adds its rounding, which the 8-ULP input moves cover",
            },
        },
        Case {
            name: "atmos::single_scattering (densities ×100, g 0.9999)",
            imports: &["atmos::single_scattering"],
            arity: (7, 6),
            wgsl: concat!(
                dense_wgsl!(),
                "let s = single_scattering(earth, x0, x1, x2, x3, x4, u32(x5), u32(x6)); \
                 y0 = s.radiance.x; y1 = s.radiance.y; y2 = s.radiance.z; \
                 y3 = s.transmittance.x; y4 = s.transmittance.y; y5 = s.transmittance.z;"
            ),
            grid: || single_scattering_grid(f64::INFINITY, 17),
            cpu: |x| single_scattering_in(&dense_atmosphere(), x),
            reference: |x| {
                evaluate_f64_in(
                    &uniforms_as_f64(&dense_atmosphere()),
                    f64ref::single_scattering,
                    x,
                )
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 1e-8,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| {
                    single_scattering_bound_in(
                        &uniforms_as_f64(&dense_atmosphere()),
                        f64ref::single_scattering,
                        x,
                    )
                }),
                why: "as atmos::single_scattering, in the stability sweep's densest medium: \
                      the conditioning term (inputs moved by 32 ULPs) carries the needle-sharp \
                      g = 0.9999 lobe and the steep transmittances, the arithmetic term grows \
                      with τ (thousands on grazing paths)",
            },
        },
        Case {
            name: "atmos::single_scattering (densities ×0)",
            imports: &["atmos::single_scattering"],
            arity: (7, 6),
            wgsl: concat!(
                vacuum_wgsl!(),
                "let s = single_scattering(earth, x0, x1, x2, x3, x4, u32(x5), u32(x6)); \
                 y0 = s.radiance.x; y1 = s.radiance.y; y2 = s.radiance.z; \
                 y3 = s.transmittance.x; y4 = s.transmittance.y; y5 = s.transmittance.z;"
            ),
            grid: || single_scattering_grid(f64::INFINITY, 17),
            cpu: |x| single_scattering_in(&vacuum_atmosphere(), x),
            reference: |x| {
                evaluate_f64_in(
                    &uniforms_as_f64(&vacuum_atmosphere()),
                    f64ref::single_scattering,
                    x,
                )
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "a vacuum: no radiance and transmittance exactly 1 on both sides (0·x and \
                      e^{-0} are exact); any NaN from 0/0 would fail",
            },
        },
    ]
}
