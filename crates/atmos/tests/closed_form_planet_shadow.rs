//! The closed form's planet shadow: points along the view path that are in the planet's
//! shadow get no sunlight. Lighting the whole path with the sunlight at the camera would
//! show a camera high above the terminator looking down at the night side (sun at 0°)
//! a lit night. Measured against the single-scattering
//! rung, which lights each sample only where the sun is above its horizon.

use atmos::closed_form_sky::{ClosedFormSky, closed_form_shadow_interval};
use atmos::ladder::luminance;
use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
use atmos::{Atmosphere, SkyModel, SkyQuery};
use glam::DVec3;

/// Cameras high enough to see ground 10° into the night (more than 98 km up), where the
/// shadow covers the whole air column (up to 6,360 km·(1/cos 10° − 1) = 98 km).
const ALTITUDES_KM: [f64; 5] = [150.0, 300.0, 1_000.0, 3_000.0, 10_000.0];

/// A camera above (0, 0) with the sun on its horizon along +x, looking at the ground
/// point `angle_deg` (planet-centred) from the point below it towards −x, the night
/// side (the sun `angle_deg` below that point's horizon), or towards +x, the day side.
fn query(atmosphere: &Atmosphere, altitude_km: f64, angle_deg: f64, night: bool) -> SkyQuery {
    let camera = DVec3::new(0.0, 0.0, atmosphere.planet_radius + altitude_km * 1e3);
    let (sin, cos) = angle_deg.to_radians().sin_cos();
    let toward = if night { -1.0 } else { 1.0 };
    let ground = atmosphere.planet_radius * DVec3::new(toward * sin, 0.0, cos);
    SkyQuery::new(
        atmosphere.planet_radius,
        camera,
        (ground - camera).normalize(),
        DVec3::X,
    )
    .unwrap()
}

#[test]
fn the_night_side_is_dark_at_every_altitude() {
    let atmosphere = Atmosphere::earth();
    let closed = ClosedFormSky::new(&atmosphere).unwrap();
    let single = SingleScatteringSky::new(
        &atmosphere,
        SingleScatteringSettings {
            view_samples: 256,
            light_samples: 32,
        },
    )
    .unwrap();
    let mut worst: f64 = 0.0;
    for altitude_km in ALTITUDES_KM {
        let r = atmosphere.planet_radius + altitude_km * 1e3;
        let visible = (atmosphere.planet_radius / r).acos().to_degrees();
        for angle in [10.0, 20.0, 40.0, 0.9 * visible] {
            if angle >= visible {
                continue;
            }
            let night = query(&atmosphere, altitude_km, angle, true);
            let day = query(&atmosphere, altitude_km, angle, false);
            let closed_night = luminance(closed.evaluate(&night).radiance);
            let closed_day = luminance(closed.evaluate(&day).radiance);
            let single_night = luminance(single.evaluate(&night).radiance);
            let single_day = luminance(single.evaluate(&day).radiance);
            let fraction = closed_night / closed_day;
            eprintln!(
                "{altitude_km} km, ground {angle:.1}° into the night: {closed_night:.3e} = \
                 {fraction:.4} of the day side (single scattering {single_night:.3e} = {:.4})",
                single_night / single_day
            );
            // Dark: under 1 % of the day side's light (single scattering: < 0.3 %).
            worst = worst.max(fraction);
            assert!(
                fraction < 0.01,
                "{altitude_km} km, ground {angle:.1}° into the night is lit: {closed_night:e} \
                 = {fraction:.3} of the day side's {closed_day:e} (single scattering: {:.4})",
                single_night / single_day
            );
        }
    }
    eprintln!("night side / day side, worst: {worst:.4}");
}

/// The shadow interval against a direct test of sample points: inside the cylinder
/// behind the planet exactly where the interval says (away from its ends).
#[test]
fn the_shadow_interval_is_where_the_points_are_in_shadow() {
    let planet = 6_360_000.0f64;
    let mut checked = 0;
    for altitude in [0.0, 1.0, 1e4, 1e5, 1e6, 1e7] {
        let r = planet + altitude;
        for i in 0..=20 {
            let mu = -1.0 + 0.1 * f64::from(i);
            for j in 0..=12 {
                let mu_s = -0.6 + 0.1 * f64::from(j);
                for k in 0..8 {
                    let phi = std::f64::consts::PI * f64::from(k) / 7.0;
                    let view = DVec3::new(
                        (1.0 - mu * mu).sqrt() * phi.cos(),
                        (1.0 - mu * mu).sqrt() * phi.sin(),
                        mu,
                    );
                    let sun = DVec3::new((1.0 - mu_s * mu_s).sqrt(), 0.0, mu_s);
                    let nu = view.dot(sun);
                    let [t_in, t_out] = closed_form_shadow_interval(r, mu, mu_s, nu, planet);
                    assert!(0.0 <= t_in && t_in <= t_out, "{t_in} {t_out}");
                    for step in 0..200 {
                        let t = 50_000.0 * f64::from(step);
                        if (t - t_in).abs() < 1.0 || (t - t_out).abs() < 1.0 {
                            continue;
                        }
                        let p = DVec3::new(0.0, 0.0, r) + t * view;
                        let along = p.dot(sun);
                        let shadowed = along < 0.0 && (p - along * sun).length() < planet;
                        let inside = t > t_in && t < t_out;
                        assert_eq!(
                            shadowed, inside,
                            "r {r}, mu {mu}, mu_s {mu_s}, phi {phi}: t {t} in [{t_in}, {t_out}]"
                        );
                        checked += 1;
                    }
                }
            }
        }
    }
    assert!(checked > 1_000_000);
}
