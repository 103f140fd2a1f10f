// Dobashi's weighted space-time smoothing of the cloud field into a continuous density,
// one invocation per cell. Twin: cloudsim::density (Rust). The weighted sums are exact
// integers on both sides; only the final division and the slice scale round (f32 here,
// f64 then one rounding to f32 on the CPU).
//
// density = scale[z] * Σ_tau Σ_d (T+1-tau) (R+1-|dx|)(R+1-|dy|)(R+1-|dz|) cld_tau(c + d)
//           / (Σ_tau (T+1-tau) * (R+1)^6)
//
// History buffer: radius_steps + 1 slots of word_count packed cld words; `ring.newest`
// is the slot of the newest field, age tau lives in slot (newest + keep - tau) % keep,
// `ring.len` slots are filled.

struct DensityParams {
    nx: u32,
    ny: u32,
    nz: u32,
    words_per_row: u32,
    word_count: u32,
    periodic: u32,
    radius_cells: u32,
    radius_steps: u32,
}

struct Ring {
    newest: u32,
    len: u32,
    unused0: u32,
    unused1: u32,
}

const DENSITY_WORKGROUP_SIZE: u32 = 64u;

@group(0) @binding(0) var<uniform> density_params: DensityParams;
@group(0) @binding(1) var<uniform> ring: Ring;
@group(0) @binding(2) var<storage, read> history: array<u32>;
@group(0) @binding(3) var<storage, read> slice_scale: array<f32>;
@group(0) @binding(4) var<storage, read_write> density_out: array<f32>;

// cld of cell (x, y, z) in history slot `slot`: 0 outside the grid, x and y wrap when
// periodic, z never wraps.
fn cloud_bit(slot: u32, x: i32, y: i32, z: i32) -> u32 {
    let nx = i32(density_params.nx);
    let ny = i32(density_params.ny);
    if z < 0 || z >= i32(density_params.nz) {
        return 0u;
    }
    var xx = x;
    var yy = y;
    if density_params.periodic != 0u {
        xx = ((x % nx) + nx) % nx;
        yy = ((y % ny) + ny) % ny;
    } else if x < 0 || x >= nx || y < 0 || y >= ny {
        return 0u;
    }
    let row = u32(yy) + density_params.ny * u32(z);
    let word = slot * density_params.word_count + row * density_params.words_per_row
        + u32(xx) / 32u;
    return (history[word] >> (u32(xx) % 32u)) & 1u;
}

@compute @workgroup_size(64)
fn density_main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let cell = gid.x + gid.y * groups.x * DENSITY_WORKGROUP_SIZE;
    let plane = density_params.nx * density_params.ny;
    if cell >= plane * density_params.nz {
        return;
    }
    let x = i32(cell % density_params.nx);
    let y = i32((cell / density_params.nx) % density_params.ny);
    let z = cell / plane;
    let r = i32(density_params.radius_cells);
    let keep = density_params.radius_steps + 1u;
    var sum = 0u;
    var time_weight = 0u;
    for (var tau = 0u; tau < ring.len; tau++) {
        let slot = (ring.newest + keep - tau) % keep;
        let w_t = keep - tau;
        time_weight += w_t;
        var s = 0u;
        for (var dz = -r; dz <= r; dz++) {
            let w_z = u32(r + 1 - abs(dz));
            for (var dy = -r; dy <= r; dy++) {
                let w_zy = w_z * u32(r + 1 - abs(dy));
                for (var dx = -r; dx <= r; dx++) {
                    let w = w_zy * u32(r + 1 - abs(dx));
                    s += w * cloud_bit(slot, x + dx, y + dy, i32(z) + dz);
                }
            }
        }
        sum += w_t * s;
    }
    let side = u32(r + 1);
    let norm = time_weight * side * side * side * side * side * side;
    density_out[cell] = f32(sum) / f32(norm) * slice_scale[z];
}
