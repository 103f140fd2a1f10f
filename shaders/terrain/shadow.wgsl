// terrain::shadow — horizon-map shadow queries.
// Twin: terrain::shadow (Rust, crates/terrain/src/shadow.rs): same names, argument
// order and units. Angles in radians, azimuths clockwise from north (east = PI/2),
// directions unit vectors in the local east-north-up frame pointing towards the sun.

#import common::constants

// Angular radius of the sun's disc (0.2666 degrees).
const SUN_ANGULAR_RADIUS: f32 = 0.004650467;

// Horizon angle from a unorm alpha value (8- or 16-bit texture): alpha * PI - PI/2.
fn decode_horizon_angle(alpha: f32) -> f32 {
    return alpha * PI - 0.5 * PI;
}

// 1 when the sun's centre is above the horizon angle, else 0.
fn hard_shadow(sun_elevation: f32, horizon_angle: f32) -> f32 {
    return select(0.0, 1.0, sun_elevation > horizon_angle);
}

// Visible fraction of a disc whose centre is x radii above a horizontal line.
// Circular segment: (theta - a sqrt(1 - a^2)) / PI with a = |x|, theta = acos(a) as
// atan2(sqrt((1 - a)(1 + a)), a) (stable near a = 1), and the series of (u - sin u) / 2,
// u = 2 theta, for thin segments (u < 0.5, no cancellation). No sin() (WGSL allows it
// an absolute error of 2^-11) and no asin() (1.4e-4 off on lavapipe here).
fn sun_disc_visible_fraction(x: f32) -> f32 {
    let a = min(abs(x), 1.0);
    let root = sqrt((1.0 - a) * (1.0 + a));
    let theta = atan2(root, a);
    let u = 2.0 * theta;
    var twice_area: f32;
    if u < 0.5 {
        let u2 = u * u;
        twice_area = u * u2 * (1.0 / 6.0 - u2 * (1.0 / 120.0 - u2 * (1.0 / 5040.0 - u2 * (1.0 / 362880.0))));
    } else {
        twice_area = 2.0 * (theta - a * root);
    }
    let segment = twice_area * (0.5 / PI);
    return select(segment, 1.0 - segment, x >= 0.0);
}

// Visible fraction of the sun's disc above the horizon; radius <= 0 gives the hard shadow.
fn soft_shadow(sun_elevation: f32, horizon_angle: f32, sun_angular_radius: f32) -> f32 {
    if sun_angular_radius > 0.0 {
        return sun_disc_visible_fraction((sun_elevation - horizon_angle) / sun_angular_radius);
    }
    return hard_shadow(sun_elevation, horizon_angle);
}

// Elevation of a direction above the horizontal plane: atan2(z, |xy|).
fn sun_elevation(sun_direction: vec3<f32>) -> f32 {
    return atan2(sun_direction.z, sqrt(sun_direction.x * sun_direction.x + sun_direction.y * sun_direction.y));
}

// Azimuth of a direction, clockwise from north, in [0, TAU).
fn sun_azimuth(sun_direction: vec3<f32>) -> f32 {
    let a = atan2(sun_direction.x, sun_direction.y);
    return select(a, a + TAU, a < 0.0);
}

// The two layers of an N-azimuth horizon stack around an azimuth (layer k at
// k * TAU / N) and the weight of the upper one.
struct AzimuthLayers {
    lower: u32,
    upper: u32,
    weight: f32,
}

fn azimuth_layers(sun_azimuth: f32, count: u32) -> AzimuthLayers {
    let n = f32(count);
    let f0 = sun_azimuth / TAU * n;
    let f = f0 - floor(f0 / n) * n;
    let k = floor(f);
    let lower = u32(k) % count;
    return AzimuthLayers(lower, (lower + 1u) % count, f - k);
}

// Self-shadow from the east/west pair of horizon maps: east horizon while the sun is in the east.
fn self_shadow_east_west(horizon_east: f32, horizon_west: f32, sun_direction: vec3<f32>, sun_angular_radius: f32) -> f32 {
    let horizon = select(horizon_west, horizon_east, sun_direction.x >= 0.0);
    return soft_shadow(sun_elevation(sun_direction), horizon, sun_angular_radius);
}
