// Presents a frame of sky radiance from any rung of the atmos ladder (FrameOutput:
// in-scattered radiance and transmittance per pixel): adds the sun disc seen through
// the atmosphere, applies the display transform, sRGB-encodes, dithers and packs RGBA8.
// Twin: render::present (Rust).

#import atmos::frame
#import atmos::geometry
#import render::tonemap

struct PresentParameters {
    // Radiance of the sun disc above the atmosphere (irradiance / solid angle).
    sun_disc_radiance: vec3<f32>,
    // cos(sun angular radius).
    cos_sun_radius: f32,
    planet_radius: f32,
    exposure: f32,
    dither_seed: u32,
    // render::tonemap::DisplayTransform::code.
    display_transform: u32,
}

@group(0) @binding(0) var<uniform> camera: FrameCamera;
@group(0) @binding(1) var<uniform> present: PresentParameters;
@group(0) @binding(2) var radiance_in: texture_2d<f32>;
@group(0) @binding(3) var transmittance_in: texture_2d<f32>;
@group(0) @binding(4) var<storage, read_write> pixels: array<u32>;

// Radiance reaching the pixel: the atmosphere's in-scatter, plus the sun disc through
// the segment's transmittance where the view ray sees the disc and not the ground.
fn present_radiance(view: vec3<f32>, radiance: vec3<f32>, transmittance: vec3<f32>, camera: FrameCamera, present: PresentParameters) -> vec3<f32> {
    let r = length(camera.position);
    let mu = dot(view, camera.position) / r;
    let ground = ray_sphere_intersect(r, mu, present.planet_radius);
    if ground.x < 0.0 && dot(view, camera.sun) >= present.cos_sun_radius {
        return radiance + transmittance * present.sun_disc_radiance;
    }
    return radiance;
}

@compute @workgroup_size(8, 8)
fn present_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= camera.width || gid.y >= camera.height {
        return;
    }
    let index = gid.x + camera.width * gid.y;
    let view = frame_view_direction(gid.xy, camera);
    let radiance = present_radiance(view, textureLoad(radiance_in, gid.xy, 0).xyz, textureLoad(transmittance_in, gid.xy, 0).xyz, camera, present);
    let display = display_transform(radiance, present.exposure, present.display_transform);
    pixels[index] = pack_rgba8(quantize_srgb8(display, gid.xy, present.dither_seed));
}
