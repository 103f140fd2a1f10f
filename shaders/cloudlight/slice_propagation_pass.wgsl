// Slice propagation (Dobashi et al. 2000) as a compute pass: one dispatch per slice, from the sun
// side. The previous slice's carried value (optical depth in physical mode, light in
// faithful mode) is read from one ping-pong buffer and this slice's written to the other;
// the light of every cell goes into one 3-D output (the seed's combine step folded in).
// Twin: cloudlight::propagate::propagate::<f32> (Rust), operation for operation.

#import cloudlight::slice_propagation
#import cloudlight::slice_attenuation

struct Sweep {
    nx: u32,
    ny: u32,
    nz: u32,
    // The volume axis the slices are perpendicular to (0 = x, 1 = y, 2 = z).
    axis: u32,
    // Texels along the in-slice axes b = axis + 1, c = axis + 2 (mod 3).
    nb: u32,
    nc: u32,
    // 0: physical, 1: faithful.
    mode: u32,
    // Physical mode's depth resampling: 0 bilinear, 1 clamped Catmull–Rom.
    resampling: u32,
    // Where the light ray through a centre crosses the previous slice, in texels.
    shift_b: f32,
    shift_c: f32,
    // σ_t·Δs (physical mode).
    sigma_ds: f32,
    // Light passed by a fully dense slice (faithful mode).
    attenuation_ratio: f32,
}

struct Step {
    // Position in the sweep (0 = the sun-side slice).
    k: u32,
    // The volume slice written and the one before it (toward the sun).
    slice: u32,
    prev_slice: u32,
    unused0: u32,
    // Faithful mode's whole-texel offsets of this slice.
    offset_b: i32,
    offset_c: i32,
    unused1: u32,
    unused2: u32,
}

@group(0) @binding(0) var<uniform> sweep: Sweep;
@group(0) @binding(1) var<uniform> step: Step;
@group(0) @binding(2) var<storage, read> density: array<f32>;
@group(0) @binding(3) var<storage, read> prev_carried: array<f32>;
@group(0) @binding(4) var<storage, read_write> cur_carried: array<f32>;
@group(0) @binding(5) var<storage, read_write> light_out: array<f32>;

// Linear index (x fastest) of in-slice texel (i, j) of volume slice `slice`.
fn cell_index(slice: u32, i: u32, j: u32) -> u32 {
    var cell = vec3<u32>(0u);
    cell[sweep.axis] = slice;
    cell[(sweep.axis + 1u) % 3u] = i;
    cell[(sweep.axis + 2u) % 3u] = j;
    return cell.x + sweep.nx * (cell.y + sweep.ny * cell.z);
}

// Texel (i, j) of the previous slice: its carried value (field 0) or density (field 1).
fn previous_texel(field: u32, i: u32, j: u32) -> f32 {
    if field == 0u {
        return prev_carried[i + sweep.nb * j];
    }
    return density[cell_index(step.prev_slice, i, j)];
}

// Texel (i, j) of the previous slice with the indices clamped onto it.
fn previous_texel_clamped(field: u32, i: i32, j: i32) -> f32 {
    let ic = u32(clamp(i, 0, i32(sweep.nb) - 1));
    let jc = u32(clamp(j, 0, i32(sweep.nc) - 1));
    return previous_texel(field, ic, jc);
}

// The previous slice sampled at (u, v): `outside` beyond half a texel past the edge
// centres, the edge value within it; bilinear, or Catmull–Rom with edge-clamped taps
// clamped to the 4 nearest texels' range.
fn sample_previous(field: u32, u: f32, v: f32, outside: f32, cubic: bool) -> f32 {
    let max_u = f32(sweep.nb - 1u);
    let max_v = f32(sweep.nc - 1u);
    if u < -0.5 || v < -0.5 || u > max_u + 0.5 || v > max_v + 0.5 {
        return outside;
    }
    let uc = min(max(u, 0.0), max_u);
    let vc = min(max(v, 0.0), max_v);
    let fi = floor(uc);
    let fj = floor(vc);
    let i = i32(fi);
    let j = i32(fj);
    let fu = uc - fi;
    let fv = vc - fj;
    let c00 = previous_texel_clamped(field, i, j);
    let c10 = previous_texel_clamped(field, i + 1, j);
    let c01 = previous_texel_clamped(field, i, j + 1);
    let c11 = previous_texel_clamped(field, i + 1, j + 1);
    if !cubic {
        return bilinear(c00, c10, c01, c11, fu, fv);
    }
    var rows: array<f32, 4>;
    for (var r = 0; r < 4; r++) {
        let jr = j + r - 1;
        rows[r] = catmull_rom(
            previous_texel_clamped(field, i - 1, jr),
            previous_texel_clamped(field, i, jr),
            previous_texel_clamped(field, i + 1, jr),
            previous_texel_clamped(field, i + 2, jr),
            fu,
        );
    }
    let value = catmull_rom(rows[0], rows[1], rows[2], rows[3], fv);
    let lo = min(min(c00, c10), min(c01, c11));
    let hi = max(max(c00, c10), max(c01, c11));
    return min(max(value, lo), hi);
}

// Whole-texel read of the previous slice: `outside` off the slice.
fn previous_texel_or(field: u32, i: i32, j: i32, outside: f32) -> f32 {
    if i < 0 || j < 0 || i >= i32(sweep.nb) || j >= i32(sweep.nc) {
        return outside;
    }
    return previous_texel(field, u32(i), u32(j));
}

@compute @workgroup_size(8, 8, 1)
fn propagate_slice(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    let j = gid.y;
    if i >= sweep.nb || j >= sweep.nc {
        return;
    }
    let cell = cell_index(step.slice, i, j);
    let rho = density[cell];
    var carried: f32;
    var light: f32;
    if sweep.mode == 0u {
        var tau: f32;
        if step.k == 0u {
            tau = slice_optical_depth(0.0, 0.0, rho, sweep.sigma_ds);
        } else {
            let u = f32(i) + sweep.shift_b;
            let v = f32(j) + sweep.shift_c;
            let tau_prev = sample_previous(0u, u, v, 0.0, sweep.resampling == 1u);
            let rho_prev = sample_previous(1u, u, v, 0.0, false);
            tau = slice_optical_depth(tau_prev, rho_prev, rho, sweep.sigma_ds);
        }
        carried = tau;
        light = exp(-tau);
    } else {
        if step.k == 0u {
            light = 1.0;
        } else {
            let pi = i32(i) + step.offset_b;
            let pj = i32(j) + step.offset_c;
            let smoothed = cross_smooth(
                previous_texel_or(1u, pi, pj, 0.0),
                previous_texel_or(1u, pi - 1, pj, 0.0),
                previous_texel_or(1u, pi + 1, pj, 0.0),
                previous_texel_or(1u, pi, pj - 1, 0.0),
                previous_texel_or(1u, pi, pj + 1, 0.0),
            );
            let light_prev = previous_texel_or(0u, pi, pj, 1.0);
            light = slice_attenuation(light_prev, smoothed, sweep.attenuation_ratio);
        }
        carried = light;
    }
    cur_carried[i + sweep.nb * j] = carried;
    light_out[cell] = light;
}
