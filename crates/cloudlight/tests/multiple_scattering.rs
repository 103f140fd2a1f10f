//! The ray march's multiple-scattering octaves within 10 % of the Monte Carlo reference on
//! mean radiance of the cumulus case at sun 60°.
//!
//! The case: cloudsim's cumulus (the `light_accuracy` example's: seed 2026, 64×64×24 cells,
//! 600 steps, two ellipsoids, smoothed density) in 50 m cells at 1.5 km, σ_t = 0.03 /m per
//! unit density (a physical cumulus extinction: 0.02–0.1 /m), a white sun of irradiance 1 at
//! 60° elevation, azimuth 30°, albedo 1, the march's default dual-lobe phase (0.8, −0.3,
//! back weight 0.2), no ground, no ambient light, black background. A pinhole camera 8 km
//! from the cloud's centre, 20° above it, at azimuth 150° (the sun 120° to its side)
//! sees the whole cloud in a 64 × 48 image. The mean radiance over those pixels is
//! estimated by the path tracer (every order; each path picks a pixel uniformly, so its
//! standard error is the mean's) and computed by `march::march_view` over every pixel
//! (256 view steps, a 64-step full light march: the octaves are what is measured).
//!
//! Measured (the ignored test below, release, this machine's 2 shared cores, 2,000,000
//! paths): MC 0.006558 ± 0.71 %, orders ≥ 2 are 89.3 % of it; the march's single
//! scattering is the exact single-scattering reference to −0.01 %; the usual octave
//! defaults a = b = c = 0.5 are 72.7 / 52.1 / 43.9 % too dark at N = 2 / 4 / 8: the
//! 10 % bound is **not** met by them. N = 8, a = 0.5, b = 0.65, c = 0.5 (still a ≤ b) gives
//! +0.4 % on this case, +7.7 % with the camera facing the sun, −12.3 % with the sun behind
//! it, and +68 % at sun 10° (where a = b = c = 0.5 gives −9.7 %): a fit to one sun
//! elevation, not a model that holds across them. With σ_t 0.02 / 0.05 /m
//! (`CLOUDLIGHT_SIGMA_T`) the goal case's MC is 0.005730 / 0.007499 (orders ≥ 2: 87.7 /
//! 90.6 %), a = b = c = 0.5 at N = 8 −36.8 / −50.4 %, and b = 0.65 +12.6 / −10.8 %. Seeds
//! 1, 2, 3 with 4,000,000 paths (`CLOUDLIGHT_MC_SEED`): MC 0.006554 / 0.006571 / 0.006614
//! ± 0.000033, order 1 0.000703 / 0.000699 / 0.000704 ± 0.000002 against the exact
//! 0.000701.
//!
//! * `octaves_follow_the_monte_carlo_reference_at_ci_size` (CI, ~8 s in debug): the goal
//!   case at a 32 × 24 image, 200,000 paths, 128 view / 32 light steps; fails if the
//!   march's single scattering leaves the path tracer's order 1, if single scattering
//!   stops being less than half the total, or if N = 8, a = 0.5, b = 0.65, c = 0.5 leaves
//!   10 % (+ 3σ) of the reference.
//! * `octaves_against_the_monte_carlo_reference_on_the_cumulus` (`#[ignore]`, ~35 s in
//!   release): the goal case and three others (camera facing the sun, sun behind the camera,
//!   sun 10°) at 64 × 48, every setting tried (`CLOUDLIGHT_OCTAVE_SCAN=1` adds 16 more,
//!   `CLOUDLIGHT_MC_SAMPLES` sets the paths, `CLOUDLIGHT_MC_SEED` their seed, `CLOUDLIGHT_SIGMA_T` the extinction: the goal
//!   assertion holds at the default 0.03 /m only), and the exact single-scattering reference over
//!   the goal image; prints markdown tables;
//!   `cargo test --release -p cloudlight --test multiple_scattering -- --ignored --nocapture`.

use std::num::NonZeroU32;

use cloudlight::CloudVolume;
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchSettings, Octaves, march_view,
};
use cloudlight::reference::path_tracer::{PathTracerSettings, RaySample, estimate};
use cloudlight::reference::single_scattering::{SingleScatteringSettings, single_scattering};
use cloudlight::reference::{Phase, Sun};
use rayon::prelude::*;

/// The march's default phase, for both sides.
const G_FORWARD: f64 = 0.8;
const G_BACK: f64 = -0.3;
const BACK_WEIGHT: f64 = 0.2;

struct Cumulus {
    volume: CloudVolume,
}

/// cloudsim's cumulus: `n × n × nz` cells, `steps` automaton steps, the ellipsoids of
/// `light_accuracy` (full size) scaled to the grid.
fn cumulus(n: u32, nz: u32, steps: u32, sigma_t: f64) -> Cumulus {
    let size = cloudsim::GridSize::new(n, n, nz);
    let mut config = cloudsim::Config::new(size);
    config.seed = 2026;
    let s = n as f32 / 64.0;
    let sz = nz as f32 / 24.0;
    config.ellipsoids = vec![
        cloudsim::Ellipsoid {
            center: [28.0 * s, 32.0 * s, 9.0 * sz],
            radii: [20.0 * s, 18.0 * s, 8.0 * sz],
        },
        cloudsim::Ellipsoid {
            center: [40.0 * s, 30.0 * s, 13.0 * sz],
            radii: [16.0 * s, 20.0 * s, 9.0 * sz],
        },
    ];
    let model = cloudsim::Model::new(config).unwrap();
    let mut sim = cloudsim::Simulation::new(model).unwrap();
    sim.advance(steps).unwrap();
    let density = sim.density().unwrap();
    let volume = CloudVolume::new([n, n, nz], [0.0, 0.0, 1500.0], 50.0, sigma_t, density).unwrap();
    Cumulus { volume }
}

/// Prints the volume's density statistics and its largest vertical optical depth.
fn describe(volume: &CloudVolume) {
    let d = volume.density();
    let filled = d.iter().filter(|&&v| v > 0.0).count();
    let max = d.iter().fold(0.0f32, |m, &v| m.max(v));
    let mean_filled = d.iter().map(|&v| f64::from(v)).sum::<f64>() / filled.max(1) as f64;
    let [nx, ny, nz] = volume.dims();
    let h = volume.voxel_size();
    let o = volume.origin();
    let mut tau_max = 0.0f64;
    for y in 0..ny {
        for x in 0..nx {
            let p = [
                o[0] + (f64::from(x) + 0.5) * h,
                o[1] + (f64::from(y) + 0.5) * h,
                o[2] - 1.0,
            ];
            let tau =
                cloudlight::reference::optical_depth(volume, p, [0.0, 0.0, 1.0], f64::INFINITY)
                    .unwrap();
            tau_max = tau_max.max(tau);
        }
    }
    eprintln!(
        "volume {nx}x{ny}x{nz} cells of {h} m: {filled} cells > 0 ({:.1} %), max density {max:.3}, \
         mean over those {mean_filled:.3}, sigma_t {} /m, largest vertical optical depth {tau_max:.1} (nz {nz})",
        100.0 * filled as f64 / d.len() as f64,
        volume.extinction_per_density()
    );
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalise(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / n)
}

/// A pinhole camera `distance` from the volume's centre at `elevation` and `azimuth`
/// (degrees), looking at the centre, its vertical field of view fitted to the volume's
/// bounding sphere; the unit view directions of a `width × height` image's pixel centres.
fn camera_rays(
    volume: &CloudVolume,
    distance: f64,
    elevation: f64,
    azimuth: f64,
    width: u32,
    height: u32,
) -> ([f64; 3], Vec<[f64; 3]>) {
    let dims = volume.dims();
    let o = volume.origin();
    let h = volume.voxel_size();
    let extent = dims.map(|d| f64::from(d) * h);
    let centre = [0, 1, 2].map(|i| o[i] + 0.5 * extent[i]);
    let radius = 0.5 * (extent[0].powi(2) + extent[1].powi(2) + extent[2].powi(2)).sqrt();
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    let eye = [
        centre[0] + distance * e.cos() * a.cos(),
        centre[1] + distance * e.cos() * a.sin(),
        centre[2] + distance * e.sin(),
    ];
    let forward = normalise(sub(centre, eye));
    let right = normalise(cross(forward, [0.0, 0.0, 1.0]));
    let up = cross(right, forward);
    // Half-angle covering the bounding sphere, vertically and horizontally.
    let half = (radius / distance).asin() * 1.05;
    let tan_v = half.tan() / (f64::from(width.min(height)) / f64::from(height));
    let tan_h = tan_v * f64::from(width) / f64::from(height);
    let mut rays = Vec::new();
    for j in 0..height {
        for i in 0..width {
            let x = (2.0 * (f64::from(i) + 0.5) / f64::from(width) - 1.0) * tan_h;
            let y = (1.0 - 2.0 * (f64::from(j) + 0.5) / f64::from(height)) * tan_v;
            rays.push(normalise(
                [0, 1, 2].map(|k| forward[k] + x * right[k] + y * up[k]),
            ));
        }
    }
    (eye, rays)
}

struct MonteCarlo {
    mean: f64,
    se: f64,
    single: f64,
    single_se: f64,
    mean_collisions: f64,
    seconds: f64,
}

fn monte_carlo(
    volume: &CloudVolume,
    sun: &Sun,
    eye: [f64; 3],
    rays: &[[f64; 3]],
    samples: u64,
) -> MonteCarlo {
    let phase = Phase::DualLobe {
        g_forward: G_FORWARD,
        g_back: G_BACK,
        back_weight: BACK_WEIGHT,
    };
    let settings = PathTracerSettings {
        samples,
        seed: std::env::var("CLOUDLIGHT_MC_SEED")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(2026),
        ..Default::default()
    };
    let start = std::time::Instant::now();
    let r = estimate(volume, sun, &phase, &settings, |[u, _]| {
        let k = ((u * rays.len() as f64) as usize).min(rays.len() - 1);
        RaySample {
            origin: eye,
            direction: rays[k],
            weight: 1.0,
        }
    })
    .unwrap();
    MonteCarlo {
        mean: r.total.mean[0],
        se: r.total.standard_error[0],
        single: r.single.mean[0],
        single_se: r.single.standard_error[0],
        mean_collisions: r.mean_collisions,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// The march's mean radiance over the image's pixels.
fn march_mean(
    volume: &CloudVolume,
    to_sun: [f64; 3],
    eye: [f64; 3],
    rays: &[[f64; 3]],
    octaves: Octaves,
    view_steps: u32,
    light_steps: u32,
) -> f64 {
    let settings = MarchSettings::new(MarchConfig {
        view_steps,
        jitter: Jitter::None,
        transmittance_epsilon: 0.0,
        light: LightMarch::Full {
            steps: NonZeroU32::new(light_steps).unwrap(),
        },
        albedo: 1.0,
        g_forward: G_FORWARD,
        g_back: G_BACK,
        back_weight: BACK_WEIGHT,
        octaves,
        powder: false,
        ambient_steps: 0,
    })
    .unwrap();
    let lighting = Lighting::<f64>::white_sun(to_sun).unwrap();
    rays.iter()
        .map(|&d| march_view::<f64>(volume, eye, d, &settings, &lighting).radiance[0])
        .sum::<f64>()
        / rays.len() as f64
}

/// Extra settings from `CLOUDLIGHT_OCTAVE_SCAN=1`: N = 8, a ∈ {0.25, 0.5}, b ∈ {0.55 … 0.7},
/// c ∈ {0.5, 0.85}.
fn scan() -> Vec<Octaves> {
    if std::env::var("CLOUDLIGHT_OCTAVE_SCAN").is_err() {
        return Vec::new();
    }
    let mut v = Vec::new();
    for a in [0.25, 0.5] {
        for b in [0.55, 0.6, 0.65, 0.7] {
            for c in [0.5, 0.85] {
                v.push(octaves(8, a, b, c));
            }
        }
    }
    v
}

fn sun_60() -> Sun {
    Sun::from_elevation_azimuth(60f64.to_radians(), 30f64.to_radians(), [1.0; 3]).unwrap()
}

fn octaves(count: u32, a: f64, b: f64, c: f64) -> Octaves {
    Octaves { count, a, b, c }
}

#[test]
fn octaves_follow_the_monte_carlo_reference_at_ci_size() {
    // The goal case at CI size: the same cumulus, sun and camera, a 32 × 24 image,
    // 200,000 paths, a 128-step view march with a 32-step light march.
    let case = cumulus(64, 24, 600, 0.03);
    let sun = sun_60();
    let (eye, rays) = camera_rays(&case.volume, 8000.0, 20.0, 150.0, 32, 24);
    let mc = monte_carlo(&case.volume, &sun, eye, &rays, 200_000);
    let mean = |o| march_mean(&case.volume, sun.to_sun(), eye, &rays, o, 128, 32);
    let single = mean(Octaves::SINGLE);
    let default = mean(octaves(8, 0.5, 0.5, 0.5));
    let fitted = mean(octaves(8, 0.5, 0.65, 0.5));
    let rel = |m: f64| 100.0 * (m / mc.mean - 1.0);
    eprintln!(
        "CI-size goal case: MC {:.6} ± {:.6} ({:.1} %; order 1 {:.6} ± {:.6}; {:.1} s); march \
         1 octave {single:.6} ({:+.1} %), 8 octaves a=b=c=0.5 {default:.6} ({:+.1} %), \
         8 octaves a=0.5 b=0.65 c=0.5 {fitted:.6} ({:+.1} %)",
        mc.mean,
        mc.se,
        100.0 * mc.se / mc.mean,
        mc.single,
        mc.single_se,
        mc.seconds,
        rel(single),
        rel(default),
        rel(fitted),
    );
    assert!(mc.se < 0.03 * mc.mean, "{} ± {}", mc.mean, mc.se);
    // The march's single scattering is the path tracer's order 1 (to its discretisation).
    assert!(
        (single - mc.single).abs() < 3.5 * mc.single_se + 0.02 * mc.single,
        "march single {single} vs MC order 1 {} ± {}",
        mc.single,
        mc.single_se
    );
    // Multiple scattering is most of the light: single scattering alone is far too dark.
    assert!(single < 0.5 * mc.mean, "{single} vs {}", mc.mean);
    // The octave setting that meets the 10 % bound here must keep meeting it.
    assert!(
        (fitted - mc.mean).abs() < 0.10 * mc.mean + 3.0 * mc.se,
        "8 octaves a=0.5 b=0.65 c=0.5: {fitted} vs MC {} ± {}",
        mc.mean,
        mc.se
    );
}

/// The settings every case of the full comparison tries.
fn settings_tried() -> Vec<Octaves> {
    let mut v = vec![
        Octaves::SINGLE,
        octaves(2, 0.5, 0.5, 0.5),
        octaves(4, 0.5, 0.5, 0.5),
        octaves(8, 0.5, 0.5, 0.5),
        octaves(8, 0.25, 0.5, 0.5),
        octaves(8, 0.5, 0.65, 0.5),
        octaves(4, 0.5, 0.65, 0.5),
        octaves(8, 0.5, 0.75, 0.5),
    ];
    v.extend(scan());
    v
}

#[test]
#[ignore = "about a minute in release: cargo test --release -p cloudlight --test multiple_scattering -- --ignored --nocapture"]
fn octaves_against_the_monte_carlo_reference_on_the_cumulus() {
    let samples: u64 = std::env::var("CLOUDLIGHT_MC_SAMPLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2_000_000);
    let sigma_t: f64 = std::env::var("CLOUDLIGHT_SIGMA_T")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0.03);
    let case = cumulus(64, 24, 600, sigma_t);
    describe(&case.volume);
    let cases = [
        (
            "sun 60°, camera at azimuth 150° (side-lit; the goal)",
            60.0,
            150.0,
        ),
        (
            "sun 60°, camera at azimuth 210° (facing the sun)",
            60.0,
            210.0,
        ),
        ("sun 60°, camera at azimuth 30° (sun behind)", 60.0, 30.0),
        ("sun 10°, camera at azimuth 150°", 10.0, 150.0),
    ];
    let mut goal = None;
    let mut goal_order_1 = (0.0, 0.0);
    for (k, (name, elevation, azimuth)) in cases.into_iter().enumerate() {
        let sun =
            Sun::from_elevation_azimuth(f64::to_radians(elevation), 30f64.to_radians(), [1.0; 3])
                .unwrap();
        let (eye, rays) = camera_rays(&case.volume, 8000.0, 20.0, azimuth, 64, 48);
        let mc = monte_carlo(&case.volume, &sun, eye, &rays, samples);
        eprintln!(
            "\n{name}: MC all orders ({samples} paths, {:.1} s) {:.6} ± {:.6} ({:.2} %); \
             order 1 {:.6} ± {:.6}; orders ≥ 2 {:.1} % of the total; {:.2} collisions/path",
            mc.seconds,
            mc.mean,
            mc.se,
            100.0 * mc.se / mc.mean,
            mc.single,
            mc.single_se,
            100.0 * (1.0 - mc.single / mc.mean),
            mc.mean_collisions,
        );
        eprintln!("| N | a | b | c | march mean | vs MC |");
        eprintln!("|---|---|---|---|---|---|");
        for o in settings_tried() {
            let m = march_mean(&case.volume, sun.to_sun(), eye, &rays, o, 256, 64);
            let rel = m / mc.mean - 1.0;
            eprintln!(
                "| {} | {} | {} | {} | {m:.6} | {:+.1} ± {:.1} % |",
                o.count,
                o.a,
                o.b,
                o.c,
                100.0 * rel,
                100.0 * mc.se / mc.mean
            );
            if o == Octaves::SINGLE {
                assert!(
                    (m - mc.single).abs() < 3.5 * mc.single_se + 0.01 * mc.single,
                    "{name}: march single {m} vs MC order 1 {} ± {}",
                    mc.single,
                    mc.single_se
                );
            }
            if k == 0 {
                goal_order_1 = (mc.single, mc.single_se);
                goal = goal.or((o == octaves(8, 0.5, 0.65, 0.5)).then_some((rel, mc.se / mc.mean)));
            }
        }
    }
    // The exact single-scattering reference over the goal case's image: the march's single
    // scattering (256 view / 64 light steps) and the path tracer's order 1 against it.
    let sun = sun_60();
    let (eye, rays) = camera_rays(&case.volume, 8000.0, 20.0, 150.0, 64, 48);
    let start = std::time::Instant::now();
    let phase = Phase::DualLobe {
        g_forward: G_FORWARD,
        g_back: G_BACK,
        back_weight: BACK_WEIGHT,
    };
    let results: Vec<_> = rays
        .par_iter()
        .map(|&d| {
            single_scattering(
                &case.volume,
                eye,
                d,
                &sun,
                &phase,
                &SingleScatteringSettings::default(),
            )
            .unwrap()
        })
        .collect();
    let exact = results.iter().map(|r| r.radiance[0]).sum::<f64>() / rays.len() as f64;
    let error = results
        .iter()
        .map(|r| r.integral.error_estimate)
        .sum::<f64>()
        / rays.len() as f64;
    let converged = results.iter().filter(|r| r.integral.converged).count();
    let evaluations: usize = results.iter().map(|r| r.integral.evaluations).sum();
    let march_single = march_mean(
        &case.volume,
        sun.to_sun(),
        eye,
        &rays,
        Octaves::SINGLE,
        256,
        64,
    );
    eprintln!(
        "\nsingle-scattering reference over the goal image: {exact:.6} (reached integral error \
         {error:.1e} per pixel, {converged}/{} pixels converged, {evaluations} evaluations, {:.1} s); \
         march 1 octave {march_single:.6} ({:+.2} %)",
        rays.len(),
        start.elapsed().as_secs_f64(),
        100.0 * (march_single / exact - 1.0),
    );
    eprintln!(
        "path tracer order 1 {:.6} ± {:.6} vs the reference: {:+.1} σ",
        goal_order_1.0,
        goal_order_1.1,
        (goal_order_1.0 - exact) / goal_order_1.1
    );
    assert!((goal_order_1.0 - exact).abs() < 3.5 * goal_order_1.1);
    assert_eq!(converged, rays.len());
    assert!((march_single / exact - 1.0).abs() < 0.01);

    let (rel, se) = goal.unwrap();
    assert!(
        rel.abs() < 0.10 + 3.0 * se,
        "8 octaves a=0.5 b=0.65 c=0.5 on the goal case: {:+.1} ± {:.1} %",
        100.0 * rel,
        100.0 * se
    );
}
