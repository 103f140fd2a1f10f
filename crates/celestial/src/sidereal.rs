//! Nutation, obliquity of the ecliptic and sidereal time (Meeus, *Astronomical
//! Algorithms*, 2nd ed., chapters 12 and 22).
//!
//! Nutation uses Meeus' abridged series (p. 144: the four largest terms of the
//! IAU 1980 theory), good to 0.5″ in Δψ and 0.1″ in Δε. Through the equation of
//! the equinoxes that is 0.03 s of sidereal time, far below what a rendered sky
//! resolves; the sun itself uses SPA's full 63-term series.

use crate::angle::Angle;
use crate::observer::Observer;
use crate::time::{Instant, J2000_JULIAN_DAY};

/// Nutation in longitude (Δψ) and in obliquity (Δε).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nutation {
    /// Δψ.
    pub longitude: Angle,
    /// Δε.
    pub obliquity: Angle,
}

/// Nutation at `julian_centuries_tt` since J2000.0 (Meeus p. 144, abridged).
pub fn nutation(julian_centuries_tt: f64) -> Nutation {
    let t = julian_centuries_tt;
    // Longitude of the Moon's ascending node, mean longitudes of the Sun and Moon.
    let node = Angle::from_degrees(
        125.044_52 - 1_934.136_261 * t + 0.002_070_8 * t * t + t * t * t / 450_000.0,
    )
    .radians();
    let sun = Angle::from_degrees(280.466_5 + 36_000.769_8 * t).radians();
    let moon = Angle::from_degrees(218.316_5 + 481_267.881_3 * t).radians();
    let longitude = -17.20 * node.sin() - 1.32 * (2.0 * sun).sin() - 0.23 * (2.0 * moon).sin()
        + 0.21 * (2.0 * node).sin();
    let obliquity = 9.20 * node.cos() + 0.57 * (2.0 * sun).cos() + 0.10 * (2.0 * moon).cos()
        - 0.09 * (2.0 * node).cos();
    Nutation {
        longitude: Angle::from_arcseconds(longitude),
        obliquity: Angle::from_arcseconds(obliquity),
    }
}

/// Mean obliquity of the ecliptic ε₀ (Meeus eq. 22.2, IAU; 1″ over 2000 ± 2000 years).
pub fn mean_obliquity(julian_centuries_tt: f64) -> Angle {
    let t = julian_centuries_tt;
    Angle::from_degrees(23.0 + 26.0 / 60.0)
        + Angle::from_arcseconds(21.448 - 46.815_0 * t - 0.000_59 * t * t + 0.001_813 * t * t * t)
}

/// True obliquity ε = ε₀ + Δε.
pub fn true_obliquity(julian_centuries_tt: f64) -> Angle {
    mean_obliquity(julian_centuries_tt) + nutation(julian_centuries_tt).obliquity
}

/// Greenwich mean sidereal time θ₀ in [0, 2π) (Meeus eq. 12.4, UT argument).
pub fn greenwich_mean_sidereal_time(instant: &Instant) -> Angle {
    let days = instant.julian_day_ut() - J2000_JULIAN_DAY;
    let t = instant.julian_centuries_ut();
    // Split the linear term so its large integer part of turns cancels exactly.
    let turns = days.floor() * 0.985_647_366_29 / 360.0;
    let degrees = 280.460_618_37
        + 360.0 * (turns - turns.floor())
        + 360.985_647_366_29 * (days - days.floor())
        + 0.000_387_933 * t * t
        - t * t * t / 38_710_000.0;
    Angle::from_degrees(degrees).wrapped_positive()
}

/// Greenwich apparent sidereal time: θ₀ + Δψ·cos ε (the equation of the equinoxes).
pub fn greenwich_apparent_sidereal_time(instant: &Instant) -> Angle {
    let t = instant.julian_centuries_tt();
    let equation_of_equinoxes =
        Angle::from_radians(nutation(t).longitude.radians() * true_obliquity(t).cos());
    (greenwich_mean_sidereal_time(instant) + equation_of_equinoxes).wrapped_positive()
}

/// Local mean sidereal time at `longitude` (east positive), in [0, 2π).
pub fn local_mean_sidereal_time(instant: &Instant, longitude: Angle) -> Angle {
    (greenwich_mean_sidereal_time(instant) + longitude).wrapped_positive()
}

/// Local apparent sidereal time for `observer`, in [0, 2π).
pub fn local_apparent_sidereal_time(instant: &Instant, observer: &Observer) -> Angle {
    (greenwich_apparent_sidereal_time(instant) + observer.longitude()).wrapped_positive()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hms(h: f64, m: f64, s: f64) -> f64 {
        h + m / 60.0 + s / 3600.0
    }

    /// Meeus Example 12.a: 1987 April 10, 0h UT: θ₀ = 13h10m46.3668s, apparent
    /// 13h10m46.1351s (Meeus' Δψ = −3.788″, ε = 23°26′36.85″).
    #[test]
    fn meeus_example_12a() {
        let instant = Instant::parse("1987-04-10T00:00:00Z").unwrap();
        let mean = greenwich_mean_sidereal_time(&instant).hours();
        assert!(
            (mean - hms(13.0, 10.0, 46.3668)).abs() * 3600.0 < 1e-3,
            "{mean}"
        );
        let apparent = greenwich_apparent_sidereal_time(&instant).hours();
        // Abridged nutation: 0.5″ in Δψ → ≤ 0.03 s of time.
        assert!(
            (apparent - hms(13.0, 10.0, 46.1351)).abs() * 3600.0 < 0.03,
            "{apparent}"
        );
    }

    /// Meeus Example 12.b: 1987 April 10, 19h21m00s UT: θ₀ = 8h34m57.0896s.
    #[test]
    fn meeus_example_12b() {
        let instant = Instant::parse("1987-04-10T19:21:00Z").unwrap();
        let mean = greenwich_mean_sidereal_time(&instant).hours();
        assert!(
            (mean - hms(8.0, 34.0, 57.0896)).abs() * 3600.0 < 1e-3,
            "{mean}"
        );
    }

    /// Meeus Example 22.a: 1987 April 10, 0h TD: Δψ = −3.788″, Δε = +9.443″,
    /// ε₀ = 23°26′27.407″, ε = 23°26′36.850″ (abridged series: 0.5″ and 0.1″).
    #[test]
    fn meeus_example_22a() {
        let t = (2_446_895.5 - J2000_JULIAN_DAY) / 36_525.0;
        let n = nutation(t);
        assert!((n.longitude.degrees() * 3600.0 + 3.788).abs() < 0.5);
        assert!((n.obliquity.degrees() * 3600.0 - 9.443).abs() < 0.1);
        let eps0 = mean_obliquity(t).degrees() - (23.0 + 26.0 / 60.0);
        assert!((eps0 * 3600.0 - 27.407).abs() < 1e-3);
        let eps = true_obliquity(t).degrees() - (23.0 + 26.0 / 60.0);
        assert!((eps * 3600.0 - 36.850).abs() < 0.1);
    }

    #[test]
    fn local_time_adds_east_longitude() {
        let instant = Instant::parse("1987-04-10T19:21:00Z").unwrap();
        let greenwich = greenwich_mean_sidereal_time(&instant);
        let local = local_mean_sidereal_time(&instant, Angle::from_degrees(-77.0));
        let diff = (greenwich - local).wrapped_signed().degrees();
        assert!((diff - 77.0).abs() < 1e-9);
    }
}
