// `[clouds.volume]` drawn as seed 002's billboards over the opaque scene: cloudlight's
// instanced quads (cloudlight::billboard_quad: one per particle, sorted back to front on
// the CPU; instance layout of cloudlight::gpu::billboard), each a pixel wider than its
// splat's disc so the fragment shader decides coverage at the pixel centre
// (cloudlight::billboard's billboard_screen and splat_alpha). Each particle is seen
// through the air between the camera and its centre (atmos' aerial_perspective, per
// instance in the vertex stage), and sits at the reverse-z depth near / z: the
// pipeline's depth test (Greater, read-only) against the terrain's depth hides it behind
// mountains. Premultiplied output, blended "over" (One, OneMinusSrcAlpha). The HDR
// target holds radiance × exposure: radiance_scale.
// Twin: render::billboard_clouds::composite_billboards_cpu (Rust).
//
// At night (moonlit = 1) the moonlit air in front of each particle, computed on the CPU
// for both renderers (render::billboard_clouds::moonlit_air), is added to the sun's air.
//
// Bindings: the LUTs in groups 0 and 1 (atmos::lut_bindings), the parameters and the
// moonlit air per instance in group 2.
#import atmos::aerial_perspective
#import cloudlight::billboard
#import cloudlight::billboard_quad
#import render::billboard_air

struct BillboardCloudParams {
    // The camera (east/north/up basis) and size rule, cloudlight::billboard::ScreenFrame.
    frame: BillboardFrame,
    // The near plane of the scene's reverse-z projection (m).
    near: f32,
    // Multiplies the particles' light (the HDR target holds radiance × exposure).
    radiance_scale: f32,
    // 1: moon_air holds the moonlit air in front of each instance; 0: none.
    moonlit: u32,
    pad1: u32,
}

@group(2) @binding(0) var<uniform> params: BillboardCloudParams;
// The moonlit air's radiance in front of instance i (xyz), when params.moonlit = 1.
@group(2) @binding(1) var<storage, read> moon_air: array<vec4<f32>>;

@vertex
fn billboard_clouds_vertex(in: BillboardInstance, @builtin(instance_index) instance: u32) -> BillboardVarying {
    let relative = in.relative_density.xyz;
    let s = billboard_screen(params.frame, relative, in.relative_density.w);
    let z = billboard_dot(relative, params.frame.forward);
    // East/north/up to the world frame (x east, y up, z south).
    let air = aerial_perspective(vec3<f32>(relative.x, relative.z, -relative.y));
    var radiance = air.radiance;
    if params.moonlit == 1u {
        radiance = radiance + moon_air[instance].xyz;
    }
    let seen = billboard_seen_through_air(in.colour_alpha.xyz, air.transmittance, radiance);
    // The varying's colour: the scaled radiance seen through the air.
    let seen_alpha = vec4<f32>(seen * params.radiance_scale, in.colour_alpha.w);
    return billboard_quad_vertex(params.frame, s, in.vertex, params.near / z, seen_alpha);
}

@fragment
fn billboard_clouds_fragment(in: BillboardVarying) -> @location(0) vec4<f32> {
    return billboard_quad_fragment(in);
}
