// The sky (and ground seen through aerial perspective) with seed 000's closed-form
// model, one compute invocation per pixel. Twin: render::sky (Rust).
// Frame: planet-centred, the camera on the +y axis at distance r from the centre, so
// a direction's zenith cosine mu is its y component.
#import common::constants
#import atmos::geometry
#import atmos::closed_form_sky
#import render::tonemap

struct SkyUniforms {
    // xyz: camera right, w: tan(horizontal half field of view)
    camera_right: vec4<f32>,
    // xyz: camera up, w: tan(vertical half field of view)
    camera_up: vec4<f32>,
    // xyz: camera forward, w: r, the camera's distance from the planet centre (m)
    camera_forward: vec4<f32>,
    // xyz: unit direction towards the sun, w: cos(sun angular radius)
    sun_direction: vec4<f32>,
    // xyz: Rayleigh scattering (1/m), w: Mie anisotropy g
    beta_rayleigh: vec4<f32>,
    // xyz: Mie scattering (1/m) of the equivalent homogeneous layer, w: planet radius (m)
    beta_mie: vec4<f32>,
    // xyz: sun irradiance at the camera (after extinction along the sun path),
    // w: radius of the homogeneous shell's top (m)
    sun_irradiance_at_camera: vec4<f32>,
    // xyz: sun disc radiance above the atmosphere (E / (π α²)), w: ground albedo
    sun_disc_radiance: vec4<f32>,
    // xyz: sunlight driving in-scatter: the sun irradiance times its transmittance
    // averaged over the shell's column, (1 − e^{−τs})/τs (w unused)
    sunlight_in_scatter: vec4<f32>,
    // x: exposure, yzw unused
    display: vec4<f32>,
    // x: width, y: height, z: dither seed, w unused
    image: vec4<u32>,
}

@group(0) @binding(0) var<uniform> sky: SkyUniforms;
@group(0) @binding(1) var<storage, read_write> sky_pixels: array<u32>;

// Unit view direction through the centre of pixel (x, y), y down.
fn sky_view_direction(pixel: vec2<u32>, uniforms: SkyUniforms) -> vec3<f32> {
    let size = vec2<f32>(f32(uniforms.image.x), f32(uniforms.image.y));
    let ndc = (vec2<f32>(pixel) + 0.5) / size * 2.0 - 1.0;
    let direction = uniforms.camera_forward.xyz
        + ndc.x * uniforms.camera_right.w * uniforms.camera_right.xyz
        - ndc.y * uniforms.camera_up.w * uniforms.camera_up.xyz;
    return normalize(direction);
}

// Radiance (same units as the sun irradiance, per sr) arriving at the camera from
// view_direction: in-scatter along the path through the homogeneous shell, plus
// the lit ground or the sun disc behind it, attenuated along the path.
fn shade_sky_pixel(view_direction: vec3<f32>, uniforms: SkyUniforms) -> vec3<f32> {
    let r = uniforms.camera_forward.w;
    let mu = view_direction.y;
    let planet_radius = uniforms.beta_mie.w;
    // The shell, coefficients and path are atmos's rung 1 (closed_form_sky); this pass
    // only adds the lit ground or the sun disc behind the path.
    let params = ClosedFormSkyParameters(
        uniforms.beta_rayleigh.xyz,
        uniforms.beta_rayleigh.w,
        uniforms.beta_mie.xyz,
        planet_radius,
        uniforms.sun_irradiance_at_camera.xyz,
        uniforms.sun_irradiance_at_camera.w,
    );
    let hits_ground = ray_sphere_intersect(r, mu, planet_radius).x >= 0.0;
    let cos_theta = dot(view_direction, uniforms.sun_direction.xyz);
    let sunlight = uniforms.sun_irradiance_at_camera.xyz;
    var radiance = closed_form_sky_radiance(r, mu, cos_theta, 1e30, uniforms.sunlight_in_scatter.xyz, params);
    let extinction = closed_form_sky_transmittance(r, mu, 1e30, params);
    if hits_ground {
        // Lambertian ground lit by the (camera's) sunlight: albedo/π · E · cos(sun zenith).
        let cos_sun_zenith = max(uniforms.sun_direction.y, 0.0);
        radiance += extinction * sunlight * (uniforms.sun_disc_radiance.w * INV_PI * cos_sun_zenith);
    } else if cos_theta >= uniforms.sun_direction.w {
        radiance += extinction * uniforms.sun_disc_radiance.xyz;
    }
    return radiance;
}

@compute @workgroup_size(8, 8)
fn sky_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= sky.image.x || gid.y >= sky.image.y {
        return;
    }
    let pixel = gid.xy;
    let radiance = shade_sky_pixel(sky_view_direction(pixel, sky), sky);
    let display = tonemap_exposure(radiance, sky.display.x);
    sky_pixels[pixel.y * sky.image.x + pixel.x] = pack_rgba8(quantize_srgb8(display, pixel, sky.image.z));
}
