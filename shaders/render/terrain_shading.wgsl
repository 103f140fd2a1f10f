// What a scene adds to Hoffman & Preetham 2002's terrain term: the albedo ramp by elevation and slope,
// and the sum of the sun's and the sky's light. Twin: render::terrain_shading (Rust),
// same names, argument order and units.
#import common::constants
#import terrain::shading

// The ramp's stops (at most 8), heights packed four to a vec4. Rust: AlbedoRampUniform.
struct AlbedoRamp {
    heights: array<vec4<f32>, 2>,
    colors: array<vec4<f32>, 8>,
    steep_color: vec3<f32>,
    stop_count: u32,
    cos_steep: f32,
    cos_gentle: f32,
    padding: vec2<f32>,
}

fn ramp_height(ramp: AlbedoRamp, k: u32) -> f32 {
    return ramp.heights[k / 4u][k % 4u];
}

// Albedo at `elevation` (m) on a surface whose unit normal has up component `up`:
// piecewise linear between the stops, the steep colour blended in over the 10° below
// the steep slope.
fn terrain_albedo(ramp: AlbedoRamp, elevation: f32, up: f32) -> vec3<f32> {
    let n = ramp.stop_count;
    var by_height: vec3<f32>;
    if elevation <= ramp_height(ramp, 0u) {
        by_height = ramp.colors[0].xyz;
    } else if elevation >= ramp_height(ramp, n - 1u) {
        by_height = ramp.colors[n - 1u].xyz;
    } else {
        var k = 0u;
        for (var i = 1u; i < n; i++) {
            if ramp_height(ramp, i) <= elevation {
                k = i;
            }
        }
        let t = (elevation - ramp_height(ramp, k)) / (ramp_height(ramp, k + 1u) - ramp_height(ramp, k));
        by_height = mix(ramp.colors[k].xyz, ramp.colors[k + 1u].xyz, t);
    }
    let rock = clamp((ramp.cos_gentle - up) / (ramp.cos_gentle - ramp.cos_steep), 0.0, 1.0);
    return mix(by_height, ramp.steep_color, rock);
}

// Outgoing radiance of a Lambertian terrain point: [terrain_shading(N, L, albedo,
// self_shadow, cloud_shadow) · E_sun·T_sun + albedo · E_sky · (1 + N·up)/2] / π.
fn surface_radiance(normal: vec3<f32>, up: f32, sun: vec3<f32>, albedo: vec3<f32>, self_shadow: f32, cloud_shadow: f32, sun_irradiance_at_point: vec3<f32>, sky_irradiance: vec3<f32>) -> vec3<f32> {
    let direct = terrain_shading(normal, sun, albedo, self_shadow, cloud_shadow) * sun_irradiance_at_point;
    let ambient = albedo * sky_irradiance * (0.5 * (1.0 + up));
    return (direct + ambient) * INV_PI;
}
