//! The sun's position: NREL's Solar Position Algorithm (Reda & Andreas 2004,
//! NREL/TP-560-34302; ±0.0003° over −2000…6000), through the maintained crate
//! `solar-positioning` (MIT; its tests reproduce the SPA report's worked example to
//! 10⁻⁶°). SPA gives the *topocentric* position (parallax of the observer's place
//! on the WGS 84 ellipsoid at its elevation included); `celestial` asks it for the
//! airless position and applies refraction as its own, separate step
//! ([`crate::refraction`]).

use solar_positioning::time::JulianDate;
use solar_positioning::{Location, SolarPositions};

use crate::angle::Angle;
use crate::error::{CelestialError, Result};
use crate::horizontal::Horizontal;
use crate::moon_phase::EquatorialPlace;
use crate::observer::Observer;
use crate::refraction::{AirConditions, apparent_direction};
use crate::time::Instant;

/// The astronomical unit (m, IAU 2012 resolution B2).
pub const ASTRONOMICAL_UNIT_M: f64 = 149_597_870_700.0;
/// The sun's radius (m, IAU 2015 resolution B3 nominal value).
pub const SUN_RADIUS_M: f64 = 6.957e8;

/// Where the sun is for one observer at one instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunPosition {
    /// Topocentric direction without refraction.
    pub airless: Horizontal,
    /// Geocentric apparent right ascension.
    pub right_ascension: Angle,
    /// Geocentric apparent declination.
    pub declination: Angle,
    /// Earth–sun distance (m).
    pub distance_m: f64,
}

impl SunPosition {
    /// The direction an observer sees through `air`: azimuth unchanged, elevation
    /// lifted by refraction.
    pub fn apparent(&self, air: &AirConditions) -> Horizontal {
        apparent_direction(self.airless, air)
    }

    /// Angular radius of the solar disc.
    pub fn angular_radius(&self) -> Angle {
        Angle::from_radians((SUN_RADIUS_M / self.distance_m).asin())
    }
}

/// The sun's geocentric apparent place (SPA's α, δ and distance) at `instant`: it
/// does not depend on the observer, whose place SPA needs only for the topocentric
/// direction.
pub(crate) fn geocentric_place(instant: &Instant) -> Result<EquatorialPlace> {
    let anywhere = Observer::new(Angle::ZERO, Angle::ZERO, 0.0)?;
    let sun = sun_position(instant, &anywhere)?;
    Ok(EquatorialPlace {
        right_ascension: sun.right_ascension,
        declination: sun.declination,
        distance_m: sun.distance_m,
    })
}

/// The sun's position for `observer` at `instant` (SPA, airless topocentric).
pub fn sun_position(instant: &Instant, observer: &Observer) -> Result<SunPosition> {
    let ephemeris = |source| CelestialError::Ephemeris {
        field: "sun_position",
        source,
    };
    let time =
        JulianDate::new(instant.julian_day_ut(), instant.delta_t_seconds()).map_err(ephemeris)?;
    let prepared = SolarPositions::new()
        .for_time_from_julian(time)
        .map_err(ephemeris)?;
    let location = Location {
        latitude: observer.latitude().degrees(),
        longitude: observer.longitude().degrees(),
    };
    let position = prepared
        .at(location, observer.elevation_m(), None)
        .map_err(ephemeris)?;
    let radius_vector_au = prepared
        .earth_radius_vector()
        .expect("the SPA model always reports the radius vector");
    Ok(SunPosition {
        airless: Horizontal {
            azimuth: Angle::from_degrees(position.azimuth()),
            elevation: Angle::from_degrees(position.elevation_angle()),
        },
        right_ascension: Angle::from_degrees(prepared.right_ascension()),
        declination: Angle::from_degrees(prepared.declination()),
        distance_m: radius_vector_au * ASTRONOMICAL_UNIT_M,
    })
}
