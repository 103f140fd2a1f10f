//! The topocentric moon against an independent ephemeris over 1950–2100: 200 instants
//! and observers (poles and the date line included) from astropy 8.0.1's builtin
//! ephemeris (ERFA moon98 = Meeus ch. 47 in full; IAU 2006/2000A precession-nutation).
//! How the table was made: `tests/data/moon_reference.py`.

use celestial::{Angle, Instant, Observer, moon_position};

/// Great-circle angle between two (azimuth, elevation) directions, degrees.
fn separation_deg(az1: f64, el1: f64, az2: f64, el2: f64) -> f64 {
    let (az1, el1, az2, el2) = (
        az1.to_radians(),
        el1.to_radians(),
        az2.to_radians(),
        el2.to_radians(),
    );
    let h = ((el2 - el1) / 2.0).sin().powi(2)
        + el1.cos() * el2.cos() * ((az2 - az1) / 2.0).sin().powi(2);
    (2.0 * h.sqrt().min(1.0).asin()).to_degrees()
}

#[test]
fn topocentric_moon_within_0_2_degrees_1950_2100() {
    let table = include_str!("data/moon_reference.csv");
    let (mut worst, mut sum_sq, mut n, mut worst_distance) = (0.0_f64, 0.0, 0, 0.0_f64);
    for line in table.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let num = |i: usize| f[i].parse::<f64>().unwrap();
        let instant = Instant::parse(f[0]).unwrap();
        let observer = Observer::new(
            Angle::from_degrees(num(1)),
            Angle::from_degrees(num(2)),
            num(3),
        )
        .unwrap();
        let moon = moon_position(&instant, &observer).unwrap();
        let sep = separation_deg(
            moon.airless.azimuth.degrees(),
            moon.airless.elevation.degrees(),
            num(4),
            num(5),
        );
        worst = worst.max(sep);
        sum_sq += sep * sep;
        n += 1;
        let rel = (moon.topocentric.distance_m / 1e3 - num(6)).abs() / num(6);
        worst_distance = worst_distance.max(rel);
    }
    let rms = (sum_sq / f64::from(n)).sqrt();
    println!(
        "moon vs astropy ({n} cases): max {worst:.4} deg, rms {rms:.4} deg, distance max rel {worst_distance:.2e}"
    );
    assert_eq!(n, 200);
    assert!(worst < 0.2, "{worst}");
    // The distance drives the angular size: 0.5 % is 0.0025° on a 0.5° disc.
    assert!(worst_distance < 5e-3, "{worst_distance}");
}

/// Parallax: seen from the surface the moon is lower than from the centre by up to
/// ~1° (horizontal parallax 0.9–1.0°), and its topocentric distance is shorter when
/// it is high.
#[test]
fn parallax_lowers_the_moon() {
    let instant = Instant::parse("2024-03-25T06:00:00Z").unwrap();
    for lat in [-60.0, 0.0, 45.0, 89.0] {
        for lon in [-150.0, -30.0, 60.0, 170.0] {
            let observer =
                Observer::new(Angle::from_degrees(lat), Angle::from_degrees(lon), 0.0).unwrap();
            let moon = moon_position(&instant, &observer).unwrap();
            let shift = (moon.geocentric.right_ascension - moon.topocentric.right_ascension)
                .wrapped_signed()
                .degrees()
                .abs()
                .max(
                    (moon.geocentric.declination - moon.topocentric.declination)
                        .degrees()
                        .abs(),
                );
            assert!(shift < 1.05, "{shift}");
            let radius = moon.angular_radius.degrees();
            assert!((0.24..0.28).contains(&radius), "{radius}");
            assert!((0.0..=1.0).contains(&moon.phase.illuminated_fraction));
        }
    }
}

/// The drawing builds the moon's lighting in 3-D (the direction from the moon to the
/// sun in the observer's east/north/up frame, `MoonLight::toward_sun`); Meeus ch. 48
/// gives the phase angle i and the bright limb χ from right ascensions and
/// declinations, and χ − q its tilt from the zenith. The two agree over a lunation
/// every 7 h, at three latitudes (both hemispheres).
#[test]
fn three_dimensional_lighting_matches_meeus_phase_and_bright_limb_tilt() {
    use celestial::{LuminanceScale, MoonLight, sun_position};
    let atmosphere = atmos::Atmosphere::earth();
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let reject = |a: [f64; 3], m: [f64; 3]| {
        let d = dot(a, m);
        [a[0] - d * m[0], a[1] - d * m[1], a[2] - d * m[2]]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let (mut worst_phase, mut worst_tilt, mut checked) = (0.0_f64, 0.0_f64, 0);
    for lat in [-45.0, 10.0, 60.0] {
        let observer =
            Observer::new(Angle::from_degrees(lat), Angle::from_degrees(20.0), 0.0).unwrap();
        for step in 0..100 {
            let start = Instant::parse("2024-04-01T00:00:00Z").unwrap();
            let utc = start.utc() + chrono::Duration::hours(7 * step);
            let instant = Instant::from_utc(utc).unwrap();
            let sun = sun_position(&instant, &observer).unwrap();
            let moon = moon_position(&instant, &observer).unwrap();
            let scale = LuminanceScale::new(&atmosphere, sun.distance_m).unwrap();
            let light = MoonLight::new(&moon, &sun, &atmosphere, &scale).unwrap();
            let m = light.direction;
            let phase = dot(light.toward_sun, m.map(|c| -c))
                .clamp(-1.0, 1.0)
                .acos()
                .to_degrees();
            worst_phase = worst_phase.max((phase - moon.phase.phase_angle.degrees()).abs());
            let i = moon.phase.phase_angle.degrees();
            if !(10.0..170.0).contains(&i) {
                continue;
            }
            let pole = [0.0, observer.latitude().cos(), observer.latitude().sin()];
            let north = reject(pole, m);
            let east = cross(north, m);
            let position_angle = |d: [f64; 3]| {
                let d = reject(d, m);
                dot(d, east).atan2(dot(d, north))
            };
            let tilt = position_angle(light.toward_sun) - position_angle([0.0, 0.0, 1.0]);
            let diff = (Angle::from_radians(tilt) - moon.bright_limb_from_zenith())
                .wrapped_signed()
                .degrees();
            worst_tilt = worst_tilt.max(diff.abs());
            checked += 1;
        }
    }
    println!(
        "3-D lighting vs Meeus 48: phase angle max {worst_phase:.4}°, tilt max {worst_tilt:.4}° ({checked} cases)"
    );
    assert!(checked > 200);
    // Both use the same topocentric moon; Meeus' i and χ use the sun's geocentric place
    // (8.8″ of parallax) and an exact formula, so they agree to rounding plus that.
    assert!(worst_phase < 0.01, "{worst_phase}");
    assert!(worst_tilt < 0.05, "{worst_tilt}");
}
