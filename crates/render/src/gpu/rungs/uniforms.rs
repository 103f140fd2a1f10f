//! The rung passes' uniforms, `#[repr(C)]` twins of their WGSL structs.

/// The light of a rung's terrain draw (layout identical to WGSL `RungLight` in
/// `shaders/render/terrain_rung.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RungLightUniform {
    /// The camera, planet-centred (m).
    pub camera_position: [f32; 3],
    /// The atmosphere's top (m from the planet's centre).
    pub top_radius: f32,
    /// Unit direction toward the light.
    pub direction: [f32; 3],
    /// The planet's radius (m).
    pub planet_radius: f32,
    /// The terrain's lowest and highest elevation (m): the light table's span.
    pub elevation_range: [f32; 2],
    /// Alignment.
    pub padding: [f32; 2],
}

/// The terrain's aerial-perspective pass of a rung (layout identical to WGSL `RungAir`
/// in `shaders/render/rung_air.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct RungAirUniform {
    /// The scene camera (its `sun` the sun's direction).
    pub camera: atmos::frame::FrameCamera,
    /// Unit direction toward the moon (when `moon` is 1).
    pub moon_direction: [f32; 3],
    /// 1: add the moonlit in-scatter.
    pub moon: u32,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Multiplies the in-scatter written (the scene's exposure).
    pub radiance_scale: f32,
    /// Alignment.
    pub padding: [f32; 2],
}
