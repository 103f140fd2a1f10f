//! Stars: the Hipparcos catalogue to visual magnitude 8 with B−V, as shipped inside
//! the crate `star-catalog` 0.2 (MIT/Apache-2.0; ESA's public Hipparcos data,
//! positions ICRS at epoch J1991.25), precessed from J2000 to the date (Meeus ch. 21,
//! rigorous method), placed in the observer's sky, with illuminance and colour.
//!
//! Not applied: proper motion (the catalogue carries none; ≤ 0.1″/yr for nearly all
//! stars, Barnard's star 10.4″/yr, i.e. 0.3° by 2100), nutation (≤ 17″) and annual
//! aberration (≤ 20.5″): together ≤ 0.011° for all but a handful of high-proper-motion
//! stars, far below a rendered star's size.

use crate::angle::Angle;
use crate::colour::star_colour_from_b_minus_v;
use crate::error::{CelestialError, Result, check_range};
use crate::horizontal::Horizontal;
use crate::observer::Observer;
use crate::photometry::illuminance_from_magnitude;
use crate::sidereal::local_apparent_sidereal_time;
use crate::time::Instant;

/// Faintest magnitude the shipped catalogue holds.
pub const CATALOGUE_LIMITING_MAGNITUDE: f64 = 8.0;

/// One catalogue star.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CatalogueStar {
    /// Hipparcos number.
    pub hip: usize,
    /// Right ascension (ICRS ≈ J2000 equinox).
    pub right_ascension: Angle,
    /// Declination (ICRS ≈ J2000 equinox).
    pub declination: Angle,
    /// Visual magnitude V.
    pub magnitude: f64,
    /// Colour index B−V.
    pub b_minus_v: f64,
}

/// A star as the observer sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyStar {
    /// Hipparcos number.
    pub hip: usize,
    /// Direction without refraction.
    pub airless: Horizontal,
    /// Visual magnitude V.
    pub magnitude: f64,
    /// Illuminance outside the atmosphere (lux).
    pub illuminance_lx: f64,
    /// Linear sRGB chromaticity at unit luminance.
    pub colour: [f64; 3],
}

/// The stars brighter than a limiting magnitude.
#[derive(Clone, Debug)]
pub struct StarCatalogue {
    stars: Vec<CatalogueStar>,
    /// What does not depend on the instant, per star in catalogue order: illuminance
    /// outside the atmosphere (lux) and linear sRGB chromaticity, computed once here so
    /// that [`StarCatalogue::sky`] only moves the stars.
    appearance: Vec<(f64, [f64; 3])>,
}

impl StarCatalogue {
    /// The shipped Hipparcos stars of magnitude ≤ `limiting_magnitude` ∈ [−2, 8].
    pub fn hipparcos(limiting_magnitude: f64) -> Result<Self> {
        let limit = check_range(
            "limiting_magnitude",
            limiting_magnitude,
            -2.0,
            CATALOGUE_LIMITING_MAGNITUDE,
            "mag",
        )?;
        let catalogue =
            star_catalog::Catalog::load_catalog("hipp_bright", limit as f32).map_err(|source| {
                CelestialError::Catalogue {
                    field: "hipp_bright",
                    source,
                }
            })?;
        let stars = catalogue
            .iter_stars()
            .map(|star| CatalogueStar {
                hip: star.id(),
                right_ascension: Angle::from_radians(star.ra()),
                declination: Angle::from_radians(star.de()),
                magnitude: f64::from(star.magnitude()),
                b_minus_v: f64::from(star.bv()),
            })
            .collect::<Vec<_>>();
        let appearance = stars
            .iter()
            .map(|star| {
                (
                    illuminance_from_magnitude(star.magnitude),
                    star_colour_from_b_minus_v(star.b_minus_v),
                )
            })
            .collect();
        Ok(StarCatalogue { stars, appearance })
    }

    /// The stars, in catalogue order.
    pub fn stars(&self) -> &[CatalogueStar] {
        &self.stars
    }

    /// Every star placed in `observer`'s sky at `instant` (above and below the horizon).
    pub fn sky(&self, instant: &Instant, observer: &Observer) -> Vec<SkyStar> {
        let t = instant.julian_centuries_tt();
        let sidereal = local_apparent_sidereal_time(instant, observer);
        let precession = Precession::from_j2000(t);
        self.stars
            .iter()
            .zip(&self.appearance)
            .map(|(star, &(illuminance_lx, colour))| {
                let (ra, dec) = precession.apply(star.right_ascension, star.declination);
                SkyStar {
                    hip: star.hip,
                    airless: Horizontal::from_equatorial(sidereal - ra, dec, observer.latitude()),
                    magnitude: star.magnitude,
                    illuminance_lx,
                    colour,
                }
            })
            .collect()
    }
}

/// The precession angles ζ, z, θ from J2000.0 to a date (Meeus eq. 21.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Precession {
    zeta: f64,
    z: f64,
    theta: f64,
}

impl Precession {
    /// From J2000.0 to `julian_centuries_tt` after it.
    pub fn from_j2000(julian_centuries_tt: f64) -> Self {
        let t = julian_centuries_tt;
        let arcsec = |x: f64| Angle::from_arcseconds(x).radians();
        Precession {
            zeta: arcsec(2306.2181 * t + 0.30188 * t * t + 0.017998 * t * t * t),
            z: arcsec(2306.2181 * t + 1.09468 * t * t + 0.018203 * t * t * t),
            theta: arcsec(2004.3109 * t - 0.42665 * t * t - 0.041833 * t * t * t),
        }
    }

    /// Precess (α₀, δ₀) of J2000 to the date (Meeus eq. 21.4).
    pub fn apply(&self, right_ascension: Angle, declination: Angle) -> (Angle, Angle) {
        let (sin_d, cos_d) = declination.radians().sin_cos();
        let (sin_a, cos_a) = (right_ascension.radians() + self.zeta).sin_cos();
        let (sin_t, cos_t) = self.theta.sin_cos();
        let a = cos_d * sin_a;
        let b = cos_t * cos_d * cos_a - sin_t * sin_d;
        let c = sin_t * cos_d * cos_a + cos_t * sin_d;
        (
            Angle::from_radians(a.atan2(b) + self.z).wrapped_positive(),
            Angle::from_radians(c.atan2(a.hypot(b))),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meeus Example 21.b: θ Persei, J2000 place with proper motion to the date
    /// α₀ = 41.054063°, δ₀ = 49.227750°, precessed to 2028 Nov 13.19 TD
    /// (JDE 2462088.69) → α = 2h46m11.331s, δ = +49°20′54.54″.
    #[test]
    fn meeus_example_21b() {
        let t = (2_462_088.69 - crate::time::J2000_JULIAN_DAY) / 36_525.0;
        let (ra, dec) = Precession::from_j2000(t).apply(
            Angle::from_degrees(41.054_063),
            Angle::from_degrees(49.227_750),
        );
        let alpha = (2.0 + 46.0 / 60.0 + 11.331 / 3600.0) * 15.0;
        let delta = 49.0 + 20.0 / 60.0 + 54.54 / 3600.0;
        println!(
            "Meeus 21.b: dα {:+.2e} deg, dδ {:+.2e} deg",
            ra.degrees() - alpha,
            dec.degrees() - delta
        );
        // Printed to 0.001 s (4·10⁻⁶°) and 0.01″ (2.8·10⁻⁶°); input rounding 10⁻⁶°.
        assert!((ra.degrees() - alpha).abs() < 1e-5);
        assert!((dec.degrees() - delta).abs() < 1e-5);
    }

    #[test]
    fn catalogue_holds_known_stars() {
        let catalogue = StarCatalogue::hipparcos(8.0).unwrap();
        let find = |hip: usize| *catalogue.stars().iter().find(|s| s.hip == hip).unwrap();
        // Sirius (HIP 32349): V = −1.44, B−V = 0.009; Polaris (HIP 11767): V = 1.97,
        // B−V = 0.636, δ = +89.264° (Hipparcos main catalogue, as quoted in
        // star-catalog's source).
        let sirius = find(32_349);
        assert!((sirius.magnitude + 1.44).abs() < 0.01 && sirius.b_minus_v.abs() < 0.02);
        let polaris = find(11_767);
        assert!((polaris.magnitude - 1.97).abs() < 0.01);
        assert!((polaris.declination.degrees() - 89.264_138).abs() < 1e-5);
        assert!(
            catalogue.stars().len() > 20_000,
            "{}",
            catalogue.stars().len()
        );
        assert!(catalogue.stars().iter().all(|s| s.magnitude <= 8.0));
        let bright = StarCatalogue::hipparcos(2.0).unwrap();
        assert!(bright.stars().len() < 100 && bright.stars().iter().all(|s| s.magnitude <= 2.0));
        assert!(matches!(
            StarCatalogue::hipparcos(f64::NAN),
            Err(CelestialError::NotFinite {
                field: "limiting_magnitude",
                ..
            })
        ));
        assert!(matches!(
            StarCatalogue::hipparcos(9.0),
            Err(CelestialError::OutOfRange {
                field: "limiting_magnitude",
                ..
            })
        ));
    }

    /// Polaris stays within 1° of the pole: from 52° N its elevation is 52° ± 1°, its
    /// azimuth within 2° of north, at any time of the span.
    #[test]
    fn polaris_stands_north() {
        let catalogue = StarCatalogue::hipparcos(2.0).unwrap();
        let observer =
            Observer::new(Angle::from_degrees(52.0), Angle::from_degrees(4.9), 0.0).unwrap();
        for iso in [
            "1950-01-01T00:00:00Z",
            "2026-11-24T02:00:00Z",
            "2100-12-31T23:00:00Z",
        ] {
            let instant = Instant::parse(iso).unwrap();
            let polaris = catalogue
                .sky(&instant, &observer)
                .into_iter()
                .find(|s| s.hip == 11_767)
                .unwrap();
            assert!(
                (polaris.airless.elevation.degrees() - 52.0).abs() < 1.0,
                "{polaris:?}"
            );
            assert!(
                polaris.airless.azimuth.wrapped_signed().degrees().abs() < 2.0,
                "{polaris:?}"
            );
        }
    }
}
