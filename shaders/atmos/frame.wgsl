// A pinhole camera for rendering a frame of sky radiance, shared by every rung's
// renderer. Twin: atmos::frame (Rust). Units: metres; directions are unit vectors.

struct FrameCamera {
    // Planet-centred position (m).
    position: vec3<f32>,
    width: u32,
    // Orthonormal basis: right, up and forward (the view direction of the centre).
    right: vec3<f32>,
    height: u32,
    up: vec3<f32>,
    // tan(vertical field of view / 2).
    tan_half_fov_y: f32,
    forward: vec3<f32>,
    // Segment length limit (m); ≥ 1e30 means "to the ground or space".
    max_distance: f32,
    // Unit direction toward the sun.
    sun: vec3<f32>,
    padding: u32,
}

// Unit view direction through the centre of `pixel` (x right, y down, row-major).
fn frame_view_direction(pixel: vec2<u32>, camera: FrameCamera) -> vec3<f32> {
    let aspect = f32(camera.width) / f32(camera.height);
    let ndc_x = (2.0 * (f32(pixel.x) + 0.5) / f32(camera.width) - 1.0) * camera.tan_half_fov_y * aspect;
    let ndc_y = (1.0 - 2.0 * (f32(pixel.y) + 0.5) / f32(camera.height)) * camera.tan_half_fov_y;
    return normalize(camera.forward + ndc_x * camera.right + ndc_y * camera.up);
}
