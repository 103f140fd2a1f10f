//! The path tracer (`reference::path_tracer`): validated on closed forms and on the
//! quadrature single scattering, its statistics, its conventions; then (release,
//! `#[ignore]`) the iterated-orders Reference measured against it.

use atmos::ladder::luminance;
use atmos::reference::{
    FreePaths, PathTracedSample, PathTracedSky, PathTracerSettings, ReferenceSettings,
    ReferenceSky, cornette_shanks_phase, rayleigh_phase, single_scattering,
};
use atmos::{Atmosphere, SkyModel, SkyQuery};
use glam::DVec3;

fn direction(mu: f64, phi: f64) -> DVec3 {
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), mu)
}

fn sun_at(elevation_deg: f64) -> DVec3 {
    let e = elevation_deg.to_radians();
    DVec3::new(e.cos(), 0.0, e.sin())
}

fn query(atmosphere: &Atmosphere, altitude: f64, view: DVec3, sun: DVec3, max: f64) -> SkyQuery {
    let position = DVec3::new(0.0, 0.0, atmosphere.planet_radius + altitude);
    SkyQuery::with_max_distance(atmosphere.planet_radius, position, view, sun, max).unwrap()
}

fn tracer(atmosphere: &Atmosphere, samples: u32, max_order: Option<u32>) -> PathTracedSky {
    PathTracedSky::new(
        atmosphere,
        PathTracerSettings {
            samples,
            max_order,
            ..PathTracerSettings::default()
        },
    )
    .unwrap()
}

/// `got` within `sigmas` standard errors of `want` per channel, and the standard error
/// below `max_relative_error` of the value (so the check has teeth).
fn assert_within(
    got: &PathTracedSample,
    want: [f64; 3],
    sigmas: f64,
    max_relative_error: f64,
    what: &str,
) {
    for k in 0..3 {
        let (mean, error) = (got.total.mean[k], got.total.standard_error[k]);
        assert!(
            error <= max_relative_error * want[k],
            "{what}: channel {k}: standard error {error:e} too large for {want:?}"
        );
        assert!(
            (mean - want[k]).abs() <= sigmas * error,
            "{what}: channel {k}: {mean:e} ± {error:e} vs {:e} ({:.1} σ)",
            want[k],
            (mean - want[k]) / error
        );
    }
}

#[test]
fn settings_are_validated_naming_the_field() {
    let earth = Atmosphere::earth();
    let bad = |settings: PathTracerSettings| {
        PathTracedSky::new(&earth, settings)
            .unwrap_err()
            .to_string()
    };
    let base = PathTracerSettings::default();
    assert!(bad(PathTracerSettings { samples: 1, ..base }).contains("samples"));
    assert!(
        bad(PathTracerSettings {
            max_order: Some(0),
            ..base
        })
        .contains("max_order")
    );
    let mut broken = earth.clone();
    broken.mie_g = 1.0;
    assert!(
        PathTracedSky::new(&broken, base)
            .unwrap_err()
            .to_string()
            .contains("mie_g")
    );
}

#[test]
fn conventions_match_the_ladder() {
    let earth = Atmosphere::earth();
    let sky = tracer(&earth, 64, None);
    let sun = sun_at(30.0);
    // Above the atmosphere looking away, on the ground looking down: nothing, T = 1.
    for q in [
        query(&earth, 1e6, DVec3::Z, sun, f64::INFINITY),
        query(&earth, 0.0, direction(-0.5, 0.0), sun, f64::INFINITY),
        query(&earth, 1e3, DVec3::Z, sun, 0.0),
    ] {
        let s = sky.estimate(&q);
        assert_eq!(s.total.mean, [0.0; 3]);
        assert_eq!(s.transmittance, [1.0; 3]);
    }
    // A horizontal ray from the ground sees the sky (the crate's tangent-ray convention).
    let s = sky.estimate(&query(&earth, 0.0, direction(0.0, 1.0), sun, f64::INFINITY));
    assert!(s.total.mean.iter().all(|&l| l > 0.0), "{s:?}");
    // A viewer below the ground (−5 m) is on it.
    let below = sky.estimate(&query(&earth, -5.0, DVec3::Z, sun, f64::INFINITY));
    let on = sky.estimate(&query(&earth, 0.0, DVec3::Z, sun, f64::INFINITY));
    assert_eq!(below.transmittance, on.transmittance);
}

/// Earth with every coefficient times `scale`.
fn scaled_earth(scale: f64) -> Atmosphere {
    let earth = Atmosphere::earth();
    Atmosphere {
        rayleigh_scattering: earth.rayleigh_scattering.map(|b| b * scale),
        mie_scattering: earth.mie_scattering.map(|b| b * scale),
        mie_extinction: earth.mie_extinction.map(|b| b * scale),
        ozone_absorption: earth.ozone_absorption.map(|b| b * scale),
        ..earth
    }
}

#[test]
fn optically_thin_limit_is_the_closed_form() {
    // Densities ×1e−4 over a black ground (a bright one adds its reflection scattered
    // once more, as first-order in τ as single scattering: +10 % at albedo 0.1): a
    // vertical column scatters E·Σ β_i H_i (1 − e^{−Z/H_i}) p_i(ν); the attenuation and
    // the higher orders change that by ~τ ≈ 3e−5, far below the standard error (≤ 1 %).
    let thin = Atmosphere {
        ground_albedo: [0.0; 3],
        ..scaled_earth(1e-4)
    };
    let sky = tracer(&thin, 4096, None);
    let z = thin.top_radius - thin.planet_radius;
    let column = |scale_height: f64| scale_height * -(-z / scale_height).exp_m1();
    let sun = sun_at(30.0);
    for (altitude, view) in [(0.0, DVec3::Z), (1e6, -DVec3::Z)] {
        let nu = view.dot(sun);
        let want: [f64; 3] = std::array::from_fn(|k| {
            thin.sun_irradiance[k]
                * (thin.rayleigh_scattering[k]
                    * column(thin.rayleigh_scale_height)
                    * rayleigh_phase(nu)
                    + thin.mie_scattering[k]
                        * column(thin.mie_scale_height)
                        * cornette_shanks_phase(nu, thin.mie_g))
        });
        let got = sky.estimate(&query(&thin, altitude, view, sun, f64::INFINITY));
        assert_within(
            &got,
            want,
            4.0,
            0.01,
            &format!("thin column from {altitude} m"),
        );
    }
}

#[test]
fn a_pure_absorber_scatters_nothing_and_transmits_exactly() {
    let earth = Atmosphere::earth();
    let absorber = Atmosphere {
        rayleigh_scattering: [0.0; 3],
        mie_scattering: [0.0; 3],
        ground_albedo: [1.0; 3],
        ..earth.clone()
    };
    let sky = tracer(&absorber, 64, None);
    let sun = sun_at(20.0);
    for (altitude, view) in [
        (0.0, DVec3::Z),
        (0.0, direction(0.0, 0.5)),
        (1e6, direction(-0.95, 0.0)),
    ] {
        let s = sky.estimate(&query(&absorber, altitude, view, sun, f64::INFINITY));
        assert_eq!(s.total.mean, [0.0; 3]);
        assert_eq!(s.total.standard_error, [0.0; 3]);
    }
    // The vertical column: τ = β_M H_M (1 − e^{−Z/H_M}) + β_O · (tent area = half width).
    let z = absorber.top_radius - absorber.planet_radius;
    let s = sky.estimate(&query(&absorber, 0.0, DVec3::Z, sun, f64::INFINITY));
    for k in 0..3 {
        let tau = absorber.mie_extinction[k]
            * absorber.mie_scale_height
            * -(-z / absorber.mie_scale_height).exp_m1()
            + absorber.ozone_absorption[k] * absorber.ozone_half_width;
        let got = -s.transmittance[k].ln();
        assert!(
            (got - tau).abs() < 1e-9 * tau,
            "channel {k}: τ {got} vs {tau}"
        );
    }
}

#[test]
fn order_one_is_the_quadrature_single_scattering() {
    // Single scattering of the Reference (quadrature, 2048 view / 512 light samples: its
    // own error ~1e−5) against the path tracer restricted to one scattering event.
    let earth = Atmosphere::earth();
    let sky = tracer(&earth, 2048, Some(1));
    let cases = [
        (0.0, direction(1.0, 0.0), 30.0, f64::INFINITY),
        (0.0, direction(0.05, 0.3), 10.0, f64::INFINITY),
        (10e3, direction(-0.3, 2.0), 45.0, f64::INFINITY),
        (1e6, direction(-0.9, 0.5), 20.0, f64::INFINITY),
        (0.0, direction(0.17, 3.0), -3.0, f64::INFINITY),
        (1e3, direction(0.0, 1.0), 5.0, 5e3),
    ];
    for (altitude, view, elevation, max) in cases {
        let q = query(&earth, altitude, view, sun_at(elevation), max);
        let want = single_scattering(&earth, q.r(), q.mu(), q.mu_s(), q.nu(), max, 2048, 512);
        let got = sky.estimate(&q);
        assert_eq!(got.multiple.mean, [0.0; 3]);
        assert_within(
            &got,
            want.radiance,
            3.5,
            0.02,
            &format!("h {altitude} view {view} sun {elevation}° max {max}"),
        );
        for k in 0..3 {
            assert!((got.transmittance[k] - want.transmittance[k]).abs() < 1e-6);
        }
    }
}

#[test]
fn statistics_the_error_falls_as_one_over_root_n() {
    let earth = Atmosphere::earth();
    let q = query(
        &earth,
        1e3,
        direction(0.3, 1.0),
        sun_at(15.0),
        f64::INFINITY,
    );
    let at = |samples: u32, seed: u64| {
        PathTracedSky::new(
            &earth,
            PathTracerSettings {
                samples,
                seed,
                ..PathTracerSettings::default()
            },
        )
        .unwrap()
        .estimate(&q)
        .total
    };
    let (small, large) = (at(256, 1), at(1024, 2));
    let ratio = small.luminance_standard_error / large.luminance_standard_error;
    assert!(
        (1.6..2.5).contains(&ratio),
        "4× the samples: error ratio {ratio}"
    );
    let combined = small
        .luminance_standard_error
        .hypot(large.luminance_standard_error);
    assert!((small.luminance - large.luminance).abs() < 4.0 * combined);
    // The reported error is the spread of independent estimates: 16 seeds × 128 samples.
    let runs: Vec<_> = (10..26).map(|seed| at(128, seed)).collect();
    let mean = runs.iter().map(|r| r.luminance).sum::<f64>() / runs.len() as f64;
    let spread = (runs
        .iter()
        .map(|r| (r.luminance - mean).powi(2))
        .sum::<f64>()
        / (runs.len() - 1) as f64)
        .sqrt();
    let reported = runs.iter().map(|r| r.luminance_standard_error).sum::<f64>() / runs.len() as f64;
    // χ² with 15 degrees of freedom: the ratio lies in [0.6, 1.45] with probability 0.99.
    assert!(
        (0.6..1.45).contains(&(spread / reported)),
        "spread {spread:e} vs reported {reported:e}"
    );
}

#[test]
fn estimates_are_deterministic_whatever_the_threads() {
    let earth = Atmosphere::earth();
    let sky = tracer(&earth, 96, None);
    let q = query(&earth, 0.0, direction(0.1, 2.0), sun_at(3.0), f64::INFINITY);
    let a = sky.estimate(&q);
    let b = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap()
        .install(|| sky.estimate(&q));
    assert_eq!(a, b);
    let other = sky
        .with_settings(PathTracerSettings {
            seed: 99,
            ..sky.settings()
        })
        .unwrap()
        .estimate(&q);
    assert_ne!(a.total.mean, other.total.mean);
    assert_eq!(sky.evaluate(&q).radiance, a.total.mean);
}

/// A setting of the measurement from the environment (documented defaults).
fn env_or<T: std::str::FromStr>(name: &str, default: T) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Directions covering the sphere evenly (a Fibonacci lattice, as the trade-off set).
fn sphere_directions(count: usize) -> Vec<DVec3> {
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    (0..count)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / count as f64;
            let radius = (1.0 - z * z).sqrt();
            let phi = golden * i as f64;
            DVec3::new(radius * phi.cos(), radius * phi.sin(), z)
        })
        .collect()
}

/// Relative errors (reference − path tracer)/path tracer of one group of views, each
/// with its Monte Carlo standard deviation.
#[derive(Default)]
struct Errors {
    values: Vec<(f64, f64)>,
}

impl Errors {
    fn add(&mut self, reference: f64, traced: f64, traced_error: f64) {
        if traced > 0.0 {
            let e = (reference - traced) / traced;
            self.values
                .push((e, traced_error * reference / (traced * traced)));
        }
    }
    /// (mean |e|, its standard error, mean e, its standard error, max |e|, σ of that
    /// view, mean σ).
    fn summary(&self) -> [f64; 7] {
        let n = self.values.len().max(1) as f64;
        let mean_abs = self.values.iter().map(|v| v.0.abs()).sum::<f64>() / n;
        let mean = self.values.iter().map(|v| v.0).sum::<f64>() / n;
        let error_of_mean = self.values.iter().map(|v| v.1 * v.1).sum::<f64>().sqrt() / n;
        let (max, max_sigma) = self.values.iter().fold((0.0f64, 0.0), |m, v| {
            if v.0.abs() > m.0 { (v.0.abs(), v.1) } else { m }
        });
        let mean_sigma = self.values.iter().map(|v| v.1).sum::<f64>() / n;
        [
            mean_abs,
            error_of_mean,
            mean,
            error_of_mean,
            max,
            max_sigma,
            mean_sigma,
        ]
    }
}

/// The iterated-orders Reference (default settings) against the path tracer.
///
/// `cargo test --release -p atmos --test path_tracer -- --ignored --nocapture
/// reference_against_the_path_tracer` (environment: `SKYSCAPE_PT_SAMPLES`, default
/// 2048 per view; `SKYSCAPE_PT_DIRECTIONS`, default 24; `SKYSCAPE_PT_ALBEDO`, default
/// the atmosphere's 0.1).
#[test]
#[ignore]
fn reference_against_the_path_tracer() {
    let samples: u32 = env_or("SKYSCAPE_PT_SAMPLES", 2048);
    let directions: usize = env_or("SKYSCAPE_PT_DIRECTIONS", 24);
    let mut atmosphere = Atmosphere::earth();
    let albedo: f64 = env_or("SKYSCAPE_PT_ALBEDO", atmosphere.ground_albedo[0]);
    atmosphere.ground_albedo = [albedo; 3];
    let started = std::time::Instant::now();
    let reference = ReferenceSky::new(&atmosphere, ReferenceSettings::default()).unwrap();
    eprintln!(
        "reference precomputation {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let traced = tracer(&atmosphere, samples, None);
    let altitudes = [0.0, 1e3, 1e4, 1e5, 1e6];
    let suns = [-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 5.0, 10.0, 30.0, 60.0, 90.0];
    let views = sphere_directions(directions);
    let started = std::time::Instant::now();
    eprintln!(
        "{samples} samples per view, {directions} directions, albedo {albedo}; relative luminance \
         error (reference − path tracer)/path tracer, ± its Monte Carlo standard error; views \
         darker than 1e−6 left out"
    );
    eprintln!(
        "| sun | camera | views | mean abs | mean signed | max abs (σ) | orders ≥ 2 mean signed | order 1 mean signed | mean σ |"
    );
    eprintln!("|---|---|---|---|---|---|---|---|---|");
    let mut day = Errors::default();
    let mut twilight = Errors::default();
    let mut per_group = Vec::new();
    for (is_day, range) in [(true, 5.0..=90.0), (false, -6.0..=4.0)] {
        for &altitude in &altitudes {
            let mut total = Errors::default();
            let mut multiple = Errors::default();
            let mut single = Errors::default();
            let queries: Vec<SkyQuery> = suns
                .iter()
                .filter(|e| range.contains(*e))
                .flat_map(|&e| views.iter().map(move |&v| (e, v)))
                .map(|(e, v)| query(&atmosphere, altitude, v, sun_at(e), f64::INFINITY))
                .collect();
            let estimates = traced.estimate_batch(&queries);
            for (q, pt) in queries.iter().zip(&estimates) {
                if pt.total.luminance < 1e-6 {
                    continue;
                }
                let (ref_single, ref_multiple, _) = reference.evaluate_orders(q);
                let ref_total: [f64; 3] = std::array::from_fn(|k| ref_single[k] + ref_multiple[k]);
                total.add(
                    luminance(ref_total),
                    pt.total.luminance,
                    pt.total.luminance_standard_error,
                );
                multiple.add(
                    luminance(ref_multiple),
                    pt.multiple.luminance,
                    pt.multiple.luminance_standard_error,
                );
                single.add(
                    luminance(ref_single),
                    pt.single.luminance,
                    pt.single.luminance_standard_error,
                );
            }
            let t = total.summary();
            let m = multiple.summary();
            let s = single.summary();
            eprintln!(
                "| {} | {:.0} km | {} | {:.2} ± {:.2} % | {:+.2} ± {:.2} % | {:.1} % ({:.1}) | {:+.2} ± {:.2} % | {:+.3} ± {:.3} % | {:.2} % |",
                if is_day { "day" } else { "twilight" },
                altitude / 1e3,
                total.values.len(),
                100.0 * t[0],
                100.0 * t[1],
                100.0 * t[2],
                100.0 * t[3],
                100.0 * t[4],
                100.0 * t[5],
                100.0 * m[2],
                100.0 * m[3],
                100.0 * s[2],
                100.0 * s[3],
                100.0 * t[6]
            );
            per_group.push((is_day, altitude, t));
            let target = if is_day { &mut day } else { &mut twilight };
            target.values.extend(total.values);
        }
    }
    for (name, errors) in [("day", &day), ("twilight", &twilight)] {
        let t = errors.summary();
        eprintln!(
            "{name}: {} views, mean |e| {:.2} ± {:.2} %, mean e {:+.2} ± {:.2} %, max |e| {:.1} % (σ {:.1} %), mean σ {:.2} %",
            errors.values.len(),
            100.0 * t[0],
            100.0 * t[1],
            100.0 * t[2],
            100.0 * t[3],
            100.0 * t[4],
            100.0 * t[5],
            100.0 * t[6]
        );
    }
    eprintln!("path tracing {:.1} s", started.elapsed().as_secs_f64());
}

/// SplitMix64 for the energy test's own sampling of the top of the atmosphere.
struct SplitMix(u64);

impl SplitMix {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A unit vector in the cosine lobe about unit `normal`.
    fn cosine_direction(&mut self, normal: DVec3) -> DVec3 {
        let (e1, e2) = normal.any_orthonormal_pair();
        let cos_theta = self.uniform().sqrt();
        let phi = 2.0 * std::f64::consts::PI * self.uniform();
        let sin_theta = (1.0 - cos_theta * cos_theta).sqrt();
        (cos_theta * normal + sin_theta * (phi.cos() * e1 + phi.sin() * e2)).normalize()
    }
}

/// Energy balance of a conservative atmosphere over a white ground, sun along +z:
/// everything that enters through the top (π R_top² E) leaves through it, as the
/// unscattered beam beside the planet plus the radiance leaving the top in every
/// direction. The radiance leaving the top at x along ω is what a viewer at x looking
/// along −ω sees: the path tracer's air radiance plus, where that ray meets the ground,
/// the ground's own radiance α/π·(E_direct + E_sky) times the ray's transmittance, with
/// E_sky = π·(path-traced sky radiance along a cosine-distributed direction). Sampled
/// over x uniform on the top sphere and ω in the outward cosine lobe; every factor is an
/// unbiased estimate, so the sum is.
fn energy_balance(points: usize, samples: u32) -> (f64, f64, f64) {
    let earth = Atmosphere::earth();
    let atmosphere = Atmosphere {
        mie_extinction: earth.mie_scattering,
        ozone_absorption: [0.0; 3],
        ground_albedo: [1.0; 3],
        ..earth
    };
    let (planet, top) = (atmosphere.planet_radius, atmosphere.top_radius);
    let sky = tracer(&atmosphere, samples, None);
    let sun = DVec3::Z;
    let at = |position: DVec3, view: DVec3| {
        sky.estimate(&SkyQuery::new(planet, position, view, sun).unwrap())
    };
    // The beam that misses the ground: ∫_R^{R_top} T(b) 2πb db (midpoint in b).
    let steps = 400;
    let db = (top - planet) / f64::from(steps);
    let beam: f64 = (0..steps)
        .map(|i| {
            let b = planet + (f64::from(i) + 0.5) * db;
            let t = at(DVec3::new(b, 0.0, 2.0 * top), -DVec3::Z).transmittance[1];
            t * 2.0 * std::f64::consts::PI * b * db
        })
        .sum();
    // Stratified in the cosine of the angle to the sun (one point per stratum; the field
    // is symmetric about the sun's axis, so the azimuth is fixed); the variance is
    // estimated from the differences within pairs of neighbouring strata.
    let mut random = SplitMix(12345);
    let values: Vec<f64> = (0..points)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + random.uniform()) / points as f64;
            let normal = DVec3::new((1.0 - z * z).sqrt(), 0.0, z);
            let outward = random.cosine_direction(normal);
            let position = normal * top;
            let seen = at(position, -outward);
            let mut radiance = seen.total.mean[1];
            // Where the ray meets the ground: b = x·(−ω) < 0 and the discriminant ≥ 0.
            let b = position.dot(-outward);
            let discriminant = b * b - (top * top - planet * planet);
            if b < 0.0 && discriminant >= 0.0 {
                let up = (position - outward * (-b - discriminant.sqrt())).normalize();
                let ground = up * planet;
                let direct = if up.dot(sun) > 0.0 {
                    up.dot(sun) * at(ground, sun).transmittance[1]
                } else {
                    0.0
                };
                let sky_irradiance =
                    std::f64::consts::PI * at(ground, random.cosine_direction(up)).total.mean[1];
                radiance +=
                    seen.transmittance[1] / std::f64::consts::PI * (direct + sky_irradiance);
            }
            // Estimator of ∫∫ L cos dω dA: L · (4π R_top²) · π.
            radiance * 4.0 * std::f64::consts::PI * top * top * std::f64::consts::PI
        })
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let variance_of_mean = values
        .chunks_exact(2)
        .map(|pair| (pair[0] - pair[1]).powi(2))
        .sum::<f64>()
        / (n * n);
    let incoming = std::f64::consts::PI * top * top;
    (
        (beam + mean) / incoming,
        variance_of_mean.sqrt() / incoming,
        beam / incoming,
    )
}

#[test]
fn energy_balance_white_ground_conservative_air() {
    let (out, error, beam) = energy_balance(16_000, 2);
    eprintln!("out/in {out:.4} ± {error:.4} (unscattered beam {beam:.4})");
    assert!(error < 0.005, "standard error {error}");
    assert!((out - 1.0).abs() < 4.0 * error, "out/in {out} ± {error}");
}

/// The energy balance at 25× the points (about a minute):
/// `cargo test --release -p atmos --test path_tracer -- --ignored --nocapture
/// energy_balance_precise` → out/in 0.99899 ± 0.00054 (another seed of the test's own
/// sampling: 0.99979 ± 0.00054).
#[test]
#[ignore]
fn energy_balance_precise() {
    let (out, error, beam) = energy_balance(400_000, 2);
    eprintln!("out/in {out:.5} ± {error:.5} (unscattered beam {beam:.4})");
    assert!((out - 1.0).abs() < 4.0 * error, "out/in {out} ± {error}");
}

#[test]
fn the_two_walks_agree() {
    // Forced events and analog delta tracking are independent estimators of orders ≥ 2
    // (the first points are shared): they agree within 4 combined standard errors.
    let earth = Atmosphere::earth();
    for (altitude, view, elevation) in [
        (0.0, direction(0.1, 1.0), 20.0),
        (5e3, direction(-0.2, 2.5), -3.0),
        (1e6, direction(-0.85, 0.3), 40.0),
    ] {
        let q = query(&earth, altitude, view, sun_at(elevation), f64::INFINITY);
        let walk = |free_paths| {
            PathTracedSky::new(
                &earth,
                PathTracerSettings {
                    samples: 8192,
                    free_paths,
                    ..PathTracerSettings::default()
                },
            )
            .unwrap()
            .estimate(&q)
            .multiple
        };
        let (forced, tracked) = (walk(FreePaths::Forced), walk(FreePaths::DeltaTracking));
        let combined = forced
            .luminance_standard_error
            .hypot(tracked.luminance_standard_error);
        assert!(combined < 0.1 * forced.luminance, "{forced:?} {tracked:?}");
        assert!(
            (forced.luminance - tracked.luminance).abs() < 4.0 * combined,
            "h {altitude}, sun {elevation}°: forced {forced:?} vs tracked {tracked:?}"
        );
    }
}

/// The two walks on 24 views per case: agreement (χ²/n of the luminance difference)
/// and efficiency 1/(σ²·time), σ the mean relative standard error of the luminance.
/// `cargo test --release -p atmos --test path_tracer -- --ignored --nocapture
/// the_two_walks_agree_and_their_efficiency`
#[test]
#[ignore]
fn the_two_walks_agree_and_their_efficiency() {
    let earth = Atmosphere::earth();
    let views = sphere_directions(24);
    for elevation in [30.0, 2.0, -4.0] {
        for altitude in [0.0, 1e4, 1e6] {
            let queries: Vec<SkyQuery> = views
                .iter()
                .map(|&v| query(&earth, altitude, v, sun_at(elevation), f64::INFINITY))
                .collect();
            let mut line = format!("sun {elevation}°, camera {} km: ", altitude / 1e3);
            let mut estimates = Vec::new();
            for free_paths in [FreePaths::Forced, FreePaths::DeltaTracking] {
                let sky = PathTracedSky::new(
                    &earth,
                    PathTracerSettings {
                        samples: 1024,
                        free_paths,
                        ..PathTracerSettings::default()
                    },
                )
                .unwrap();
                let started = std::time::Instant::now();
                let estimate = sky.estimate_batch(&queries);
                let seconds = started.elapsed().as_secs_f64();
                let relative: Vec<f64> = estimate
                    .iter()
                    .filter(|e| e.total.luminance > 1e-6)
                    .map(|e| e.total.luminance_standard_error / e.total.luminance)
                    .collect();
                let mean = relative.iter().sum::<f64>() / relative.len() as f64;
                let max = relative.iter().copied().fold(0.0, f64::max);
                line += &format!(
                    "{free_paths:?} {seconds:.2} s, σ mean {:.2} % max {:.1} %, 1/(σ²·s) {:.0} | ",
                    100.0 * mean,
                    100.0 * max,
                    1.0 / (mean * mean * seconds)
                );
                estimates.push(estimate);
            }
            let (mut chi2, mut n) = (0.0, 0);
            for (a, b) in estimates[0].iter().zip(&estimates[1]) {
                if a.total.luminance > 1e-6 {
                    let sigma = a
                        .total
                        .luminance_standard_error
                        .hypot(b.total.luminance_standard_error);
                    chi2 += ((a.total.luminance - b.total.luminance) / sigma).powi(2);
                    n += 1;
                }
            }
            eprintln!("{line}χ²/n {:.2}", chi2 / f64::from(n));
        }
    }
}

/// Luminance estimates of the path tracer (total ± σ, orders ≥ 2 ± σ) for a list of
/// queries, read from `cache` when it holds them (one line per query), else traced and
/// written there: several References can then be measured against one traced set.
fn traced_luminances(
    traced: &PathTracedSky,
    queries: &[SkyQuery],
    cache: Option<&str>,
) -> Vec<[f64; 4]> {
    if let Some(text) = cache.and_then(|path| std::fs::read_to_string(path).ok()) {
        let rows: Vec<[f64; 4]> = text
            .lines()
            .map(|line| {
                let v: Vec<f64> = line.split(' ').map(|x| x.parse().unwrap()).collect();
                [v[0], v[1], v[2], v[3]]
            })
            .collect();
        if rows.len() == queries.len() {
            eprintln!("path-traced estimates read from {}", cache.unwrap());
            return rows;
        }
    }
    let started = std::time::Instant::now();
    let rows: Vec<[f64; 4]> = traced
        .estimate_batch(queries)
        .iter()
        .map(|pt| {
            [
                pt.total.luminance,
                pt.total.luminance_standard_error,
                pt.multiple.luminance,
                pt.multiple.luminance_standard_error,
            ]
        })
        .collect();
    eprintln!("path tracing {:.1} s", started.elapsed().as_secs_f64());
    if let Some(path) = cache {
        let text: String = rows
            .iter()
            .map(|r| format!("{:e} {:e} {:e} {:e}\n", r[0], r[1], r[2], r[3]))
            .collect();
        std::fs::write(path, text).unwrap();
    }
    rows
}

/// Which part of the iterated-orders Reference is wrong: each of its resolutions
/// doubled in turn (or the grid made finer where it matters), against one path-traced
/// set (cameras 0 m … 1,000 km, suns as the main measurement).
/// `cargo test --release -p atmos --test path_tracer -- --ignored --nocapture
/// reference_error_causes` (`SKYSCAPE_PT_SAMPLES`, default 4096;
/// `SKYSCAPE_PT_DIRECTIONS`, default 24; `SKYSCAPE_PT_CACHE`, a file for the traced
/// estimates; `SKYSCAPE_PT_VARIANTS`, how many of the variants below to run, default all;
/// `SKYSCAPE_PT_ONLY`, a comma-separated list of the variants' name prefixes).
#[test]
#[ignore]
fn reference_error_causes() {
    let samples: u32 = env_or("SKYSCAPE_PT_SAMPLES", 4096);
    let directions: usize = env_or("SKYSCAPE_PT_DIRECTIONS", 24);
    let variant_count: usize = env_or("SKYSCAPE_PT_VARIANTS", usize::MAX);
    let cache = std::env::var("SKYSCAPE_PT_CACHE").ok();
    let atmosphere = Atmosphere::earth();
    let traced = tracer(&atmosphere, samples, None);
    let altitudes = [0.0, 1e3, 1e4, 1e5, 1e6];
    // SKYSCAPE_PT_SUNS: a comma-separated subset of the sun elevations (degrees).
    let all_suns = [-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 5.0, 10.0, 30.0, 60.0, 90.0];
    let suns: Vec<f64> = std::env::var("SKYSCAPE_PT_SUNS").map_or(all_suns.to_vec(), |v| {
        v.split(',').map(|x| x.trim().parse().unwrap()).collect()
    });
    let views = sphere_directions(directions);
    let queries: Vec<(f64, f64, SkyQuery)> = altitudes
        .iter()
        .flat_map(|&h| suns.iter().map(move |&e| (h, e)))
        .flat_map(|(h, e)| views.iter().map(move |&v| (h, e, v)))
        .map(|(h, e, v)| (h, e, query(&atmosphere, h, v, sun_at(e), f64::INFINITY)))
        .collect();
    let estimates = traced_luminances(
        &traced,
        &queries.iter().map(|q| q.2).collect::<Vec<_>>(),
        cache.as_deref(),
    );
    eprintln!("{samples} samples per view, {directions} directions");
    let base = ReferenceSettings::default();
    let variants = [
        ("default", base),
        (
            "7 → 10 orders",
            ReferenceSettings {
                scattering_orders: 10,
                ..base
            },
        ),
        (
            "sun zenith ×2",
            ReferenceSettings {
                sun_zenith_size: 2 * base.sun_zenith_size,
                ..base
            },
        ),
        (
            "view zenith ×2",
            ReferenceSettings {
                view_zenith_size: 2 * base.view_zenith_size,
                ..base
            },
        ),
        (
            "radius ×2",
            ReferenceSettings {
                radius_size: 2 * base.radius_size,
                ..base
            },
        ),
        (
            "azimuth ×2",
            ReferenceSettings {
                azimuth_size: 2 * base.azimuth_size,
                ..base
            },
        ),
        (
            "sphere zenith ×2",
            ReferenceSettings {
                sphere_zenith_size: 2 * base.sphere_zenith_size,
                ..base
            },
        ),
        (
            "sphere azimuth ×2",
            ReferenceSettings {
                sphere_azimuth_size: 2 * base.sphere_azimuth_size,
                ..base
            },
        ),
        (
            "march samples ×2",
            ReferenceSettings {
                march_samples: 2 * base.march_samples,
                ..base
            },
        ),
    ];
    eprintln!(
        "| reference variant | precompute | day mean abs / signed | day max abs (σ) | day ≥ 2 signed 0–10 km / ≥ 100 km | twilight mean abs / signed | twilight ≥ 2 signed | mean σ day / twilight |"
    );
    eprintln!("|---|---|---|---|---|---|---|---|");
    let only = std::env::var("SKYSCAPE_PT_ONLY").unwrap_or_default();
    for (name, settings) in variants.into_iter().take(variant_count) {
        if !only.is_empty() && !only.split(',').any(|o| name.starts_with(o)) {
            continue;
        }
        let reference = ReferenceSky::new(&atmosphere, settings).unwrap();
        let mut day = Errors::default();
        let mut twilight = Errors::default();
        let mut day_low = Errors::default();
        let mut day_high = Errors::default();
        let mut twilight_multiple = Errors::default();
        for ((altitude, elevation, q), pt) in queries.iter().zip(&estimates) {
            if pt[0] < 1e-6 {
                continue;
            }
            let (single, multiple, _) = reference.evaluate_orders(q);
            let total = luminance(single) + luminance(multiple);
            let m = (luminance(multiple), pt[2], pt[3]);
            if *elevation >= 5.0 {
                day.add(total, pt[0], pt[1]);
                if *altitude <= 1e4 {
                    day_low.add(m.0, m.1, m.2)
                } else {
                    day_high.add(m.0, m.1, m.2)
                }
            } else {
                twilight.add(total, pt[0], pt[1]);
                twilight_multiple.add(m.0, m.1, m.2);
            }
        }
        let (d, t) = (day.summary(), twilight.summary());
        eprintln!(
            "| {name} | {:.1} s | {:.2} / {:+.2} ± {:.2} % | {:.2} % ({:.2}) | {:+.2} / {:+.2} % | {:.2} / {:+.2} ± {:.2} % | {:+.1} % | {:.2} / {:.2} % |",
            reference.precompute_seconds(),
            100.0 * d[0],
            100.0 * d[2],
            100.0 * d[3],
            100.0 * d[4],
            100.0 * d[5],
            100.0 * day_low.summary()[2],
            100.0 * day_high.summary()[2],
            100.0 * t[0],
            100.0 * t[2],
            100.0 * t[3],
            100.0 * twilight_multiple.summary()[2],
            100.0 * d[6],
            100.0 * t[6],
        );
    }
}

/// The iterated-orders Reference's orders ≥ 2 against the path tracer where coarse
/// resolutions fail, at the small `ReferenceSettings::low()`
/// tables so that it runs in CI: cameras at 100 and 1,000 km looking down in daylight
/// (the source interpolated the exponential densities linearly between its radius
/// rows: the Mie source over 1–5 km several tens of % too bright), a ground camera
/// looking along the horizon (uniform zenith cells straddled the incoming field's
/// horizon peak), and twilight views in and near the planet's shadow (linear
/// interpolation between sun-angle rows 10° apart, across the terminator).
///
/// Measured (`cargo test -p atmos --test path_tracer -- --nocapture
/// reference_orders_two_and_up`, deterministic): −2.3 / −2.8 / −1.5 / −4.6 % in daylight
/// and −8.9 / −21.3 % in twilight (the low tables stop at order 4; the path tracer has all).
#[test]
fn reference_orders_two_and_up_follow_the_path_tracer() {
    let earth = Atmosphere::earth();
    let reference = ReferenceSky::new(&earth, ReferenceSettings::low()).unwrap();
    let traced = tracer(&earth, 4096, None);
    let cases = [
        (1e5, direction(-0.6, 0.5), 30.0),
        (1e6, direction(-0.95, 2.0), 45.0),
        (1e6, direction(-0.8, 0.0), 20.0),
        (0.0, direction(0.02, 2.5), 30.0),
        (0.0, direction(0.3, 3.0), -4.0),
        (1e4, direction(0.1, 0.0), -2.0),
    ];
    let queries: Vec<SkyQuery> = cases
        .iter()
        .map(|&(h, v, e)| query(&earth, h, v, sun_at(e), f64::INFINITY))
        .collect();
    let estimates = traced.estimate_batch(&queries);
    for ((h, _, e), (q, pt)) in cases.iter().zip(queries.iter().zip(&estimates)) {
        let (_, multiple, _) = reference.evaluate_orders(q);
        let got = luminance(multiple);
        let (want, sigma) = (pt.multiple.luminance, pt.multiple.luminance_standard_error);
        let error = got / want - 1.0;
        eprintln!(
            "{} km, sun {e}°: orders ≥ 2 {got:.4e} vs path tracer {want:.4e} ± {sigma:.1e} \
             ({:+.2} %)",
            h / 1e3,
            100.0 * error
        );
        let allowed = if *e >= 5.0 { 0.06 } else { 0.3 };
        assert!(
            error.abs() < allowed,
            "{} km, sun {e}°: orders ≥ 2 off by {:+.1} % (allowed {:.0} %)",
            h / 1e3,
            100.0 * error,
            100.0 * allowed
        );
    }
}

/// Rung 3 (the precomputed sky, default settings) against the same path-traced set as
/// `reference_error_causes`, twilight included.
/// `SKYSCAPE_PT_SAMPLES=4096 SKYSCAPE_PT_CACHE=… cargo test -p atmos --test path_tracer
/// -- --ignored --nocapture precomputed_against_the_path_tracer` (`SKYSCAPE_PT_SUNS`: a
/// subset of the suns; `SKYSCAPE_PT_REFINE`: re-trace the worst twilight views with that
/// many times the samples).
#[test]
#[ignore = "minutes of path tracing; CI runs precomputed_twilight_follows_the_path_tracer"]
fn precomputed_against_the_path_tracer() {
    let samples: u32 = env_or("SKYSCAPE_PT_SAMPLES", 4096);
    let directions: usize = env_or("SKYSCAPE_PT_DIRECTIONS", 24);
    let cache = std::env::var("SKYSCAPE_PT_CACHE").ok();
    let atmosphere = Atmosphere::earth();
    let traced = tracer(&atmosphere, samples, None);
    let altitudes = [0.0, 1e3, 1e4, 1e5, 1e6];
    // SKYSCAPE_PT_SUNS: a comma-separated subset of the sun elevations (degrees).
    let all_suns = [-6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 5.0, 10.0, 30.0, 60.0, 90.0];
    let suns: Vec<f64> = std::env::var("SKYSCAPE_PT_SUNS").map_or(all_suns.to_vec(), |v| {
        v.split(',').map(|x| x.trim().parse().unwrap()).collect()
    });
    let views = sphere_directions(directions);
    let queries: Vec<(f64, f64, SkyQuery)> = altitudes
        .iter()
        .flat_map(|&h| suns.iter().map(move |&e| (h, e)))
        .flat_map(|(h, e)| views.iter().map(move |&v| (h, e, v)))
        .map(|(h, e, v)| (h, e, query(&atmosphere, h, v, sun_at(e), f64::INFINITY)))
        .collect();
    let mut estimates = traced_luminances(
        &traced,
        &queries.iter().map(|q| q.2).collect::<Vec<_>>(),
        cache.as_deref(),
    );
    // Settings to try (environment): SKYSCAPE_LUT_T = "μ×r" transmittance size,
    // SKYSCAPE_LUT_MS = "μ_s×altitude" multiple-scattering size.
    let size = |name: &str, default: [u32; 2]| {
        std::env::var(name).ok().map_or(default, |v| {
            let p: Vec<u32> = v.split('x').map(|x| x.parse().unwrap()).collect();
            [p[0], p[1]]
        })
    };
    let defaults = atmos::lut::LutSettings::default();
    let settings = atmos::lut::LutSettings {
        transmittance_size: size("SKYSCAPE_LUT_T", defaults.transmittance_size),
        multiple_scattering_size: size("SKYSCAPE_LUT_MS", defaults.multiple_scattering_size),
        ..defaults
    };
    eprintln!(
        "transmittance {:?}, multiple scattering {:?}",
        settings.transmittance_size, settings.multiple_scattering_size
    );
    let sky = atmos::lut::PrecomputedSky::new(&atmosphere, &settings).unwrap();
    // The max over ~450 twilight views is a max over noisy values: a view whose error is
    // a few of its own σ from 0 may be noise. SKYSCAPE_PT_REFINE = k re-traces the
    // twilight views whose |e| exceeds 15 %, or whose |e| + 3σ exceeds the 30 % goal,
    // with k times the samples (a σ √k smaller), so the reported max is the view's
    // error, not its noise.
    let refine: u32 = env_or("SKYSCAPE_PT_REFINE", 1);
    if refine > 1 {
        let finer = tracer(&atmosphere, samples * refine, None);
        let worst: Vec<usize> = queries
            .iter()
            .zip(&estimates)
            .enumerate()
            .filter(|(_, ((_, elevation, q), pt))| {
                *elevation < 5.0 && pt[0] >= 1e-6 && {
                    let got = luminance(sky.evaluate(q).radiance);
                    let error = ((got - pt[0]) / pt[0]).abs();
                    let sigma = pt[1] * got / (pt[0] * pt[0]);
                    error > 0.15 || error + 3.0 * sigma > 0.30
                }
            })
            .map(|(i, _)| i)
            .collect();
        let refined = traced_luminances(
            &finer,
            &worst.iter().map(|&i| queries[i].2).collect::<Vec<_>>(),
            None,
        );
        for (&i, pt) in worst.iter().zip(&refined) {
            let (altitude, elevation, q) = &queries[i];
            let got = luminance(sky.evaluate(q).radiance);
            eprintln!(
                "refined: camera {altitude} m, sun {elevation}°, view {:.3?}: e {:+.1} % (σ {:.1} %) at {} samples, {:+.1} % (σ {:.1} %) at {}",
                q.view(),
                100.0 * (got - estimates[i][0]) / estimates[i][0],
                100.0 * estimates[i][1] * got / (estimates[i][0] * estimates[i][0]),
                samples,
                100.0 * (got - pt[0]) / pt[0],
                100.0 * pt[1] * got / (pt[0] * pt[0]),
                samples * refine
            );
            estimates[i] = *pt;
        }
    }
    let mut day = Errors::default();
    let mut twilight = Errors::default();
    let mut by_sun: Vec<(f64, Errors)> = Vec::new();
    for ((_, elevation, q), pt) in queries.iter().zip(&estimates) {
        if pt[0] < 1e-6 {
            continue;
        }
        let got = luminance(sky.evaluate(q).radiance);
        if *elevation >= 5.0 {
            day.add(got, pt[0], pt[1]);
        } else {
            twilight.add(got, pt[0], pt[1]);
            match by_sun.iter_mut().find(|(e, _)| e == elevation) {
                Some((_, errors)) => errors.add(got, pt[0], pt[1]),
                None => {
                    let mut errors = Errors::default();
                    errors.add(got, pt[0], pt[1]);
                    by_sun.push((*elevation, errors));
                }
            }
        }
    }
    for (name, errors) in [("day", &day), ("twilight", &twilight)]
        .into_iter()
        .map(|(n, e)| (n.to_owned(), e))
        .chain(
            by_sun
                .iter()
                .map(|(e, errors)| (format!("sun {e}°"), errors)),
        )
    {
        let t = errors.summary();
        eprintln!(
            "precomputed, {name}: {} views, mean |e| {:.2} %, mean e {:+.2} ± {:.2} %, max |e| {:.1} % (σ {:.1} %), mean σ {:.2} %",
            errors.values.len(),
            100.0 * t[0],
            100.0 * t[2],
            100.0 * t[3],
            100.0 * t[4],
            100.0 * t[5],
            100.0 * t[6]
        );
    }
    // Rung 3's bounds (measured at 4,096 samples: day 0.50 %, twilight 2.2 %;
    // refined 16×, twilight max 19.8 % (σ 1.9 %)).
    if refine > 1 {
        assert!(
            twilight.summary()[4] <= 0.30,
            "twilight max {:.1} %",
            100.0 * twilight.summary()[4]
        );
    }
    assert!(
        day.values.is_empty() || day.summary()[0] <= 0.01,
        "day mean {:.2} %",
        100.0 * day.summary()[0]
    );
    assert!(
        twilight.summary()[0] <= 0.05,
        "twilight mean {:.2} %",
        100.0 * twilight.summary()[0]
    );
}

/// Rung 3's twilight against the path tracer, CI-sized: views from the
/// ground and from 10 km at sun −4° and −2°, where Hillaire's 32 μ_s texels of the
/// multiple-scattering table read the light across the terminator too bright.
/// Measured (`cargo test -p atmos --test path_tracer -- --nocapture
/// precomputed_twilight_follows`): with 32 texels the first view is +58 % off; with
/// the default 128 the four are −1.0 / +1.4 / +0.7 / +1.2 % (σ 2.3 / 2.8 / 0.3 / 0.6 %).
#[test]
fn precomputed_twilight_follows_the_path_tracer() {
    let earth = Atmosphere::earth();
    let sky = atmos::lut::PrecomputedSky::new(&earth, &atmos::lut::LutSettings::default()).unwrap();
    let traced = tracer(&earth, 4096, None);
    let cases = [
        (0.0, direction(0.3, 3.0), -4.0),
        (0.0, direction(0.05, 1.5), -4.0),
        (1e4, direction(0.2, 2.5), -2.0),
        (0.0, direction(0.5, 0.5), -2.0),
    ];
    let queries: Vec<SkyQuery> = cases
        .iter()
        .map(|&(h, v, e)| query(&earth, h, v, sun_at(e), f64::INFINITY))
        .collect();
    let estimates = traced.estimate_batch(&queries);
    for ((h, _, e), (q, pt)) in cases.iter().zip(queries.iter().zip(&estimates)) {
        let got = luminance(sky.evaluate(q).radiance);
        let (want, sigma) = (pt.total.luminance, pt.total.luminance_standard_error);
        let error = got / want - 1.0;
        eprintln!(
            "{} km, sun {e}°: {got:.4e} vs path tracer {want:.4e} ± {sigma:.1e} ({:+.2} %)",
            h / 1e3,
            100.0 * error
        );
        assert!(
            error.abs() < 0.1,
            "{} km, sun {e}°: rung 3 off by {:+.1} % in twilight",
            h / 1e3,
            100.0 * error
        );
    }
}
