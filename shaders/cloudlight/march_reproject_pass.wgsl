// The reprojection pass of a temporally amortised march (cloudlight::gpu::TemporalMarch):
// every pixel the frame does not march takes the last frame's result from where its
// cloud was then (march_temporal's reprojected_position; bilinear between the four
// nearest pixel centres, clamped at the image's edges) and is marked done (the second
// texel's y = 0, z its age: frames since it was marched); a pixel marched this frame,
// one whose cloud was outside the last image, or one whose value would be older than
// MAX_AGE frames is marked for the march (y = 1), which then marches exactly those. The
// age bound keeps a value that a moving camera carries from pixel to pixel, dodging
// each frame's marched pixels, from living on.
#import cloudlight::field_march
#import cloudlight::march_temporal

@group(0) @binding(0) var<uniform> params: MarchParams;
// The last frame's camera as MarchParams' first four rows; w of the fifth: the distance
// (m) a pixel without cloud is taken at.
@group(0) @binding(1) var<uniform> before: array<vec4<f32>, 5>;
// The last frame's image (the march's layout).
@group(0) @binding(2) var<storage, read> history: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> image_out: array<vec4<f32>>;

// The oldest value a pixel may carry: a still camera's pixel is marched every fourth frame.
const MAX_AGE: f32 = 3.0;

fn camera_of(rows: array<vec4<f32>, 5>) -> MarchCamera {
    return MarchCamera(rows[0].xyz, rows[1].xyz, rows[2].xyz, rows[3].xyz, vec2<f32>(rows[1].w, rows[2].w));
}

@compute @workgroup_size(8, 8)
fn reproject_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = params.image.xy;
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let index = 2u * (gid.x + size.x * gid.y);
    if interleave_marches(gid.xy, params.view.w) {
        image_out[index + 1u] = vec4<f32>(0.0, 1.0, 0.0, 0.0);
        return;
    }
    let now = MarchCamera(
        params.cam_origin.xyz,
        params.cam_forward.xyz,
        params.cam_right.xyz,
        params.cam_up.xyz,
        vec2<f32>(params.cam_forward.w, params.cam_right.w),
    );
    let last = camera_of(before);
    let position = reprojected_position(now, last, size, gid.xy, history[index + 1u].x, before[4].w);
    if position.x < 0.0 {
        image_out[index + 1u] = vec4<f32>(0.0, 1.0, 0.0, 0.0);
        return;
    }
    // The four pixel centres around the position and their weights.
    let centre = position - vec2<f32>(0.5);
    let low = floor(centre);
    let t = centre - low;
    let top = vec2<i32>(size) - vec2<i32>(1);
    let x0 = clamp(i32(low.x), 0, top.x);
    let y0 = clamp(i32(low.y), 0, top.y);
    let x1 = clamp(i32(low.x) + 1, 0, top.x);
    let y1 = clamp(i32(low.y) + 1, 0, top.y);
    let corners = array<vec2<i32>, 4>(vec2(x0, y0), vec2(x1, y0), vec2(x0, y1), vec2(x1, y1));
    let weights = array<f32, 4>((1.0 - t.x) * (1.0 - t.y), t.x * (1.0 - t.y), (1.0 - t.x) * t.y, t.x * t.y);
    var colour = vec4<f32>(0.0);
    var depth = 0.0;
    var age = 0.0;
    for (var i = 0u; i < 4u; i = i + 1u) {
        let at = 2u * (u32(corners[i].x) + size.x * u32(corners[i].y));
        colour = colour + weights[i] * history[at];
        depth = depth + weights[i] * history[at + 1u].x;
        if weights[i] > 0.0 {
            age = max(age, history[at + 1u].z);
        }
    }
    age = age + 1.0;
    if age > MAX_AGE {
        image_out[index + 1u] = vec4<f32>(0.0, 1.0, 0.0, 0.0);
        return;
    }
    image_out[index] = colour;
    image_out[index + 1u] = vec4<f32>(depth, 0.0, age, 0.0);
}
