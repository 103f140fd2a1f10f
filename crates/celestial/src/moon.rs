//! The moon's position: P. Schlyter's method ("How to compute planetary positions":
//! osculating-style mean elements of date plus the 12 largest longitude, 5 latitude
//! and 2 distance perturbation terms — evection, variation, the yearly and
//! parallactic equations, …), stated good to 1–2′. Then nutation in longitude, the
//! true obliquity, and the observer's parallax (Meeus ch. 40, up to ~1°), which is
//! what separates the topocentric moon from the geocentric one.
//!
//! Measured against Meeus Example 47.a (his full ELP-2000/82 truncation): see the
//! tests and `docs/celestial-methods.md`.

use std::f64::consts::TAU;

use crate::angle::Angle;
use crate::error::Result;
use crate::horizontal::{Horizontal, parallactic_angle};
use crate::moon_phase::{EquatorialPlace, MoonPhase, moon_phase};
use crate::observer::Observer;
use crate::refraction::{AirConditions, apparent_direction};
use crate::sidereal::{local_apparent_sidereal_time, nutation, true_obliquity};
use crate::time::Instant;

/// Earth's equatorial radius (m), the unit of the moon's mean distance below.
pub const EARTH_EQUATORIAL_RADIUS_M: f64 = 6_378_140.0;
/// WGS 84-like polar/equatorial axis ratio b/a (SPA's value).
const EARTH_AXIS_RATIO: f64 = 0.996_647_19;
/// The moon's mean radius (m, IAU).
pub const MOON_RADIUS_M: f64 = 1_737_400.0;
/// Schlyter's day 0: 1999-12-31T00:00 (JD 2451543.5).
const SCHLYTER_EPOCH_JULIAN_DAY: f64 = 2_451_543.5;

/// Geocentric ecliptic place of the moon, mean equinox of date.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EclipticPlace {
    /// Ecliptic longitude.
    pub longitude: Angle,
    /// Ecliptic latitude.
    pub latitude: Angle,
    /// Distance from the Earth's centre (m).
    pub distance_m: f64,
}

fn degrees(d: f64) -> f64 {
    d.to_radians()
}

/// The moon's geocentric ecliptic place (mean equinox of date) at `julian_day_tt`.
pub fn moon_ecliptic(julian_day_tt: f64) -> EclipticPlace {
    let d = julian_day_tt - SCHLYTER_EPOCH_JULIAN_DAY;
    // Moon's elements (degrees, Earth radii).
    let node = degrees(125.1228 - 0.052_953_808_3 * d);
    let inclination = degrees(5.1454);
    let perigee = degrees(318.0634 + 0.164_357_322_3 * d);
    let a = 60.2666;
    let e = 0.054_900;
    let mean_anomaly = degrees(115.3654 + 13.064_992_950_9 * d).rem_euclid(TAU);
    // The sun's mean anomaly and argument of perihelion.
    let sun_anomaly = degrees(356.0470 + 0.985_600_258_5 * d).rem_euclid(TAU);
    let sun_perihelion = degrees(282.9404 + 4.709_35e-5 * d);

    // Kepler's equation by Newton iteration (e = 0.055 converges in a few steps).
    let mut eccentric = mean_anomaly + e * mean_anomaly.sin() * (1.0 + e * mean_anomaly.cos());
    for _ in 0..6 {
        eccentric -= (eccentric - e * eccentric.sin() - mean_anomaly) / (1.0 - e * eccentric.cos());
    }
    let xv = a * (eccentric.cos() - e);
    let yv = a * (1.0 - e * e).sqrt() * eccentric.sin();
    let true_anomaly = yv.atan2(xv);
    let r = xv.hypot(yv);
    let (sin_n, cos_n) = node.sin_cos();
    let (sin_u, cos_u) = (true_anomaly + perigee).sin_cos();
    let xh = r * (cos_n * cos_u - sin_n * sin_u * inclination.cos());
    let yh = r * (sin_n * cos_u + cos_n * sin_u * inclination.cos());
    let zh = r * sin_u * inclination.sin();
    let mut longitude = yh.atan2(xh);
    let mut latitude = zh.atan2(xh.hypot(yh));
    let mut distance = r;

    // Perturbations (Schlyter): arguments from mean longitudes and anomalies.
    let sun_longitude = sun_anomaly + sun_perihelion;
    let moon_longitude = mean_anomaly + perigee + node;
    let elongation = moon_longitude - sun_longitude;
    let latitude_argument = moon_longitude - node;
    let (m, ms, dd, f) = (mean_anomaly, sun_anomaly, elongation, latitude_argument);
    let longitude_terms: [(f64, f64); 12] = [
        (-1.274, m - 2.0 * dd), // evection
        (0.658, 2.0 * dd),      // variation
        (-0.186, ms),           // yearly equation
        (-0.059, 2.0 * m - 2.0 * dd),
        (-0.057, m - 2.0 * dd + ms),
        (0.053, m + 2.0 * dd),
        (0.046, 2.0 * dd - ms),
        (0.041, m - ms),
        (-0.035, dd), // parallactic equation
        (-0.031, m + ms),
        (-0.015, 2.0 * f - 2.0 * dd),
        (0.011, m - 4.0 * dd),
    ];
    longitude += longitude_terms
        .iter()
        .map(|&(amplitude, argument)| degrees(amplitude) * argument.sin())
        .sum::<f64>();
    let latitude_terms: [(f64, f64); 5] = [
        (-0.173, f - 2.0 * dd),
        (-0.055, m - f - 2.0 * dd),
        (-0.046, m + f - 2.0 * dd),
        (0.033, f + 2.0 * dd),
        (0.017, 2.0 * m + f),
    ];
    latitude += latitude_terms
        .iter()
        .map(|&(amplitude, argument)| degrees(amplitude) * argument.sin())
        .sum::<f64>();
    distance += -0.58 * (m - 2.0 * dd).cos() - 0.46 * (2.0 * dd).cos();

    EclipticPlace {
        longitude: Angle::from_radians(longitude).wrapped_positive(),
        latitude: Angle::from_radians(latitude),
        distance_m: distance * EARTH_EQUATORIAL_RADIUS_M,
    }
}

/// Ecliptic (λ, β) → equatorial (α, δ) for obliquity ε (Meeus eqs. 13.3, 13.4).
pub fn ecliptic_to_equatorial(
    longitude: Angle,
    latitude: Angle,
    obliquity: Angle,
) -> (Angle, Angle) {
    let (sin_l, cos_l) = longitude.radians().sin_cos();
    let (sin_b, cos_b) = latitude.radians().sin_cos();
    let (sin_e, cos_e) = obliquity.radians().sin_cos();
    let right_ascension = (sin_l * cos_b * cos_e - sin_b * sin_e).atan2(cos_l * cos_b);
    let declination = (sin_b * cos_e + cos_b * sin_e * sin_l)
        .clamp(-1.0, 1.0)
        .asin();
    (
        Angle::from_radians(right_ascension).wrapped_positive(),
        Angle::from_radians(declination),
    )
}

/// The observer's geocentric position factors ρ·sin φ′ and ρ·cos φ′ (Meeus ch. 11),
/// in Earth equatorial radii.
fn geocentric_factors(observer: &Observer) -> (f64, f64) {
    let latitude = observer.latitude().radians();
    let u = (EARTH_AXIS_RATIO * latitude.tan()).atan();
    let height = observer.elevation_m() / EARTH_EQUATORIAL_RADIUS_M;
    (
        EARTH_AXIS_RATIO * u.sin() + height * latitude.sin(),
        u.cos() + height * latitude.cos(),
    )
}

/// Geocentric → topocentric place (Meeus eqs. 40.2, 40.3, exact form): the parallax
/// of a body at `place` seen from `observer` at local hour angle `hour_angle`.
/// Returns the topocentric place and its topocentric hour angle.
pub fn topocentric(
    place: &EquatorialPlace,
    hour_angle: Angle,
    observer: &Observer,
) -> (EquatorialPlace, Angle) {
    let (rho_sin, rho_cos) = geocentric_factors(observer);
    let sin_parallax = EARTH_EQUATORIAL_RADIUS_M / place.distance_m;
    let (sin_h, cos_h) = hour_angle.radians().sin_cos();
    let (sin_d, cos_d) = place.declination.radians().sin_cos();
    let denominator = cos_d - rho_cos * sin_parallax * cos_h;
    let delta_ra = (-rho_cos * sin_parallax * sin_h).atan2(denominator);
    let declination = ((sin_d - rho_sin * sin_parallax) * delta_ra.cos()).atan2(denominator);
    // Topocentric distance: the geocentric vector minus the observer's, in units of
    // the geocentric distance.
    let (sin_a, cos_a) = (-hour_angle.radians()).sin_cos();
    let x = cos_d * cos_a - rho_cos * sin_parallax;
    let y = cos_d * sin_a;
    let z = sin_d - rho_sin * sin_parallax;
    let distance_m = place.distance_m * (x * x + y * y + z * z).sqrt();
    (
        EquatorialPlace {
            right_ascension: (place.right_ascension + Angle::from_radians(delta_ra))
                .wrapped_positive(),
            declination: Angle::from_radians(declination),
            distance_m,
        },
        hour_angle - Angle::from_radians(delta_ra),
    )
}

/// Topocentric → geocentric place, the inverse of [`topocentric`]: the body's vector
/// from `observer` plus the observer's from the Earth's centre (Meeus ch. 11's
/// ρ sin φ′ and ρ cos φ′), on the equator of date at `local_sidereal_time`.
pub fn geocentric_from_topocentric(
    place: &EquatorialPlace,
    local_sidereal_time: Angle,
    observer: &Observer,
) -> EquatorialPlace {
    let (rho_sin, rho_cos) = geocentric_factors(observer);
    let (sin_a, cos_a) = place.right_ascension.radians().sin_cos();
    let (sin_d, cos_d) = place.declination.radians().sin_cos();
    let (sin_t, cos_t) = local_sidereal_time.radians().sin_cos();
    let (d, a) = (place.distance_m, EARTH_EQUATORIAL_RADIUS_M);
    let x = d * cos_d * cos_a + a * rho_cos * cos_t;
    let y = d * cos_d * sin_a + a * rho_cos * sin_t;
    let z = d * sin_d + a * rho_sin;
    EquatorialPlace {
        right_ascension: Angle::from_radians(y.atan2(x)).wrapped_positive(),
        declination: Angle::from_radians(z.atan2(x.hypot(y))),
        distance_m: (x * x + y * y + z * z).sqrt(),
    }
}

/// Where the moon is, and how it looks, for one observer at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoonPosition {
    /// Topocentric direction without refraction.
    pub airless: Horizontal,
    /// Geocentric apparent place (distance from the Earth's centre).
    pub geocentric: EquatorialPlace,
    /// Topocentric apparent place (distance from the observer).
    pub topocentric: EquatorialPlace,
    /// Angular radius of the disc seen by the observer.
    pub angular_radius: Angle,
    /// Phase, illuminated fraction and bright limb seen by the observer.
    pub phase: MoonPhase,
    /// Parallactic angle q at the topocentric place: the position angle of the zenith
    /// direction on the disc ([`crate::horizontal::parallactic_angle`]).
    pub parallactic_angle: Angle,
}

impl MoonPosition {
    /// The direction an observer sees through `air`: azimuth unchanged, elevation
    /// lifted by refraction ([`crate::refraction::apparent_direction`], as for every
    /// body).
    pub fn apparent(&self, air: &AirConditions) -> Horizontal {
        apparent_direction(self.airless, air)
    }

    /// The bright limb's tilt as the observer sees it: the angle χ − q of the bright
    /// limb's midpoint from the zenith direction on the disc, counted like position
    /// angles (toward celestial east's side), in [0°, 360°) (Meeus ch. 48).
    pub fn bright_limb_from_zenith(&self) -> Angle {
        (self.phase.bright_limb - self.parallactic_angle).wrapped_positive()
    }
}

/// The moon's geocentric apparent place at `instant`: Schlyter's place with
/// nutation in longitude, on the true equator of date.
pub(crate) fn geocentric_place(instant: &Instant) -> EquatorialPlace {
    let t = instant.julian_centuries_tt();
    let place = moon_ecliptic(instant.julian_day_tt());
    let longitude = place.longitude + nutation(t).longitude;
    let (right_ascension, declination) =
        ecliptic_to_equatorial(longitude, place.latitude, true_obliquity(t));
    EquatorialPlace {
        right_ascension,
        declination,
        distance_m: place.distance_m,
    }
}

/// The moon for `observer` at `instant`: Schlyter's place, apparent (nutation,
/// true obliquity), then topocentric; the phase from the topocentric moon and the
/// sun by SPA.
pub fn moon_position(instant: &Instant, observer: &Observer) -> Result<MoonPosition> {
    let geocentric = geocentric_place(instant);
    let hour_angle = local_apparent_sidereal_time(instant, observer) - geocentric.right_ascension;
    let (topocentric, topocentric_hour_angle) = topocentric(&geocentric, hour_angle, observer);
    let airless = Horizontal::from_equatorial(
        topocentric_hour_angle,
        topocentric.declination,
        observer.latitude(),
    );
    let sun_place = crate::sun::geocentric_place(instant)?;
    let parallactic_angle = Angle::from_radians(parallactic_angle(
        topocentric_hour_angle.radians(),
        topocentric.declination.radians(),
        observer.latitude().radians(),
    ));
    Ok(MoonPosition {
        airless,
        geocentric,
        topocentric,
        angular_radius: Angle::from_radians((MOON_RADIUS_M / topocentric.distance_m).asin()),
        phase: moon_phase(&topocentric, &sun_place),
        parallactic_angle,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meeus Example 47.a: 1992 April 12, 0h TD (JDE 2448724.5): λ = 133.162655°,
    /// β = −3.229126°, Δ = 368 409.7 km; apparent α = 134.688470°, δ = 13.768368°.
    #[test]
    fn meeus_example_47a() {
        let place = moon_ecliptic(2_448_724.5);
        let d_lon = (place.longitude - Angle::from_degrees(133.162_655))
            .wrapped_signed()
            .degrees();
        let d_lat = place.latitude.degrees() + 3.229_126;
        let d_km = place.distance_m / 1e3 - 368_409.7;
        println!(
            "Meeus 47.a: longitude {d_lon:+.4} deg, latitude {d_lat:+.4} deg, distance {d_km:+.1} km"
        );
        // Schlyter's method is stated good to 1–2′ in angle; its two distance terms
        // leave ~0.1 % (a 0.001° change of the ~0.95° parallax).
        assert!(d_lon.abs() < 0.05 && d_lat.abs() < 0.05 && d_km.abs() < 500.0);
        let t = (2_448_724.5 - crate::time::J2000_JULIAN_DAY) / 36_525.0;
        let (ra, dec) = ecliptic_to_equatorial(
            place.longitude + nutation(t).longitude,
            place.latitude,
            true_obliquity(t),
        );
        let d_ra = (ra - Angle::from_degrees(134.688_470))
            .wrapped_signed()
            .degrees();
        let d_dec = dec.degrees() - 13.768_368;
        println!("Meeus 47.a: right ascension {d_ra:+.4} deg, declination {d_dec:+.4} deg");
        assert!(d_ra.abs() < 0.06 && d_dec.abs() < 0.05);
    }

    /// Meeus Example 13.a's converse and ch. 13 check: the ecliptic pole maps to
    /// α = 270°, δ = 90° − ε, and a point on the ecliptic at λ = 90° to δ = ε.
    #[test]
    fn ecliptic_to_equatorial_axes() {
        let eps = Angle::from_degrees(23.44);
        let (ra, dec) = ecliptic_to_equatorial(Angle::from_degrees(90.0), Angle::ZERO, eps);
        assert!((ra.degrees() - 90.0).abs() < 1e-9 && (dec.degrees() - 23.44).abs() < 1e-9);
        let (ra, dec) = ecliptic_to_equatorial(Angle::ZERO, Angle::from_degrees(90.0), eps);
        assert!((ra.degrees() - 270.0).abs() < 1e-9 && (dec.degrees() - 66.56).abs() < 1e-9);
    }

    /// Meeus Example 40.a (Mars from Palomar, 2003 Aug 28 3h17m UT): α = 339.530208°,
    /// δ = −15.771083°, Δ = 0.37276 AU, H = 288.7958°, ρ sin φ′ = 0.546861,
    /// ρ cos φ′ = 0.836339 → Δα = +1.29 s (of time), α′ = 22h38m08.54s, δ′ = −15°46′30.0″.
    #[test]
    fn meeus_example_40a() {
        let observer = Observer::new(
            Angle::from_degrees(33.0 + 21.0 / 60.0 + 22.0 / 3600.0),
            Angle::from_degrees(-(116.0 + 51.0 / 60.0 + 45.0 / 3600.0)),
            1_706.0,
        )
        .unwrap();
        let (rho_sin, rho_cos) = geocentric_factors(&observer);
        assert!((rho_sin - 0.546_861).abs() < 2e-6 && (rho_cos - 0.836_339).abs() < 2e-6);
        let place = EquatorialPlace {
            right_ascension: Angle::from_degrees(339.530_208),
            declination: Angle::from_degrees(-15.771_083),
            distance_m: 0.372_76 * crate::sun::ASTRONOMICAL_UNIT_M,
        };
        let (topo, _) = topocentric(&place, Angle::from_degrees(288.795_8), &observer);
        // 22h38m08.54s, printed to 0.01 s (4·10⁻⁵°).
        let alpha = (22.0 + 38.0 / 60.0 + 8.54 / 3600.0) * 15.0;
        assert!(
            (topo.right_ascension.degrees() - alpha).abs() < 4e-5,
            "{topo:?}"
        );
        // −15°46′30.0″, printed to 0.1″ (half of it: 1.4·10⁻⁵°).
        let delta = -(15.0 + 46.0 / 60.0 + 30.0 / 3600.0);
        assert!(
            (topo.declination.degrees() - delta).abs() < 1.4e-5,
            "{topo:?}"
        );
    }
}
