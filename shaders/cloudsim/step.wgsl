// One step of Dobashi's cloud automaton on the bit-packed layout (32 cells per u32
// along x), one invocation per word, ping-pong buffers. Twin: cloudsim::packed (Rust);
// the results are bit-identical.
//
// State buffer layout (u32): [0] step counter, [1..4) zero, then HEADER_WORDS +
//   hum[word_count], act[word_count], cld[word_count];
//   word = wx + words_per_row * (y + ny * z); bit i of word wx is cell x = 32 wx + i.
//
// step_main: src -> dst, rules + stochastic terms of step src[0]; dst[0] = src[0] + 1.
// wind_main: src -> dst, wind shift of step src[0] - 1 (run after step_main).

#import cloudsim::rng

struct Params {
    nx: u32,
    ny: u32,
    nz: u32,
    words_per_row: u32,
    word_count: u32,
    periodic: u32,
    seed: u32,
    last_word_mask: u32,
}

const HEADER_WORDS: u32 = 4u;
const WORKGROUP_SIZE: u32 = 64u;

@group(0) @binding(0) var<uniform> params: Params;
// Mask level (0..=255) of each cell, four cells per word, little end first.
@group(0) @binding(1) var<storage, read> mask_levels: array<u32>;
// Per mask level: (extinction, humidity, activation, unused) thresholds.
@group(0) @binding(2) var<storage, read> thresholds: array<vec4<u32>, 256>;
// Per z slice: wind velocity in cells per step, 16.16 fixed point.
@group(0) @binding(3) var<storage, read> wind: array<vec2<i32>>;
@group(0) @binding(4) var<storage, read> src: array<u32>;
@group(0) @binding(5) var<storage, read_write> dst: array<u32>;

fn field_base(field: u32) -> u32 {
    return HEADER_WORDS + field * params.word_count;
}

fn act_at(word: u32) -> u32 {
    return src[field_base(1u) + word];
}

// The act word `wx` of row (y, z) after the boundary rule: 0 outside the grid, y wraps
// when periodic, z never wraps.
fn act_word(wx: u32, y: i32, z: i32) -> u32 {
    if z < 0 || z >= i32(params.nz) {
        return 0u;
    }
    let ny = i32(params.ny);
    var yy = y;
    if params.periodic != 0u {
        yy = ((y % ny) + ny) % ny;
    } else if y < 0 || y >= ny {
        return 0u;
    }
    let row = u32(yy) + params.ny * u32(z);
    return act_at(row * params.words_per_row + wx);
}

fn mask_level(cell: u32) -> u32 {
    return (mask_levels[cell >> 2u] >> ((cell & 3u) * 8u)) & 0xffu;
}

// The events among `candidates` (one bit per lane) for stream `stream`.
fn events(key: u32, base_cell: u32, candidates: u32, stream: u32) -> u32 {
    var bits = 0u;
    var rest = candidates;
    loop {
        if rest == 0u {
            break;
        }
        let lane = firstTrailingBit(rest);
        rest &= rest - 1u;
        let cell = base_cell + lane;
        let threshold = thresholds[mask_level(cell)][stream];
        if draw_event(key, cell, threshold) {
            bits |= 1u << lane;
        }
    }
    return bits;
}

fn word_index(gid: vec3<u32>, groups: vec3<u32>) -> u32 {
    return gid.x + gid.y * groups.x * WORKGROUP_SIZE;
}

@compute @workgroup_size(64)
fn step_main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let w = word_index(gid, groups);
    if w >= params.word_count {
        return;
    }
    let step = src[0];
    if w == 0u {
        dst[0] = step + 1u;
        dst[1] = 0u;
        dst[2] = 0u;
        dst[3] = 0u;
    }
    let wpr = params.words_per_row;
    let wx = w % wpr;
    let row = w / wpr;
    let y = i32(row % params.ny);
    let z = i32(row / params.ny);
    let periodic = params.periodic != 0u;

    let a = act_at(w);
    var prev = 0u;
    var next = 0u;
    if wx > 0u {
        prev = act_at(w - 1u);
    } else if periodic {
        prev = act_at(w + wpr - 1u);
    }
    if wx + 1u < wpr {
        next = act_at(w + 1u);
    } else if periodic {
        next = act_at(w + 1u - wpr);
    }
    // bit i of (a << 1 | prev >> 31) is act(x - 1), and so on.
    var f_act = (a << 1u) | (prev >> 31u) | (a << 2u) | (prev >> 30u)
        | (a >> 1u) | (next << 31u) | (a >> 2u) | (next << 30u);
    f_act |= act_word(wx, y - 1, z) | act_word(wx, y + 1, z)
        | act_word(wx, y - 2, z) | act_word(wx, y + 2, z)
        | act_word(wx, y, z + 1) | act_word(wx, y, z - 1) | act_word(wx, y, z - 2);

    let h = src[field_base(0u) + w];
    let c = src[field_base(2u) + w];
    var valid = 0xffffffffu;
    if wx + 1u == wpr {
        valid = params.last_word_mask;
    }
    var hum_next = h & ~a;
    var cld_next = c | a;
    var act_next = ~a & h & f_act;

    let base_cell = wx * 32u + params.nx * row;
    // Clouds vanish where the mask level is 0.
    var alive = 0u;
    let lanes = min(params.nx - wx * 32u, 32u);
    for (var lane = 0u; lane < lanes; lane++) {
        if mask_level(base_cell + lane) != 0u {
            alive |= 1u << lane;
        }
    }
    cld_next &= alive;

    let key_ext = stream_key(params.seed, step, STREAM_EXTINCTION);
    let key_hum = stream_key(params.seed, step, STREAM_HUMIDITY);
    let key_act = stream_key(params.seed, step, STREAM_ACTIVATION);
    cld_next &= ~events(key_ext, base_cell, cld_next, STREAM_EXTINCTION);
    hum_next |= events(key_hum, base_cell, ~hum_next & valid, STREAM_HUMIDITY);
    act_next |= events(key_act, base_cell, ~act_next & valid, STREAM_ACTIVATION);

    dst[field_base(0u) + w] = hum_next;
    dst[field_base(1u) + w] = act_next;
    dst[field_base(2u) + w] = cld_next;
}

// Word `q` of the src row starting at `row_start` (0 outside unless periodic).
fn row_word(row_start: u32, q: i32) -> u32 {
    let wpr = i32(params.words_per_row);
    var qq = q;
    if params.periodic != 0u {
        qq = ((q % wpr) + wpr) % wpr;
    } else if q < 0 || q >= wpr {
        return 0u;
    }
    return src[row_start + u32(qq)];
}

@compute @workgroup_size(64)
fn wind_main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let w = word_index(gid, groups);
    if w >= params.word_count {
        return;
    }
    let step_after = src[0];
    if w == 0u {
        dst[0] = step_after;
        dst[1] = 0u;
        dst[2] = 0u;
        dst[3] = 0u;
    }
    let step = step_after - 1u;
    let wpr = params.words_per_row;
    let wx = w % wpr;
    let row = w / wpr;
    let y = i32(row % params.ny);
    let z = row / params.ny;
    let velocity = wind[z];
    let dx = wind_shift(velocity.x, step);
    let dy = wind_shift(velocity.y, step);

    let ny = i32(params.ny);
    var from_y = y - dy;
    var inside = true;
    if params.periodic != 0u {
        from_y = ((from_y % ny) + ny) % ny;
    } else if from_y < 0 || from_y >= ny {
        inside = false;
    }
    var valid = 0xffffffffu;
    if wx + 1u == wpr {
        valid = params.last_word_mask;
    }
    // Cells [start, start + 32) of the source row land in this word.
    let start = i32(wx * 32u) - dx;
    let q = start >> 5u;
    let b = u32(start & 31);
    let src_row = u32(from_y) + params.ny * z;
    for (var field = 0u; field < 3u; field++) {
        var value = 0u;
        if inside {
            let row_start = field_base(field) + src_row * wpr;
            let lo = row_word(row_start, q);
            if b == 0u {
                value = lo;
            } else {
                value = (lo >> b) | (row_word(row_start, q + 1) << (32u - b));
            }
        }
        dst[field_base(field) + w] = value & valid;
    }
}
