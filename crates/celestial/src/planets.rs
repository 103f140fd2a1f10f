//! Planets Mercury–Neptune: positions by P. Schlyter's method ("How to compute
//! planetary positions": mean orbital elements of the equinox of date, Kepler's
//! equation, and for Jupiter, Saturn and Uranus the perturbations by the others — the
//! "great inequality" alone moves Saturn by 0.8°), and visual magnitudes by the
//! formulas of G. Müller as given in Meeus, *Astronomical Algorithms* (2nd ed.),
//! ch. 41.
//! Müller's coefficients date from 1893; modern ones (Mallama & Hilton 2018) differ
//! by up to several tenths of a magnitude, and only Meeus' Example 41.a is checked
//! here — replacing them is future work.
//!
//! Light time and aberration are not applied (≤ 0.02°, for Mercury near inferior
//! conjunction). Accuracy measured against astropy's builtin ephemeris in
//! `tests/planets.rs` and stated in `docs/celestial-methods.md`.

use std::f64::consts::TAU;

use crate::angle::Angle;
use crate::error::Result;
use crate::horizontal::Horizontal;
use crate::moon::{ecliptic_to_equatorial, topocentric};
use crate::moon_phase::EquatorialPlace;
use crate::observer::Observer;
use crate::refraction::{AirConditions, apparent_direction};
use crate::sidereal::{local_apparent_sidereal_time, nutation, true_obliquity};
use crate::sun::ASTRONOMICAL_UNIT_M;
use crate::time::Instant;

/// Schlyter's day 0: 1999-12-31T00:00 (JD 2451543.5).
const SCHLYTER_EPOCH_JULIAN_DAY: f64 = 2_451_543.5;

/// The planets `celestial` places.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Planet {
    /// Mercury.
    Mercury,
    /// Venus.
    Venus,
    /// Mars.
    Mars,
    /// Jupiter.
    Jupiter,
    /// Saturn.
    Saturn,
    /// Uranus.
    Uranus,
    /// Neptune.
    Neptune,
}

impl Planet {
    /// All of them, inner to outer.
    pub const ALL: [Planet; 7] = [
        Planet::Mercury,
        Planet::Venus,
        Planet::Mars,
        Planet::Jupiter,
        Planet::Saturn,
        Planet::Uranus,
        Planet::Neptune,
    ];

    /// The planet's B−V colour index (Allen's *Astrophysical Quantities*, 4th ed., Cox
    /// 2000, §12.3): its reflected sunlight's colour, for drawing it.
    pub fn b_minus_v(self) -> f64 {
        match self {
            Planet::Mercury => 0.93,
            Planet::Venus => 0.82,
            Planet::Mars => 1.36,
            Planet::Jupiter => 0.83,
            Planet::Saturn => 1.04,
            Planet::Uranus => 0.56,
            Planet::Neptune => 0.41,
        }
    }
}

/// Orbital elements at day `d` (Schlyter's): node, inclination, argument of
/// perihelion (radians), semi-major axis (AU), eccentricity, mean anomaly (radians).
struct Elements {
    node: f64,
    inclination: f64,
    perihelion: f64,
    semi_major_axis: f64,
    eccentricity: f64,
    mean_anomaly: f64,
}

fn elements(planet: Planet, d: f64) -> Elements {
    // (N0, N1, i0, i1, w0, w1, a0, a1, e0, e1, M0, M1): degrees, degrees/day, AU and
    // AU/day.
    let c: [f64; 12] = match planet {
        Planet::Mercury => [
            48.3313,
            3.24587e-5,
            7.0047,
            5.00e-8,
            29.1241,
            1.01444e-5,
            0.387098,
            0.0,
            0.205635,
            5.59e-10,
            168.6562,
            4.092_334_436_8,
        ],
        Planet::Venus => [
            76.6799,
            2.46590e-5,
            3.3946,
            2.75e-8,
            54.8910,
            1.38374e-5,
            0.723330,
            0.0,
            0.006773,
            -1.302e-9,
            48.0052,
            1.602_130_224_4,
        ],
        Planet::Mars => [
            49.5574,
            2.11081e-5,
            1.8497,
            -1.78e-8,
            286.5016,
            2.92961e-5,
            1.523688,
            0.0,
            0.093405,
            2.516e-9,
            18.6021,
            0.524_020_776_6,
        ],
        Planet::Jupiter => [
            100.4542,
            2.76854e-5,
            1.3030,
            -1.557e-7,
            273.8777,
            1.64505e-5,
            5.20256,
            0.0,
            0.048498,
            4.469e-9,
            19.8950,
            0.083_085_300_1,
        ],
        Planet::Saturn => [
            113.6634,
            2.38980e-5,
            2.4886,
            -1.081e-7,
            339.3939,
            2.97661e-5,
            9.55475,
            0.0,
            0.055546,
            -9.499e-9,
            316.9670,
            0.033_444_228_2,
        ],
        Planet::Uranus => [
            74.0005,
            1.3978e-5,
            0.7733,
            1.9e-8,
            96.6612,
            3.0565e-5,
            19.18171,
            -1.55e-8,
            0.047318,
            7.45e-9,
            142.5905,
            0.011_725_806,
        ],
        Planet::Neptune => [
            131.7806,
            3.0173e-5,
            1.7700,
            -2.55e-7,
            272.8461,
            -6.027e-6,
            30.05826,
            3.313e-8,
            0.008606,
            2.15e-9,
            260.2471,
            0.005_995_147,
        ],
    };
    Elements {
        node: (c[0] + c[1] * d).to_radians(),
        inclination: (c[2] + c[3] * d).to_radians(),
        perihelion: (c[4] + c[5] * d).to_radians(),
        semi_major_axis: c[6] + c[7] * d,
        eccentricity: c[8] + c[9] * d,
        mean_anomaly: (c[10] + c[11] * d).to_radians().rem_euclid(TAU),
    }
}

/// Eccentric anomaly from the mean anomaly by Newton's method (e ≤ 0.21 here).
fn eccentric_anomaly(mean_anomaly: f64, eccentricity: f64) -> f64 {
    let e = eccentricity;
    let mut ecc = mean_anomaly + e * mean_anomaly.sin() * (1.0 + e * mean_anomaly.cos());
    for _ in 0..8 {
        ecc -= (ecc - e * ecc.sin() - mean_anomaly) / (1.0 - e * ecc.cos());
    }
    ecc
}

/// Heliocentric ecliptic (longitude, latitude, distance AU) of `planet`, equinox of date.
fn heliocentric(planet: Planet, d: f64) -> (f64, f64, f64) {
    let el = elements(planet, d);
    let ecc = eccentric_anomaly(el.mean_anomaly, el.eccentricity);
    let xv = el.semi_major_axis * (ecc.cos() - el.eccentricity);
    let yv = el.semi_major_axis * (1.0 - el.eccentricity * el.eccentricity).sqrt() * ecc.sin();
    let v = yv.atan2(xv);
    let r = xv.hypot(yv);
    let (sin_n, cos_n) = el.node.sin_cos();
    let (sin_u, cos_u) = (v + el.perihelion).sin_cos();
    let cos_i = el.inclination.cos();
    let x = r * (cos_n * cos_u - sin_n * sin_u * cos_i);
    let y = r * (sin_n * cos_u + cos_n * sin_u * cos_i);
    let z = r * sin_u * el.inclination.sin();
    let mut longitude = y.atan2(x);
    let mut latitude = z.atan2(x.hypot(y));
    // Jupiter–Saturn–Uranus perturbations (Schlyter; degrees).
    let mj = elements(Planet::Jupiter, d).mean_anomaly;
    let ms = elements(Planet::Saturn, d).mean_anomaly;
    let mu = elements(Planet::Uranus, d).mean_anomaly;
    let s = |amplitude: f64, argument_deg: f64| {
        amplitude.to_radians() * argument_deg.to_radians().sin()
    };
    let c = |amplitude: f64, argument_deg: f64| {
        amplitude.to_radians() * argument_deg.to_radians().cos()
    };
    let (mj, ms, mu) = (mj.to_degrees(), ms.to_degrees(), mu.to_degrees());
    match planet {
        Planet::Jupiter => {
            longitude += s(-0.332, 2.0 * mj - 5.0 * ms - 67.6)
                + s(-0.056, 2.0 * mj - 2.0 * ms + 21.0)
                + s(0.042, 3.0 * mj - 5.0 * ms + 21.0)
                + s(-0.036, mj - 2.0 * ms)
                + c(0.022, mj - ms)
                + s(0.023, 2.0 * mj - 3.0 * ms + 52.0)
                + s(-0.016, mj - 5.0 * ms - 69.0);
        }
        Planet::Saturn => {
            longitude += s(0.812, 2.0 * mj - 5.0 * ms - 67.6)
                + c(-0.229, 2.0 * mj - 4.0 * ms - 2.0)
                + s(0.119, mj - 2.0 * ms - 3.0)
                + s(0.046, 2.0 * mj - 6.0 * ms - 69.0)
                + s(0.014, mj - 3.0 * ms + 32.0);
            latitude += c(-0.020, 2.0 * mj - 4.0 * ms - 2.0) + s(0.018, 2.0 * mj - 6.0 * ms - 49.0);
        }
        Planet::Uranus => {
            longitude += s(0.040, ms - 2.0 * mu + 6.0)
                + s(0.035, ms - 3.0 * mu + 33.0)
                + s(-0.015, mj - mu + 20.0);
        }
        _ => {}
    }
    (longitude, latitude, r)
}

/// The sun's geocentric ecliptic rectangular position (AU), equinox of date (Schlyter).
fn sun_rectangular(d: f64) -> [f64; 3] {
    let perihelion = (282.9404 + 4.709_35e-5 * d).to_radians();
    let e = 0.016_709 - 1.151e-9 * d;
    let mean_anomaly = (356.0470 + 0.985_600_258_5 * d)
        .to_radians()
        .rem_euclid(TAU);
    let ecc = eccentric_anomaly(mean_anomaly, e);
    let xv = ecc.cos() - e;
    let yv = (1.0 - e * e).sqrt() * ecc.sin();
    let longitude = yv.atan2(xv) + perihelion;
    let r = xv.hypot(yv);
    [r * longitude.cos(), r * longitude.sin(), 0.0]
}

/// Where a planet is and how bright, for one observer at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanetPosition {
    /// Which planet.
    pub planet: Planet,
    /// Topocentric direction without refraction.
    pub airless: Horizontal,
    /// Geocentric apparent place (distance from the Earth's centre).
    pub geocentric: EquatorialPlace,
    /// Distance from the sun (m).
    pub heliocentric_distance_m: f64,
    /// Phase angle (sun–planet–Earth).
    pub phase_angle: Angle,
    /// Visual magnitude (Müller's formulas, Meeus ch. 41).
    pub magnitude: f64,
}

impl PlanetPosition {
    /// The direction an observer sees through `air`: azimuth unchanged, elevation
    /// lifted by refraction ([`crate::refraction::apparent_direction`], as for every
    /// body).
    pub fn apparent(&self, air: &AirConditions) -> Horizontal {
        apparent_direction(self.airless, air)
    }
}

/// Müller's visual magnitude (Meeus ch. 41) for heliocentric distance `r`, geocentric
/// distance `delta` (AU), phase angle `i` (degrees) and, for Saturn, the rings'
/// tilt `ring_tilt` B toward the Earth (degrees). Saturn's |ΔU| term uses the phase
/// angle, an upper bound of |ΔU| (≤ 6.4°, i.e. ≤ 0.28 mag of that term).
pub fn visual_magnitude(planet: Planet, r: f64, delta: f64, i: f64, ring_tilt: f64) -> f64 {
    let distance = 5.0 * (r * delta).log10();
    match planet {
        Planet::Mercury => {
            1.16 + distance + 0.02838 * (i - 50.0) + 0.000_102_3 * (i - 50.0).powi(2)
        }
        Planet::Venus => -4.00 + distance + 0.013_22 * i + 0.000_000_424_7 * i.powi(3),
        Planet::Mars => -1.30 + distance + 0.014_86 * i,
        Planet::Jupiter => -8.93 + distance,
        Planet::Saturn => {
            let sin_b = ring_tilt.to_radians().sin().abs();
            -8.68 + distance + 0.044 * i - 2.60 * sin_b + 1.25 * sin_b * sin_b
        }
        Planet::Uranus => -6.85 + distance,
        Planet::Neptune => -7.05 + distance,
    }
}

/// The planet's position and magnitude for `observer` at `instant`.
pub fn planet_position(
    planet: Planet,
    instant: &Instant,
    observer: &Observer,
) -> Result<PlanetPosition> {
    let d = instant.julian_day_tt() - SCHLYTER_EPOCH_JULIAN_DAY;
    let (lon, lat, r) = heliocentric(planet, d);
    let helio = [
        r * lat.cos() * lon.cos(),
        r * lat.cos() * lon.sin(),
        r * lat.sin(),
    ];
    let sun = sun_rectangular(d);
    let geo = [helio[0] + sun[0], helio[1] + sun[1], helio[2] + sun[2]];
    let delta = (geo[0] * geo[0] + geo[1] * geo[1] + geo[2] * geo[2]).sqrt();
    let geo_longitude = geo[1].atan2(geo[0]);
    let geo_latitude = geo[2].atan2(geo[0].hypot(geo[1]));
    let sun_distance = sun[0].hypot(sun[1]);

    let t = instant.julian_centuries_tt();
    let (right_ascension, declination) = ecliptic_to_equatorial(
        Angle::from_radians(geo_longitude) + nutation(t).longitude,
        Angle::from_radians(geo_latitude),
        true_obliquity(t),
    );
    let geocentric = EquatorialPlace {
        right_ascension,
        declination,
        distance_m: delta * ASTRONOMICAL_UNIT_M,
    };
    let hour_angle = local_apparent_sidereal_time(instant, observer) - right_ascension;
    let (topo, topo_hour_angle) = topocentric(&geocentric, hour_angle, observer);
    let airless =
        Horizontal::from_equatorial(topo_hour_angle, topo.declination, observer.latitude());

    let cos_phase = ((r * r + delta * delta - sun_distance * sun_distance) / (2.0 * r * delta))
        .clamp(-1.0, 1.0);
    let phase_deg = cos_phase.acos().to_degrees();
    // Saturn's ring plane (Schlyter): inclination 28.06° to the ecliptic, node
    // 169.51° + 3.82e-5 °/day.
    let ring_tilt = if planet == Planet::Saturn {
        let (ir, nr) = (28.06_f64.to_radians(), (169.51 + 3.82e-5 * d).to_radians());
        (geo_latitude.sin() * ir.cos() - geo_latitude.cos() * ir.sin() * (geo_longitude - nr).sin())
            .asin()
            .to_degrees()
    } else {
        0.0
    };
    Ok(PlanetPosition {
        planet,
        airless,
        geocentric,
        heliocentric_distance_m: r * ASTRONOMICAL_UNIT_M,
        phase_angle: Angle::from_degrees(phase_deg),
        magnitude: visual_magnitude(planet, r, delta, phase_deg, ring_tilt),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meeus Example 41.a: Venus on 1992 December 20, r = 0.724604 AU,
    /// Δ = 0.910947 AU, i = 72.96° → m = −3.8.
    #[test]
    fn meeus_example_41a() {
        let m = visual_magnitude(Planet::Venus, 0.724_604, 0.910_947, 72.96, 0.0);
        assert!((m + 3.8).abs() < 0.05, "{m}");
    }
}
