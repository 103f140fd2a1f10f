//! The moon's phase from where the sun and moon are: phase angle, illuminated
//! fraction and the position angle of the bright limb (Meeus, *Astronomical
//! Algorithms*, 2nd ed., ch. 48), and the lit part of the disc per point.
//!
//! [`moon_phase`] takes the geocentric (or, for the observer's own view,
//! topocentric) right ascensions, declinations and distances of the sun and the moon.
//! The phase an observer sees is [`crate::MoonPosition::phase`] (topocentric: it
//! differs from the geocentric one by up to the moon's parallax, ~1°, in phase
//! angle); the phase of the almanacs, the same for everyone on Earth, is
//! [`geocentric_moon_phase`], one call from an instant.
//!
//! [`moon_disc_incidence_cosine`] is written once over the float type: its f32
//! instance is the twin of the WGSL function of the same name.

use num_traits::Float;

use crate::angle::Angle;
use crate::error::Result;
use crate::time::Instant;

/// Equatorial place of a body: right ascension, declination, distance (m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EquatorialPlace {
    /// Right ascension.
    pub right_ascension: Angle,
    /// Declination.
    pub declination: Angle,
    /// Distance from the observer (m).
    pub distance_m: f64,
}

/// The moon's phase as seen from where both places were computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MoonPhase {
    /// Elongation ψ of the moon from the sun.
    pub elongation: Angle,
    /// Phase angle i (sun–moon–observer), 0 at full moon, 180° at new moon.
    pub phase_angle: Angle,
    /// Illuminated fraction of the disc k = (1 + cos i) / 2.
    pub illuminated_fraction: f64,
    /// Position angle χ of the midpoint of the bright limb, from the disc's north
    /// point toward east, in [0°, 360°).
    pub bright_limb: Angle,
}

/// Phase, illuminated fraction and bright limb of the moon at `moon` lit by the sun
/// at `sun` (Meeus eqs. 48.2, 48.3, 48.1, 48.5; the `atan2` forms).
pub fn moon_phase(moon: &EquatorialPlace, sun: &EquatorialPlace) -> MoonPhase {
    let (sin_d, cos_d) = moon.declination.radians().sin_cos();
    let (sin_d0, cos_d0) = sun.declination.radians().sin_cos();
    let delta_ra = (sun.right_ascension - moon.right_ascension).radians();
    let cos_elongation = (sin_d0 * sin_d + cos_d0 * cos_d * delta_ra.cos()).clamp(-1.0, 1.0);
    let elongation = cos_elongation.acos();
    let phase_angle = (sun.distance_m * elongation.sin())
        .atan2(moon.distance_m - sun.distance_m * cos_elongation);
    let bright_limb =
        (cos_d0 * delta_ra.sin()).atan2(sin_d0 * cos_d - cos_d0 * sin_d * delta_ra.cos());
    MoonPhase {
        elongation: Angle::from_radians(elongation),
        phase_angle: Angle::from_radians(phase_angle),
        illuminated_fraction: 0.5 * (1.0 + phase_angle.cos()),
        bright_limb: Angle::from_radians(bright_limb).wrapped_positive(),
    }
}

/// The moon's phase seen from the Earth's centre at `instant`: the geocentric
/// apparent places of the moon ([`crate::moon::moon_ecliptic`] with nutation, the
/// method of [`crate::moon_position`]) and of the sun (SPA's geocentric α, δ and
/// distance) through [`moon_phase`]. It does not depend on the observer; for the
/// phase and bright limb a given observer sees, use [`crate::MoonPosition::phase`].
pub fn geocentric_moon_phase(instant: &Instant) -> Result<MoonPhase> {
    let moon = crate::moon::geocentric_place(instant);
    let sun = crate::sun::geocentric_place(instant)?;
    Ok(moon_phase(&moon, &sun))
}

/// Cosine of the sun's incidence on the moon's sphere at the disc point (`east`,
/// `north`) — coordinates in disc radii, +north toward the celestial north pole,
/// +east toward celestial east — for `phase_angle` i and `bright_limb` χ (radians);
/// 0 on the dark side and outside the disc.
///
/// The sphere's normal there is n = (east, north, √(1 − east² − north²)) with the
/// third axis toward the observer; the sun's direction is
/// s = (sin i · sin χ, sin i · cos χ, cos i), so the terminator is n·s = 0 and the
/// bright limb lies at position angle χ. The lit area over the disc is the
/// illuminated fraction (1 + cos i)/2.
pub fn moon_disc_incidence_cosine<F: Float>(
    east: F,
    north: F,
    phase_angle: F,
    bright_limb: F,
) -> F {
    let rho2 = east * east + north * north;
    if rho2 > F::one() {
        return F::zero();
    }
    let toward_observer = (F::one() - rho2).sqrt();
    let (sin_i, cos_i) = phase_angle.sin_cos();
    let (sin_x, cos_x) = bright_limb.sin_cos();
    let incidence = east * sin_i * sin_x + north * sin_i * cos_x + toward_observer * cos_i;
    incidence.max(F::zero())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meeus Example 48.a: 1992 April 12, 0h TD. Moon α = 134.6885°, δ = 13.7684°,
    /// Δ = 368 410 km; sun α₀ = 20.6579°, δ₀ = 8.6964°, R = 149 971 520 km →
    /// ψ = 110.7929°, i = 69.0756°, k = 0.6786, χ = 285.0°.
    #[test]
    fn meeus_example_48a() {
        let moon = EquatorialPlace {
            right_ascension: Angle::from_degrees(134.6885),
            declination: Angle::from_degrees(13.7684),
            distance_m: 368_410e3,
        };
        let sun = EquatorialPlace {
            right_ascension: Angle::from_degrees(20.6579),
            declination: Angle::from_degrees(8.6964),
            distance_m: 149_971_520e3,
        };
        let phase = moon_phase(&moon, &sun);
        assert!(
            (phase.elongation.degrees() - 110.7929).abs() < 1e-4,
            "{phase:?}"
        );
        assert!(
            (phase.phase_angle.degrees() - 69.0756).abs() < 1e-4,
            "{phase:?}"
        );
        assert!(
            (phase.illuminated_fraction - 0.6786).abs() < 5e-5,
            "{phase:?}"
        );
        assert!(
            (phase.bright_limb.degrees() - 285.0).abs() < 0.05,
            "{phase:?}"
        );
    }

    /// Meeus Example 48.a from the ephemerides in one call: 1992 April 12, 0h
    /// (UT here, TD there: 58 s apart, 0.008° of lunar motion) → i = 69.0756°,
    /// k = 0.6786, χ = 285.0°. Schlyter's moon is 0.015° off Meeus' there
    /// (`moon::tests::meeus_example_47a`), so i within 0.05°.
    #[test]
    fn geocentric_phase_of_meeus_example_48a() {
        let instant = Instant::parse("1992-04-12T00:00:00Z").unwrap();
        let phase = geocentric_moon_phase(&instant).unwrap();
        println!(
            "Meeus 48.a from the ephemerides: i {:.4}°, k {:.4}, χ {:.2}°",
            phase.phase_angle.degrees(),
            phase.illuminated_fraction,
            phase.bright_limb.degrees()
        );
        assert!(
            (phase.phase_angle.degrees() - 69.0756).abs() < 0.05,
            "{phase:?}"
        );
        assert!(
            (phase.illuminated_fraction - 0.6786).abs() < 1e-3,
            "{phase:?}"
        );
        assert!(
            (phase.bright_limb.degrees() - 285.0).abs() < 0.5,
            "{phase:?}"
        );
    }

    /// The observer's phase differs from the geocentric one by at most the moon's
    /// parallax (≤ 1.02°: its horizontal parallax at perigee), and the geocentric
    /// one is the same from anywhere.
    #[test]
    fn topocentric_phase_is_within_the_parallax_of_the_geocentric() {
        use crate::{Observer, moon_position};
        let mut largest = 0.0_f64;
        for day in 0..30 {
            let instant = Instant::from_calendar(2024, 4, 1, 0, 0, 0.0).unwrap();
            let instant =
                Instant::from_utc(instant.utc() + chrono::Duration::hours(day * 23)).unwrap();
            let geocentric = geocentric_moon_phase(&instant).unwrap();
            for (lat, lon) in [(52.0, 5.0), (-33.9, 18.4), (0.0, -100.0)] {
                let observer =
                    Observer::new(Angle::from_degrees(lat), Angle::from_degrees(lon), 0.0).unwrap();
                let seen = moon_position(&instant, &observer).unwrap().phase;
                let difference = (seen.phase_angle - geocentric.phase_angle).degrees().abs();
                assert!(difference <= 1.02, "{instant:?} {lat}: {difference}");
                largest = largest.max(difference);
            }
        }
        assert!(largest > 0.5, "{largest}");
    }

    /// The lit area of the disc (midpoint rule on a 400×400 grid) is the illuminated
    /// fraction, and the brightest limb point is at the bright-limb position angle.
    #[test]
    fn disc_shading_matches_fraction_and_limb() {
        let n = 400;
        for (phase_deg, limb_deg) in [
            (0.0, 0.0),
            (69.0756, 285.0),
            (90.0, 90.0),
            (150.0, 200.0),
            (179.0, 10.0),
        ] {
            let (i, chi) = (f64::to_radians(phase_deg), f64::to_radians(limb_deg));
            let (mut lit, mut inside) = (0usize, 0usize);
            for a in 0..n {
                for b in 0..n {
                    let east = -1.0 + (2 * a + 1) as f64 / n as f64;
                    let north = -1.0 + (2 * b + 1) as f64 / n as f64;
                    if east * east + north * north <= 1.0 {
                        inside += 1;
                        if moon_disc_incidence_cosine(east, north, i, chi) > 0.0 {
                            lit += 1;
                        }
                    }
                }
            }
            let fraction = lit as f64 / inside as f64;
            let expected = 0.5 * (1.0 + i.cos());
            assert!(
                (fraction - expected).abs() < 0.01,
                "i = {phase_deg}: {fraction} vs {expected}"
            );
            // Just inside the limb at χ the incidence is sin i (+ √(2ε)·cos i); the
            // opposite limb point is dark unless the moon is (nearly) full.
            let r = 1.0 - 1e-9;
            let limb = moon_disc_incidence_cosine(r * chi.sin(), r * chi.cos(), i, chi);
            assert!(
                (limb - (i.sin() + 4.5e-5 * i.cos()).max(0.0)).abs() < 1e-6,
                "{limb}"
            );
            let opposite = moon_disc_incidence_cosine(-r * chi.sin(), -r * chi.cos(), i, chi);
            if phase_deg > 0.01 {
                assert_eq!(opposite, 0.0);
            }
        }
        assert_eq!(moon_disc_incidence_cosine(1.0_f32, 0.5, 0.0, 0.0), 0.0);
    }
}
