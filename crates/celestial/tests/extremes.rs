//! Property tests at the extremes: poles, the date line, the span's ends, NaN.

use celestial::sidereal::{greenwich_apparent_sidereal_time, local_apparent_sidereal_time};
use celestial::{
    AirConditions, Angle, CelestialError, Instant, Observer, apparent_elevation,
    equatorial_to_horizontal, sun_position,
};
use proptest::prelude::*;

/// Seconds from 1950-01-01T00:00Z to 2101-01-01T00:00Z.
const SPAN_SECONDS: i64 = 4_765_132_800;
const SPAN_START_UNIX: i64 = -631_152_000;

fn instant_at(offset_s: i64) -> Instant {
    let utc = chrono::DateTime::from_timestamp(SPAN_START_UNIX + offset_s, 0).unwrap();
    Instant::from_utc(utc).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Anywhere, any time in the span: the sun's direction is finite, azimuth in
    /// [0°, 360°), elevation in [−90°, 90°], distance within 0.983–1.017 AU.
    #[test]
    fn sun_is_finite_everywhere(
        offset in prop_oneof![0..SPAN_SECONDS, Just(0), Just(SPAN_SECONDS - 1)],
        latitude in prop_oneof![-90.0..=90.0, Just(90.0), Just(-90.0)],
        longitude in prop_oneof![-180.0..=180.0, Just(180.0), Just(-180.0)],
        elevation_m in -500.0..=100_000.0,
    ) {
        let observer = Observer::new(
            Angle::from_degrees(latitude), Angle::from_degrees(longitude), elevation_m).unwrap();
        let sun = sun_position(&instant_at(offset), &observer).unwrap();
        let az = sun.airless.azimuth.degrees();
        let el = sun.airless.elevation.degrees();
        prop_assert!((0.0..360.0).contains(&az), "azimuth {az}");
        prop_assert!((-90.0..=90.0).contains(&el), "elevation {el}");
        let au = sun.distance_m / celestial::sun::ASTRONOMICAL_UNIT_M;
        prop_assert!((0.983..1.017).contains(&au), "{au}");
        let apparent = apparent_elevation(sun.airless.elevation, &AirConditions::REFERENCE).degrees();
        // Refraction is largest just above SPA's cutoff: 37.1′ = 0.618° at h = −0.8333°.
        prop_assert!(apparent >= el && apparent - el < 0.62, "{el} → {apparent}");
    }

    /// At a pole the sun's elevation is its declination (± parallax): the sky turns
    /// about the zenith, whatever the longitude.
    #[test]
    fn at_the_poles_elevation_is_declination(
        offset in 0..SPAN_SECONDS,
        longitude in -180.0..=180.0,
        north in any::<bool>(),
    ) {
        let sign = if north { 1.0 } else { -1.0 };
        let observer = Observer::new(
            Angle::from_degrees(90.0 * sign), Angle::from_degrees(longitude), 0.0).unwrap();
        let sun = sun_position(&instant_at(offset), &observer).unwrap();
        let expected = sign * sun.declination.degrees();
        prop_assert!((sun.airless.elevation.degrees() - expected).abs() < 0.003);
    }

    /// The date line: +180° and −180° are the same meridian, so sidereal time and the
    /// sun agree there.
    #[test]
    fn date_line_is_one_meridian(offset in 0..SPAN_SECONDS, latitude in -89.0..=89.0) {
        let instant = instant_at(offset);
        let east = Observer::new(Angle::from_degrees(latitude), Angle::from_degrees(180.0), 0.0).unwrap();
        let west = Observer::new(Angle::from_degrees(latitude), Angle::from_degrees(-180.0), 0.0).unwrap();
        let diff = (local_apparent_sidereal_time(&instant, &east)
            - local_apparent_sidereal_time(&instant, &west)).wrapped_signed().degrees();
        prop_assert!(diff.abs() < 1e-9);
        let a = sun_position(&instant, &east).unwrap().airless;
        let b = sun_position(&instant, &west).unwrap().airless;
        prop_assert!((a.elevation - b.elevation).degrees().abs() < 1e-9);
        prop_assert!((a.azimuth - b.azimuth).wrapped_signed().degrees().abs() < 1e-7);
    }

    /// Sidereal time is finite and in [0, 2π) over the span.
    #[test]
    fn sidereal_time_in_range(offset in prop_oneof![0..SPAN_SECONDS, Just(0), Just(SPAN_SECONDS - 1)]) {
        let gast = greenwich_apparent_sidereal_time(&instant_at(offset)).radians();
        prop_assert!((0.0..std::f64::consts::TAU).contains(&gast));
    }

    /// The transform keeps elevation within ±90° and is finite for all finite angles,
    /// in f64 and in the f32 twin.
    #[test]
    fn transform_is_finite(h in -10.0f64..10.0, d in -1.6f64..1.6, p in -1.6f64..1.6) {
        let [az, el] = equatorial_to_horizontal(h, d, p);
        prop_assert!(az.is_finite() && (0.0..=std::f64::consts::TAU).contains(&az));
        prop_assert!(el.abs() <= std::f64::consts::FRAC_PI_2 + 1e-15);
        let [az32, el32] = equatorial_to_horizontal(h as f32, d as f32, p as f32);
        prop_assert!(az32.is_finite() && el32.is_finite());
    }

    /// Latitudes beyond the poles are rejected, never clamped.
    #[test]
    fn out_of_range_latitude_is_an_error(excess in 1e-9f64..1e6, north in any::<bool>()) {
        let latitude = if north { 90.0 + excess } else { -90.0 - excess };
        let result = Observer::new(Angle::from_degrees(latitude), Angle::ZERO, 0.0);
        let rejected = matches!(result, Err(CelestialError::OutOfRange { field: "latitude", .. }));
        prop_assert!(rejected);
    }
}

#[test]
fn nan_inputs_are_typed_errors() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let a = Angle::from_degrees(bad);
        assert!(matches!(
            Observer::new(a, Angle::ZERO, 0.0),
            Err(CelestialError::NotFinite {
                field: "latitude",
                ..
            })
        ));
        assert!(matches!(
            Observer::new(Angle::ZERO, a, 0.0),
            Err(CelestialError::NotFinite {
                field: "longitude",
                ..
            })
        ));
        assert!(matches!(
            Observer::new(Angle::ZERO, Angle::ZERO, bad),
            Err(CelestialError::NotFinite {
                field: "elevation_m",
                ..
            })
        ));
    }
}

#[test]
fn span_ends() {
    assert!(Instant::parse("1950-01-01T00:00:00Z").is_ok());
    assert!(Instant::parse("2100-12-31T23:59:59.999999999Z").is_ok());
    for outside in [
        "1949-12-31T23:59:59.999Z",
        "2101-01-01T00:00:00Z",
        "1900-06-01T00:00:00Z",
    ] {
        let error = Instant::parse(outside).unwrap_err();
        assert!(
            matches!(
                error,
                CelestialError::OutsideSpan {
                    field: "instant",
                    ..
                }
            ),
            "{outside}"
        );
    }
}

/// The sun exactly at the zenith and at the nadir: δ = φ on the meridian gives 90°,
/// the antimeridian with δ = −φ gives −90°, with a finite azimuth either way.
#[test]
fn zenith_and_nadir_are_finite() {
    for lat in [-89.0, -23.44, 0.0, 23.44, 60.0] {
        let phi = Angle::from_degrees(lat);
        let up = celestial::Horizontal::from_equatorial(Angle::ZERO, phi, phi);
        assert!((up.elevation.degrees() - 90.0).abs() < 1e-12 && up.azimuth.is_finite());
        let down = celestial::Horizontal::from_equatorial(Angle::from_degrees(180.0), -phi, phi);
        assert!((down.elevation.degrees() + 90.0).abs() < 1e-9 && down.azimuth.is_finite());
    }
    // A real instant with the sun near the zenith: 2024-03-20 ~12:07 UTC at the
    // equator on the Greenwich meridian (equinox; equation of time −7 min).
    let observer = Observer::new(Angle::ZERO, Angle::ZERO, 0.0).unwrap();
    let sun = sun_position(&Instant::parse("2024-03-20T12:07:00Z").unwrap(), &observer).unwrap();
    assert!(sun.airless.elevation.degrees() > 89.5 && sun.airless.azimuth.is_finite());
}

/// Perigee and apogee: over a 15-month sweep (several anomalistic months) the moon's
/// topocentric angular radius spans the published extremes (geocentric 0.2448° at
/// apogee 406 700 km to 0.2793° at perigee 356 400 km; the observer's 6 378 km offset
/// changes it by up to +1.8 % with the moon overhead and −1.6 % with it at the nadir:
/// 0.2410°…0.2844°) and never leaves them.
#[test]
fn moon_at_perigee_and_apogee() {
    let observer =
        Observer::new(Angle::from_degrees(10.0), Angle::from_degrees(20.0), 0.0).unwrap();
    let (mut smallest, mut largest) = (f64::INFINITY, 0.0_f64);
    for hour in (0..24 * 460).step_by(3) {
        let unix = 1_704_067_200 + i64::from(hour) * 3600;
        let instant =
            Instant::from_utc(chrono::DateTime::from_timestamp(unix, 0).unwrap()).unwrap();
        let moon = celestial::moon_position(&instant, &observer).unwrap();
        let radius = moon.angular_radius.degrees();
        smallest = smallest.min(radius);
        largest = largest.max(radius);
    }
    println!("moon angular radius {smallest:.4}..{largest:.4} deg");
    assert!(smallest > 0.2405 && smallest < 0.2470, "{smallest}");
    assert!(largest > 0.2780 && largest < 0.2850, "{largest}");
}
