//! The view march against closed forms and at its extremes.
#![allow(clippy::needless_range_loop)] // channel loops read three arrays

mod common;

use std::num::NonZeroU32;

use cloudlight::CloudVolume;
use cloudlight::cone::{ConeWeights, dual_lobe_henyey_greenstein};
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchError, MarchSettings, Octaves, march_view,
    march_view_at_pixel, octave_scattering, step_integral,
};

fn settings(config: MarchConfig) -> MarchSettings {
    MarchSettings::new(config).unwrap()
}

fn full(steps: u32) -> LightMarch {
    LightMarch::Full {
        steps: NonZeroU32::new(steps).unwrap(),
    }
}

/// A flat homogeneous slab: a 100×100×1 grid of 200 m cells, 1000–1200 m up.
fn flat_slab(sigma: f64) -> CloudVolume {
    CloudVolume::new(
        [100, 100, 1],
        [-10_000.0, -10_000.0, 1000.0],
        200.0,
        sigma,
        vec![1.0; 10_000],
    )
    .unwrap()
}

/// Single scattering of a homogeneous slab of thickness D seen straight up from below,
/// sun at zenith cosine μ: σ_s·E·p·∫₀^D e^{−σt}·e^{−σ(D−t)/μ} dt.
fn slab_single_scattering(sigma: f64, depth: f64, mu: f64, phase: f64) -> f64 {
    let k = sigma * (1.0 - 1.0 / mu);
    let integral = if k.abs() < 1e-12 {
        depth
    } else {
        ((-k * depth).exp() - 1.0) / -k
    };
    sigma * phase * (-sigma * depth / mu).exp() * integral
}

#[test]
fn single_scattering_of_a_slab_converges_to_the_closed_form() {
    let sigma = 0.01;
    let volume = flat_slab(sigma);
    let mu: f64 = 0.6;
    let sun = [(1.0 - mu * mu).sqrt(), 0.0, mu];
    let lighting = Lighting::<f64>::white_sun(sun).unwrap();
    let config = MarchConfig {
        transmittance_epsilon: 0.0,
        light: full(64),
        ..MarchConfig::default()
    };
    let phase =
        dual_lobe_henyey_greenstein(mu, config.g_forward, config.g_back, config.back_weight);
    let exact = slab_single_scattering(sigma, 200.0, mu, phase);
    let mut errors = Vec::new();
    for steps in [2, 8, 32, 128] {
        let s = settings(MarchConfig {
            view_steps: steps,
            ..config
        });
        let r = march_view(&volume, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], &s, &lighting);
        assert!((r.transmittance - (-2.0f64).exp()).abs() < 1e-12);
        let rel = (r.radiance[0] - exact).abs() / exact;
        println!(
            "view steps {steps}: radiance {:.6e} vs {exact:.6e}, rel {rel:.2e}",
            r.radiance[0]
        );
        errors.push(rel);
    }
    for w in errors.windows(2) {
        assert!(w[1] < w[0], "not converging: {errors:?}");
    }
    assert!(errors[3] < 1e-4, "{errors:?}");
}

#[test]
fn sun_at_zenith_looking_up_is_sigma_e_p_d_exp() {
    // Sun and view along +z: every sample sees e^{−σD} in total, L = σ p D e^{−σD}.
    let sigma = 0.004;
    let volume = flat_slab(sigma);
    let lighting = Lighting::<f64>::white_sun([0.0, 0.0, 1.0]).unwrap();
    let config = MarchConfig {
        view_steps: 5,
        light: full(3),
        transmittance_epsilon: 0.0,
        ..MarchConfig::default()
    };
    let phase =
        dual_lobe_henyey_greenstein(1.0, config.g_forward, config.g_back, config.back_weight);
    let exact = sigma * phase * 200.0 * (-sigma * 200.0f64).exp();
    let r = march_view(
        &volume,
        [5.0, 5.0, 0.0],
        [0.0, 0.0, 1.0],
        &settings(config),
        &lighting,
    );
    // Not exact with 5 steps: the step integral weights the light of the step's centre.
    assert!(
        (r.radiance[1] - exact).abs() < 2e-3 * exact,
        "{} vs {exact}",
        r.radiance[1]
    );
}

#[test]
fn one_octave_is_single_scattering_and_powder_is_off_by_default() {
    assert!(!MarchConfig::default().powder);
    assert_eq!(MarchConfig::default().octaves.count, 1);
    for tau in [0.0f64, 0.3, 5.0] {
        for cos in [-1.0, 0.0, 0.7, 1.0] {
            let one = octave_scattering(tau, cos, 0.8, -0.3, 0.2, 1, 0.3, 0.9, 0.1);
            let single = (-tau).exp() * dual_lobe_henyey_greenstein(cos, 0.8, -0.3, 0.2);
            assert_eq!(one, single);
        }
    }
    let volume = flat_slab(0.01);
    let lighting = Lighting::<f64>::white_sun([0.6, 0.0, 0.8]).unwrap();
    let a = march_view(
        &volume,
        [0.0; 3],
        [0.0, 0.0, 1.0],
        &settings(MarchConfig::default()),
        &lighting,
    );
    let b = march_view(
        &volume,
        [0.0; 3],
        [0.0, 0.0, 1.0],
        &settings(MarchConfig {
            octaves: Octaves {
                count: 1,
                a: 0.1,
                b: 0.9,
                c: 0.2,
            },
            ..MarchConfig::default()
        }),
        &lighting,
    );
    assert_eq!(a, b);
    // More octaves add light.
    let c = march_view(
        &volume,
        [0.0; 3],
        [0.0, 0.0, 1.0],
        &settings(MarchConfig {
            octaves: Octaves {
                count: 4,
                a: 0.5,
                b: 0.5,
                c: 0.5,
            },
            ..MarchConfig::default()
        }),
        &lighting,
    );
    assert!(c.radiance[0] > a.radiance[0]);
}

#[test]
fn step_integral_is_stable_at_zero_extinction() {
    assert_eq!(step_integral(0.0f64, 3.0), 3.0);
    assert_eq!(step_integral(0.0f32, 3.0), 3.0);
    let tiny = step_integral(1e-30f64, 10.0);
    assert!((tiny - 10.0).abs() < 1e-12);
    let f32_tiny = step_integral(1e-20f32, 10.0);
    assert!((f32_tiny - 10.0).abs() < 1e-5);
    let big = step_integral(1.0f64, 1e6);
    assert!((big - 1.0).abs() < 1e-12);
}

fn check(r: cloudlight::march::MarchResult<f64>, what: &str) {
    assert!(
        r.transmittance.is_finite() && (0.0..=1.0).contains(&r.transmittance),
        "{what}: T {}",
        r.transmittance
    );
    for c in r.radiance {
        assert!(c.is_finite() && c >= 0.0, "{what}: L {c}");
    }
    assert!(
        r.depth.is_finite() && r.depth >= 0.0,
        "{what}: depth {}",
        r.depth
    );
}

fn check32(r: cloudlight::march::MarchResult<f32>, what: &str) {
    assert!(
        r.transmittance.is_finite() && (0.0..=1.0).contains(&r.transmittance),
        "{what}: T {}",
        r.transmittance
    );
    for c in r.radiance {
        assert!(c.is_finite() && c >= 0.0, "{what}: L {c}");
    }
}

#[test]
fn extremes_give_no_nan_and_transmittance_in_unit_range() {
    let suns = [
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 0.0],  // horizon
        [0.6, 0.0, -0.8], // below
        [0.0, 0.0, -1.0], // nadir
        [0.577_350_3, 0.577_350_3, 0.577_350_3],
    ];
    let views = [
        ([16.0, 16.0, -50.0], [0.0, 0.0, 1.0]), // below, looking up
        ([16.0, 16.0, 16.0], [0.6, 0.0, 0.8]),  // inside the cloud
        ([16.0, 16.0, 16.0], [0.0, 0.0, -1.0]),
        ([-100.0, 16.0, 16.0], [1.0, 0.0, 0.0]), // grazing through
        ([-100.0, -100.0, -100.0], [-1.0, 0.0, 0.0]), // missing
    ];
    let lights = [
        full(1),
        full(32),
        LightMarch::Cone {
            step: 3.0,
            spread: 0.2,
            weights: ConeWeights::Raw,
        },
        LightMarch::Cone {
            step: 50.0,
            spread: 0.0,
            weights: ConeWeights::Partitioned,
        },
    ];
    for density in [0.0f32, 1e-6, 1.0, 1e6] {
        for sigma in [0.0, 1e-4, 0.1, 1.0] {
            let volume =
                CloudVolume::new([4, 4, 4], [0.0; 3], 8.0, sigma, vec![density; 64]).unwrap();
            for sun in suns {
                let lighting =
                    Lighting::<f64>::new(sun, [1.0, 0.9, 0.8], [0.1, 0.2, 0.3], [0.0, 0.0, 1.0])
                        .unwrap();
                let lighting32 =
                    Lighting::<f32>::new(sun, [1.0, 0.9, 0.8], [0.1, 0.2, 0.3], [0.0, 0.0, 1.0])
                        .unwrap();
                for (origin, dir) in views {
                    for light in lights {
                        for (octaves, powder) in [(1, false), (8, true)] {
                            let s = settings(MarchConfig {
                                view_steps: 16,
                                light,
                                powder,
                                octaves: Octaves {
                                    count: octaves,
                                    a: 0.5,
                                    b: 0.7,
                                    c: 0.5,
                                },
                                jitter: Jitter::InterleavedGradient,
                                ..MarchConfig::default()
                            });
                            let what = format!(
                                "ρ {density} σ {sigma} sun {sun:?} from {origin:?} {light:?} octaves {octaves}"
                            );
                            check(march_view(&volume, origin, dir, &s, &lighting), &what);
                            let o32 = origin.map(|c| c as f32);
                            let d32 = dir.map(|c| c as f32);
                            check32(
                                march_view_at_pixel(&volume, o32, d32, &s, &lighting32, [7, 3]),
                                &what,
                            );
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn bad_settings_name_the_field_and_value() {
    let bad = |config: MarchConfig, field: &str| match MarchSettings::new(config) {
        Err(MarchError::Invalid { field: f, .. }) => assert_eq!(f, field),
        other => panic!("{field}: {other:?}"),
    };
    let d = MarchConfig::default();
    bad(MarchConfig { view_steps: 0, ..d }, "view_steps");
    bad(
        MarchConfig {
            transmittance_epsilon: -0.1,
            ..d
        },
        "transmittance_epsilon",
    );
    bad(
        MarchConfig {
            transmittance_epsilon: f64::NAN,
            ..d
        },
        "transmittance_epsilon",
    );
    bad(
        MarchConfig {
            octaves: Octaves {
                count: 0,
                ..d.octaves
            },
            ..d
        },
        "octaves.count",
    );
    bad(
        MarchConfig {
            octaves: Octaves {
                a: f64::NAN,
                ..d.octaves
            },
            ..d
        },
        "octaves.a",
    );
    bad(MarchConfig { albedo: 1.5, ..d }, "albedo");
    bad(
        MarchConfig {
            g_forward: 1.0,
            ..d
        },
        "g_forward",
    );
    bad(
        MarchConfig {
            light: LightMarch::Cone {
                step: 0.0,
                spread: 0.1,
                weights: ConeWeights::Raw,
            },
            ..d
        },
        "light.step",
    );
    let err = MarchSettings::new(MarchConfig { view_steps: 0, ..d }).unwrap_err();
    assert!(err.to_string().contains("view_steps = 0"), "{err}");
    assert!(matches!(
        Lighting::<f64>::new([0.0, 0.0, 2.0], [1.0; 3], [0.0; 3], [0.0, 0.0, 1.0]),
        Err(MarchError::Invalid {
            field: "sun_direction",
            ..
        })
    ));
    assert!(matches!(
        Lighting::<f64>::new([0.0, 0.0, 1.0], [1.0, -1.0, 1.0], [0.0; 3], [0.0, 0.0, 1.0]),
        Err(MarchError::Invalid {
            field: "sun_irradiance",
            ..
        })
    ));
}

#[test]
fn early_exit_stops_below_epsilon() {
    let volume = flat_slab(0.1); // τ = 20 through the slab
    let lighting = Lighting::<f64>::white_sun([0.0, 0.0, 1.0]).unwrap();
    let s = settings(MarchConfig {
        view_steps: 100,
        transmittance_epsilon: 1e-3,
        ..MarchConfig::default()
    });
    let r = march_view(&volume, [0.0; 3], [0.0, 0.0, 1.0], &s, &lighting);
    assert!(
        r.transmittance < 1e-3 && r.transmittance > 1e-5,
        "{}",
        r.transmittance
    );
    // The cloud's front face at 1000 m: the weighted depth is just behind it.
    assert!(r.depth > 1000.0 && r.depth < 1020.0, "{}", r.depth);
}

#[test]
fn the_f32_twin_follows_the_f64_march() {
    let volume = flat_slab(0.01);
    let s = settings(MarchConfig {
        view_steps: 32,
        octaves: Octaves {
            count: 3,
            a: 0.5,
            b: 0.5,
            c: 0.5,
        },
        ..MarchConfig::default()
    });
    let l64 = Lighting::<f64>::new([0.6, 0.0, 0.8], [1.0; 3], [0.05; 3], [0.0, 0.0, 1.0]).unwrap();
    let l32 = Lighting::<f32>::new([0.6, 0.0, 0.8], [1.0; 3], [0.05; 3], [0.0, 0.0, 1.0]).unwrap();
    let a = march_view(&volume, [0.0, 0.0, 0.0], [0.0, 0.6, 0.8], &s, &l64);
    let b = march_view(&volume, [0.0f32; 3], [0.0, 0.6, 0.8], &s, &l32);
    for k in 0..3 {
        let rel = (a.radiance[k] - f64::from(b.radiance[k])).abs() / a.radiance[k];
        assert!(rel < 1e-4, "{rel}");
    }
    assert!((a.transmittance - f64::from(b.transmittance)).abs() < 1e-5);
}

#[test]
fn atmos_lighting_and_aerial_perspective() {
    use atmos::SkyModel;
    use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
    use cloudlight::march::{apply_aerial_perspective, atmos_light};
    use glam::DVec3;
    let earth = atmos::Atmosphere::earth();
    let sky = SingleScatteringSky::new(&earth, SingleScatteringSettings::default()).unwrap();
    let point = DVec3::new(0.0, 0.0, earth.planet_radius + 2000.0);
    let high = DVec3::new(0.5, 0.0, 0.75f64.sqrt());
    let low = DVec3::new(0.995f64.sqrt(), 0.0, 0.005f64.sqrt());
    let quadrature = atmos::ground_irradiance::HemisphereQuadrature::default();
    let noon = atmos_light(&sky, &earth, point, high, quadrature).unwrap();
    let dusk = atmos_light(&sky, &earth, point, low, quadrature).unwrap();
    // Transmittance < 1, redder at a low sun; a blue sky.
    for k in 0..3 {
        assert!(noon.sun_irradiance[k] < 1.0 && noon.sun_irradiance[k] > dusk.sun_irradiance[k]);
    }
    assert!(dusk.sun_irradiance[0] > dusk.sun_irradiance[2]);
    assert!(noon.ambient_radiance[2] > noon.ambient_radiance[0]);
    let behind = atmos_light(&sky, &earth, point, DVec3::new(0.0, 0.0, -1.0), quadrature).unwrap();
    assert_eq!(behind.sun_irradiance, [0.0; 3]);
    // An opaque cloud 5 km away keeps its radiance times the air's transmittance plus air light.
    let camera = DVec3::new(0.0, 0.0, earth.planet_radius + 2.0);
    let view = DVec3::new(0.0, 0.6, 0.8);
    let cloud = cloudlight::march::MarchResult {
        radiance: [0.3; 3],
        transmittance: 0.0,
        depth: 5000.0,
    };
    let seen = apply_aerial_perspective(&sky, &earth, camera, view, high, &cloud).unwrap();
    let air = sky.evaluate(
        &atmos::SkyQuery::with_max_distance(earth.planet_radius, camera, view, high, 5000.0)
            .unwrap(),
    );
    for k in 0..3 {
        assert!((seen[k] - (0.3 * air.transmittance[k] + air.radiance[k])).abs() < 1e-15);
        assert!(seen[k] < 0.3 + air.radiance[k]);
    }
}

#[test]
fn a_shell_marches_from_below_inside_and_above_without_nan() {
    use cloudlight::{CloudShell, ShellSettings};
    let earth = atmos::Atmosphere::earth();
    let r = earth.planet_radius;
    let mut settings = ShellSettings::cumulus_over(r);
    if let cloudlight::shell::WeatherMap::Procedural(w) = &mut settings.weather {
        w.coverage_mean = 0.9; // dense: most rays meet cloud
    }
    let shell = CloudShell::new(&earth, settings).unwrap();
    let s = settings_for_shell();
    let origins = [
        [0.0, 0.0, r + 2.0],        // on the ground
        [300.0, 200.0, r + 2500.0], // inside the layer
        [0.0, 0.0, r + 14_000.0],   // above it
    ];
    let c = std::f64::consts::FRAC_1_SQRT_2;
    let dirs = [[0.0, 0.0, 1.0], [c, 0.0, c], [1.0, 0.0, 0.0], [0.0, c, -c]];
    let suns = [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [0.6, 0.0, -0.8]];
    let mut hits = 0;
    for origin in origins {
        for dir in dirs {
            for sun in suns {
                let l64 = Lighting::<f64>::new(sun, [1.0; 3], [0.1; 3], [0.0, 0.0, 1.0]).unwrap();
                let l32 = Lighting::<f32>::new(sun, [1.0; 3], [0.1; 3], [0.0, 0.0, 1.0]).unwrap();
                let what = format!("shell from {origin:?} along {dir:?}, sun {sun:?}");
                let a = march_view(&shell, origin, dir, &s, &l64);
                check(a, &what);
                if a.transmittance < 0.999 {
                    hits += 1;
                }
                let o32 = origin.map(|x| x as f32);
                let d32 = dir.map(|x| x as f32);
                check32(
                    march_view_at_pixel(&shell, o32, d32, &s, &l32, [3, 5]),
                    &what,
                );
            }
        }
    }
    assert!(
        hits >= 6,
        "only {hits} rays met cloud: the test would test little"
    );
}

fn settings_for_shell() -> MarchSettings {
    settings(MarchConfig {
        view_steps: 8,
        jitter: Jitter::Bayer4x4,
        light: full(4),
        ambient_steps: 2,
        octaves: Octaves {
            count: 3,
            a: 0.5,
            b: 0.5,
            c: 0.5,
        },
        ..MarchConfig::default()
    })
}

/// The march's single scattering against `reference::single_scattering` (adaptive, exact
/// optical depths) on a lumpy 32³ blob seen from below, and its CPU cost per pixel.
/// `cargo test --release -p cloudlight --test march -- --ignored --nocapture march_accuracy`
#[test]
#[ignore = "a measurement (seconds in release): run it with --ignored --nocapture"]
fn march_accuracy_and_cost() {
    use cloudlight::march::{PinholeCamera, pixel_direction};
    use cloudlight::reference::single_scattering::{SingleScatteringSettings, single_scattering};
    use cloudlight::reference::{Phase, Sun};
    let volume = common::lumpy_blob();
    let size = [32u32, 32];
    let camera =
        PinholeCamera::look_at([0.0, -100.0, 0.0], [0.0, 0.0, 1400.0], [0.0, 0.0, 1.0], 0.9)
            .unwrap();
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half(size);
    let rays: Vec<[f64; 3]> = (0..size[1])
        .flat_map(|y| (0..size[0]).map(move |x| [x, y]))
        .map(|p| pixel_direction(p, size, forward, right, up, tan_half))
        .collect();
    let d = MarchConfig::default();
    let phase = Phase::DualLobe {
        g_forward: d.g_forward,
        g_back: d.g_back,
        back_weight: d.back_weight,
    };
    let cone = |step: f64, weights| LightMarch::Cone {
        step,
        spread: 0.0,
        weights,
    };
    let methods: Vec<(&str, u32, LightMarch)> = vec![
        ("view 16, full light 8", 16, full(8)),
        ("view 64, full light 8", 64, full(8)),
        ("view 64, full light 32", 64, full(32)),
        ("view 256, full light 64", 256, full(64)),
        (
            "view 64, cone 6+1 partitioned, step 1e9 (L/7)",
            64,
            cone(1e9, ConeWeights::Partitioned),
        ),
        (
            "view 64, cone 6+1 raw, step 25 m (1 cell)",
            64,
            cone(25.0, ConeWeights::Raw),
        ),
    ];
    for elevation in [60.0f64, 10.0] {
        let (e, a) = (elevation.to_radians(), 30f64.to_radians());
        let to_sun = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
        let sun = Sun::new(to_sun, [1.0; 3]).unwrap();
        let lighting = Lighting::<f64>::white_sun(to_sun).unwrap();
        let start = std::time::Instant::now();
        let reference: Vec<_> = rays
            .iter()
            .map(|&dir| {
                single_scattering(
                    &volume,
                    camera.origin(),
                    dir,
                    &sun,
                    &phase,
                    &SingleScatteringSettings::default(),
                )
                .unwrap()
            })
            .collect();
        let reference_ms = start.elapsed().as_secs_f64() * 1e3;
        let total: f64 = reference.iter().map(|r| r.radiance[0]).sum();
        println!(
            "sun {elevation}°: reference {reference_ms:.0} ms for {} rays; mean radiance {:.4e}",
            rays.len(),
            total / rays.len() as f64
        );
        // Jitter at 8 view steps: the same pixels marched with each start offset.
        for jitter in [Jitter::None, Jitter::Bayer4x4, Jitter::InterleavedGradient] {
            let s = settings(MarchConfig {
                view_steps: 8,
                jitter,
                light: full(32),
                ..MarchConfig::reference_comparison()
            });
            let (mut abs_sum, mut bias) = (0.0, 0.0);
            for (k, &dir) in rays.iter().enumerate() {
                let pixel = [k as u32 % size[0], k as u32 / size[0]];
                let m = march_view_at_pixel(&volume, camera.origin(), dir, &s, &lighting, pixel);
                abs_sum += (m.radiance[0] - reference[k].radiance[0]).abs();
                bias += m.radiance[0] - reference[k].radiance[0];
            }
            println!(
                "  view 8, full light 32, jitter {jitter:?}: radiance mean |error| {:.2} % of the \
                 mean, bias {:+.3} %",
                100.0 * abs_sum / total,
                100.0 * bias / total
            );
        }
        for (name, steps, light) in &methods {
            let s = settings(MarchConfig {
                view_steps: *steps,
                light: *light,
                ..MarchConfig::reference_comparison()
            });
            let start = std::time::Instant::now();
            let marched: Vec<_> = rays
                .iter()
                .map(|&dir| march_view(&volume, camera.origin(), dir, &s, &lighting))
                .collect();
            let per_ray_us = start.elapsed().as_secs_f64() * 1e6 / rays.len() as f64;
            let start = std::time::Instant::now();
            let o32 = camera.origin().map(|c| c as f32);
            let l32 = Lighting::<f32>::white_sun(to_sun).unwrap();
            for &dir in &rays {
                std::hint::black_box(march_view(&volume, o32, dir.map(|c| c as f32), &s, &l32));
            }
            let per_ray_us_f32 = start.elapsed().as_secs_f64() * 1e6 / rays.len() as f64;
            let abs_sum: f64 = marched
                .iter()
                .zip(&reference)
                .map(|(m, r)| (m.radiance[0] - r.radiance[0]).abs())
                .sum();
            let bias: f64 = marched
                .iter()
                .zip(&reference)
                .map(|(m, r)| m.radiance[0] - r.radiance[0])
                .sum();
            let t_max = marched
                .iter()
                .zip(&reference)
                .map(|(m, r)| (m.transmittance - r.transmittance).abs())
                .fold(0.0, f64::max);
            println!(
                "  {name}: radiance mean |error| {:.2} % of the mean, bias {:+.2} %, view T max \
                 |error| {t_max:.1e}; {per_ray_us:.0} µs/ray f64, {per_ray_us_f32:.0} µs/ray f32",
                100.0 * abs_sum / total,
                100.0 * bias / total
            );
        }
    }
}

/// A 200 m × 100 m × 100 m block of 25 m cells (x from 0 to `25·nx`), its density varying
/// in y and z only, so the block cut at a plane `x = const` on a cell face has the same
/// density in front of the plane.
fn block(nx: u32) -> CloudVolume {
    let mut density = Vec::new();
    for z in 0..4u32 {
        for y in 0..4u32 {
            for _x in 0..nx {
                density.push(0.4 + 0.3 * ((y * 3 + z * 5) % 4) as f32);
            }
        }
    }
    CloudVolume::new([nx, 4, 4], [0.0, 0.0, 1000.0], 25.0, 0.015, density).unwrap()
}

#[test]
fn a_limited_march_is_the_unlimited_march_of_the_field_cut_there() {
    use cloudlight::march::march_view_limited;
    use cloudlight::march::march_view_with_offset;
    // A wall at x = 100 m cuts the 200 m block in half; the sun is overhead and the ambient
    // comes from above, so the light paths never cross the wall: the march stopped at the
    // wall is the march of the front half alone.
    let (whole, front) = (block(8), block(4));
    let settings = settings(MarchConfig {
        view_steps: 24,
        light: full(6),
        transmittance_epsilon: 0.0,
        ..MarchConfig::default()
    });
    let lighting64 = Lighting::<f64>::new(
        [0.0, 0.0, 1.0],
        [1.0, 0.9, 0.8],
        [0.1, 0.1, 0.2],
        [0.0, 0.0, 1.0],
    )
    .unwrap();
    let lighting32 = Lighting::<f32>::new(
        [0.0, 0.0, 1.0],
        [1.0, 0.9, 0.8],
        [0.1, 0.1, 0.2],
        [0.0, 0.0, 1.0],
    )
    .unwrap();
    let origin = [-50.0, 40.0, 1030.0];
    let mut worst64 = 0.0f64;
    let mut worst32 = 0.0f64;
    for dir in [
        [1.0, 0.0, 0.0],
        [0.98, 0.1, 0.17],
        [0.9, 0.3, -0.1],
        [0.95, -0.2, 0.24],
    ] {
        let n: f64 = dir.iter().map(|c| c * c).sum::<f64>().sqrt();
        let d = dir.map(|c| c / n);
        let wall = (100.0 - origin[0]) / d[0];
        for offset in [0.5, 0.13, 0.87] {
            let limited =
                march_view_limited::<f64>(&whole, origin, d, &settings, &lighting64, offset, wall);
            let cut =
                march_view_with_offset::<f64>(&front, origin, d, &settings, &lighting64, offset);
            assert!(
                limited.transmittance < 0.9,
                "{limited:?}: the front half is seen"
            );
            for ch in 0..3 {
                let e = (limited.radiance[ch] - cut.radiance[ch]).abs() / cut.radiance[ch];
                worst64 = worst64.max(e);
            }
            worst64 = worst64.max((limited.transmittance - cut.transmittance).abs());
            worst64 = worst64.max((limited.depth - cut.depth).abs() / cut.depth);
            let unlimited =
                march_view_with_offset::<f64>(&whole, origin, d, &settings, &lighting64, offset);
            assert!(unlimited.transmittance < limited.transmittance - 0.01);
            let o32 = origin.map(|c| c as f32);
            let d32 = d.map(|c| c as f32);
            let limited = march_view_limited::<f32>(
                &whole,
                o32,
                d32,
                &settings,
                &lighting32,
                offset as f32,
                wall as f32,
            );
            let cut = march_view_with_offset::<f32>(
                &front,
                o32,
                d32,
                &settings,
                &lighting32,
                offset as f32,
            );
            for ch in 0..3 {
                let e = (limited.radiance[ch] - cut.radiance[ch]).abs() as f64
                    / cut.radiance[ch] as f64;
                worst32 = worst32.max(e);
            }
            worst32 = worst32.max((limited.transmittance - cut.transmittance).abs() as f64);
        }
    }
    println!("limited march vs the cut field: f64 worst relative {worst64:.2e}, f32 {worst32:.2e}");
    assert!(worst64 < 1e-12, "{worst64}");
    assert!(worst32 < 1e-5, "{worst32}");
}

#[test]
fn a_zero_limit_sees_nothing_and_a_far_limit_everything() {
    use cloudlight::march::march_view_limited;
    use cloudlight::march::march_view_with_offset;
    let whole = block(8);
    let settings = settings(MarchConfig {
        view_steps: 16,
        light: full(4),
        ..MarchConfig::default()
    });
    let lighting =
        Lighting::<f64>::white_sun([0.3, 0.0, 0.3f64.mul_add(-0.3, 1.0).sqrt()]).unwrap();
    let origin = [-50.0, 40.0, 1030.0];
    let d = [1.0, 0.0, 0.0];
    for limit in [0.0, -5.0, f64::NEG_INFINITY, 50.0] {
        // 50 m: the wall is where the block starts.
        let r = march_view_limited::<f64>(&whole, origin, d, &settings, &lighting, 0.5, limit);
        assert_eq!(r.radiance, [0.0; 3], "limit {limit}");
        assert_eq!(r.transmittance, 1.0, "limit {limit}");
        assert_eq!(r.depth, 0.0, "limit {limit}");
    }
    let unlimited = march_view_with_offset::<f64>(&whole, origin, d, &settings, &lighting, 0.5);
    assert!(unlimited.transmittance < 0.5);
    for limit in [250.0, 1e6, f64::INFINITY, f64::NAN] {
        // The block ends 250 m along the ray.
        let r = march_view_limited::<f64>(&whole, origin, d, &settings, &lighting, 0.5, limit);
        assert_eq!(r, unlimited, "limit {limit}");
    }
}

#[test]
fn clipped_spans_and_the_limited_image() {
    use cloudlight::RaySpans;
    use cloudlight::march::{PinholeCamera, clip_spans, render_image, render_image_limited};
    let two = RaySpans {
        spans: [(10.0f64, 20.0), (50.0, 80.0)],
        count: 2,
    };
    assert_eq!(
        clip_spans(two, 60.0).as_slice(),
        &[(10.0, 20.0), (50.0, 60.0)]
    );
    assert_eq!(clip_spans(two, 30.0).as_slice(), &[(10.0, 20.0)]);
    assert_eq!(clip_spans(two, 50.0).as_slice(), &[(10.0, 20.0)]);
    assert_eq!(clip_spans(two, 15.0).as_slice(), &[(10.0, 15.0)]);
    assert_eq!(clip_spans(two, 10.0).count, 0);
    assert_eq!(clip_spans(two, -1.0).count, 0);
    assert_eq!(clip_spans(two, f64::INFINITY), two);
    assert_eq!(clip_spans(two, f64::NAN), two);
    let whole = block(8);
    let camera = PinholeCamera::look_at(
        [-50.0, 50.0, 1050.0],
        [100.0, 50.0, 1050.0],
        [0.0, 0.0, 1.0],
        0.6,
    )
    .unwrap();
    let settings = MarchSettings::default();
    let lighting = Lighting::<f32>::white_sun([0.0, 0.0, 1.0]).unwrap();
    let size = [4, 3];
    let err = render_image_limited::<f32>(&whole, &camera, size, &settings, &lighting, &[1.0; 5])
        .unwrap_err();
    assert!(err.to_string().contains("max_distance.len() = 5"), "{err}");
    let unlimited = render_image::<f32>(&whole, &camera, size, &settings, &lighting);
    let all = render_image_limited::<f32>(
        &whole,
        &camera,
        size,
        &settings,
        &lighting,
        &[f32::INFINITY; 12],
    )
    .unwrap();
    assert_eq!(all, unlimited);
    let none = render_image_limited::<f32>(&whole, &camera, size, &settings, &lighting, &[0.0; 12])
        .unwrap();
    assert!(
        none.iter()
            .all(|r| r.transmittance == 1.0 && r.radiance == [0.0; 3])
    );
}
