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

/// Parallactic angle q (radians) of a body at local `hour_angle` (west positive) and
/// `declination`, seen from `latitude`: the position angle of the zenith direction on
/// the body's disc, counted like position angles from the direction of the north
/// celestial pole toward east (Meeus eq. 14.1,
/// `tan q = sin H / (tan φ cos δ − sin δ cos H)`, in the `atan2` form with `tan φ`
/// multiplied through by `cos φ`, so it stays finite at the poles). A disc feature at
/// position angle χ lies at χ − q from the zenith direction (Meeus ch. 48: the bright
/// limb's tilt as the observer sees it). At the zenith itself q is `atan2(0, 0)` of
/// the rounded components: arbitrary but finite.
pub fn parallactic_angle<F: Float>(hour_angle: F, declination: F, latitude: F) -> F {
    let (sin_h, cos_h) = hour_angle.sin_cos();
    let (sin_d, cos_d) = declination.sin_cos();
    let (sin_p, cos_p) = latitude.sin_cos();
    (sin_h * cos_p).atan2(sin_p * cos_d - cos_p * sin_d * cos_h)
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

    /// The unit vector of this direction in the observer's east/north/up frame
    /// (x east, y north, z up): the frame `celestial`'s drawing and the `Sky` facade
    /// use, with the atmosphere's planet-centred viewer on the +z axis.
    pub fn to_enu(&self) -> [f64; 3] {
        let (sin_a, cos_a) = self.azimuth.radians().sin_cos();
        let (sin_e, cos_e) = self.elevation.radians().sin_cos();
        [cos_e * sin_a, cos_e * cos_a, sin_e]
    }

    /// The direction of an east/north/up vector (need not be unit; a zero vector gives
    /// azimuth 0, elevation 0).
    pub fn from_enu(enu: [f64; 3]) -> Self {
        let [east, north, up] = enu;
        Horizontal {
            azimuth: Angle::from_radians(east.atan2(north)).wrapped_positive(),
            elevation: Angle::from_radians(up.atan2(east.hypot(north))),
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

    /// q is the position angle of the zenith direction: built independently from the
    /// unit vectors (the disc's north and east in the sky plane, and the zenith's
    /// projection), at many places and hour angles, including the poles' neighbourhood.
    #[test]
    fn parallactic_angle_is_the_position_angle_of_the_zenith() {
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let reject = |a: [f64; 3], m: [f64; 3]| {
            let d = dot(a, m);
            [a[0] - d * m[0], a[1] - d * m[1], a[2] - d * m[2]]
        };
        for lat in [-89.0, -60.0, -10.0, 0.0, 20.0, 52.0, 89.0] {
            for h in [-170.0, -90.0, -30.0, -1.0, 1.0, 45.0, 120.0] {
                for dec in [-50.0, -5.0, 0.0, 30.0, 70.0] {
                    let latitude = Angle::from_degrees(lat);
                    let body = Horizontal::from_equatorial(
                        Angle::from_degrees(h),
                        Angle::from_degrees(dec),
                        latitude,
                    )
                    .to_enu();
                    // The north celestial pole in east/north/up.
                    let pole = [0.0, latitude.cos(), latitude.sin()];
                    let north = reject(pole, body);
                    let east = cross(north, body);
                    let zenith = reject([0.0, 0.0, 1.0], body);
                    let expected = dot(zenith, east).atan2(dot(zenith, north));
                    let q = parallactic_angle(
                        Angle::from_degrees(h).radians(),
                        Angle::from_degrees(dec).radians(),
                        latitude.radians(),
                    );
                    let diff = Angle::from_radians(q - expected).wrapped_signed().degrees();
                    assert!(
                        diff.abs() < 1e-9,
                        "φ {lat} H {h} δ {dec}: {q} vs {expected}"
                    );
                }
            }
        }
        // On the meridian south of the zenith (northern observer) the zenith is toward
        // the pole: q = 0; north of the zenith it is opposite: q = 180°.
        let q = parallactic_angle(0.0, 0.2, 0.8_f64);
        assert!(q.abs() < 1e-12);
        let q = parallactic_angle(0.0, 1.2, 0.8_f64);
        assert!((q.abs() - std::f64::consts::PI).abs() < 1e-12);
    }

    #[test]
    fn enu_round_trip() {
        for (az, el) in [(0.0, 0.0), (90.0, 10.0), (200.0, -30.0), (359.0, 89.0)] {
            let h = Horizontal {
                azimuth: Angle::from_degrees(az),
                elevation: Angle::from_degrees(el),
            };
            let back = Horizontal::from_enu(h.to_enu());
            assert!((back.azimuth - h.azimuth).wrapped_signed().degrees().abs() < 1e-9);
            assert!((back.elevation - h.elevation).degrees().abs() < 1e-9);
        }
        let east = Horizontal {
            azimuth: Angle::from_degrees(90.0),
            elevation: Angle::ZERO,
        }
        .to_enu();
        assert!((east[0] - 1.0).abs() < 1e-15 && east[1].abs() < 1e-15);
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
