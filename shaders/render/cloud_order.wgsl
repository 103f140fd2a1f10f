// Two marched clouds seen at one pixel, composited in depth order (no bindings, so
// parity can call it): the shell and the volume cloud of one scene
// (render::cloud_order_composite).

// Twin of render::cloud_order::in_depth_order. Each cloud is (S, T_c): S the radiance
// it adds in front of what is behind it (its light through the air in front of it and
// the air's in-scatter it hides), T_c its transmittance; a cloud absent at the pixel is
// (0, 0, 0, 1). The one with the smaller opacity-weighted depth goes over the other (a
// over b when the depths tie): (S_near + T_near · S_far, T_near · T_far); the caller
// adds T · L_behind.
fn clouds_in_depth_order(a: vec4<f32>, a_depth: f32, b: vec4<f32>, b_depth: f32) -> vec4<f32> {
    var near = a;
    var far = b;
    if b_depth < a_depth {
        near = b;
        far = a;
    }
    return vec4<f32>(near.rgb + near.w * far.rgb, near.w * far.w);
}
