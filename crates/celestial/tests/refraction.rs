//! Refraction is one step for every body: the moon, a planet and a star caught on the
//! horizon as they rise are lifted exactly as the sun would be at that airless
//! elevation, by the ~34′ that makes a body whose airless elevation is −0.573° appear
//! on the horizon (Sæmundsson, reference air 1010 hPa, 10 °C).

use celestial::refraction::{AirConditions, apparent_direction, refraction};
use celestial::{
    Angle, Horizontal, Instant, Observer, Planet, StarCatalogue, SunPosition, moon_position,
    planet_position, sun_position,
};

/// The airless elevation h with h + R(h) = 0 in the reference air (bisection).
fn horizon_airless_elevation(air: &AirConditions) -> Angle {
    let (mut low, mut high) = (-0.8_f64, 0.0_f64);
    for _ in 0..60 {
        let mid = 0.5 * (low + high);
        let apparent = mid + refraction(Angle::from_degrees(mid), air).degrees();
        if apparent < 0.0 {
            low = mid;
        } else {
            high = mid;
        }
    }
    Angle::from_degrees(0.5 * (low + high))
}

/// The instant within `[start, start + 1 day)` at which `airless(t)` rises through
/// `target` (bisection between a sample below and the next above, 1-minute grid).
fn rising_through(
    start: &Instant,
    target: Angle,
    airless: impl Fn(&Instant) -> Horizontal,
) -> Instant {
    let at = |seconds: f64| {
        Instant::from_utc(start.utc() + chrono::Duration::milliseconds((seconds * 1e3) as i64))
            .unwrap()
    };
    let above = |seconds: f64| airless(&at(seconds)).elevation > target;
    let mut low = (0..1440)
        .map(|minute| f64::from(minute) * 60.0)
        .find(|&s| !above(s) && above(s + 60.0))
        .expect("the body rises within the day");
    let mut high = low + 60.0;
    for _ in 0..30 {
        let mid = 0.5 * (low + high);
        if above(mid) {
            high = mid;
        } else {
            low = mid;
        }
    }
    at(high)
}

#[test]
fn every_body_on_the_horizon_is_lifted_as_the_sun() {
    let air = AirConditions::REFERENCE;
    let horizon = horizon_airless_elevation(&air);
    // Sæmundsson: R(−0.5732°) = 1.02′/tan(1.6987°) = 34.39′.
    assert!((horizon.degrees() + 0.5732).abs() < 1e-3, "{horizon:?}");
    let observer = Observer::new(Angle::from_degrees(52.0), Angle::from_degrees(5.0), 0.0).unwrap();
    let start = Instant::parse("2024-03-10T00:00:00Z").unwrap();
    let catalogue = StarCatalogue::hipparcos(2.0).unwrap();
    let sirius = |instant: &Instant| {
        catalogue
            .sky(instant, &observer)
            .into_iter()
            .find(|s| s.hip == 32_349)
            .unwrap()
    };
    let moon = |i: &Instant| moon_position(i, &observer).unwrap();
    let jupiter = |i: &Instant| planet_position(Planet::Jupiter, i, &observer).unwrap();

    let t = rising_through(&start, horizon, |i| moon(i).airless);
    let moon_now = moon(&t);
    let t = rising_through(&start, horizon, |i| jupiter(i).airless);
    let jupiter_now = jupiter(&t);
    let t = rising_through(&start, horizon, |i| sirius(i).airless);
    let sirius_now = sirius(&t);
    let sun_now = sun_position(&t, &observer).unwrap();
    for (body, airless, apparent) in [
        ("moon", moon_now.airless, moon_now.apparent(&air)),
        ("Jupiter", jupiter_now.airless, jupiter_now.apparent(&air)),
        ("Sirius", sirius_now.airless, sirius_now.apparent(&air)),
    ] {
        // The sun, were it at this airless direction.
        let sun = SunPosition { airless, ..sun_now }.apparent(&air);
        let lift = (apparent.elevation - airless.elevation).degrees();
        println!(
            "{body}: airless {:.5}°, apparent {:.5}°, lifted {lift:.4}°",
            airless.elevation.degrees(),
            apparent.elevation.degrees()
        );
        assert_eq!(apparent, sun, "{body}");
        assert_eq!(apparent, apparent_direction(airless, &air), "{body}");
        assert_eq!(apparent.azimuth, airless.azimuth, "{body}");
        assert!(
            apparent.elevation.degrees().abs() < 1e-3,
            "{body}: {apparent:?}"
        );
        assert!((lift - 0.5732).abs() < 1e-3, "{body}: {lift}");
    }
}
