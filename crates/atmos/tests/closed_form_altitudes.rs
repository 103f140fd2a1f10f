//! The closed form at any camera altitude: a homogeneous shell `H_R` thick would give a
//! camera at 7.9 km or higher a black sky over a bright lower half. Measured here against the single-scattering rung (which integrates the exact
//! exponential profiles) at 0, 5, 8, 10, 50 and 1,000 km.

use atmos::closed_form_sky::ClosedFormSky;
use atmos::ladder::luminance;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{Atmosphere, SkyModel, SkyQuery};
use glam::DVec3;

const ALTITUDES_KM: [f64; 6] = [0.0, 5.0, 8.0, 10.0, 50.0, 1_000.0];

fn direction(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

#[test]
fn closed_form_follows_single_scattering_at_every_altitude() {
    let atmosphere = Atmosphere::earth();
    let closed = ClosedFormSky::new(&atmosphere).unwrap();
    let single = SingleScatteringSky::new(
        &atmosphere,
        SingleScatteringSettings {
            view_samples: 64,
            light_samples: 16,
        },
    )
    .unwrap();
    let sun = direction(30.0, 60.0);
    let (mut lowest, mut highest) = (f64::MAX, 0.0f64);
    for altitude_km in ALTITUDES_KM {
        let r = atmosphere.planet_radius + altitude_km * 1_000.0;
        let dip = -(atmosphere.planet_radius / r).acos().to_degrees();
        // Up, along the horizon, just above and below the geometric horizon, down.
        for elevation in [60.0, 20.0, 0.0, dip + 0.5, dip - 0.5, -30.0, -89.0] {
            let query = SkyQuery::new(
                atmosphere.planet_radius,
                DVec3::new(0.0, 0.0, r),
                direction(elevation, 0.0),
                sun,
            )
            .unwrap();
            let expected = luminance(single.evaluate(&query).radiance);
            let got = luminance(closed.evaluate(&query).radiance);
            if expected < 1e-4 {
                // Above the air looking away from it: both (nearly) black.
                assert!(
                    got < 1e-4,
                    "{altitude_km} km, {elevation:.2}°: closed form {got:e}, single {expected:e}"
                );
                continue;
            }
            let ratio = got / expected;
            lowest = lowest.min(ratio);
            highest = highest.max(ratio);
            assert!(
                (0.5..2.0).contains(&ratio),
                "{altitude_km} km, elevation {elevation:.2}°: closed form {got:e} vs single \
                 scattering {expected:e} (ratio {ratio:.3})"
            );
        }
    }
    eprintln!("closed form / single scattering luminance: {lowest:.3} … {highest:.3}");
}
