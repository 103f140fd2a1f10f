//! Conversions between the render world frame (x east, y up, z south, metres from the
//! camera's ground point) and the east/north/up frame of terrain and the clouds.

/// A world direction or offset (x east, y up, z south) in the east/north/up frame of
/// terrain, the clouds and celestial: the workspace's one rotation between the two,
/// `skyscape_wgsl::common::world_to_enu` (WGSL twin in `common::frames`).
pub use skyscape_wgsl::common::world_to_enu;
