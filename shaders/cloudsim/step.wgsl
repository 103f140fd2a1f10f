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
    // floor(p * 2^16) of extinction, humidity, activation
    threshold_ext: u32,
    threshold_hum: u32,
    threshold_act: u32,
    // 1 when ellipsoids scale the probabilities per lane (region table), else 0
    regions: u32,
}

const HEADER_WORDS: u32 = 4u;
const WORKGROUP_SIZE: u32 = 64u;

@group(0) @binding(0) var<uniform> params: Params;
// With ellipsoids: per packed word its entry in `region_entries`, or NO_REGION.
@group(0) @binding(1) var<storage, read> region_index: array<u32>;
// Per z slice: wind velocity in cells per step, 16.16 fixed point.
@group(0) @binding(2) var<storage, read> wind: array<vec2<i32>>;
@group(0) @binding(3) var<storage, read> src: array<u32>;
@group(0) @binding(4) var<storage, read_write> dst: array<u32>;
// REGION_ENTRY_WORDS per entry: the lanes above mask level 0, then LANE_PLANES
// threshold planes of extinction, humidity and activation.
@group(0) @binding(5) var<storage, read> region_entries: array<u32>;

const NO_REGION: u32 = 0xffffffffu;
const REGION_ENTRY_WORDS: u32 = 55u;

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

// The threshold planes of stream `stream` of region entry `entry`.
fn entry_planes(entry: u32, stream: u32) -> array<u32, 18> {
    var planes: array<u32, 18>;
    let base = entry * REGION_ENTRY_WORDS + 1u + stream * LANE_PLANES;
    for (var k = 0u; k < LANE_PLANES; k++) {
        planes[k] = region_entries[base + k];
    }
    return planes;
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
    var act_next = ~a & h & f_act & valid;

    // The stochastic terms, each drawn 32 lanes at a time for the lanes it can change
    // and compared with each lane's own threshold.
    var alive = valid;
    var planes_ext: array<u32, 18>;
    var planes_hum: array<u32, 18>;
    var planes_act: array<u32, 18>;
    if params.regions != 0u {
        let entry = region_index[w];
        if entry == NO_REGION {
            // no cell above mask level 0: nothing can happen, clouds vanish
            alive = 0u;
        } else {
            alive = region_entries[entry * REGION_ENTRY_WORDS];
            planes_ext = entry_planes(entry, STREAM_EXTINCTION);
            planes_hum = entry_planes(entry, STREAM_HUMIDITY);
            planes_act = entry_planes(entry, STREAM_ACTIVATION);
        }
    } else {
        planes_ext = uniform_threshold_planes(params.threshold_ext);
        planes_hum = uniform_threshold_planes(params.threshold_hum);
        planes_act = uniform_threshold_planes(params.threshold_act);
    }
    // Clouds vanish where the mask level is 0.
    cld_next &= alive;
    let seed = params.seed;
    let ext = below_lane_thresholds(stream_key(seed, step, STREAM_EXTINCTION), w, cld_next,
        planes_ext);
    cld_next &= ~ext;
    hum_next |= below_lane_thresholds(stream_key(seed, step, STREAM_HUMIDITY), w,
        ~hum_next & alive, planes_hum);
    act_next |= below_lane_thresholds(stream_key(seed, step, STREAM_ACTIVATION), w,
        ~act_next & alive, planes_act);

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
