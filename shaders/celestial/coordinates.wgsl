// celestial::coordinates — sky directions and point-source brightness.
// Twin: crates/celestial/src/horizontal.rs and photometry.rs (Rust, generic over the
// float type; the f32 instance mirrors this file): same names, argument order and
// units. Angles in radians; azimuth from north through east (east = PI/2).

#import common::constants

// Illuminance (lux) of a magnitude-0 point source outside the atmosphere:
// L0 * (1 arcsec)^2 with L0 = 10.96e4 cd/m^2 (Bara, CIE V(lambda) AB zero point).
const ZERO_MAGNITUDE_ILLUMINANCE_LX: f32 = 2.576085587085128e-6;

// (azimuth, elevation) of a body at local hour angle `hour_angle` (west positive) and
// `declination`, seen from `latitude`. East/north/up components and two atan2 (no
// tan(declination), no asin), so poles, zenith and celestial poles stay finite.
fn equatorial_to_horizontal(hour_angle: f32, declination: f32, latitude: f32) -> vec2<f32> {
    let sin_h = sin(hour_angle);
    let cos_h = cos(hour_angle);
    let sin_d = sin(declination);
    let cos_d = cos(declination);
    let sin_p = sin(latitude);
    let cos_p = cos(latitude);
    let east = -cos_d * sin_h;
    let north = sin_d * cos_p - cos_d * cos_h * sin_p;
    let up = sin_d * sin_p + cos_d * cos_h * cos_p;
    var azimuth = atan2(east, north);
    azimuth = select(azimuth, azimuth + TAU, azimuth < 0.0);
    let elevation = atan2(up, sqrt(east * east + north * north));
    return vec2<f32>(azimuth, elevation);
}

// Pogson: E0 * 10^(-0.4 m) as exp(-0.4 ln 10 * m).
fn illuminance_from_magnitude(magnitude: f32) -> f32 {
    return ZERO_MAGNITUDE_ILLUMINANCE_LX * exp(-0.9210340371976183 * magnitude);
}
