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

// A camera given by a caller's view and projection matrices and viewport. Twin:
// atmos::view (Rust).
struct FrameView {
    // Takes a target position (x, y, 1) (pixels, pixel centres at +0.5: a fragment's
    // @builtin(position).xy) to a planet-frame direction through it (not normalised).
    direction_from_position: mat3x3<f32>,
    // The inverse projection: clip space (ndc.xy, depth, 1) to view space (homogeneous).
    view_from_clip: mat4x4<f32>,
    // The viewport: x, y, width, height (pixels).
    viewport: vec4<f32>,
}

// Unit planet-frame view direction through the target position `position`.
fn frame_view_direction_at(position: vec2<f32>, view: FrameView) -> vec3<f32> {
    let m = view.direction_from_position;
    return normalize(m[0] * position.x + m[1] * position.y + m[2]);
}

// The normalised device coordinates of a target position in the view's viewport.
fn frame_view_ndc(position: vec2<f32>, view: FrameView) -> vec2<f32> {
    let u = (position.x - view.viewport.x) / view.viewport.z;
    let v = (position.y - view.viewport.y) / view.viewport.w;
    return vec2<f32>(2.0 * u - 1.0, 1.0 - 2.0 * v);
}

// Distance (view-space units) from the eye to the point a depth buffer holds at
// `position`: the inverse projection of (ndc, depth).
fn frame_view_distance(position: vec2<f32>, depth: f32, view: FrameView) -> f32 {
    let ndc = frame_view_ndc(position, view);
    let m = view.view_from_clip;
    let point = m[0] * ndc.x + m[1] * ndc.y + m[2] * depth + m[3];
    return length(point.xyz / point.w);
}
