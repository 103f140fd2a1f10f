// The billboards (render::billboard_clouds) under a rung without tables (the closed
// form, single scattering): the same quads, depth test and blending, each particle seen
// through the sun's air in front of it that the rung's billboard air pass
// (render::billboard_air_rung) wrote per particle before the draw, read here per
// instance; at night (moonlit = 2) the moon's air from the same pass run for the moon
// is added.
// Twin: render::billboard_clouds::composite_billboards_cpu without tables (Rust).
//
// Bindings: group 2 only (groups 0 and 1 unused): render::billboard_clouds_io's
// parameters and moonlit air (read when moonlit = 1), and the sun's and the moon's air per
// particle.
#import render::billboard_clouds_io

// Two vec4 per instance: the sun's air's in-scattered radiance, then its transmittance
// (render::billboard_air_io's output).
@group(2) @binding(2) var<storage, read> sun_air: array<vec4<f32>>;
// The moon's, the same layout (when params.moonlit = 2).
@group(2) @binding(3) var<storage, read> moon_rung_air: array<vec4<f32>>;

@vertex
fn billboard_clouds_rung_vertex(in: BillboardInstance, @builtin(instance_index) instance: u32) -> BillboardVarying {
    var radiance = sun_air[2u * instance].xyz;
    if params.moonlit == 2u {
        radiance = radiance + moon_rung_air[2u * instance].xyz;
    }
    let transmittance = sun_air[2u * instance + 1u].xyz;
    return billboard_clouds_seen_vertex(in, instance, transmittance, radiance);
}

@fragment
fn billboard_clouds_rung_fragment(in: BillboardVarying) -> @location(0) vec4<f32> {
    return billboard_quad_fragment(in);
}
