// Tileable 3-D noise for the cloud shell (Schneider 2015): Perlin gradient noise and Worley F1
// with an integer period, their fBm sums, Schneider's Perlin–Worley, and the shape
// (4-channel) and detail (3-channel) noise the shell samples and the bake pass writes.
// Twin: cloudlight::noise (Rust, generic over the float type: the f32 instantiation
// mirrors these operations; same names, argument order and units). Coordinates are in
// lattice cells; a function with period P wraps its lattice indices modulo P.
#import common::hash

// Lattice cells per tile of the shape noise's lowest octave, and of the detail noise's.
const SHAPE_CELLS: u32 = 4u;
const DETAIL_CELLS: u32 = 2u;

// The hash of a (wrapped) lattice cell under a seed.
fn noise_cell_hash(cell: vec3<u32>, seed: u32) -> u32 {
    return hash_combine(hash_combine(hash_combine(seed, cell.x), cell.y), cell.z);
}

// The seed of octave or channel k derived from seed.
fn noise_octave_seed(seed: u32, k: u32) -> u32 {
    return hash_combine(seed, k);
}

// Lattice index i wrapped into [0, period).
fn noise_wrap(i: i32, period: u32) -> u32 {
    let p = i32(period);
    return u32(((i % p) + p) % p);
}

// (noise_wrap(i − 1, period), noise_wrap(i + 1, period)) from here = noise_wrap(i, period):
// a step around the period instead of two more integer divisions, the same modulo where
// i ± 1 does not overflow and period ≤ 2³⁰ (noise_wrap is then the Euclidean remainder);
// the full wraps elsewhere.
fn noise_wrap_neighbours(i: i32, here: u32, period: u32) -> vec2<u32> {
    if i == -2147483647 - 1 || i == 2147483647 || period > 1073741824u {
        return vec2<u32>(noise_wrap(i - 1, period), noise_wrap(i + 1, period));
    }
    let below = select(here - 1u, period - 1u, here == 0u);
    let above = select(here + 1u, 0u, here + 1u == period);
    return vec2<u32>(below, above);
}

// The top 24 bits of a hash in [0, 1), exact.
fn noise_unit_from_bits(bits: u32) -> f32 {
    return f32(bits >> 8u) * (1.0 / 16777216.0);
}

// Perlin's quintic fade t³(t(6t − 15) + 10).
fn perlin_fade(t: f32) -> f32 {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

// Dot product of gradient hash >> 28 (Perlin's 16-entry edge table) with (x, y, z).
fn perlin_gradient_dot(hash: u32, x: f32, y: f32, z: f32) -> f32 {
    let h = hash >> 28u;
    let u = select(y, x, h < 8u);
    let v = select(select(z, x, h == 12u || h == 14u), y, h < 4u);
    let a = select(-u, u, (h & 1u) == 0u);
    let b = select(-v, v, (h & 2u) == 0u);
    return a + b;
}

fn noise_lerp(a: f32, b: f32, t: f32) -> f32 {
    return a + t * (b - a);
}

// Perlin's improved gradient noise at p (lattice cells) with an integer period.
fn perlin_noise(p: vec3<f32>, period: u32, seed: u32) -> f32 {
    let floor_p = floor(p);
    let i = vec3<i32>(floor_p);
    let f = p - floor_p;
    let x0 = noise_wrap(i.x, period);
    let y0 = noise_wrap(i.y, period);
    let z0 = noise_wrap(i.z, period);
    let x1 = noise_wrap_neighbours(i.x, x0, period).y;
    let y1 = noise_wrap_neighbours(i.y, y0, period).y;
    let z1 = noise_wrap_neighbours(i.z, z0, period).y;
    let g = f - vec3<f32>(1.0);
    // noise_cell_hash of the eight corners, sharing the x and xy prefixes of its chain.
    let hash_x0 = hash_combine(seed, x0);
    let hash_x1 = hash_combine(seed, x1);
    let hash_x0y0 = hash_combine(hash_x0, y0);
    let hash_x1y0 = hash_combine(hash_x1, y0);
    let hash_x0y1 = hash_combine(hash_x0, y1);
    let hash_x1y1 = hash_combine(hash_x1, y1);
    let n000 = perlin_gradient_dot(hash_combine(hash_x0y0, z0), f.x, f.y, f.z);
    let n100 = perlin_gradient_dot(hash_combine(hash_x1y0, z0), g.x, f.y, f.z);
    let n010 = perlin_gradient_dot(hash_combine(hash_x0y1, z0), f.x, g.y, f.z);
    let n110 = perlin_gradient_dot(hash_combine(hash_x1y1, z0), g.x, g.y, f.z);
    let n001 = perlin_gradient_dot(hash_combine(hash_x0y0, z1), f.x, f.y, g.z);
    let n101 = perlin_gradient_dot(hash_combine(hash_x1y0, z1), g.x, f.y, g.z);
    let n011 = perlin_gradient_dot(hash_combine(hash_x0y1, z1), f.x, g.y, g.z);
    let n111 = perlin_gradient_dot(hash_combine(hash_x1y1, z1), g.x, g.y, g.z);
    let u = perlin_fade(f.x);
    let v = perlin_fade(f.y);
    let w = perlin_fade(f.z);
    let nx00 = noise_lerp(n000, n100, u);
    let nx10 = noise_lerp(n010, n110, u);
    let nx01 = noise_lerp(n001, n101, u);
    let nx11 = noise_lerp(n011, n111, u);
    let nxy0 = noise_lerp(nx00, nx10, v);
    let nxy1 = noise_lerp(nx01, nx11, v);
    return noise_lerp(nxy0, nxy1, w);
}

// A cell is skipped in worley_noise's search only when WORLEY_SKIP_MARGIN times a lower
// bound of its squared distance reaches the best found: the bound is rounded as the
// distance is and never exceeds it; the margin covers a compiler fusing the sums of
// squares into fma (a few ULP of a sum of non-negative terms).
const WORLEY_SKIP_MARGIN: f32 = 0.99;

// One axis of worley_noise's 3×3×3 search around cell i for a point with fraction f: the
// cell offsets in the order 0, nearer neighbour, farther neighbour, the cells wrapped into
// the period, and lower bounds of the feature point's |offset| along the axis (ascending).
// The point of cell i + d is at (d + u) − f, u in [0, 1): ≤ −f for d = −1 (d + u ≤ 0 after
// rounding), ≥ 1 − f for d = +1 (d + u ≥ 1 after rounding), anything for d = 0.
struct WorleyAxis {
    offset: vec3<f32>,
    cell: vec3<u32>,
    bound: vec3<f32>,
}

fn worley_axis(i: i32, f: f32, period: u32) -> WorleyAxis {
    let here = noise_wrap(i, period);
    let neighbours = noise_wrap_neighbours(i, here, period);
    let below = neighbours.x;
    let above = neighbours.y;
    let bound_below = f;
    let bound_above = 1.0 - f;
    if bound_below <= bound_above {
        return WorleyAxis(vec3<f32>(0.0, -1.0, 1.0), vec3<u32>(here, below, above), vec3<f32>(0.0, bound_below, bound_above));
    }
    return WorleyAxis(vec3<f32>(0.0, 1.0, -1.0), vec3<u32>(here, above, below), vec3<f32>(0.0, bound_above, bound_below));
}

// Worley F1 at p (lattice cells) with an integer period: the distance in cells to the
// nearest feature point of the 3×3×3 cells around p's cell. The minimum does not depend
// on the visiting order: the own cell first, per axis the nearer neighbour before the
// farther, and a cell is skipped when the sum of its squared per-axis bounds (x, then y,
// then z, as the distance sums) cannot be below the best; the bounds ascend along each
// axis, so the rest of that row, column or slab is skipped with it. A skipped cell is
// never nearer than the best: the result is the full search's. The cell hash is chained
// axis by axis (noise_cell_hash's x, y, z order).
fn worley_noise(p: vec3<f32>, period: u32, seed: u32) -> f32 {
    let floor_p = floor(p);
    let i = vec3<i32>(floor_p);
    let f = p - floor_p;
    let x = worley_axis(i.x, f.x, period);
    let y = worley_axis(i.y, f.y, period);
    let z = worley_axis(i.z, f.z, period);
    var best = 16.0;
    for (var a = 0u; a < 3u; a++) {
        let bound_x = x.bound[a] * x.bound[a];
        if WORLEY_SKIP_MARGIN * bound_x >= best {
            break;
        }
        let hash_x = hash_combine(seed, x.cell[a]);
        for (var b = 0u; b < 3u; b++) {
            let bound_xy = bound_x + y.bound[b] * y.bound[b];
            if WORLEY_SKIP_MARGIN * bound_xy >= best {
                break;
            }
            let hash_xy = hash_combine(hash_x, y.cell[b]);
            for (var c = 0u; c < 3u; c++) {
                let bound_xyz = bound_xy + z.bound[c] * z.bound[c];
                if WORLEY_SKIP_MARGIN * bound_xyz >= best {
                    break;
                }
                let h0 = hash_combine(hash_xy, z.cell[c]);
                let h1 = hash_u32(h0);
                let h2 = hash_u32(h1);
                let ox = x.offset[a] + noise_unit_from_bits(h0) - f.x;
                let oy = y.offset[b] + noise_unit_from_bits(h1) - f.y;
                let oz = z.offset[c] + noise_unit_from_bits(h2) - f.z;
                best = min(best, ox * ox + oy * oy + oz * oz);
            }
        }
    }
    return sqrt(best);
}

// Three octaves of inverted Worley max(1 − F1, 0), weights 0.625, 0.25, 0.125.
fn worley_fbm(p: vec3<f32>, period: u32, seed: u32) -> f32 {
    let weights = vec3<f32>(0.625, 0.25, 0.125);
    var sum = 0.0;
    var frequency = 1.0;
    for (var k = 0u; k < 3u; k++) {
        let q = p * frequency;
        let f1 = worley_noise(q, period << k, noise_octave_seed(seed, k));
        sum = sum + weights[k] * max(1.0 - f1, 0.0);
        frequency = frequency * 2.0;
    }
    return sum;
}

// Three octaves of Perlin (weights 1, ½, ¼) times 1/1.75, mapped to [0, 1].
fn perlin_fbm(p: vec3<f32>, period: u32, seed: u32) -> f32 {
    var sum = 0.0;
    var frequency = 1.0;
    var amplitude = 1.0;
    for (var k = 0u; k < 3u; k++) {
        let q = p * frequency;
        sum = sum + amplitude * perlin_noise(q, period << k, noise_octave_seed(seed, k));
        frequency = frequency * 2.0;
        amplitude = amplitude * 0.5;
    }
    return min(max(0.5 + 0.5 * (sum * (1.0 / 1.75)), 0.0), 1.0);
}

// Schneider's Perlin–Worley: remap(perlin, 0, 1, worley, 1) = worley + perlin·(1 − worley).
fn perlin_worley(p: vec3<f32>, period: u32, seed: u32) -> f32 {
    let perlin = perlin_fbm(p, period, noise_octave_seed(seed, 0u));
    let worley = worley_fbm(p, period, noise_octave_seed(seed, 1u));
    return worley + perlin * (1.0 - worley);
}

// The shape noise at u (tiles, period 1): Perlin–Worley with 4 cells per tile, then
// inverted Worley with 4, 8 and 16 cells per tile. Each channel in [0, 1].
fn cloud_shape_noise(u: vec3<f32>, seed: u32) -> vec4<f32> {
    let p = u * f32(SHAPE_CELLS);
    var out = vec4<f32>(perlin_worley(p, SHAPE_CELLS, noise_octave_seed(seed, 0u)), 0.0, 0.0, 0.0);
    var frequency = 1.0;
    for (var k = 0u; k < 3u; k++) {
        let q = p * frequency;
        let f1 = worley_noise(q, SHAPE_CELLS << k, noise_octave_seed(seed, 1u + k));
        out[1u + k] = max(1.0 - f1, 0.0);
        frequency = frequency * 2.0;
    }
    return out;
}

// The detail noise at u (tiles, period 1): inverted Worley with 2, 4 and 8 cells per tile.
fn cloud_detail_noise(u: vec3<f32>, seed: u32) -> vec3<f32> {
    let p = u * f32(DETAIL_CELLS);
    var out = vec3<f32>(0.0);
    var frequency = 1.0;
    for (var k = 0u; k < 3u; k++) {
        let q = p * frequency;
        let f1 = worley_noise(q, DETAIL_CELLS << k, noise_octave_seed(seed, 4u + k));
        out[k] = max(1.0 - f1, 0.0);
        frequency = frequency * 2.0;
    }
    return out;
}

// The fBm of three Worley channels with weights 0.625, 0.25, 0.125.
fn worley_channels_fbm(c: vec3<f32>) -> f32 {
    return 0.625 * c.x + 0.25 * c.y + 0.125 * c.z;
}

// One axis of a trilinear lookup at tile coordinate u in a size-texel repeating texture
// (texel centres at (i + ½)/size): (i0, i1, t) — the two wrapped texels as floats (exact)
// and the weight of i1.
fn noise_texel_lerp(u: f32, size: u32) -> vec3<f32> {
    let g = u * f32(size) - 0.5;
    let floor_g = floor(g);
    let i = i32(floor_g);
    return vec3<f32>(f32(noise_wrap(i, size)), f32(noise_wrap(i + 1, size)), g - floor_g);
}

// Trilinear lookup of a baked noise texture (cubic, repeating) at tile coordinate u with
// textureLoad: c000 + t·(c100 − c000) along x, then y, then z. Twin:
// cloudlight::noise::NoiseTexture::sample_trilinear.
fn noise_texture_trilinear(tex: texture_3d<f32>, u: vec3<f32>) -> vec4<f32> {
    let size = textureDimensions(tex).x;
    let lx = noise_texel_lerp(u.x, size);
    let ly = noise_texel_lerp(u.y, size);
    let lz = noise_texel_lerp(u.z, size);
    let x0 = u32(lx.x);
    let x1 = u32(lx.y);
    let y0 = u32(ly.x);
    let y1 = u32(ly.y);
    let z0 = u32(lz.x);
    let z1 = u32(lz.y);
    let c000 = textureLoad(tex, vec3<u32>(x0, y0, z0), 0);
    let c100 = textureLoad(tex, vec3<u32>(x1, y0, z0), 0);
    let c010 = textureLoad(tex, vec3<u32>(x0, y1, z0), 0);
    let c110 = textureLoad(tex, vec3<u32>(x1, y1, z0), 0);
    let c001 = textureLoad(tex, vec3<u32>(x0, y0, z1), 0);
    let c101 = textureLoad(tex, vec3<u32>(x1, y0, z1), 0);
    let c011 = textureLoad(tex, vec3<u32>(x0, y1, z1), 0);
    let c111 = textureLoad(tex, vec3<u32>(x1, y1, z1), 0);
    let x00 = c000 + lx.z * (c100 - c000);
    let x10 = c010 + lx.z * (c110 - c010);
    let x01 = c001 + lx.z * (c101 - c001);
    let x11 = c011 + lx.z * (c111 - c011);
    let xy0 = x00 + ly.z * (x10 - x00);
    let xy1 = x01 + ly.z * (x11 - x01);
    return xy0 + lz.z * (xy1 - xy0);
}
