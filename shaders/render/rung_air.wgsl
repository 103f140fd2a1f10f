// The aerial perspective of the terrain for a rung without tables, per pixel in a
// compute pass over the drawn frame: where the terrain's reverse-z depth shows a
// surface, the segment camera → surface along the pixel's ray (render::air_segment; the
// CPU's SkyQuery::with_max_distance to the hit) gives the rung's transmittance and
// in-scatter (render::rung_sky's segment_air, bound to the rung's module, as the
// clouds' and the billboards' air passes call it), and the pixel becomes surface ×
// transmittance + in-scatter (the moon's in-scatter added on a moonlit night; its
// atmosphere differs from the sun's in irradiance only, so the transmittance is the
// same). Sky pixels are copied. Bindings in group 0; the rung's parameters of the sun's
// and the moon's atmospheres in group 1.
// Twin: render::cpu_renderer's shade_terrain (surface × T + L of the segment model).
#import atmos::frame
#import render::scene_distance
#import render::air_segment
#import render::rung_sky

// Layout identical to render::gpu::rungs::RungAirUniform.
struct RungAir {
    // The scene camera, its `sun` the sun's direction.
    camera: FrameCamera,
    // Unit direction toward the moon (when `moon` is 1).
    moon_direction: vec3<f32>,
    // 1: add the moonlit in-scatter.
    moon: u32,
    // The reverse-z projection's near plane (m).
    near: f32,
    // Multiplies the in-scatter written (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    padding0: f32,
    padding1: f32,
}

@group(0) @binding(0) var<uniform> air: RungAir;
@group(0) @binding(1) var air_depth: texture_depth_2d;
@group(0) @binding(2) var air_surface: texture_2d<f32>;
@group(0) @binding(3) var air_out: texture_storage_2d<rgba16float, write>;
@group(1) @binding(0) var<uniform> air_sun: RungParameters;
@group(1) @binding(1) var<uniform> air_moon: RungParameters;

// A pixel's segment (render::air_segment): camera → the surface along the pixel's ray,
// of no length on the sky. Its `index` is unused (0): the pass writes the pixel of a
// texture (air_store).
fn rung_air_segment(pixel: vec2<u32>) -> AirSegment {
    let depth = textureLoad(air_depth, pixel, 0);
    let view = frame_view_direction(pixel, air.camera);
    var distance = 0.0;
    if depth > 0.0 {
        distance = scene_distance_from_depth(depth, view, air.camera.forward, air.near);
    }
    return air_segment(0u, view, distance, air.camera);
}

// A pixel of the pass: its surface colour (what the terrain pass drew) and its segment,
// whose `has_air` is false where the pass has nothing to add (outside the image, or the
// sky).
struct AirPixel {
    surface: vec4<f32>,
    segment: AirSegment,
}

// The pixel `gid` of the pass's dispatch: outside the image, no air; on the sky (a
// segment of no length), the surface is copied to the output here and there is no air.
fn air_pixel(gid: vec3<u32>) -> AirPixel {
    var out: AirPixel;
    if gid.x >= air.camera.width || gid.y >= air.camera.height {
        return out;
    }
    out.surface = textureLoad(air_surface, gid.xy, 0);
    out.segment = rung_air_segment(gid.xy);
    if out.segment.distance <= 0.0 {
        textureStore(air_out, gid.xy, out.surface);
        out.segment.has_air = false;
    }
    return out;
}

// Writes the pixel `p` seen through the air: surface × `transmittance` + `radiance`
// (in-scatter) × the radiance scale.
fn air_store(gid: vec3<u32>, p: AirPixel, transmittance: vec3<f32>, radiance: vec3<f32>) {
    textureStore(air_out, gid.xy, vec4<f32>(p.surface.xyz * transmittance + radiance * air.radiance_scale, 1.0));
}

@compute @workgroup_size(8, 8)
fn rung_air(@builtin(global_invocation_id) gid: vec3<u32>) {
    let p = air_pixel(gid);
    if !p.segment.has_air {
        return;
    }
    let sun = segment_air(p.segment, air.camera.sun, air_sun);
    var radiance = sun.radiance;
    if air.moon != 0u {
        radiance += segment_air(p.segment, air.moon_direction, air_moon).radiance;
    }
    air_store(gid, p, sun.transmittance, radiance);
}
