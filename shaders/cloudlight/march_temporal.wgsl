// Temporal amortisation of a view march (after Schneider's Nubis talks, which march a
// fraction of the cloud pixels each frame and reproject the rest): each frame marches
// one pixel of every 2×2 block, in turn, and takes the others from the last frame's
// image where the cloud seen through them was then. Twins: cloudlight::march::temporal
// (interleave_marches, reprojected_pixel).
#import cloudlight::march

// Whether `pixel` is marched in the frame of `phase` (0..3): the block's pixel
// x mod 2 + 2·(y mod 2) = phase.
fn interleave_marches(pixel: vec2<u32>, phase: u32) -> bool {
    return (pixel.x & 1u) + 2u * (pixel.y & 1u) == phase % 4u;
}

// A pinhole camera as the march's params hold it: origin; unit forward, right, up; the
// tangents of the horizontal and vertical half fields of view.
struct MarchCamera {
    origin: vec3<f32>,
    forward: vec3<f32>,
    right: vec3<f32>,
    up: vec3<f32>,
    tan_half: vec2<f32>,
}

// Where the point `distance` metres along `now`'s ray through `pixel` was in `before`'s
// image of the same size: its image position in pixels (pixel (i, j) spans [i, i + 1) ×
// [j, j + 1)), or (-1, -1) when it was behind that camera or outside its image. A pixel
// the last frame saw no cloud through is taken at `fallback_distance` (the sky far away:
// the view's turn only).
fn reprojected_position(
    now: MarchCamera,
    before: MarchCamera,
    size: vec2<u32>,
    pixel: vec2<u32>,
    distance: f32,
    fallback_distance: f32,
) -> vec2<f32> {
    let direction = pixel_direction(pixel, size, now.forward, now.right, now.up, now.tan_half);
    var along = distance;
    if !(along > 0.0) {
        along = fallback_distance;
    }
    let point = now.origin + direction * along;
    let v = point - before.origin;
    let depth = dot(v, before.forward);
    if !(depth > 0.0) {
        return vec2<f32>(-1.0, -1.0);
    }
    let sx = dot(v, before.right) / (depth * before.tan_half.x);
    let sy = dot(v, before.up) / (depth * before.tan_half.y);
    let x = (sx + 1.0) * 0.5 * f32(size.x);
    let y = (1.0 - sy) * 0.5 * f32(size.y);
    if !(x >= 0.0 && y >= 0.0 && x < f32(size.x) && y < f32(size.y)) {
        return vec2<f32>(-1.0, -1.0);
    }
    return vec2<f32>(x, y);
}
