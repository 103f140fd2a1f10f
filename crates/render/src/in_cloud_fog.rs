//! The fog of the cloud layers around a camera inside or near one: SGSky's closed-in
//! visibility (`celestial::sky::Sky::in_cloud_fog`: the layers' in-cloud extinction at
//! the camera and its columns up and down) seen through along each view, over the
//! terrain and the sky alike. Drawn by the cloud layers' pass after the layers; twin of
//! `shaders/render/in_cloud_fog.wgsl` (same names, argument order and units).

/// The fog's uniform block; layout identical to WGSL `InCloudFogUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
pub struct InCloudFogUniforms {
    /// The fog's radiance (the most immersed layer's inside), the atmosphere's unit.
    pub radiance: [f32; 3],
    /// The layers' in-cloud extinction at the camera (1/m).
    pub extinction: f32,
    /// Vertical optical depth of that extinction above the camera.
    pub optical_depth_up: f32,
    /// Vertical optical depth of that extinction below the camera, to sea level.
    pub optical_depth_down: f32,
    /// Height above the camera (m) past which no layer's band reaches.
    pub band_above: f32,
    /// Depth below the camera (m) past which no layer's band reaches.
    pub band_below: f32,
    /// 1 when the camera is in a layer's band, 0 otherwise.
    pub enabled: u32,
    /// Padding to 16 bytes.
    pub padding0: u32,
    /// Padding.
    pub padding1: u32,
    /// Padding.
    pub padding2: u32,
}

impl InCloudFogUniforms {
    /// The uniforms of celestial's fog (`None`: inactive).
    pub fn new(fog: Option<&celestial::sky::InCloudFog>) -> Self {
        match fog {
            None => Self::default(),
            Some(fog) => Self {
                radiance: fog.radiance,
                extinction: fog.extinction_per_m as f32,
                optical_depth_up: fog.optical_depth_up as f32,
                optical_depth_down: fog.optical_depth_down as f32,
                band_above: fog.band_above_m as f32,
                band_below: fog.band_below_m as f32,
                enabled: 1,
                ..Self::default()
            },
        }
    }
}

/// Fraction of the light from `scene_distance` (m along the view; infinite or ≥ 3e38
/// for the sky) that crosses the fog along a view of zenith cosine `mu` (flat bands):
/// `exp(−τ)`. A view that climbs (or descends) past the bands (`band_above`,
/// `band_below`) has crossed the whole column, τ = optical depth / max(|μ|, 10⁻³)
/// (celestial's `in_cloud_transmittance`); one that ends inside them takes the smaller
/// of that and the camera's extinction × distance, both upper bounds of its τ.
#[allow(clippy::too_many_arguments)]
pub fn in_cloud_fog_transmittance(
    mu: f32,
    scene_distance: f32,
    extinction: f32,
    optical_depth_up: f32,
    optical_depth_down: f32,
    band_above: f32,
    band_below: f32,
) -> f32 {
    let (column, band) = if mu > 0.0 {
        (optical_depth_up, band_above)
    } else {
        (optical_depth_down, band_below)
    };
    let distance = scene_distance.min(3.0e38);
    let slant = column / mu.abs().max(1.0e-3);
    if distance * mu.abs() >= band {
        return (-slant).exp();
    }
    (-(extinction * distance).min(slant)).exp()
}

/// `background` seen through the fog along `mu` to `scene_distance`: mixed toward the
/// fog's radiance by its transmittance.
pub fn in_cloud_fog(
    mu: f32,
    scene_distance: f32,
    fog: &InCloudFogUniforms,
    background: [f32; 3],
) -> [f32; 3] {
    if fog.enabled == 0 {
        return background;
    }
    let t = in_cloud_fog_transmittance(
        mu,
        scene_distance,
        fog.extinction,
        fog.optical_depth_up,
        fog.optical_depth_down,
        fog.band_above,
        fog.band_below,
    );
    std::array::from_fn(|i| t * background[i] + (1.0 - t) * fog.radiance[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_sky_sees_the_column_and_near_terrain_the_camera_extinction() {
        // Inside an overcast layer (3.912/25 m⁻¹), 120 m of it above and 200 m below.
        let k = 3.912_023 / 25.0;
        let (up, down) = (k * 120.0, k * 200.0);
        // The sky straight up: the column above.
        let sky = in_cloud_fog_transmittance(1.0, f32::INFINITY, k, up, down, 220.0, 300.0);
        assert!((sky - (-up).exp()).abs() < 1e-9, "{sky}");
        // Terrain 10 m away: the camera's extinction over 10 m (Koschmieder: 2 % at 25 m).
        let near = in_cloud_fog_transmittance(-0.5, 10.0, k, up, down, 220.0, 300.0);
        assert!((near - (-k * 10.0).exp()).abs() < 1e-6, "{near}");
        let at_visibility = in_cloud_fog_transmittance(-0.01, 25.0, k, up, down, 220.0, 300.0);
        // Terrain 1 km below, past the bands: the whole column below, as the ground.
        let below = in_cloud_fog_transmittance(-0.5, 2000.0, k, up, down, 220.0, 300.0);
        assert!((below - (-down / 0.5).exp()).abs() < 1e-9, "{below}");
        assert!((at_visibility - 0.02).abs() < 1e-4, "{at_visibility}");
        // No extinction (a layer of zero coverage): nothing changes, even for the sky.
        let clear = InCloudFogUniforms {
            enabled: 1,
            ..Default::default()
        };
        assert_eq!(in_cloud_fog(0.0, f32::INFINITY, &clear, [0.5; 3]), [0.5; 3]);
    }
}
