// Bake of the sky-irradiance LUT: one workgroup per texel (μ_s, r), one invocation
// per normal layer. The 32 × 32 directions' radiance (air light through this rung's
// view march, plus the ground's Lambertian radiance on ground rays) is marched four
// per invocation into workgroup memory, then each invocation integrates its normal's
// clamped cosine over all of them. Twin: atmos::lut::sky_irradiance.
#import atmos::lut_sampling

@group(2) @binding(0) var sky_irradiance_out: texture_storage_2d_array<rgba32float, write>;

// w·L (rgb) and μ of each direction.
var<workgroup> sky_irradiance_field: array<vec4<f32>, 1024>;

// Zenith sample i of the bake's direction quadrature at radius r: (μ, share of dμ,
// the exact μ-length of its cell). Half the samples on the sky's zenith angles
// [0, θ_h] at θ_h sin(πu/2), half on the ground's [θ_h, π] at
// θ_h + (π − θ_h)(1 − cos(πu/2)): cells crowd towards the horizon and stay under 9° at
// the zenith and the nadir.
fn sky_irradiance_direction_zenith_angle(horizon: f32, i: u32, edge: f32) -> f32 {
    let half = SKY_IRRADIANCE_DIRECTION_ZENITHS / 2u;
    if i < half {
        return horizon * sin(0.5 * PI * edge / f32(half));
    }
    return horizon + (PI - horizon) * (1.0 - cos(0.5 * PI * edge / f32(half)));
}

fn sky_irradiance_direction_zenith(r: f32, planet_radius: f32, i: u32) -> vec2<f32> {
    let horizon = horizon_zenith_angle(r, planet_radius);
    let k = f32(i % (SKY_IRRADIANCE_DIRECTION_ZENITHS / 2u));
    let low = sky_irradiance_direction_zenith_angle(horizon, i, k);
    let high = sky_irradiance_direction_zenith_angle(horizon, i, k + 1.0);
    return vec2<f32>(cos(sky_irradiance_direction_zenith_angle(horizon, i, k + 0.5)), cos(low) - cos(high));
}

// Direction `index` (zenith index / 32, azimuth index % 32) of a texel at (r, μ_s):
// (w·L, μ), the radiance arriving from it times its solid angle, and its zenith cosine.
fn sky_irradiance_direction_radiance(r: f32, mu_s: f32, index: u32) -> vec4<f32> {
    let zenith = sky_irradiance_direction_zenith(r, lut_atmosphere.planet_radius, index / SKY_IRRADIANCE_DIRECTION_AZIMUTHS);
    let mu = zenith.x;
    let azimuth_count = f32(SKY_IRRADIANCE_DIRECTION_AZIMUTHS);
    let phi = PI * (f32(index % SKY_IRRADIANCE_DIRECTION_AZIMUTHS) + 0.5) / azimuth_count;
    let sin_v = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    let nu = mu * mu_s + sin_v * sin_s * cos(phi);
    let segment = march_view_segment(r, mu, mu_s, nu, UNLIMITED_DISTANCE, SKY_IRRADIANCE_SAMPLES);
    var radiance = segment.radiance;
    let bounds = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    if bounds.z > 0.5 {
        let r_g = radius_along_ray(r, mu, bounds.y);
        let mu_s_g = clamp((r * mu_s + bounds.y * nu) / r_g, -1.0, 1.0);
        let direct = sun_transmittance(r_g, mu_s_g);
        let sky = multiple_scattering_ground_irradiance(lookup_multiple_scattering(r_g, mu_s_g));
        let irradiance_over_pi = direct * max(mu_s_g, 0.0) / PI + sky;
        radiance += segment.transmittance * irradiance_over_pi * lut_atmosphere.ground_albedo * lut_atmosphere.sun_irradiance;
    }
    let weight = zenith.y * PI / azimuth_count;
    return vec4<f32>(radiance * weight, mu);
}

@compute @workgroup_size(256)
fn bake_sky_irradiance_lut(@builtin(workgroup_id) texel: vec3<u32>, @builtin(local_invocation_index) layer: u32) {
    let uv = vec2<f32>((f32(texel.x) + 0.5) / f32(SKY_IRRADIANCE_WIDTH), (f32(texel.y) + 0.5) / f32(SKY_IRRADIANCE_HEIGHT));
    let r_mu_s = sky_irradiance_lut_r_mu_s(uv, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    for (var m = 0u; m < 4u; m++) {
        let index = layer + 256u * m;
        sky_irradiance_field[index] = sky_irradiance_direction_radiance(r_mu_s.x, r_mu_s.y, index);
    }
    workgroupBarrier();
    let normal = sky_irradiance_layer_normal(layer);
    var irradiance = vec3<f32>(0.0);
    for (var index = 0u; index < 1024u; index++) {
        let entry = sky_irradiance_field[index];
        irradiance += entry.xyz * sky_irradiance_cosines(normal, entry.w, index % SKY_IRRADIANCE_DIRECTION_AZIMUTHS);
    }
    textureStore(sky_irradiance_out, texel.xy, layer, vec4<f32>(irradiance, 1.0));
}
