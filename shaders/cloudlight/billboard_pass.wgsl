// Dobashi et al. 2000's billboards as a render pass: cloudlight::billboard_quad's instanced quads
// (one per particle, sorted back to front on the CPU) at depth 0, premultiplied, blended
// "over" (One, OneMinusSrcAlpha). Twin: cloudlight::billboard::rasterise (Rust).

#import cloudlight::billboard
#import cloudlight::billboard_quad

@group(0) @binding(0) var<uniform> frame: BillboardFrame;

@vertex
fn billboard_vertex(in: BillboardInstance) -> BillboardVarying {
    let s = billboard_screen(frame, in.relative_density.xyz, in.relative_density.w);
    return billboard_quad_vertex(frame, s, in.vertex, 0.0, in.colour_alpha);
}

@fragment
fn billboard_fragment(in: BillboardVarying) -> @location(0) vec4<f32> {
    return billboard_quad_fragment(in);
}
