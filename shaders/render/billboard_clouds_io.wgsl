// What the billboard pipelines share (render::billboard_clouds: the particles' air from
// the precomputed rung's tables; render::billboard_clouds_rung: from a rung's
// functions, computed per particle before the draw): the frame's parameters and the
// moonlit air per instance (group 2), and the vertex stage once the particle's air is
// known. Twin: render::billboard_clouds::composite_billboards_cpu (Rust).
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
    // 1: moon_air holds the moonlit air in front of each instance; 0: none; 2: the
    // moon's air from a rung's pass (render::billboard_clouds_rung adds it itself).
    moonlit: u32,
    pad1: u32,
}

@group(2) @binding(0) var<uniform> params: BillboardCloudParams;
// The moonlit air's radiance in front of instance i (xyz), when params.moonlit = 1.
@group(2) @binding(1) var<storage, read> moon_air: array<vec4<f32>>;

// The particle's centre relative to the eye in the world frame (x east, y up, z south;
// the instance holds east/north/up). Twin: render::billboard_clouds::world_offset.
fn billboard_world_offset(in: BillboardInstance) -> vec3<f32> {
    let relative = in.relative_density.xyz;
    return vec3<f32>(relative.x, relative.z, -relative.y);
}

// The particle's quad corner, its colour seen through the sun's air in front of it
// (`air_transmittance`, `air_radiance`) plus, at night (moonlit = 1), the moonlit air's
// radiance of moon_air.
fn billboard_clouds_seen_vertex(in: BillboardInstance, instance: u32, air_transmittance: vec3<f32>, air_radiance: vec3<f32>) -> BillboardVarying {
    let relative = in.relative_density.xyz;
    let s = billboard_screen(params.frame, relative, in.relative_density.w);
    let z = billboard_dot(relative, params.frame.forward);
    var radiance = air_radiance;
    if params.moonlit == 1u {
        radiance = radiance + moon_air[instance].xyz;
    }
    let seen = billboard_seen_through_air(in.colour_alpha.xyz, air_transmittance, radiance);
    // The varying's colour: the scaled radiance seen through the air.
    let seen_alpha = vec4<f32>(seen * params.radiance_scale, in.colour_alpha.w);
    return billboard_quad_vertex(params.frame, s, in.vertex, params.near / z, seen_alpha);
}
