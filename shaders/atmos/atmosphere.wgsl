// Physical parameters of a planet's atmosphere and its density profiles.
// Twin: atmos::atmosphere (Rust; f32 uniforms from the f64 `Atmosphere`).
// Units: metres, 1/m for coefficients; densities are relative (1 at their reference).

struct AtmosphereParameters {
    rayleigh_scattering: vec3<f32>,
    rayleigh_scale_height: f32,
    mie_scattering: vec3<f32>,
    mie_scale_height: f32,
    mie_extinction: vec3<f32>,
    mie_g: f32,
    ozone_absorption: vec3<f32>,
    ozone_center_altitude: f32,
    ground_albedo: vec3<f32>,
    ozone_half_width: f32,
    sun_irradiance: vec3<f32>,
    sun_angular_radius: f32,
    planet_radius: f32,
    top_radius: f32,
    padding: vec2<f32>,
}

// exp(−altitude/scale_height): Rayleigh and Mie density relative to the ground.
fn exponential_density(altitude: f32, scale_height: f32) -> f32 {
    return exp(-altitude / scale_height);
}

// A tent: 1 at center, falling linearly to 0 at center ± half_width (ozone).
fn tent_density(altitude: f32, center: f32, half_width: f32) -> f32 {
    return max(0.0, 1.0 - abs(altitude - center) / half_width);
}

// Extinction coefficient (1/m) per channel at an altitude: Rayleigh scattering,
// Mie extinction and ozone absorption, each weighted by its density.
fn extinction_at_altitude(atmosphere: AtmosphereParameters, altitude: f32) -> vec3<f32> {
    let rayleigh = exponential_density(altitude, atmosphere.rayleigh_scale_height);
    let mie = exponential_density(altitude, atmosphere.mie_scale_height);
    let ozone = tent_density(altitude, atmosphere.ozone_center_altitude, atmosphere.ozone_half_width);
    return atmosphere.rayleigh_scattering * rayleigh
        + atmosphere.mie_extinction * mie
        + atmosphere.ozone_absorption * ozone;
}
