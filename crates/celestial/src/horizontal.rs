//! Equatorial → horizontal coordinates (Meeus ch. 13), azimuth measured from north
//! through east (N = 0, E = π/2), elevation above the astronomical horizon.
//!
//! [`equatorial_to_horizontal`] is written once over the float type: the f64
//! instance is the reference, the f32 instance is the twin of the WGSL function of
//! the same name in `shaders/celestial/coordinates.wgsl`.

use num_traits::Float;

use crate::angle::Angle;

/// (azimuth, elevation) in radians of a body at local `hour_angle` (radians, west
/// positive) and `declination` (radians) for an observer at `latitude` (radians).
///
/// Built from the body's unit vector in the east/north/up frame and two `atan2`s
/// (no `tan δ`, no `asin`), so it stays defined at the poles, at the zenith and for
/// a body at a celestial pole. Azimuth is in [0, 2π] (2π only where f32 rounding
/// lifts a tiny negative angle); at the exact zenith or nadir it is `atan2(0, 0)`
/// of the rounded components, i.e. arbitrary but finite.
pub fn equatorial_to_horizontal<F: Float>(hour_angle: F, declination: F, latitude: F) -> [F; 2] {
    let (sin_h, cos_h) = hour_angle.sin_cos();
    let (sin_d, cos_d) = declination.sin_cos();
    let (sin_p, cos_p) = latitude.sin_cos();
    let east = -cos_d * sin_h;
    let north = sin_d * cos_p - cos_d * cos_h * sin_p;
    let up = sin_d * sin_p + cos_d * cos_h * cos_p;
    let mut azimuth = east.atan2(north);
    if azimuth < F::zero() {
        azimuth = azimuth + F::from(std::f64::consts::TAU).expect("2π fits the float type");
    }
    let elevation = up.atan2((east * east + north * north).sqrt());
    [azimuth, elevation]
}

/// A direction in the observer's sky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Horizontal {
    /// From north through east, in [0°, 360°].
    pub azimuth: Angle,
    /// Above the horizon (negative below).
    pub elevation: Angle,
}

impl Horizontal {
    /// The direction of a body at `hour_angle` and `declination`, seen from `latitude`.
    pub fn from_equatorial(hour_angle: Angle, declination: Angle, latitude: Angle) -> Self {
        let [azimuth, elevation] = equatorial_to_horizontal(
            hour_angle.radians(),
            declination.radians(),
            latitude.radians(),
        );
        Horizontal {
            azimuth: Angle::from_radians(azimuth),
            elevation: Angle::from_radians(elevation),
        }
    }

    /// Zenith angle (90° − elevation).
    pub fn zenith_angle(&self) -> Angle {
        Angle::from_degrees(90.0) - self.elevation
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Meeus Example 13.b: Venus from the US Naval Observatory (φ = 38°55′17″ N,
    /// L = 77°03′56″ W) on 1987 April 10 at 19h21m00s UT: H = 64.352133°,
    /// δ = −6°43′11.61″ → A = 68.0337° (from south) = 248.0337° from north, h = 15.1249°.
    #[test]
    fn meeus_example_13b() {
        let h = Angle::from_degrees(64.352_133);
        let dec = -Angle::from_degrees(6.0 + 43.0 / 60.0 + 11.61 / 3600.0);
        let lat = Angle::from_degrees(38.0 + 55.0 / 60.0 + 17.0 / 3600.0);
        let sky = Horizontal::from_equatorial(h, dec, lat);
        assert!((sky.azimuth.degrees() - 248.0337).abs() < 1e-4, "{sky:?}");
        assert!((sky.elevation.degrees() - 15.1249).abs() < 1e-4, "{sky:?}");
    }

    #[test]
    fn cardinal_points() {
        let lat = Angle::from_degrees(40.0);
        // On the meridian, south of the zenith: azimuth 180°, elevation 90° − φ + δ.
        let south = Horizontal::from_equatorial(Angle::ZERO, Angle::from_degrees(10.0), lat);
        assert!((south.azimuth.degrees() - 180.0).abs() < 1e-9);
        assert!((south.elevation.degrees() - 60.0).abs() < 1e-9);
        // The celestial equator rises due east (H = −90°) and sets due west.
        let east = Horizontal::from_equatorial(Angle::from_degrees(-90.0), Angle::ZERO, lat);
        assert!(
            (east.azimuth.degrees() - 90.0).abs() < 1e-9 && east.elevation.degrees().abs() < 1e-9
        );
        let west = Horizontal::from_equatorial(Angle::from_degrees(90.0), Angle::ZERO, lat);
        assert!((west.azimuth.degrees() - 270.0).abs() < 1e-9);
        // The north celestial pole stands due north at elevation φ.
        let pole =
            Horizontal::from_equatorial(Angle::from_degrees(33.0), Angle::from_degrees(90.0), lat);
        assert!(
            pole.azimuth.degrees().abs() < 1e-9 || (pole.azimuth.degrees() - 360.0).abs() < 1e-9
        );
        assert!((pole.elevation.degrees() - 40.0).abs() < 1e-9);
    }
}
