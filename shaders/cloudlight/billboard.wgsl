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
    // 0: Dobashi et al. 2000's size = (k·ρ/d)·ρ pixels; 1: a world diameter scale·ρ metres,
    // projected; 2: a world diameter of scale metres whatever the density, projected.
    size_mode: u32,
    // k (pixel·metres), metres per unit density or the diameter in metres.
    size_scale: f32,
    // How the kernel becomes opacity (splat_opacity): 0 scaled, 1 an optical depth.
    opacity_mode: u32,
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

// The opacity a splat gives a pixel where its kernel (splat_alpha) is `kernel` and its
// weight is `weight`: weight·kernel (opacity_mode 0: Dobashi et al. 2000's texture alpha
// times the particle's), 1 − exp(−weight·kernel) (1: an optical depth spread over the
// kernel).
fn splat_opacity(weight: f32, kernel: f32, opacity_mode: u32) -> f32 {
    let x = weight * kernel;
    if opacity_mode == 1u {
        return 1.0 - exp(-x);
    }
    return x;
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
    } else if frame.size_mode == 1u {
        size = frame.size_scale * density * frame.focal / z;
    } else {
        size = frame.size_scale * frame.focal / z;
    }
    return vec3<f32>(cx, cy, 0.5 * size);
}
