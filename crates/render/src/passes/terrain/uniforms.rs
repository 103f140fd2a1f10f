//! The terrain pass's uniforms, `#[repr(C)]` twins of their WGSL structs in
//! `shaders/render/terrain.wgsl`.

use crate::terrain_shading::AlbedoRampUniform;

/// The terrain pass's uniform (layout identical to WGSL `TerrainUniform`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TerrainUniform {
    /// Clip from world.
    pub view_projection: [[f32; 4]; 4],
    /// The camera's world position (m).
    pub camera: [f32; 3],
    /// Metres per texel.
    pub spacing: f32,
    /// World (x, z) + this = map (x, y), metres.
    pub map_offset: [f32; 2],
    /// Texels (width, height).
    pub map_size: [u32; 2],
    /// The sun, east–north–up.
    pub sun_enu: [f32; 3],
    /// The sun's angular radius (rad), from the atmosphere.
    pub sun_angular_radius: f32,
    /// The sky's irradiance on a horizontal surface.
    pub sky_irradiance: [f32; 3],
    /// The sun's elevation (rad).
    pub sun_elevation: f32,
    /// The sun's azimuth (rad).
    pub sun_azimuth: f32,
    /// 0: east/west pair; N: N azimuth layers.
    pub horizon_layers: u32,
    /// The viewer's distance from the planet's centre (m): celestial's cloud frame.
    pub viewer_radius: f32,
    /// Cloud layers casting shadows (the first `cloud_layer_count` of the buffer).
    pub cloud_layer_count: u32,
    /// The albedo ramp.
    pub albedo: AlbedoRampUniform,
    /// Multiplies the radiance written (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
    /// Radians per pixel: the footprint that band-limits the materials' detail.
    pub pixel_angle: f32,
    /// 1: the procedural materials; 0: the ramp.
    pub procedural: u32,
    /// 1: a colour texture is bound.
    pub colour_enabled: u32,
    /// The colour texture's pixels (east, south).
    pub colour_size: [u32; 2],
    /// The colour texture's pixels per metre.
    pub colour_texels_per_metre: f32,
    /// Alignment.
    pub padding0: f32,
    /// The procedural materials' parameters.
    pub materials: crate::terrain_materials::MaterialsUniform,
}

/// One marched cloud's shadow map parameters of a terrain draw (layout identical to WGSL
/// `VolumeShadowUniform` in `shaders/render/terrain.wgsl`; a draw holds two, the volume's
/// and the shell's: `super::cloud_shadow`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeShadowUniform {
    /// East/north of texel (0, 0)'s corner, metres.
    pub origin: [f32; 2],
    /// Texel edge, metres.
    pub cell_size: f32,
    /// The map plane's altitude, metres.
    pub plane: f32,
    /// Unit direction toward the light, east/north/up.
    pub to_sun: [f32; 3],
    /// 1 when a map is bound, 0 otherwise (no such cloud, or none toward this light).
    pub enabled: u32,
    /// Texels east × north.
    pub resolution: [u32; 2],
    /// Where the map's values start in the terrain pass's values buffer (elements).
    pub offset: u32,
    /// The casting cloud's top altitude, metres (the fade above the plane).
    pub top: f32,
}

impl VolumeShadowUniform {
    /// No volume shadow.
    pub const DISABLED: Self = Self {
        origin: [0.0; 2],
        cell_size: 1.0,
        plane: 0.0,
        to_sun: [0.0, 0.0, 1.0],
        enabled: 0,
        resolution: [1, 1],
        offset: 0,
        top: 1.0,
    };

    /// The parameters of `shadow`'s map, its values from element `offset` on.
    pub fn of(shadow: &crate::volume_clouds::CloudShadow, offset: u32) -> Self {
        Self {
            origin: shadow.origin,
            cell_size: shadow.cell_size,
            plane: shadow.plane,
            to_sun: shadow.to_sun,
            enabled: 1,
            resolution: shadow.resolution,
            offset,
            top: shadow.top,
        }
    }
}
