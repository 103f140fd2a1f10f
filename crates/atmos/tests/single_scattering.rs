//! Rung 2 (single scattering): robustness sweeps, the known artefacts of a shell-entry
//! march (O'Neil 2005) as tests, Hoffman & Preetham 2002's observations, the default sample counts' convergence, and the GPU frame against the
//! CPU twin.

use atmos::ladder::luminance;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{Atmosphere, SkyModel, SkyQuery, SkySample};
use glam::DVec3;

const R: f64 = 6_360_000.0;
const TOP: f64 = 6_460_000.0;

fn sky(atmosphere: &Atmosphere, view: u32, light: u32) -> SingleScatteringSky {
    SingleScatteringSky::new(
        atmosphere,
        SingleScatteringSettings {
            view_samples: view,
            light_samples: light,
        },
    )
    .unwrap()
}

/// A direction at zenith cosine `mu` and azimuth `phi` in the frame where +z is up.
fn direction(mu: f64, phi: f64) -> DVec3 {
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), mu)
}

fn eval(model: &impl SkyModel, altitude: f64, view: DVec3, sun: DVec3, max: f64) -> SkySample {
    let q =
        SkyQuery::with_max_distance(R, DVec3::new(0.0, 0.0, R + altitude), view, sun, max).unwrap();
    model.evaluate(&q)
}

fn check_sample(s: &SkySample, what: &str) {
    for k in 0..3 {
        assert!(
            s.radiance[k].is_finite() && s.radiance[k] >= 0.0,
            "{what}: radiance {:?}",
            s.radiance
        );
        assert!(
            (0.0..=1.0).contains(&s.transmittance[k]),
            "{what}: transmittance {:?}",
            s.transmittance
        );
    }
}

fn scaled(densities: f64, g: f64) -> Atmosphere {
    let e = Atmosphere::earth();
    Atmosphere {
        rayleigh_scattering: e.rayleigh_scattering.map(|b| b * densities),
        mie_scattering: e.mie_scattering.map(|b| b * densities),
        mie_extinction: e.mie_extinction.map(|b| b * densities),
        ozone_absorption: e.ozone_absorption.map(|b| b * densities),
        mie_g: g,
        ..e
    }
}

fn altitudes() -> Vec<f64> {
    vec![
        -10.0, 0.0, 1.0, 100.0, 2e3, 3e4, 99_999.0, 100_000.0, 100_001.0, 4e5, 1e7,
    ]
}

/// View zenith cosines: dense, the poles, the horizon, and the ground's and the top's
/// tangents as seen from `altitude` (± a hair).
fn view_cosines(altitude: f64) -> Vec<f64> {
    let mut v: Vec<f64> = (0..=12).map(|i| -1.0 + i as f64 / 6.0).collect();
    let r = R + altitude.max(0.0);
    for radius in [R, TOP] {
        if r > radius {
            let tangent = -(1.0 - (radius / r).powi(2)).sqrt();
            v.extend([tangent, tangent - 1e-6, tangent + 1e-6, tangent + 1e-3]);
        }
    }
    v.extend([0.0, -1e-4, 1e-4]);
    v
}

#[test]
fn property_sweep_no_nan_bounded_monotone() {
    // Debug builds run this at the default opt level: small sample counts, and the
    // default counts on the Earth atmosphere only.
    let sun_elevations = [-90.0f64, -18.0, -6.0, -0.5, 0.0, 2.0, 30.0, 90.0];
    let mut evaluated = 0;
    for (densities, g, view, light) in [
        (1.0, 0.8, 32, 8),
        (0.0, 0.0, 4, 2),
        (100.0, 0.9999, 6, 3),
        (100.0, -0.9999, 6, 3),
        (1e-3, 0.5, 4, 2),
    ] {
        let atmosphere = scaled(densities, g);
        let model = sky(&atmosphere, view, light);
        for altitude in altitudes() {
            for mu in view_cosines(altitude) {
                for (i, elevation) in sun_elevations.iter().enumerate() {
                    let sun = direction(elevation.to_radians().sin(), 0.3 + i as f64);
                    let v = direction(mu, 0.0);
                    let mut previous: Option<SkySample> = None;
                    for max in [1e3, 5e4, f64::INFINITY] {
                        let s = eval(&model, altitude, v, sun, max);
                        let what = format!(
                            "density ×{densities} g {g} h {altitude} mu {mu} sun {elevation}° max {max}"
                        );
                        check_sample(&s, &what);
                        if let Some(p) = previous {
                            for k in 0..3 {
                                assert!(
                                    s.transmittance[k] <= p.transmittance[k],
                                    "{what}: transmittance rose {:?} → {:?}",
                                    p.transmittance,
                                    s.transmittance
                                );
                                assert!(
                                    s.radiance[k] >= p.radiance[k] * (1.0 - 1e-5),
                                    "{what}: radiance fell {:?} → {:?}",
                                    p.radiance,
                                    s.radiance
                                );
                            }
                        }
                        previous = Some(s);
                        evaluated += 1;
                    }
                }
            }
        }
    }
    assert!(evaluated > 5_000, "{evaluated}");
}

#[test]
fn zero_density_is_an_empty_sky() {
    let model = sky(&scaled(0.0, 0.8), 16, 4);
    let s = eval(&model, 10.0, direction(0.1, 0.0), DVec3::Z, f64::INFINITY);
    assert_eq!(s.radiance, [0.0; 3]);
    assert_eq!(s.transmittance, [1.0; 3]);
}

#[test]
fn continuous_across_the_top_of_the_atmosphere() {
    // The "painted shell" jump of a shell-entry march: the outside path starts at the shell, the inside
    // path at the camera; ±1 m around the top must agree to 0.5 %.
    let model = sky(&Atmosphere::earth(), 32, 8);
    let tangent_ground = -(1.0 - (R / TOP).powi(2)).sqrt();
    let mut views = vec![-1.0, -0.7, -0.4, -0.25, -0.1, -0.03];
    // Rays within ±1 m of grazing the ground change physically (ground hit or not);
    // just inside and outside that they must not jump.
    views.extend([
        tangent_ground - 1e-3,
        tangent_ground + 1e-3,
        tangent_ground + 1e-4,
    ]);
    let mut compared = 0;
    for mu in views {
        for sun_elevation in [90.0f64, 30.0, 5.0, 0.0, -5.0, -12.0] {
            for azimuth in [0.0, 1.5, 3.1] {
                let v = direction(mu, 0.0);
                let sun = direction(sun_elevation.to_radians().sin(), azimuth);
                let below = eval(&model, TOP - R - 1.0, v, sun, f64::INFINITY);
                let above = eval(&model, TOP - R + 1.0, v, sun, f64::INFINITY);
                for k in 0..3 {
                    let (a, b) = (below.radiance[k], above.radiance[k]);
                    assert!(
                        (a - b).abs() <= 0.005 * a.max(b) + 1e-9,
                        "mu {mu} sun {sun_elevation}° az {azimuth}: {a} vs {b}"
                    );
                    let (a, b) = (below.transmittance[k], above.transmittance[k]);
                    assert!((a - b).abs() <= 0.005 * a.max(b) + 1e-9, "T {a} vs {b}");
                }
                compared += 1;
            }
        }
    }
    assert_eq!(compared, 9 * 6 * 3);
}

#[test]
fn no_spike_at_the_sunlit_limb_seen_from_space() {
    // The sunlit limb's edge artefact of a shell-entry march: a dense sweep of views across the limb, lit from the
    // side and from behind the viewer. The f32 twin must stay within 1 % (plus a floor
    // far below the limb's brightness) of the f64 twin at the same sample counts.
    let earth = Atmosphere::earth();
    let model = sky(&earth, 32, 8);
    for altitude in [1e6, 1e7] {
        let r = R + altitude;
        let ground_tangent = -(1.0 - (R / r).powi(2)).sqrt();
        let top_tangent = -(1.0 - (TOP / r).powi(2)).sqrt();
        let steps = 400;
        let mut peak: f64 = 0.0;
        let mut values = Vec::new();
        for i in 0..=steps {
            // From 20 % inside the disc to just beyond the top's tangent.
            let mu = ground_tangent * 1.002
                + (top_tangent * 0.999 - ground_tangent * 1.002) * i as f64 / steps as f64;
            for sun in [
                DVec3::X,
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(-0.6, 0.0, 0.8),
            ] {
                let v = direction(mu, 0.0);
                let s = eval(&model, altitude, v, sun, f64::INFINITY);
                check_sample(&s, &format!("limb h {altitude} mu {mu}"));
                let q = SkyQuery::new(R, DVec3::new(0.0, 0.0, r), v, sun).unwrap();
                let f64_twin = atmos::reference::single_scattering(
                    &earth,
                    q.r(),
                    q.mu(),
                    q.mu_s(),
                    q.nu(),
                    f64::INFINITY,
                    32,
                    8,
                );
                peak = peak.max(luminance(f64_twin.radiance));
                values.push((mu, s.radiance, f64_twin.radiance));
            }
        }
        for (mu, f32_side, f64_side) in values {
            for k in 0..3 {
                assert!(
                    (f32_side[k] - f64_side[k]).abs() <= 0.01 * f64_side[k] + 1e-4 * peak,
                    "h {altitude} mu {mu}: f32 {f32_side:?} vs f64 {f64_side:?}"
                );
            }
        }
    }
}

#[test]
fn aerial_perspective_grows_with_distance() {
    // No "painted shell": distant geometry must take more in-scatter and less
    // transmittance the farther it is.
    let model = sky(&Atmosphere::earth(), 32, 8);
    let sun = direction(0.5, 1.0);
    for (altitude, mu) in [(2.0, 0.0), (1000.0, -0.01), (1e6, -0.95)] {
        let v = direction(mu, 0.0);
        let mut previous = eval(&model, altitude, v, sun, 0.0);
        assert_eq!(previous.radiance, [0.0; 3]);
        assert_eq!(previous.transmittance, [1.0; 3]);
        for max in [100.0, 1e3, 1e4, 5e4, 2e5, 9.6e5, 1e6] {
            let s = eval(&model, altitude, v, sun, max);
            // From 1,000 km at mu = −0.95 the shell starts 955 km away.
            if altitude < 1e5 || max > 9.55e5 {
                assert!(
                    luminance(s.radiance) > luminance(previous.radiance),
                    "h {altitude} {max} m: {:?} → {:?}",
                    previous.radiance,
                    s.radiance
                );
                assert!(s.transmittance[2] < previous.transmittance[2]);
            } else {
                // From space the first 955 km are empty: nothing until the shell.
                assert_eq!(s.radiance, [0.0; 3], "{max}");
            }
            previous = s;
        }
    }
}

#[test]
fn hoffman_preetham_observations_hold() {
    let earth = Atmosphere::earth();
    // Zenith at noon without Mie: B > G > R.
    let clear = Atmosphere {
        mie_scattering: [0.0; 3],
        mie_extinction: [0.0; 3],
        ..earth.clone()
    };
    let s = eval(&sky(&clear, 32, 8), 1.0, DVec3::Z, DVec3::Z, f64::INFINITY);
    assert!(
        s.radiance[2] > s.radiance[1] && s.radiance[1] > s.radiance[0],
        "{:?}",
        s.radiance
    );
    // Strong Mie (×100: a hazy day, vertical Mie depth 0.5) with a high sun: hazy, low
    // saturation (channels within 35 %), while the clear sky's blue is > 2× its red.
    let hazy = Atmosphere {
        mie_scattering: [4e-4; 3],
        mie_extinction: [4.4e-4; 3],
        ..earth.clone()
    };
    let view = direction(0.5, 1.0);
    let sun = direction(0.9, 0.0);
    let h = eval(&sky(&hazy, 32, 8), 1.0, view, sun, f64::INFINITY).radiance;
    let c = eval(&sky(&clear, 32, 8), 1.0, view, sun, f64::INFINITY).radiance;
    let saturation = |rgb: [f64; 3]| {
        let max = rgb.iter().cloned().fold(0.0, f64::max);
        let min = rgb.iter().cloned().fold(f64::INFINITY, f64::min);
        (max - min) / max
    };
    assert!(saturation(h) < 0.35, "hazy {h:?}");
    assert!(saturation(c) > 0.5, "clear {c:?}");
    // Toward a low sun: red over blue.
    let sun = direction(2f64.to_radians().sin(), 0.0);
    let view = direction(1f64.to_radians().sin(), 0.0);
    let s = eval(&sky(&earth, 32, 8), 1.0, view, sun, f64::INFINITY).radiance;
    assert!(s[0] > s[2], "toward the low sun {s:?}");
}

#[test]
fn the_planet_shadows_exactly_below_the_horizon_dip() {
    use atmos::twins::light_path_transmittance;
    let u = Atmosphere::earth().to_uniforms().unwrap();
    for altitude in [0.3f32, 10.0, 1000.0, 50_000.0] {
        let r = R + f64::from(altitude);
        let dip = -(1.0 - (R / r).powi(2)).sqrt();
        let lit = light_path_transmittance(&u, altitude, (dip * 0.99) as f32, 8);
        let dark = light_path_transmittance(&u, altitude, (dip * 1.01) as f32, 8);
        assert!(lit.iter().all(|&t| t > 0.0), "{altitude} m: {lit:?}");
        assert_eq!(dark, [0.0; 3], "{altitude} m");
        let f64_lit = atmos::reference::light_path_transmittance(
            &Atmosphere::earth(),
            f64::from(altitude),
            dip * 0.99,
            8,
        );
        assert!(f64_lit[0] > 0.0, "{altitude} m");
    }
}

#[test]
fn earths_shadow_darkens_the_ground_views_at_night() {
    // Sun 30° below the horizon: every point within 100 km of a viewer is in the
    // planet's shadow, so looking down no single scattering reaches the viewer.
    let model = sky(&Atmosphere::earth(), 32, 8);
    let sun = direction(-(30f64.to_radians().sin()), 0.0);
    let s = eval(&model, 1000.0, direction(-0.5, 0.0), sun, f64::INFINITY);
    assert_eq!(s.radiance, [0.0; 3]);
}

/// Mean relative luminance difference of rung 2 at (view, light) against 512/128 over
/// the trade-off's camera altitudes and sun elevations ≥ 5°, directions above and below
/// the horizon.
fn mean_error_against_converged(view: u32, light: u32) -> f64 {
    let earth = Atmosphere::earth();
    let model = sky(&earth, view, light);
    let converged = sky(&earth, 512, 128);
    let mut sum = 0.0;
    let mut n = 0;
    for altitude in [0.0, 1e3, 1e4, 1e5, 1e6] {
        for elevation in [10.0f64, 30.0, 60.0, 90.0] {
            let sun = direction(elevation.to_radians().sin(), 0.0);
            for mu in [-0.9, -0.3, -0.05, 0.02, 0.1, 0.4, 0.9] {
                for phi in [0.0, 1.6, 3.1] {
                    let v = direction(mu, phi);
                    let reference =
                        luminance(eval(&converged, altitude, v, sun, f64::INFINITY).radiance);
                    if reference <= 1e-6 {
                        continue;
                    }
                    let got = luminance(eval(&model, altitude, v, sun, f64::INFINITY).radiance);
                    sum += (got - reference).abs() / reference;
                    n += 1;
                }
            }
        }
    }
    sum / f64::from(n)
}

#[test]
fn default_sample_counts_are_converged() {
    if cfg!(debug_assertions) {
        eprintln!(
            "SKIPPED default_sample_counts_are_converged: release only (cargo test --release)"
        );
        return;
    }
    let defaults = SingleScatteringSettings::default();
    let e_default = mean_error_against_converged(defaults.view_samples, defaults.light_samples);
    let e_half_view =
        mean_error_against_converged(defaults.view_samples / 2, defaults.light_samples);
    let e_half_light =
        mean_error_against_converged(defaults.view_samples, defaults.light_samples / 2);
    let e_double =
        mean_error_against_converged(2 * defaults.view_samples, 2 * defaults.light_samples);
    eprintln!(
        "rung 2 mean relative luminance error vs 512/128 (sun ≥ 10°): default {e_default:.4}, \
         half view {e_half_view:.4}, half light {e_half_light:.4}, double both {e_double:.4}"
    );
    assert!(e_default < 0.02, "{e_default}");
    assert!(e_double < e_default);
}

#[cfg(feature = "gpu")]
#[test]
fn gpu_frame_matches_the_cpu_twin() {
    use atmos::frame::FrameCamera;
    use atmos::gpu::single_scattering::render_single_scattering_pixel;
    use atmos::gpu::{FrameOutput, SingleScatteringRenderer};
    let Some(ctx) = skyscape_harness::gpu_or_skip("gpu_frame_matches_the_cpu_twin") else {
        return;
    };
    let earth = Atmosphere::earth();
    let settings = SingleScatteringSettings {
        view_samples: 16,
        light_samples: 4,
    };
    let parameters = earth.to_uniforms().unwrap();
    let (width, height) = (32, 18);
    let cameras = [
        // On the ground, looking at the horizon toward a low sun.
        FrameCamera::look_at(
            DVec3::new(0.0, 0.0, R + 2.0),
            DVec3::X,
            DVec3::Z,
            1.4,
            width,
            height,
            DVec3::new(0.99, 0.0, 0.14),
            None,
        )
        .unwrap(),
        // From 1,000 km, the limb with the sun beside it, and aerial perspective.
        FrameCamera::look_at(
            DVec3::new(0.0, 0.0, R + 1e6),
            DVec3::new(1.0, 0.0, -0.45),
            DVec3::Z,
            0.8,
            width,
            height,
            DVec3::Y,
            Some(2.5e6),
        )
        .unwrap(),
    ];
    let mut renderer = SingleScatteringRenderer::new(&ctx.device, &earth, settings).unwrap();
    let output = FrameOutput::new(&ctx.device, width, height).unwrap();
    for camera in cameras {
        renderer.prepare(&ctx.queue, &camera, &output).unwrap();
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder, None).unwrap();
        ctx.queue.submit([encoder.finish()]);
        let read = |texture: &wgpu::Texture| -> Vec<f32> {
            bytemuck::cast_slice(
                &skyscape_harness::read_texture(ctx, "single scattering frame", texture).unwrap(),
            )
            .to_vec()
        };
        let radiance = read(output.radiance());
        let transmittance = read(output.transmittance());
        let mut peak: f32 = 0.0;
        let mut cpu = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let s = render_single_scattering_pixel(&camera, &parameters, settings, [x, y]);
                peak = peak.max(s.radiance.iter().cloned().fold(0.0, f32::max));
                cpu.push(s);
            }
        }
        for (i, s) in cpu.iter().enumerate() {
            for k in 0..3 {
                let (g, c) = (radiance[4 * i + k], s.radiance[k]);
                // The WGSL exp (≤ 3 + 2|x| ULP) and normalize/length differ from Rust's
                // by a few ULP per sample; sums of ≤ 16 × 4 terms: 1e-3 relative,
                // plus 1e-4 of the frame's peak for pixels at the shadow/limb edges
                // where a 1-ULP change of mu flips a sample.
                assert!(
                    (g - c).abs() <= 1e-3 * c + 1e-4 * peak,
                    "pixel {i} channel {k}: gpu {g} cpu {c}"
                );
                let (g, c) = (transmittance[4 * i + k], s.transmittance[k]);
                assert!((g - c).abs() <= 1e-3 * c + 1e-5, "T pixel {i}: {g} vs {c}");
            }
        }
    }
}
