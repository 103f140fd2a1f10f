//! Apparent places of stars: from a catalogue place (ICRS, at the catalogue's epoch)
//! to the direction seen from the Earth's centre at an instant, referred to the true
//! equator and equinox of date.
//!
//! The steps (Meeus, *Astronomical Algorithms*, 2nd ed., ch. 21–23; the vector forms
//! of the *Explanatory Supplement to the Astronomical Almanac*, 1992, §3.2):
//!
//! 1. **space motion**: the unit vector moved along its proper motion, taken as a
//!    constant tangent velocity from the catalogue epoch (J1991.25 for Hipparcos,
//!    ESA 1997); radial velocity and the perspective acceleration it brings are left
//!    out (< 1″ over 1900–2100 for every star of the catalogue);
//! 2. **annual parallax**: the star seen from the Earth rather than the sun,
//!    u − ϖ·E with E the Earth's heliocentric position (AU), where the parallax ϖ is
//!    known (≤ 0.75″, α Centauri);
//! 3. **annual aberration**: u + V − (u·V)u to first order in the Earth's velocity
//!    V/c, from the sun's true longitude and the eccentricity and perihelion of the
//!    Earth's orbit (Meeus eq. 23.3 in vector form, with its constant of aberration
//!    κ = 20.49552″; ≤ 20.5″);
//! 4. **precession** from J2000.0 to the date, ζ, z, θ of Meeus eq. 21.3 (IAU 1976,
//!    the method [`crate::stars::Precession`] uses), as a rotation matrix;
//! 5. **nutation**: Δψ and Δε of [`crate::sidereal::nutation`] (Meeus' abridged
//!    IAU 1980 series, 0.5″) as the rotation R₁(−ε)·R₃(−Δψ)·R₁(ε₀).
//!
//! The Earth's position and velocity come from the sun's low-accuracy theory (Meeus
//! ch. 25, 0.01° in longitude: a relative error of 2 × 10⁻⁴ in a 20″ effect).
//! Left out: the frame bias between the ICRS and the J2000 mean equator (0.02″),
//! gravitational light deflection by the sun (0.004″ at 90° from it), diurnal
//! aberration (≤ 0.32″) and the IAU 2006 precession's difference from IAU 1976
//! (≈ 0.3″ per century from J2000). [`ApparentFrame`] holds everything that depends
//! only on the instant, so a star's apparent place costs a handful of flops.

use glam::{DMat3, DVec3};

use crate::angle::Angle;
use crate::error::{CelestialError, Result};
use crate::sidereal::{mean_obliquity, nutation};
use crate::stars::Precession;
use crate::time::{DAYS_PER_JULIAN_CENTURY, Instant, J2000_JULIAN_DAY};

/// Days per Julian year.
pub const DAYS_PER_JULIAN_YEAR: f64 = 365.25;
/// The Hipparcos catalogue's epoch J1991.25 as a TT Julian day (ESA 1997, vol. 1,
/// §1.2.2).
pub const HIPPARCOS_EPOCH_JULIAN_DAY_TT: f64 = 2_448_349.062_5;
/// First TT Julian day for which apparent places are computed: 1900-01-01T00:00 TT.
pub const APPARENT_PLACE_FIRST_JULIAN_DAY_TT: f64 = 2_415_020.5;
/// First TT Julian day after the span: 2101-01-01T00:00 TT.
pub const APPARENT_PLACE_END_JULIAN_DAY_TT: f64 = 2_488_434.5;
/// The constant of aberration κ (Meeus ch. 23).
const ABERRATION_CONSTANT_ARCSEC: f64 = 20.495_52;

/// A star's astrometry at its catalogue epoch, as vectors in the ICRS axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StarAstrometry {
    /// Unit vector toward the star at the epoch.
    direction: DVec3,
    /// Its rate of change (radians per Julian year): the proper motion as a tangent
    /// vector.
    motion_per_year: DVec3,
    /// Annual parallax (radians; 0 where unknown).
    parallax: f64,
    /// The epoch of `direction` (TT Julian day).
    epoch_julian_day_tt: f64,
}

impl StarAstrometry {
    /// A star at `right_ascension`, `declination` (ICRS) at the epoch
    /// `epoch_julian_day_tt`, moving by `proper_motion_ra_cos_dec` (μα·cos δ) and
    /// `proper_motion_dec` (μδ) per Julian year, at annual `parallax` (a non-positive
    /// or non-finite parallax, as a catalogue may list for a distant star, is treated
    /// as unknown: none applied).
    pub fn new(
        right_ascension: Angle,
        declination: Angle,
        proper_motion_ra_cos_dec: Angle,
        proper_motion_dec: Angle,
        parallax: Angle,
        epoch_julian_day_tt: f64,
    ) -> Self {
        let (sin_a, cos_a) = right_ascension.radians().sin_cos();
        let (sin_d, cos_d) = declination.radians().sin_cos();
        let direction = DVec3::new(cos_d * cos_a, cos_d * sin_a, sin_d);
        // Unit vectors toward increasing α and δ.
        let east = DVec3::new(-sin_a, cos_a, 0.0);
        let north = DVec3::new(-sin_d * cos_a, -sin_d * sin_a, cos_d);
        let motion_per_year =
            east * proper_motion_ra_cos_dec.radians() + north * proper_motion_dec.radians();
        let parallax = parallax.radians();
        StarAstrometry {
            direction,
            motion_per_year,
            parallax: if parallax.is_finite() && parallax > 0.0 {
                parallax
            } else {
                0.0
            },
            epoch_julian_day_tt,
        }
    }
}

/// What the apparent place depends on at one instant: the Earth's heliocentric
/// position and velocity and the rotation from the ICRS to the true equator and
/// equinox of date.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ApparentFrame {
    julian_day_tt: f64,
    /// The Earth's heliocentric position (AU), ICRS axes.
    earth_position_au: DVec3,
    /// The Earth's velocity over the speed of light, ICRS axes.
    earth_velocity_over_c: DVec3,
    /// ICRS → true equator and equinox of date: nutation · precession.
    icrs_to_true_equator: DMat3,
}

/// The frame rotation R₁(a) (Explanatory Supplement §3.21).
fn rotation_x(angle: f64) -> DMat3 {
    let (s, c) = angle.sin_cos();
    DMat3::from_cols(
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, c, -s),
        DVec3::new(0.0, s, c),
    )
}

/// The frame rotation R₂(a).
fn rotation_y(angle: f64) -> DMat3 {
    let (s, c) = angle.sin_cos();
    DMat3::from_cols(
        DVec3::new(c, 0.0, s),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(-s, 0.0, c),
    )
}

/// The frame rotation R₃(a).
pub(crate) fn rotation_z(angle: f64) -> DMat3 {
    let (s, c) = angle.sin_cos();
    DMat3::from_cols(
        DVec3::new(c, -s, 0.0),
        DVec3::new(s, c, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
    )
}

impl Precession {
    /// The rotation from the J2000.0 mean equator and equinox to the mean equator
    /// and equinox of date, R₃(−z)·R₂(θ)·R₃(−ζ) (the matrix form of Meeus eq. 21.4).
    pub fn matrix(&self) -> DMat3 {
        let (zeta, z, theta) = self.angles();
        rotation_z(-z) * rotation_y(theta) * rotation_z(-zeta)
    }
}

impl ApparentFrame {
    /// The frame at `instant`.
    pub fn at(instant: &Instant) -> Self {
        Self::from_julian_day_tt(instant.julian_day_tt())
    }

    /// The frame at the TT Julian day `julian_day_tt`, within 1900–2100
    /// ([`APPARENT_PLACE_FIRST_JULIAN_DAY_TT`] ≤ day < [`APPARENT_PLACE_END_JULIAN_DAY_TT`]):
    /// apparent places for instants before [`Instant`]'s span.
    pub fn at_julian_day_tt(julian_day_tt: f64) -> Result<Self> {
        if !julian_day_tt.is_finite() {
            return Err(CelestialError::NotFinite {
                field: "julian_day_tt",
                value: julian_day_tt,
            });
        }
        if !(APPARENT_PLACE_FIRST_JULIAN_DAY_TT..APPARENT_PLACE_END_JULIAN_DAY_TT)
            .contains(&julian_day_tt)
        {
            return Err(CelestialError::OutOfRange {
                field: "julian_day_tt",
                value: julian_day_tt,
                min: APPARENT_PLACE_FIRST_JULIAN_DAY_TT,
                max: APPARENT_PLACE_END_JULIAN_DAY_TT,
                unit: "d",
            });
        }
        Ok(Self::from_julian_day_tt(julian_day_tt))
    }

    fn from_julian_day_tt(julian_day_tt: f64) -> Self {
        let t = (julian_day_tt - J2000_JULIAN_DAY) / DAYS_PER_JULIAN_CENTURY;
        let precession = Precession::from_j2000(t).matrix();
        let mean_obliquity = mean_obliquity(t).radians();
        let nutation_now = nutation(t);
        let true_obliquity = mean_obliquity + nutation_now.obliquity.radians();
        let nutation_matrix = rotation_x(-true_obliquity)
            * rotation_z(-nutation_now.longitude.radians())
            * rotation_x(mean_obliquity);

        // The sun's geometric longitude and distance, mean equinox of date (Meeus
        // eqs. 25.2–25.5), and the Earth's orbit (eq. 25.4, ch. 23).
        let degrees = |d: f64| d.to_radians();
        let mean_longitude = degrees(280.466_46 + 36_000.769_83 * t + 0.000_303_2 * t * t);
        let mean_anomaly = degrees(357.529_11 + 35_999.050_29 * t - 0.000_153_7 * t * t);
        let eccentricity = 0.016_708_634 - 0.000_042_037 * t - 0.000_000_126_7 * t * t;
        let centre = degrees(
            (1.914_602 - 0.004_817 * t - 0.000_014 * t * t) * mean_anomaly.sin()
                + (0.019_993 - 0.000_101 * t) * (2.0 * mean_anomaly).sin()
                + 0.000_289 * (3.0 * mean_anomaly).sin(),
        );
        let sun_longitude = mean_longitude + centre;
        let sun_distance_au = 1.000_001_018 * (1.0 - eccentricity * eccentricity)
            / (1.0 + eccentricity * (mean_anomaly + centre).cos());
        let perihelion = degrees(102.937_35 + 1.719_46 * t + 0.000_46 * t * t);
        let (sin_sun, cos_sun) = sun_longitude.sin_cos();
        let (sin_peri, cos_peri) = perihelion.sin_cos();
        let kappa = Angle::from_arcseconds(ABERRATION_CONSTANT_ARCSEC).radians();
        // Ecliptic of date → mean equator of date → J2000 (ICRS axes).
        let ecliptic_to_icrs = precession.transpose() * rotation_x(-mean_obliquity);
        let earth_position_au =
            ecliptic_to_icrs * DVec3::new(-cos_sun, -sin_sun, 0.0) * sun_distance_au;
        let earth_velocity_over_c = ecliptic_to_icrs
            * DVec3::new(
                kappa * (sin_sun - eccentricity * sin_peri),
                -kappa * (cos_sun - eccentricity * cos_peri),
                0.0,
            );
        ApparentFrame {
            julian_day_tt,
            earth_position_au,
            earth_velocity_over_c,
            icrs_to_true_equator: nutation_matrix * precession,
        }
    }

    /// The rotation from the ICRS axes to the true equator and equinox of date.
    pub fn icrs_to_true_equator(&self) -> DMat3 {
        self.icrs_to_true_equator
    }

    /// The star's direction from the Earth's centre after space motion, parallax and
    /// aberration, still in the ICRS axes (rotate by [`Self::icrs_to_true_equator`],
    /// or a product of it, for the apparent place).
    pub fn aberrated_direction(&self, star: &StarAstrometry) -> DVec3 {
        let years = (self.julian_day_tt - star.epoch_julian_day_tt) / DAYS_PER_JULIAN_YEAR;
        let geocentric = (star.direction + star.motion_per_year * years
            - self.earth_position_au * star.parallax)
            .normalize();
        let velocity = self.earth_velocity_over_c;
        (geocentric + velocity - geocentric * geocentric.dot(velocity)).normalize()
    }

    /// The apparent place (α, δ), true equator and equinox of date.
    pub fn apparent_place(&self, star: &StarAstrometry) -> (Angle, Angle) {
        direction_to_place(self.icrs_to_true_equator * self.aberrated_direction(star))
    }
}

/// (α, δ) of a direction in equatorial axes (x toward the equinox, z toward the pole).
pub(crate) fn direction_to_place(v: DVec3) -> (Angle, Angle) {
    (
        Angle::from_radians(v.y.atan2(v.x)).wrapped_positive(),
        Angle::from_radians(v.z.atan2(v.x.hypot(v.y))),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hms(h: f64, m: f64, s: f64) -> Angle {
        Angle::from_hours(h + m / 60.0 + s / 3600.0)
    }

    fn dms(d: f64, m: f64, s: f64) -> Angle {
        Angle::from_degrees(d + m / 60.0 + s / 3600.0)
    }

    /// Meeus Example 23.a: θ Persei, J2000 α₀ = 2h44m11.986s, δ₀ = +49°13′42.48″,
    /// proper motion +0.03425 s/yr in α and −0.0895″/yr in δ, on 2028 Nov 13.19 TD
    /// (JDE 2462088.69) → apparent α = 2h46m14.390s, δ = +49°21′07.45″ (Meeus' full
    /// nutation; the abridged series here is good to 0.5″).
    #[test]
    fn meeus_example_23a() {
        let declination = dms(49.0, 13.0, 42.48);
        let star = StarAstrometry::new(
            hms(2.0, 44.0, 11.986),
            declination,
            Angle::from_arcseconds(0.034_25 * 15.0 * declination.cos()),
            Angle::from_arcseconds(-0.0895),
            Angle::ZERO,
            J2000_JULIAN_DAY,
        );
        let frame = ApparentFrame::at_julian_day_tt(2_462_088.69).unwrap();
        let (ra, dec) = frame.apparent_place(&star);
        let d_ra = (ra - hms(2.0, 46.0, 14.390)).wrapped_signed().degrees() * 3600.0;
        let d_dec = (dec - dms(49.0, 21.0, 7.45)).degrees() * 3600.0;
        println!(
            "Meeus 23.a: dα·cos δ {:+.3}″, dδ {d_dec:+.3}″",
            d_ra * dec.cos()
        );
        assert!(d_ra.abs() * dec.cos() < 0.5 && d_dec.abs() < 0.5);
    }

    /// The matrix form of the precession reproduces Meeus' trigonometric form.
    #[test]
    fn precession_matrix_matches_meeus_21_4() {
        let precession = Precession::from_j2000(0.843_1);
        let matrix = precession.matrix();
        for (ra, dec) in [(41.05, 49.23), (200.0, -60.0), (10.0, 89.5), (300.0, 0.0)] {
            let star = StarAstrometry::new(
                Angle::from_degrees(ra),
                Angle::from_degrees(dec),
                Angle::ZERO,
                Angle::ZERO,
                Angle::ZERO,
                J2000_JULIAN_DAY,
            );
            let v = matrix * star.direction;
            let (ra1, dec1) = precession.apply(Angle::from_degrees(ra), Angle::from_degrees(dec));
            assert!((v.y.atan2(v.x) - ra1.wrapped_signed().radians()).abs() < 1e-12);
            assert!((v.z.asin() - dec1.radians()).abs() < 1e-12);
        }
    }

    /// The Earth's velocity is κ ≈ 20.5″ (±1.7 % with the eccentricity) and its
    /// position 1 AU (±1.7 %), at right angles to within the eccentricity.
    #[test]
    fn earth_orbit_magnitudes() {
        for day in [0.0, 91.0, 182.0, 273.0, 36_525.0] {
            let frame = ApparentFrame::at_julian_day_tt(J2000_JULIAN_DAY + day).unwrap();
            let speed =
                Angle::from_radians(frame.earth_velocity_over_c.length()).degrees() * 3600.0;
            assert!((speed - 20.5).abs() < 0.4, "{speed}");
            let distance = frame.earth_position_au.length();
            assert!((distance - 1.0).abs() < 0.018, "{distance}");
            let cos = frame
                .earth_position_au
                .normalize()
                .dot(frame.earth_velocity_over_c.normalize());
            assert!(cos.abs() < 0.02, "{cos}");
        }
    }

    #[test]
    fn rejects_days_outside_the_span() {
        assert!(matches!(
            ApparentFrame::at_julian_day_tt(2_400_000.0),
            Err(CelestialError::OutOfRange {
                field: "julian_day_tt",
                ..
            })
        ));
        assert!(matches!(
            ApparentFrame::at_julian_day_tt(f64::NAN),
            Err(CelestialError::NotFinite {
                field: "julian_day_tt",
                ..
            })
        ));
    }
}
