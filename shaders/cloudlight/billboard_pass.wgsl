// Seed 002's billboards as a render pass: one instanced quad per particle (sorted back to
// front on the CPU), each a pixel wider than its splat's disc on every side so that the
// fragment shader, not the triangle edge rule, decides coverage: a pixel takes the splat
// at its centre (@builtin(position).xy = (i + ½, j + ½)). Premultiplied output; the
// pipeline blends "over" (One, OneMinusSrcAlpha). Twin: cloudlight::billboard::rasterise
// (Rust).

#import cloudlight::billboard

@group(0) @binding(0) var<uniform> frame: BillboardFrame;

struct BillboardVarying {
    @builtin(position) position: vec4<f32>,
    // Centre (pixels) and radius (pixels).
    @location(0) @interpolate(flat) centre_radius: vec3<f32>,
    // Linear RGB and the opacity at the centre.
    @location(1) @interpolate(flat) colour_alpha: vec4<f32>,
}

@vertex
fn billboard_vertex(
    @builtin(vertex_index) vertex: u32,
    @location(0) relative_density: vec4<f32>,
    @location(1) colour_alpha: vec4<f32>,
) -> BillboardVarying {
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0),
        vec2<f32>(1.0, -1.0),
        vec2<f32>(1.0, 1.0),
        vec2<f32>(-1.0, -1.0),
        vec2<f32>(1.0, 1.0),
        vec2<f32>(-1.0, 1.0),
    );
    let s = billboard_screen(frame, relative_density.xyz, relative_density.w);
    var out: BillboardVarying;
    out.centre_radius = s;
    out.colour_alpha = colour_alpha;
    if s.z > 0.0 {
        let p = s.xy + corners[vertex] * (s.z + 1.0);
        out.position = vec4<f32>(p.x / frame.half_width - 1.0, 1.0 - p.y / frame.half_height, 0.0, 1.0);
    } else {
        // No area: nothing drawn.
        out.position = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return out;
}

@fragment
fn billboard_fragment(in: BillboardVarying) -> @location(0) vec4<f32> {
    let dx = in.position.x - in.centre_radius.x;
    let dy = in.position.y - in.centre_radius.y;
    let r = sqrt(dx * dx + dy * dy) / in.centre_radius.z;
    let a = in.colour_alpha.w * splat_alpha(r);
    return vec4<f32>(in.colour_alpha.xyz * a, a);
}
