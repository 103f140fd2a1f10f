//! Rung 4 (the Reference) and ground irradiance: robustness at low settings, the
//! physics it must show, the last order's share, convergence (release only) and the
//! thin-atmosphere limit of the ground irradiance.

use std::sync::OnceLock;

use atmos::ground_irradiance::{HemisphereQuadrature, ground_irradiance};
use atmos::ladder::luminance;
use atmos::reference::{ReferenceSettings, ReferenceSky};
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{Atmosphere, SkyModel, SkyQuery, SkySample};
use glam::DVec3;

const R: f64 = 6_360_000.0;

fn direction(mu: f64, phi: f64) -> DVec3 {
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    DVec3::new(s * phi.cos(), s * phi.sin(), mu)
}

fn query(altitude: f64, view: DVec3, sun: DVec3, max: f64) -> SkyQuery {
    SkyQuery::with_max_distance(R, DVec3::new(0.0, 0.0, R + altitude), view, sun, max).unwrap()
}

fn low_earth() -> &'static ReferenceSky {
    static SKY: OnceLock<ReferenceSky> = OnceLock::new();
    SKY.get_or_init(|| ReferenceSky::new(&Atmosphere::earth(), ReferenceSettings::low()).unwrap())
}

fn check_sample(s: &SkySample, what: &str) {
    for k in 0..3 {
        assert!(
            s.radiance[k].is_finite() && s.radiance[k] >= 0.0,
            "{what}: {:?}",
            s.radiance
        );
        assert!(
            (0.0..=1.0).contains(&s.transmittance[k]),
            "{what}: {:?}",
            s.transmittance
        );
    }
}

#[test]
fn settings_are_validated_naming_the_field() {
    let bad = ReferenceSettings {
        scattering_orders: 3,
        ..ReferenceSettings::low()
    };
    let message = ReferenceSky::new(&Atmosphere::earth(), bad)
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("scattering_orders") && message.contains('3'),
        "{message}"
    );
    let bad_atmosphere = Atmosphere {
        mie_g: 1.0,
        ..Atmosphere::earth()
    };
    assert!(
        ReferenceSky::new(&bad_atmosphere, ReferenceSettings::low())
            .unwrap_err()
            .to_string()
            .contains("mie_g")
    );
}

#[test]
fn property_sweep_at_low_settings() {
    for (densities, g) in [(1.0, 0.8), (0.0, 0.0), (100.0, 0.9999), (3.0, -0.9999)] {
        let e = Atmosphere::earth();
        let atmosphere = Atmosphere {
            rayleigh_scattering: e.rayleigh_scattering.map(|b| b * densities),
            mie_scattering: e.mie_scattering.map(|b| b * densities),
            mie_extinction: e.mie_extinction.map(|b| b * densities),
            ozone_absorption: e.ozone_absorption.map(|b| b * densities),
            mie_g: g,
            ..e
        };
        let settings = ReferenceSettings {
            scattering_orders: 4,
            view_samples: 16,
            light_samples: 4,
            radius_size: 4,
            view_zenith_size: 6,
            sun_zenith_size: 5,
            azimuth_size: 3,
            sphere_zenith_size: 6,
            sphere_azimuth_size: 4,
            march_samples: 8,
            threads: 0,
        };
        let sky = ReferenceSky::new(&atmosphere, settings).unwrap();
        for altitude in [-10.0, 0.0, 1.0, 1e3, 99_999.0, 1e5, 100_001.0, 1e6, 1e7] {
            for mu in [-1.0, -0.5, -0.17, -0.1, -0.01, 0.0, 0.01, 0.3, 1.0] {
                for elevation in [-60.0f64, -6.0, 0.0, 5.0, 45.0, 90.0] {
                    let sun = direction(elevation.to_radians().sin(), 0.7);
                    let mut previous: Option<SkySample> = None;
                    for max in [1e3, 1e5, f64::INFINITY] {
                        let s = sky.evaluate(&query(altitude, direction(mu, 0.0), sun, max));
                        let what = format!(
                            "×{densities} g {g} h {altitude} mu {mu} sun {elevation} max {max}"
                        );
                        check_sample(&s, &what);
                        if let Some(p) = previous {
                            for k in 0..3 {
                                assert!(s.transmittance[k] <= p.transmittance[k], "{what}");
                                assert!(s.radiance[k] >= p.radiance[k] * (1.0 - 1e-9), "{what}");
                            }
                        }
                        previous = Some(s);
                    }
                }
            }
        }
    }
}

#[test]
fn multiple_scattering_adds_light_and_the_last_order_is_small() {
    let sky = low_earth();
    let sun = direction(30f64.to_radians().sin(), 0.0);
    for (mu, phi) in [(1.0, 0.0), (0.2, 1.0), (0.02, 3.0), (-0.5, 2.0)] {
        let q = query(10.0, direction(mu, phi), sun, f64::INFINITY);
        let (single, multiple, last) = sky.evaluate_orders(&q);
        for k in 0..3 {
            assert!(multiple[k] > 0.0 && single[k] > 0.0, "{mu}: {multiple:?}");
            // Multiple scattering is a correction (tens of % at most for Earth in daylight).
            assert!(multiple[k] < single[k], "{mu}: {single:?} {multiple:?}");
            assert!(
                last[k] < 0.05 * (single[k] + multiple[k]),
                "{mu}: last {last:?}"
            );
        }
    }
}

#[test]
fn hoffman_preetham_observations_hold_in_the_reference() {
    let earth = Atmosphere::earth();
    let clear = Atmosphere {
        mie_scattering: [0.0; 3],
        mie_extinction: [0.0; 3],
        ..earth.clone()
    };
    let clear_sky = ReferenceSky::new(&clear, ReferenceSettings::low()).unwrap();
    let s = clear_sky
        .evaluate(&query(1.0, DVec3::Z, DVec3::Z, f64::INFINITY))
        .radiance;
    assert!(s[2] > s[1] && s[1] > s[0], "{s:?}");
    let hazy = Atmosphere {
        mie_scattering: [4e-4; 3],
        mie_extinction: [4.4e-4; 3],
        ..earth
    };
    let hazy_sky = ReferenceSky::new(&hazy, ReferenceSettings::low()).unwrap();
    let h = hazy_sky
        .evaluate(&query(
            1.0,
            direction(0.5, 1.0),
            direction(0.9, 0.0),
            f64::INFINITY,
        ))
        .radiance;
    let max = h.iter().cloned().fold(0.0, f64::max);
    let min = h.iter().cloned().fold(f64::INFINITY, f64::min);
    assert!((max - min) / max < 0.35, "hazy {h:?}");
    let low_sun = direction(2f64.to_radians().sin(), 0.0);
    let s = low_earth()
        .evaluate(&query(
            1.0,
            direction(1f64.to_radians().sin(), 0.0),
            low_sun,
            f64::INFINITY,
        ))
        .radiance;
    assert!(s[0] > s[2], "toward the low sun {s:?}");
}

#[test]
fn reference_single_scattering_part_agrees_with_rung_2() {
    // The Reference's single scattering is rung 2's algorithm in f64 at higher counts:
    // at equal counts the two agree to f32 rounding.
    let earth = Atmosphere::earth();
    let rung2 = SingleScatteringSky::new(
        &earth,
        SingleScatteringSettings {
            view_samples: 64,
            light_samples: 16,
        },
    )
    .unwrap();
    let sun = direction(0.4, 0.0);
    for mu in [-0.3, 0.05, 0.5] {
        let q = query(500.0, direction(mu, 1.0), sun, f64::INFINITY);
        let (single, _, _) = low_earth().evaluate_orders(&q);
        let r2 = rung2.evaluate(&q).radiance;
        for k in 0..3 {
            assert!(
                (single[k] - r2[k]).abs() < 1e-4 * single[k],
                "{single:?} {r2:?}"
            );
        }
    }
}

#[test]
fn ground_irradiance_direct_and_sky() {
    let earth = Atmosphere::earth();
    let rung2 = SingleScatteringSky::new(&earth, SingleScatteringSettings::default()).unwrap();
    let here = DVec3::new(0.0, 0.0, R);
    let coarse = HemisphereQuadrature {
        zenith_cells: 6,
        azimuth_cells: 8,
    };
    // Sun below the horizon: no direct light; the twilight sky still glows a little.
    let night = ground_irradiance(&rung2, &earth, here, direction(-0.05, 0.0), coarse).unwrap();
    assert_eq!(night.direct, [0.0; 3]);
    // Daylight: sky ambient > 0 and bluer than the direct sun, for rung 2 and rung 4.
    let sun = direction(0.7, 0.0);
    for e in [
        ground_irradiance(&rung2, &earth, here, sun, coarse).unwrap(),
        ground_irradiance(low_earth(), &earth, here, sun, coarse).unwrap(),
    ] {
        for k in 0..3 {
            assert!(e.sky[k] > 0.0 && e.direct[k] > e.sky[k], "{e:?}");
        }
        assert!(e.sky[2] / e.direct[2] > e.sky[0] / e.direct[0], "{e:?}");
    }
    // Multiple scattering adds sky light.
    let e2 = ground_irradiance(&rung2, &earth, here, sun, coarse).unwrap();
    let e4 = ground_irradiance(low_earth(), &earth, here, sun, coarse).unwrap();
    assert!(luminance(e4.sky) > luminance(e2.sky), "{e2:?} {e4:?}");
    // Bad quadrature is an error naming the field.
    let bad = HemisphereQuadrature {
        zenith_cells: 0,
        azimuth_cells: 8,
    };
    let message = ground_irradiance(&rung2, &earth, here, sun, bad)
        .unwrap_err()
        .to_string();
    assert!(message.contains("zenith_cells"), "{message}");
}

/// f64 single scattering as a sky model (no precomputation), for the analytic limit.
struct F64SingleScattering(Atmosphere);

impl SkyModel for F64SingleScattering {
    fn label(&self) -> String {
        "f64 single scattering".into()
    }
    fn evaluate(&self, q: &SkyQuery) -> SkySample {
        atmos::reference::single_scattering(
            &self.0,
            q.r(),
            q.mu(),
            q.mu_s(),
            q.nu(),
            q.max_distance(),
            256,
            16,
        )
        .into()
    }
}

#[test]
fn ground_irradiance_thin_atmosphere_limit() {
    // Optically thin Rayleigh-only air over a planet 1000× Earth's radius (flat to
    // 1e−3 at the horizon), sun at the zenith: plane-parallel single scattering gives
    // E_sky = β ∫_{upper} p_R(cos θ) (H / cos θ) cos θ dω = β H / 2 (p_R is symmetric
    // front/back), and E_direct = e^{−βH}.
    let e = Atmosphere::earth();
    let planet_radius = 1000.0 * e.planet_radius;
    let thin = Atmosphere {
        planet_radius,
        top_radius: planet_radius + 150_000.0,
        rayleigh_scattering: e.rayleigh_scattering.map(|b| b * 1e-3),
        mie_scattering: [0.0; 3],
        mie_extinction: [0.0; 3],
        ozone_absorption: [0.0; 3],
        ..e
    };
    let got = ground_irradiance(
        &F64SingleScattering(thin.clone()),
        &thin,
        DVec3::new(0.0, 0.0, planet_radius),
        DVec3::Z,
        HemisphereQuadrature {
            zenith_cells: 32,
            azimuth_cells: 4,
        },
    )
    .unwrap();
    for k in 0..3 {
        let tau = thin.rayleigh_scattering[k] * thin.rayleigh_scale_height;
        let expected_sky = tau / 2.0;
        assert!(
            (got.sky[k] - expected_sky).abs() < 0.01 * expected_sky,
            "channel {k}: sky {} vs {expected_sky}",
            got.sky[k]
        );
        assert!((got.direct[k] - (-tau).exp()).abs() < 1e-3 * tau, "{got:?}");
    }
}

/// Mean relative luminance difference between two models over a fixed query set
/// (camera 0/1/10 km, sun elevations ≥ 5°).
fn mean_difference(a: &impl SkyModel, b: &impl SkyModel) -> f64 {
    let mut sum = 0.0;
    let mut n = 0;
    for altitude in [0.0, 1e3, 1e4] {
        for elevation in [5.0f64, 10.0, 30.0, 60.0, 90.0] {
            let sun = direction(elevation.to_radians().sin(), 0.0);
            for mu in [-0.5, -0.05, 0.02, 0.1, 0.3, 0.7, 1.0] {
                for phi in [0.0, 0.8, 1.6, 2.4, 3.1] {
                    let q = query(altitude, direction(mu, phi), sun, f64::INFINITY);
                    let la = luminance(a.evaluate(&q).radiance);
                    let lb = luminance(b.evaluate(&q).radiance);
                    if lb > 1e-7 {
                        sum += (la - lb).abs() / lb;
                        n += 1;
                    }
                }
            }
        }
    }
    sum / f64::from(n)
}

#[test]
fn reference_convergence() {
    if cfg!(debug_assertions) {
        eprintln!(
            "SKIPPED reference_convergence: release only (cargo test --release -p atmos --test reference)"
        );
        return;
    }
    let earth = Atmosphere::earth();
    let base = ReferenceSettings::default();
    let reference = ReferenceSky::new(&earth, base).unwrap();
    eprintln!(
        "default reference precomputation: {:.1} s",
        reference.precompute_seconds()
    );
    // The last order's share of the total at sun elevations ≥ 5°.
    let mut worst_last: f64 = 0.0;
    let mut mean_multiple = 0.0;
    let mut n = 0;
    for elevation in [5.0f64, 10.0, 30.0, 60.0, 90.0] {
        let sun = direction(elevation.to_radians().sin(), 0.0);
        for mu in [-0.5, 0.0, 0.02, 0.1, 0.3, 1.0] {
            for phi in [0.0, 1.6, 3.1] {
                let q = query(0.0, direction(mu, phi), sun, f64::INFINITY);
                let (single, multiple, last) = reference.evaluate_orders(&q);
                let total = luminance(single) + luminance(multiple);
                if total <= 0.0 {
                    // A camera on the ground looking down: an empty segment.
                    continue;
                }
                worst_last = worst_last.max(luminance(last) / total);
                mean_multiple += luminance(multiple) / total;
                n += 1;
            }
        }
    }
    eprintln!(
        "last order ({}) share: max {:.5}; orders ≥ 2 mean share {:.3}",
        base.scattering_orders,
        worst_last,
        mean_multiple / f64::from(n)
    );
    assert!(worst_last < 1e-3, "{worst_last}");
    let doubled = |name: &str, settings: ReferenceSettings| {
        let sky = ReferenceSky::new(&earth, settings).unwrap();
        let d = mean_difference(&sky, &reference);
        eprintln!(
            "doubling {name}: mean relative luminance change {:.5} (precompute {:.1} s)",
            d,
            sky.precompute_seconds()
        );
        d
    };
    let changes = [
        doubled(
            "query samples",
            ReferenceSettings {
                view_samples: 2 * base.view_samples,
                light_samples: 2 * base.light_samples,
                ..base
            },
        ),
        doubled(
            "source table",
            ReferenceSettings {
                radius_size: 2 * base.radius_size,
                view_zenith_size: 2 * base.view_zenith_size,
                sun_zenith_size: 2 * base.sun_zenith_size,
                azimuth_size: 2 * base.azimuth_size,
                ..base
            },
        ),
        doubled(
            "sphere directions and march samples",
            ReferenceSettings {
                sphere_zenith_size: 2 * base.sphere_zenith_size,
                sphere_azimuth_size: 2 * base.sphere_azimuth_size,
                march_samples: 2 * base.march_samples,
                ..base
            },
        ),
    ];
    for c in changes {
        assert!(c < 0.01, "{changes:?}");
    }
}
