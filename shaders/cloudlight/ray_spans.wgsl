// The parts of a ray origin + t·direction (t ≥ 0, metres) where a density field may be
// non-zero, nearest first: spans[i] = (t_enter, t_exit) for i < count (0, 1 or 2; two
// for a spherical shell seen through its inner sphere). Twin: cloudlight::RaySpans.
struct RaySpans {
    spans: array<vec2<f32>, 2>,
    count: u32,
}

// The largest f32: a span's exit when a ray never leaves the field, and a march's "no
// distance limit".
const INFINITE_DISTANCE: f32 = 3.40282347e+38;

// No span: the ray misses the field (RaySpans::none).
fn ray_spans_none() -> RaySpans {
    return RaySpans(array<vec2<f32>, 2>(vec2<f32>(0.0), vec2<f32>(0.0)), 0u);
}
