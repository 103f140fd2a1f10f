//! Conversions between the render world frame (x east, y up, z south, metres from the
//! camera's ground point) and the east/north/up frame of terrain and the clouds.

/// A world direction or offset (x east, y up, z south) in the volume's east/north/up
/// frame.
pub fn world_to_enu(v: [f64; 3]) -> [f64; 3] {
    [v[0], -v[2], v[1]]
}
