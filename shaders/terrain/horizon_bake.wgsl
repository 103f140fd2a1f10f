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
// * horizon_sweep_lines / horizon_window_lines: the same for the axes and diagonals, one
//   invocation per digital line; horizon_off_axis_lines: any other azimuth, the
//   sampling of terrain::horizon off the grid (texel's own ray for near_steps, then the
//   line's samples interpolated across it), every sample of each window (end of file).

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

// ---------------------------------------------------------------- any azimuth
// Digital lines of terrain::horizon (see its docs): line c holds the texels
// (u, c + offsets[u]) (u dominant, m minor) that lie in the map. `offsets` is uploaded
// from the CPU (round(u * t) in f64) so that both sides walk the same texels. Positions
// along the line count in-map texels in marching order, d_k = k * step.

struct HorizonLineParams {
    // 1: the dominant axis is x (columns), 0: it is y (rows).
    dominant_is_x: u32,
    // 1: march toward increasing u, 0: decreasing.
    march_forward: u32,
    n_dominant: u32,
    n_minor: u32,
    // Line id of invocation 0.
    first_line: i32,
    line_count: u32,
    // Off the axes and diagonals: march * t * step / (1 + t^2), metres per texel of
    // minor offset (where a texel's foot lies along its line), and NEAR_STEPS.
    foot: f32,
    near_steps: u32,
}

@group(0) @binding(4) var<uniform> lines: HorizonLineParams;
@group(0) @binding(5) var<storage, read> offsets: array<i32>;

// The in-map range [lo, hi] of dominant coordinates of line c (empty when lo > hi):
// m = c + offsets[u] is monotone in u, so the range is contiguous.
fn line_range(c: i32) -> vec2<i32> {
    var lo = i32(lines.n_dominant);
    var hi = -1;
    for (var u = 0; u < i32(lines.n_dominant); u++) {
        let m = c + offsets[u];
        if m >= 0 && m < i32(lines.n_minor) {
            lo = min(lo, u);
            hi = max(hi, u);
        }
    }
    return vec2<i32>(lo, hi);
}

// Texel index of position p (0 = the first texel in marching order) of line c.
fn line_texel(c: i32, range: vec2<i32>, p: u32) -> u32 {
    var u = range.x + i32(p);
    if lines.march_forward == 0u {
        u = range.y - i32(p);
    }
    let m = u32(c + offsets[u]);
    if lines.dominant_is_x != 0u {
        return m * params.width + u32(u);
    }
    return u32(u) * params.width + m;
}

fn line_curved_height(c: i32, range: vec2<i32>, p: u32) -> f32 {
    let s = f32(p) * params.step;
    return heights[line_texel(c, range, p)] - s * s * params.inv_two_r;
}

// One invocation per line: the hull sweep of horizon_sweep_rows along a digital line.
@compute @workgroup_size(64)
fn horizon_sweep_lines(@builtin(global_invocation_id) gid: vec3<u32>) {
    let line = gid.x;
    if line >= lines.line_count {
        return;
    }
    let c = lines.first_line + i32(line);
    let range = line_range(c);
    if range.x > range.y {
        return;
    }
    let n = u32(range.y - range.x + 1);
    let base = line * lines.n_dominant;
    var top = 0u;
    for (var i = 0u; i < n; i++) {
        let k = n - 1u - i;
        let gk = line_curved_height(c, range, k);
        loop {
            if top < 2u {
                break;
            }
            let a = hull[base + top - 1u];
            let b = hull[base + top - 2u];
            if (line_curved_height(c, range, b) - gk) * f32(a - k) >= (line_curved_height(c, range, a) - gk) * f32(b - k) {
                top -= 1u;
            } else {
                break;
            }
        }
        var angle = NO_HORIZON;
        if top > 0u {
            let j = hull[base + top - 1u];
            angle = atan(horizon_tangent(heights[line_texel(c, range, k)], heights[line_texel(c, range, j)], j - k));
        }
        angles[line_texel(c, range, k)] = angle;
        hull[base + top] = k;
        top += 1u;
    }
}

// One invocation per line, each texel scanning at most max_steps samples ahead (used
// with a maximum distance).
@compute @workgroup_size(64)
fn horizon_window_lines(@builtin(global_invocation_id) gid: vec3<u32>) {
    let line = gid.x;
    if line >= lines.line_count {
        return;
    }
    let c = lines.first_line + i32(line);
    let range = line_range(c);
    if range.x > range.y {
        return;
    }
    let n = u32(range.y - range.x + 1);
    for (var k = 0u; k < n; k++) {
        let last = k + min(n - 1u - k, params.max_steps);
        let h_k = heights[line_texel(c, range, k)];
        var found = false;
        var best = 0.0;
        for (var j = k + 1u; j <= last; j++) {
            let t = horizon_tangent(h_k, heights[line_texel(c, range, j)], j - k);
            best = select(t, max(best, t), found);
            found = true;
        }
        angles[line_texel(c, range, k)] = select(NO_HORIZON, atan(best), found);
    }
}

// ---------------------------------------------------------------- off the axes
// Off the axes and diagonals (terrain::horizon's module docs): the exact line c runs
// through minor position c + u * t = c + offsets[u] + fracs[u] (fracs in [-0.5, 0.5],
// from the CPU in f64). Its sample at u is linear between the two texels around it;
// texel (u, c + offsets[u]) looks along its own ray for near_steps steps, then at the
// line's samples, each at its distance along the azimuth from the texel's foot.

@group(0) @binding(6) var<storage, read> fracs: array<f32>;

fn dominant_texel(u: i32, m: i32) -> u32 {
    if lines.dominant_is_x != 0u {
        return u32(m) * params.width + u32(u);
    }
    return u32(u) * params.width + u32(m);
}

// The height at dominant coordinate u, minor position m + f (f in [-1, 1]), linear
// across the grid line; x = -1 marks a position outside [0, n_minor - 1].
fn height_across(u: i32, m: i32, f: f32) -> vec2<f32> {
    var lo = m;
    var w = f;
    if f < 0.0 {
        lo = m - 1;
        w = 1.0 + f;
    }
    let n = i32(lines.n_minor);
    if lo < 0 || lo > n - 1 || (lo == n - 1 && w > 0.0) {
        return vec2<f32>(-1.0, 0.0);
    }
    let a = heights[dominant_texel(u, lo)];
    if w == 0.0 {
        return vec2<f32>(1.0, a);
    }
    let b = heights[dominant_texel(u, lo + 1)];
    return vec2<f32>(1.0, a + (b - a) * w);
}

fn dominant_of(range: vec2<i32>, p: u32) -> i32 {
    if lines.march_forward == 0u {
        return range.y - i32(p);
    }
    return range.x + i32(p);
}

// One invocation per line; each texel scans its window (near field on its own ray,
// then the line's samples), the CPU brute force of the same sampling in f32.
@compute @workgroup_size(64)
fn horizon_off_axis_lines(@builtin(global_invocation_id) gid: vec3<u32>) {
    let line = gid.x;
    if line >= lines.line_count {
        return;
    }
    let c = lines.first_line + i32(line);
    let range = line_range(c);
    if range.x > range.y {
        return;
    }
    let n = u32(range.y - range.x + 1);
    for (var k = 0u; k < n; k++) {
        let u0 = dominant_of(range, k);
        let m0 = c + offsets[u0];
        let h_p = heights[dominant_texel(u0, m0)];
        let e = lines.foot * (-fracs[u0]);
        var found = false;
        var best = 0.0;
        let window = min(n - 1u - k, params.max_steps);
        let near = min(window, lines.near_steps);
        for (var s = 1u; s <= near; s++) {
            let u = dominant_of(range, k + s);
            // m0 + march * s * t = m0 + (offsets[u] - offsets[u0]) + (fracs[u] - fracs[u0]).
            let f = fracs[u] - fracs[u0];
            var m = m0 + (offsets[u] - offsets[u0]);
            var ff = f;
            if ff >= 1.0 {
                m += 1;
                ff -= 1.0;
            } else if ff <= -1.0 {
                m -= 1;
                ff += 1.0;
            }
            let sample = height_across(u, m, ff);
            if sample.x < 0.0 {
                break;
            }
            let d = f32(s) * params.step;
            let t = (sample.y - h_p - d * d * params.inv_two_r) / d;
            best = select(t, max(best, t), found);
            found = true;
        }
        for (var j = k + lines.near_steps + 1u; j <= k + window; j++) {
            let u = dominant_of(range, j);
            let sample = height_across(u, c + offsets[u], fracs[u]);
            if sample.x < 0.0 {
                continue;
            }
            let d = f32(j - k) * params.step - e;
            let t = (sample.y - h_p - d * d * params.inv_two_r) / d;
            best = select(t, max(best, t), found);
            found = true;
        }
        angles[dominant_texel(u0, m0)] = select(NO_HORIZON, atan(best), found);
    }
}
