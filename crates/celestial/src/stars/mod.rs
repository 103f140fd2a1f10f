//! Stars: the Hipparcos catalogue to visual magnitude 8 with V and B−V, as shipped
//! inside the crate `star-catalog` 0.2 (MIT/Apache-2.0; ESA's public Hipparcos data,
//! positions ICRS at epoch J1991.25), joined by Hipparcos number with the proper
//! motions and parallaxes of the Hipparcos new reduction (van Leeuwen 2007;
//! `data/hipparcos2_motion.bin`) and with the stars' names (the IAU's approved
//! names; `data/star_names.csv`). Each star is moved to its apparent place at the
//! instant ([`crate::astrometry`]: space motion, parallax, aberration, precession,
//! nutation) and placed in the observer's sky, with illuminance and colour.

mod motion;
mod names;

use glam::{DMat3, DVec3};

use crate::angle::Angle;
use crate::astrometry::{ApparentFrame, HIPPARCOS_EPOCH_JULIAN_DAY_TT, StarAstrometry};
use crate::colour::star_colour_from_b_minus_v;
use crate::error::{CelestialError, Result, check_range};
use crate::horizontal::Horizontal;
use crate::observer::Observer;
use crate::photometry::illuminance_from_magnitude;
use crate::refraction::{AirConditions, apparent_direction};
use crate::sidereal::local_apparent_sidereal_time;
use crate::time::Instant;

use names::{NameKind, StarName, parse_hipparcos_number};

/// Faintest magnitude the shipped catalogue holds.
pub const CATALOGUE_LIMITING_MAGNITUDE: f64 = 8.0;

/// One catalogue star.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CatalogueStar {
    /// Hipparcos number.
    pub hip: usize,
    /// The IAU's approved proper name, where it has one.
    pub name: Option<&'static str>,
    /// Right ascension (ICRS) at the catalogue epoch J1991.25.
    pub right_ascension: Angle,
    /// Declination (ICRS) at the catalogue epoch J1991.25.
    pub declination: Angle,
    /// Proper motion in right ascension, μα·cos δ, per Julian year (Hipparcos new
    /// reduction).
    pub proper_motion_ra_cos_dec: Angle,
    /// Proper motion in declination, μδ, per Julian year.
    pub proper_motion_dec: Angle,
    /// Annual parallax as measured (≤ 0 for some distant stars: then none is applied).
    pub parallax: Angle,
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
    /// Direction without refraction (the apparent place, topocentric).
    pub airless: Horizontal,
    /// Visual magnitude V.
    pub magnitude: f64,
    /// Illuminance outside the atmosphere (lux).
    pub illuminance_lx: f64,
    /// Linear sRGB chromaticity at unit luminance.
    pub colour: [f64; 3],
}

impl SkyStar {
    /// The direction an observer sees through `air`: azimuth unchanged, elevation
    /// lifted by refraction ([`crate::refraction::apparent_direction`], as for every
    /// body).
    pub fn apparent(&self, air: &AirConditions) -> Horizontal {
        apparent_direction(self.airless, air)
    }
}

/// The stars brighter than a limiting magnitude.
#[derive(Clone, Debug)]
pub struct StarCatalogue {
    limiting_magnitude: f64,
    stars: Vec<CatalogueStar>,
    /// What does not depend on the instant, per star in catalogue order: illuminance
    /// outside the atmosphere (lux), linear sRGB chromaticity and the astrometry as
    /// vectors, computed once here so that [`StarCatalogue::sky`] only moves the
    /// stars.
    appearance: Vec<(f64, [f64; 3])>,
    astrometry: Vec<StarAstrometry>,
    names: Vec<StarName>,
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
        let motions = motion::hipparcos2_motions()?;
        let names = names::star_names()?;
        // Each star's first IAU name in the table.
        let mut iau_names = std::collections::HashMap::new();
        for n in names.iter().filter(|n| n.kind == NameKind::Iau) {
            iau_names.entry(n.hip).or_insert(n.name);
        }
        let mut stars = Vec::new();
        for star in catalogue.iter_stars() {
            let hip = star.id();
            // Every star of the shipped catalogue has a row (tested); one without
            // would keep its place at the epoch.
            let motion = motions
                .binary_search_by_key(&hip, |m| m.hip)
                .ok()
                .map(|i| motions[i]);
            let name = iau_names.get(&hip).copied();
            stars.push(CatalogueStar {
                hip,
                name,
                right_ascension: Angle::from_radians(star.ra()),
                declination: Angle::from_radians(star.de()),
                proper_motion_ra_cos_dec: motion
                    .map_or(Angle::ZERO, |m| m.proper_motion_ra_cos_dec),
                proper_motion_dec: motion.map_or(Angle::ZERO, |m| m.proper_motion_dec),
                parallax: motion.map_or(Angle::ZERO, |m| m.parallax),
                magnitude: f64::from(star.magnitude()),
                b_minus_v: f64::from(star.bv()),
            });
        }
        // The catalogue gives B−V to a thousandth of a magnitude, so its tens of
        // thousands of stars share a few thousand colour indices: each colour is
        // integrated over the spectrum once.
        let mut colours: std::collections::HashMap<u64, [f64; 3]> =
            std::collections::HashMap::new();
        let appearance = stars
            .iter()
            .map(|star| {
                let colour = *colours
                    .entry(star.b_minus_v.to_bits())
                    .or_insert_with(|| star_colour_from_b_minus_v(star.b_minus_v));
                (illuminance_from_magnitude(star.magnitude), colour)
            })
            .collect();
        let astrometry = stars.iter().map(CatalogueStar::astrometry).collect();
        Ok(StarCatalogue {
            limiting_magnitude: limit,
            stars,
            appearance,
            astrometry,
            names,
        })
    }

    /// The stars, in catalogue order.
    pub fn stars(&self) -> &[CatalogueStar] {
        &self.stars
    }

    /// The catalogue's limiting magnitude.
    pub fn limiting_magnitude(&self) -> f64 {
        self.limiting_magnitude
    }

    /// The star named `name_or_hip`: a Hipparcos number (`"32349"`, `"HIP 32349"`)
    /// or a name, case-insensitive — the IAU's (`"Sirius"`, `"rigil kentaurus"`) or
    /// another in use (`"Agena"`). [`CelestialError::UnknownStar`] names the value
    /// when no star of this catalogue answers to it (a star fainter than its limit
    /// does not).
    pub fn find(&self, name_or_hip: &str) -> Result<&CatalogueStar> {
        let unknown = || CelestialError::UnknownStar {
            field: "name_or_hip",
            value: name_or_hip.to_owned(),
            limiting_magnitude: self.limiting_magnitude,
        };
        let hip = match parse_hipparcos_number(name_or_hip) {
            Some(hip) => hip,
            None => {
                let wanted = name_or_hip.trim().to_lowercase();
                self.names
                    .iter()
                    .find(|n| n.name.to_lowercase() == wanted)
                    .ok_or_else(unknown)?
                    .hip
            }
        };
        self.stars.iter().find(|s| s.hip == hip).ok_or_else(unknown)
    }

    /// Every star placed in `observer`'s sky at `instant` (above and below the
    /// horizon), airless: the apparent place turned into the observer's east, north
    /// and up by the local apparent sidereal time and latitude.
    pub fn sky(&self, instant: &Instant, observer: &Observer) -> Vec<SkyStar> {
        let frame = ApparentFrame::at(instant);
        let icrs_to_horizon = true_equator_to_horizon(
            local_apparent_sidereal_time(instant, observer),
            observer.latitude(),
        ) * frame.icrs_to_true_equator();
        self.place(&frame, |aberrated| {
            Horizontal::from_enu((icrs_to_horizon * aberrated).to_array())
        })
    }

    /// Every star's apparent place at `instant` (α, δ on the true equator and equinox
    /// of date, the astrometry [`StarCatalogue::sky`] uses) turned to the horizon by a
    /// caller's `local_sidereal_time` at `latitude`: hour angle = local sidereal time −
    /// α, then [`Horizontal::from_equatorial`]. For a sky driven by its own clock
    /// (`Sky::reposition_explicit`).
    pub fn sky_at_sidereal_time(
        &self,
        instant: &Instant,
        local_sidereal_time: Angle,
        latitude: Angle,
    ) -> Vec<SkyStar> {
        let frame = ApparentFrame::at(instant);
        let to_true_equator = frame.icrs_to_true_equator();
        self.place(&frame, |aberrated| {
            let (right_ascension, declination) =
                crate::astrometry::direction_to_place(to_true_equator * aberrated);
            Horizontal::from_equatorial(
                local_sidereal_time - right_ascension,
                declination,
                latitude,
            )
        })
    }

    /// Every star with its appearance, placed by `direction(aberrated ICRS direction)`.
    fn place(
        &self,
        frame: &ApparentFrame,
        direction: impl Fn(DVec3) -> Horizontal,
    ) -> Vec<SkyStar> {
        self.stars
            .iter()
            .zip(&self.appearance)
            .zip(&self.astrometry)
            .map(|((star, &(illuminance_lx, colour)), astrometry)| SkyStar {
                hip: star.hip,
                airless: direction(frame.aberrated_direction(astrometry)),
                magnitude: star.magnitude,
                illuminance_lx,
                colour,
            })
            .collect()
    }
}

impl CatalogueStar {
    /// The star's astrometry as vectors, for [`ApparentFrame::apparent_place`] (the
    /// apparent α, δ at an instant; what [`StarCatalogue::sky`] computes for every
    /// star).
    pub fn astrometry(&self) -> StarAstrometry {
        StarAstrometry::new(
            self.right_ascension,
            self.declination,
            self.proper_motion_ra_cos_dec,
            self.proper_motion_dec,
            self.parallax,
            HIPPARCOS_EPOCH_JULIAN_DAY_TT,
        )
    }
}

/// The rotation from the true equator and equinox of date to the observer's
/// east/north/up axes at local apparent sidereal time `sidereal` and latitude φ: the
/// hour angle H = θ − α and the rotation of Meeus eqs. 13.5–13.6 as one matrix.
fn true_equator_to_horizon(sidereal: Angle, latitude: Angle) -> DMat3 {
    let (sin_p, cos_p) = latitude.radians().sin_cos();
    // Rows: east, north, up, from (cos δ cos H, −cos δ sin H, sin δ).
    let hour_frame_to_enu = DMat3::from_cols(
        DVec3::new(0.0, -sin_p, cos_p),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, cos_p, sin_p),
    );
    hour_frame_to_enu * crate::astrometry::rotation_z(sidereal.radians())
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

    /// ζ, z, θ (radians).
    pub(crate) fn angles(&self) -> (f64, f64, f64) {
        (self.zeta, self.z, self.theta)
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
        assert_eq!(
            StarCatalogue::hipparcos(8.0).unwrap().limiting_magnitude(),
            8.0
        );
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

    /// Every star of the shipped catalogue has its row of proper motion and
    /// parallax: the join by Hipparcos number leaves none at rest.
    #[test]
    fn every_star_has_its_motion() {
        let catalogue = StarCatalogue::hipparcos(8.0).unwrap();
        let motions = motion::hipparcos2_motions().unwrap();
        assert_eq!(motions.len(), catalogue.stars().len());
        for star in catalogue.stars() {
            let row = motions[motions.binary_search_by_key(&star.hip, |m| m.hip).unwrap()];
            assert_eq!(row.proper_motion_dec, star.proper_motion_dec);
            assert_eq!(row.parallax, star.parallax);
        }
        // Groombridge 1830 (HIP 57939) moves 7.06″/yr (Hipparcos new reduction).
        let fast = catalogue.find("HIP 57939").unwrap();
        let total = fast
            .proper_motion_ra_cos_dec
            .radians()
            .hypot(fast.proper_motion_dec.radians());
        assert!((Angle::from_radians(total).degrees() * 3600.0 - 7.059).abs() < 0.001);
    }

    /// The one matrix `sky` uses gives the direction of the apparent place at the
    /// local apparent sidereal time through Meeus' equatorial → horizontal formulas.
    #[test]
    fn sky_is_the_apparent_place_turned_to_the_horizon() {
        let catalogue = StarCatalogue::hipparcos(3.0).unwrap();
        let instant = Instant::parse("2071-03-05T04:12:00Z").unwrap();
        let frame = ApparentFrame::at(&instant);
        for (lat, lon) in [(52.0, 4.9), (-33.9, 18.4), (89.9, -120.0), (0.0, 180.0)] {
            let observer =
                Observer::new(Angle::from_degrees(lat), Angle::from_degrees(lon), 0.0).unwrap();
            let sidereal = local_apparent_sidereal_time(&instant, &observer);
            for (star, placed) in catalogue
                .stars()
                .iter()
                .zip(catalogue.sky(&instant, &observer))
            {
                let (ra, dec) = frame.apparent_place(&star.astrometry());
                let expected = Horizontal::from_equatorial(sidereal - ra, dec, observer.latitude());
                let d_el = (placed.airless.elevation - expected.elevation).degrees();
                let d_az = (placed.airless.azimuth - expected.azimuth)
                    .wrapped_signed()
                    .degrees();
                assert!(d_el.abs() < 1e-9, "{star:?}");
                assert!(d_az.abs() * expected.elevation.cos() < 1e-9, "{star:?}");
            }
        }
    }

    /// By IAU name (any case, surrounding space), by another name in use, by
    /// Hipparcos number in its three spellings; unknown values are named.
    #[test]
    fn find_by_name_or_number() {
        let catalogue = StarCatalogue::hipparcos(6.6).unwrap();
        for query in [
            "Sirius",
            "sirius",
            " SIRIUS ",
            "32349",
            "HIP 32349",
            "hip32349",
        ] {
            assert_eq!(catalogue.find(query).unwrap().hip, 32_349, "{query}");
        }
        let alpha_cen = catalogue.find("Rigil Kentaurus").unwrap();
        assert_eq!(
            (alpha_cen.hip, alpha_cen.name),
            (71_683, Some("Rigil Kentaurus"))
        );
        assert_eq!(catalogue.find("rigil kent").unwrap().hip, 71_683);
        assert_eq!(catalogue.find("Agena").unwrap().name, Some("Hadar"));
        // A non-ASCII name, any case (HIP 72845, V 7.8).
        let full = StarCatalogue::hipparcos(8.0).unwrap();
        assert_eq!(full.find("ARCALÍS").unwrap().hip, 72_845);
        assert_eq!(catalogue.find("Polaris").unwrap().name, Some("Polaris"));
        assert_eq!(catalogue.find("HIP 57939").unwrap().name, None);
        for unknown in ["Vulcan", "HIP 1", "", "HIP 999999"] {
            let error = catalogue.find(unknown).unwrap_err();
            assert!(
                matches!(&error, CelestialError::UnknownStar { field: "name_or_hip", value, .. } if value == unknown),
                "{error:?}"
            );
            assert!(
                error.to_string().contains(&format!("{unknown:?}")),
                "{error}"
            );
        }
        // Groombridge 1830 is V = 6.4: in this catalogue, not in one cut at 6.
        assert!(catalogue.find("Groombridge 1830").is_ok());
        let bright = StarCatalogue::hipparcos(6.0).unwrap();
        assert!(matches!(
            bright.find("Groombridge 1830"),
            Err(CelestialError::UnknownStar { .. })
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
