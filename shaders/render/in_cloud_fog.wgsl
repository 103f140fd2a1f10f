// The fog of the cloud layers around a camera inside or near one: SGSky's closed-in
// visibility (celestial's Sky::in_cloud_fog) seen through along each view. Twin:
// render::in_cloud_fog (Rust): same names, argument order and units.

struct InCloudFogUniforms {
    // The fog's radiance (the most immersed layer's inside), the atmosphere's unit.
    radiance: vec3<f32>,
    // The layers' in-cloud extinction at the camera (1/m).
    extinction: f32,
    // Vertical optical depth of that extinction above the camera.
    optical_depth_up: f32,
    // Vertical optical depth of that extinction below the camera, to sea level.
    optical_depth_down: f32,
    // Height above and depth below the camera (m) past which no layer's band reaches.
    band_above: f32,
    band_below: f32,
    // 1 when the camera is in a layer's band, 0 otherwise (the fog then changes nothing).
    enabled: u32,
    padding0: u32,
    padding1: u32,
    padding2: u32,
}

// Fraction of the light from `scene_distance` (m along the view; ≥ 3e38 for the sky)
// that crosses the fog along a view of zenith cosine `mu` (flat bands): exp(−τ). A view
// that climbs (or descends) past the bands (band_above, band_below) has crossed the whole
// column, τ = optical depth / max(|μ|, 10⁻³) (celestial's in_cloud_transmittance);
// one that ends inside them takes the smaller of that and the camera's extinction ×
// distance (the fog as dense as at the camera all the way), both upper bounds of its τ.
fn in_cloud_fog_transmittance(mu: f32, scene_distance: f32, extinction: f32, optical_depth_up: f32, optical_depth_down: f32, band_above: f32, band_below: f32) -> f32 {
    var column = optical_depth_down;
    var band = band_below;
    if mu > 0.0 {
        column = optical_depth_up;
        band = band_above;
    }
    let distance = min(scene_distance, 3.0e38);
    let slant = column / max(abs(mu), 1.0e-3);
    if distance * abs(mu) >= band {
        return exp(-slant);
    }
    return exp(-min(extinction * distance, slant));
}

// `background` seen through the fog along `mu` to `scene_distance`: mixed toward the
// fog's radiance by its transmittance.
fn in_cloud_fog(mu: f32, scene_distance: f32, fog: InCloudFogUniforms, background: vec3<f32>) -> vec3<f32> {
    if fog.enabled == 0u {
        return background;
    }
    let t = in_cloud_fog_transmittance(mu, scene_distance, fog.extinction, fog.optical_depth_up, fog.optical_depth_down, fog.band_above, fog.band_below);
    return t * background + (1.0 - t) * fog.radiance;
}
