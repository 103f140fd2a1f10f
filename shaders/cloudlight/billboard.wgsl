// Dobashi et al. 2000's billboards: the soft splat and a billboard's place and size on the image.
// Twin: cloudlight::billboard (Rust, generic over the float type: the f32 instantiation
// mirrors these operations).

// The camera and size rule (cloudlight::billboard::ScreenFrame), 64 bytes.
struct BillboardFrame {
    // Unit camera basis; focal length in pixels.
    right: vec3<f32>,
    focal: f32,
    up: vec3<f32>,
    half_width: f32,
    forward: vec3<f32>,
    half_height: f32,
    // 0: Dobashi et al. 2000's size = (k·ρ/d)·ρ pixels; 1: a world diameter scale·ρ metres, projected.
    size_mode: u32,
    // k (pixel·metres) or metres per unit density.
    size_scale: f32,
    pad0: u32,
    pad1: u32,
}

// The soft splat: (1 − r²)² for r < 1, else 0 (r = distance from the centre over the
// radius).
fn splat_alpha(r: f32) -> f32 {
    if r < 1.0 {
        let q = 1.0 - r * r;
        return q * q;
    }
    return 0.0;
}

fn billboard_dot(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// A billboard's centre on the image (pixels from the top-left corner) and its radius in
// pixels, from its position relative to the eye (metres) and its density.
fn billboard_screen(frame: BillboardFrame, relative: vec3<f32>, density: f32) -> vec3<f32> {
    let x = billboard_dot(relative, frame.right);
    let y = billboard_dot(relative, frame.up);
    let z = billboard_dot(relative, frame.forward);
    let cx = frame.half_width + frame.focal * (x / z);
    let cy = frame.half_height - frame.focal * (y / z);
    var size: f32;
    if frame.size_mode == 0u {
        let distance = sqrt(billboard_dot(relative, relative));
        size = (frame.size_scale * density / distance) * density;
    } else {
        size = frame.size_scale * density * frame.focal / z;
    }
    return vec3<f32>(cx, cy, 0.5 * size);
}
