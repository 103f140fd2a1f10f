// The opaque scene's distance along a view ray from its reverse-z depth (no bindings:
// the volume-cloud passes import it).

// Distance along unit `view` of a reverse-z depth with an infinite far plane
// (depth = near / view-space z, `forward` the camera's axis); the sky (depth 0) is
// beyond any limit (3e38 m).
fn scene_distance_from_depth(depth: f32, view: vec3<f32>, forward: vec3<f32>, near: f32) -> f32 {
    if depth <= 0.0 {
        return 3.0e38;
    }
    return near / (depth * dot(view, forward));
}
