// Seed 002's billboards as a render pass: cloudlight::billboard_quad's instanced quads
// (one per particle, sorted back to front on the CPU) at depth 0, premultiplied, blended
// "over" (One, OneMinusSrcAlpha). Twin: cloudlight::billboard::rasterise (Rust).

#import cloudlight::billboard
#import cloudlight::billboard_quad

@group(0) @binding(0) var<uniform> frame: BillboardFrame;

@vertex
fn billboard_vertex(
    @builtin(vertex_index) vertex: u32,
    @location(0) relative_density: vec4<f32>,
    @location(1) colour_alpha: vec4<f32>,
) -> BillboardVarying {
    let s = billboard_screen(frame, relative_density.xyz, relative_density.w);
    return billboard_quad_vertex(frame, s, vertex, 0.0, colour_alpha);
}

@fragment
fn billboard_fragment(in: BillboardVarying) -> @location(0) vec4<f32> {
    return billboard_quad_fragment(in);
}
