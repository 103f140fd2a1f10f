// Dobashi et al. 2000's billboards as instanced quads, the vertex and fragment work that
// cloudlight::billboard_pass and render::billboard_clouds share: one quad per instance
// (six vertices; instance layout cloudlight::gpu::billboard::instance_layout), each a
// pixel wider than its splat's disc on every side so that the fragment shader, not the
// triangle edge rule, decides coverage: a pixel takes the splat at its centre
// (@builtin(position).xy = (i + ½, j + ½)). Premultiplied output, for a pipeline that
// blends "over" (One, OneMinusSrcAlpha). Twin: cloudlight::billboard::rasterise (Rust).
#import cloudlight::billboard

// A vertex stage's input: the vertex of the quad and the instance's attributes
// (cloudlight::gpu::billboard::instance_layout).
struct BillboardInstance {
    @builtin(vertex_index) vertex: u32,
    // Position relative to the eye (m) and density.
    @location(0) relative_density: vec4<f32>,
    // Linear RGB and the splat's weight (cloudlight::billboard::Billboard::weight).
    @location(1) colour_alpha: vec4<f32>,
}

struct BillboardVarying {
    @builtin(position) position: vec4<f32>,
    // Centre (pixels) and radius (pixels).
    @location(0) @interpolate(flat) centre_radius: vec3<f32>,
    // Linear RGB (not premultiplied) and the splat's weight.
    @location(1) @interpolate(flat) colour_alpha: vec4<f32>,
    // How the kernel becomes opacity (BillboardFrame's opacity_mode, splat_opacity).
    @location(2) @interpolate(flat) opacity_mode: u32,
}

// Vertex `vertex` (0 to 5) of the quad around the splat `s` (centre and radius in pixels,
// from billboard_screen) at clip depth `depth`, carrying `colour_alpha`. A splat without
// area is drawn nowhere.
fn billboard_quad_vertex(frame: BillboardFrame, s: vec3<f32>, vertex: u32, depth: f32, colour_alpha: vec4<f32>) -> BillboardVarying {
    var corners = array<vec2<f32>, 6>(
        vec2<f32>(-1.0, -1.0),
        vec2<f32>(1.0, -1.0),
        vec2<f32>(1.0, 1.0),
        vec2<f32>(-1.0, -1.0),
        vec2<f32>(1.0, 1.0),
        vec2<f32>(-1.0, 1.0),
    );
    var out: BillboardVarying;
    out.centre_radius = s;
    out.colour_alpha = colour_alpha;
    out.opacity_mode = frame.opacity_mode;
    if s.z > 0.0 {
        let p = s.xy + corners[vertex] * (s.z + 1.0);
        out.position = vec4<f32>(p.x / frame.half_width - 1.0, 1.0 - p.y / frame.half_height, depth, 1.0);
    } else {
        // No area: nothing drawn.
        out.position = vec4<f32>(0.0, 0.0, 0.0, 1.0);
    }
    return out;
}

// The splat's premultiplied colour and opacity at the fragment `in` (its pixel centre).
fn billboard_quad_fragment(in: BillboardVarying) -> vec4<f32> {
    let dx = in.position.x - in.centre_radius.x;
    let dy = in.position.y - in.centre_radius.y;
    let r = sqrt(dx * dx + dy * dy) / in.centre_radius.z;
    let a = splat_opacity(in.colour_alpha.w, splat_alpha(r), in.opacity_mode);
    return vec4<f32>(in.colour_alpha.xyz * a, a);
}
