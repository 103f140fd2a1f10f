// terrain::horizon_bake — GPU east/west horizon bake (one line = one heightfield row).
// Twin: terrain::gpu (Rust driver) and terrain::horizon (CPU algorithms, same sampling:
// the texels of the same row, d_k = k * step, curvature drop d^2 * inv_two_r).
//
// Entry points:
// * horizon_sweep_rows: one invocation per row, Timonen-Westerholm hull sweep in the
//   curvature-corrected frame g = h - s^2 * inv_two_r (exact, O(width) per row); the
//   hull stack lives in `hull` (width u32 per row).
// * horizon_window: one invocation per texel, brute force over at most max_steps samples
//   (used when a maximum distance is set).

struct HorizonBakeParams {
    width: u32,
    height: u32,
    // K: the largest number of steps within the maximum distance (0xffffffff: none).
    max_steps: u32,
    // 1: march east (+x), 0: march west (-x).
    march_east: u32,
    // Distance of one step (the spacing), metres.
    step: f32,
    // 1 / (2 R) for the curvature drop, 1/m (0: flat).
    inv_two_r: f32,
    _pad0: u32,
    _pad1: u32,
}

const NO_HORIZON: f32 = -1.5707963267948966;

@group(0) @binding(0) var<uniform> params: HorizonBakeParams;
@group(0) @binding(1) var<storage, read> heights: array<f32>;
@group(0) @binding(2) var<storage, read_write> hull: array<u32>;
@group(0) @binding(3) var<storage, read_write> angles: array<f32>;

// Texel index of the k-th sample of `row` in marching order.
fn row_texel(row: u32, k: u32) -> u32 {
    if params.march_east != 0u {
        return row * params.width + k;
    }
    return row * params.width + (params.width - 1u - k);
}

// Tangent of the elevation of a sample `steps` steps ahead (same formula as the CPU).
fn horizon_tangent(h_from: f32, h_to: f32, steps: u32) -> f32 {
    let d = f32(steps) * params.step;
    return (h_to - h_from - d * d * params.inv_two_r) / d;
}

fn curved_height(row: u32, k: u32) -> f32 {
    let s = f32(k) * params.step;
    return heights[row_texel(row, k)] - s * s * params.inv_two_r;
}

@compute @workgroup_size(64)
fn horizon_sweep_rows(@builtin(global_invocation_id) gid: vec3<u32>) {
    let row = gid.x;
    if row >= params.height {
        return;
    }
    let n = params.width;
    let base = row * n;
    var top = 0u;
    for (var i = 0u; i < n; i++) {
        let k = n - 1u - i;
        let gk = curved_height(row, k);
        // Pop hull points that k cannot see past: slope(k, b) >= slope(k, a).
        loop {
            if top < 2u {
                break;
            }
            let a = hull[base + top - 1u];
            let b = hull[base + top - 2u];
            if (curved_height(row, b) - gk) * f32(a - k) >= (curved_height(row, a) - gk) * f32(b - k) {
                top -= 1u;
            } else {
                break;
            }
        }
        var angle = NO_HORIZON;
        if top > 0u {
            let j = hull[base + top - 1u];
            angle = atan(horizon_tangent(heights[row_texel(row, k)], heights[row_texel(row, j)], j - k));
        }
        angles[row_texel(row, k)] = angle;
        hull[base + top] = k;
        top += 1u;
    }
}

@compute @workgroup_size(64)
fn horizon_window(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let index = gid.x + gid.y * groups.x * 64u;
    if index >= params.width * params.height {
        return;
    }
    let row = index / params.width;
    let k = index % params.width;
    let remaining = params.width - 1u - k;
    let last = k + min(remaining, params.max_steps);
    let h_k = heights[row_texel(row, k)];
    var found = false;
    var best = 0.0;
    for (var j = k + 1u; j <= last; j++) {
        let t = horizon_tangent(h_k, heights[row_texel(row, j)], j - k);
        best = select(t, max(best, t), found);
        found = true;
    }
    angles[row_texel(row, k)] = select(NO_HORIZON, atan(best), found);
}
