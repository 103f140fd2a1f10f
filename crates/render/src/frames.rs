//! Conversions between the render world frame (x east, y up, z south, metres from the
//! camera's ground point) and the east/north/up frame of terrain and the clouds.

/// A world direction or offset (x east, y up, z south) in the east/north/up frame of
/// terrain, the clouds and celestial: a rotation (f32 or f64; WGSL twin `world_to_enu`
/// in `shaders/render/clouds.wgsl`).
pub fn world_to_enu<F: Copy + std::ops::Neg<Output = F>>(v: [F; 3]) -> [F; 3] {
    [v[0], -v[2], v[1]]
}
