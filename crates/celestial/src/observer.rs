//! Where the observer stands: geodetic latitude, longitude (east positive) and
//! elevation above sea level.

use crate::angle::Angle;
use crate::error::{Result, check_range};

/// Lowest accepted elevation (m): below the Dead Sea shore (−430 m) with margin.
pub const MIN_ELEVATION_M: f64 = -500.0;
/// Highest accepted elevation (m): the top of skyscape's atmosphere.
pub const MAX_ELEVATION_M: f64 = 100_000.0;

/// A validated observer on (or above) the WGS 84 ellipsoid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Observer {
    latitude: Angle,
    longitude: Angle,
    elevation_m: f64,
}

impl Observer {
    /// An observer at geodetic `latitude` ∈ [−90°, 90°], `longitude` ∈ [−180°, 180°]
    /// (east positive) and `elevation_m` metres above sea level ∈ [−500, 100 000].
    pub fn new(latitude: Angle, longitude: Angle, elevation_m: f64) -> Result<Self> {
        check_range("latitude", latitude.degrees(), -90.0, 90.0, "°")?;
        check_range("longitude", longitude.degrees(), -180.0, 180.0, "°")?;
        check_range(
            "elevation_m",
            elevation_m,
            MIN_ELEVATION_M,
            MAX_ELEVATION_M,
            "m",
        )?;
        Ok(Observer {
            latitude,
            longitude,
            elevation_m,
        })
    }

    /// Geodetic latitude (north positive).
    pub fn latitude(&self) -> Angle {
        self.latitude
    }

    /// Longitude (east positive).
    pub fn longitude(&self) -> Angle {
        self.longitude
    }

    /// Elevation above sea level (m).
    pub fn elevation_m(&self) -> f64 {
        self.elevation_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::CelestialError;

    #[test]
    fn rejects_bad_latitude_longitude_elevation() {
        let deg = Angle::from_degrees;
        assert!(matches!(
            Observer::new(deg(90.5), deg(0.0), 0.0),
            Err(CelestialError::OutOfRange {
                field: "latitude",
                ..
            })
        ));
        assert!(matches!(
            Observer::new(deg(f64::NAN), deg(0.0), 0.0),
            Err(CelestialError::NotFinite {
                field: "latitude",
                ..
            })
        ));
        assert!(matches!(
            Observer::new(deg(0.0), deg(-180.1), 0.0),
            Err(CelestialError::OutOfRange {
                field: "longitude",
                ..
            })
        ));
        assert!(matches!(
            Observer::new(deg(0.0), deg(0.0), 1e6),
            Err(CelestialError::OutOfRange {
                field: "elevation_m",
                ..
            })
        ));
        assert!(Observer::new(deg(-90.0), deg(180.0), -500.0).is_ok());
        let message = Observer::new(deg(91.0), deg(0.0), 0.0)
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("latitude") && message.contains("91"),
            "{message}"
        );
    }
}
