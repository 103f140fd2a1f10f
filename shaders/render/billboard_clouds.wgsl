// `[clouds.volume]` drawn as Dobashi et al. 2000's billboards over the opaque scene: cloudlight's
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
// moonlit air per instance in group 2 (render::billboard_clouds_io). The rungs without
// tables draw with render::billboard_clouds_rung instead.
#import atmos::aerial_perspective
#import render::billboard_clouds_io

@vertex
fn billboard_clouds_vertex(in: BillboardInstance, @builtin(instance_index) instance: u32) -> BillboardVarying {
    let air = aerial_perspective(billboard_world_offset(in));
    return billboard_clouds_seen_vertex(in, instance, air.transmittance, air.radiance);
}

@fragment
fn billboard_clouds_fragment(in: BillboardVarying) -> @location(0) vec4<f32> {
    return billboard_quad_fragment(in);
}
