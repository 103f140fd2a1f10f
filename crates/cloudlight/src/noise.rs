//! Tileable 3-D noise for the procedural cloud shell (Schneider 2015), generated here (no
//! downloaded textures): Perlin gradient noise and Worley cellular noise with an integer
//! period, their fBm sums, Schneider's Perlin–Worley, and the two noise sets a cloud
//! shell samples (the 4-channel shape noise and the 3-channel detail noise).
//!
//! Written once over the float type: the `f32` instantiations mirror
//! `shaders/cloudlight/noise.wgsl` operation for operation (same names, argument order
//! and units), the `f64` ones are the parity references. The lattice hash is integer
//! arithmetic, bit-identical in Rust and WGSL: [`noise_cell_hash`] chains `common::hash`'s
//! `hash_combine` (Wellons' lowbias32) over the seed and the cell's three coordinates.
//!
//! Coordinates are in lattice cells. A function with period `P` (a positive integer)
//! wraps its lattice indices modulo `P` on every axis, so its value at `p` equals its
//! value at `p + P` on any axis: exactly where `p` and `p + P` are exact in the float type
//! (the fractional part is then unchanged), to rounding of the fractional part otherwise.
//!
//! * [`perlin_noise`]: Perlin's improved noise (2002): quintic fade, the 12 edge
//!   gradients (16 with 4 repeated) chosen by the hash's top four bits; zero on the
//!   lattice. Measured extremes over 4,000 points: −0.762 and 0.772
//!   (`tests/shell.rs`, `noise_values_lie_in_their_documented_ranges`).
//! * [`worley_noise`]: the distance (in cells) to the nearest feature point, one point per
//!   cell uniformly placed by the hash, searched over the 3×3×3 neighbouring cells (the
//!   usual truncation: F1 ≥ 0, and < 1 wherever the own cell's point is within a cell).
//! * [`worley_fbm`]: three octaves of inverted Worley `max(1 − F1, 0)` at frequencies 1,
//!   2, 4 with weights 0.625, 0.25, 0.125 (Schneider's low-frequency fBm), in [0, 1].
//! * [`perlin_fbm`]: three octaves of Perlin at frequencies 1, 2, 4, weights 1, ½, ¼,
//!   times 1/1.75, mapped to [0, 1] by `clamp(½ + ½n, 0, 1)`.
//! * [`perlin_worley`]: Perlin fBm remapped with the Worley fBm as its floor,
//!   `remap(perlin, 0, 1, worley, 1) = worley + perlin·(1 − worley)`, in [0, 1].
//! * [`cloud_shape_noise`] (the 128³ base texture's texel function) and
//!   [`cloud_detail_noise`] (the 32³ detail texture's): see each.

use atmos::real::Real;
use skyscape_wgsl::common::{hash_combine, hash_u32};

/// Lattice cells per tile of the shape noise's lowest octave (Perlin and Worley); its
/// higher octaves have 2× and 4× as many.
pub const SHAPE_CELLS: u32 = 4;
/// Lattice cells per tile of the detail noise's lowest Worley octave (then 2×, 4×).
pub const DETAIL_CELLS: u32 = 2;
/// Schneider's fBm weights of three Worley octaves (low to high frequency).
pub const WORLEY_FBM_WEIGHTS: [f64; 3] = [0.625, 0.25, 0.125];

/// The hash of lattice cell `cell` (already wrapped into the period) under `seed`:
/// `hash_combine(hash_combine(hash_combine(seed, x), y), z)`. WGSL twin `noise_cell_hash`.
pub fn noise_cell_hash(cell: [u32; 3], seed: u32) -> u32 {
    hash_combine(hash_combine(hash_combine(seed, cell[0]), cell[1]), cell[2])
}

/// The seed of octave or channel `k` derived from `seed`: `hash_combine(seed, k)`.
/// WGSL twin `noise_octave_seed`.
pub fn noise_octave_seed(seed: u32, k: u32) -> u32 {
    hash_combine(seed, k)
}

/// Lattice index `i` wrapped into `[0, period)` (`period ≥ 1`).
fn noise_wrap(i: i32, period: u32) -> u32 {
    let p = period as i32;
    (((i % p) + p) % p) as u32
}

/// `(noise_wrap(i − 1, period), noise_wrap(i + 1, period))` from `here = noise_wrap(i,
/// period)`, a step around the period instead of two more integer divisions. The step is
/// the same modulo wherever `i ± 1` does not overflow and `noise_wrap` is the Euclidean
/// remainder (its `(i % p) + p` cannot overflow: `period ≤ 2³⁰`); elsewhere the full wraps
/// keep `noise_wrap`'s own results. WGSL twin `noise_wrap_neighbours`.
fn noise_wrap_neighbours(i: i32, here: u32, period: u32) -> (u32, u32) {
    if i == i32::MIN || i == i32::MAX || period > 1 << 30 {
        return (
            noise_wrap(i.wrapping_sub(1), period),
            noise_wrap(i.wrapping_add(1), period),
        );
    }
    let below = if here == 0 { period - 1 } else { here - 1 };
    let above = if here + 1 == period { 0 } else { here + 1 };
    (below, above)
}

/// The integer cell containing `x` (`floor`, as i32) and the fraction `x − floor(x)`.
fn cell_and_fraction<F: Real>(x: F) -> (i32, F) {
    let floor = x.floor();
    (floor.to_i32().unwrap_or(0), x - floor)
}

/// The top 24 bits of `bits` as a float in [0, 1), exact in f32 and f64.
fn noise_unit_from_bits<F: Real>(bits: u32) -> F {
    F::of(f64::from(bits >> 8)) * F::of(1.0 / 16_777_216.0)
}

/// Perlin's quintic fade `t³(t(6t − 15) + 10)`.
pub fn perlin_fade<F: Real>(t: F) -> F {
    t * t * t * (t * (t * F::of(6.0) - F::of(15.0)) + F::of(10.0))
}

/// The dot product of gradient `hash >> 28` (Perlin's 16-entry edge table) with the
/// offset `(x, y, z)` from the lattice corner. WGSL twin `perlin_gradient_dot`.
pub fn perlin_gradient_dot<F: Real>(hash: u32, x: F, y: F, z: F) -> F {
    let h = hash >> 28;
    let u = if h < 8 { x } else { y };
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    let a = if h & 1 == 0 { u } else { -u };
    let b = if h & 2 == 0 { v } else { -v };
    a + b
}

/// `a + t·(b − a)`, the interpolation both languages spell out (WGSL's `mix` may be
/// evaluated as `a·(1 − t) + b·t`).
fn noise_lerp<F: Real>(a: F, b: F, t: F) -> F {
    a + t * (b - a)
}

/// Perlin's improved gradient noise at `p` (lattice cells) with integer period `period`
/// (≥ 1) on every axis, zero on the lattice. WGSL twin `perlin_noise`.
pub fn perlin_noise<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
    let (ix, fx) = cell_and_fraction(p[0]);
    let (iy, fy) = cell_and_fraction(p[1]);
    let (iz, fz) = cell_and_fraction(p[2]);
    let (x0, y0, z0) = (
        noise_wrap(ix, period),
        noise_wrap(iy, period),
        noise_wrap(iz, period),
    );
    let x1 = noise_wrap_neighbours(ix, x0, period).1;
    let y1 = noise_wrap_neighbours(iy, y0, period).1;
    let z1 = noise_wrap_neighbours(iz, z0, period).1;
    let one = F::one();
    let (gx, gy, gz) = (fx - one, fy - one, fz - one);
    // noise_cell_hash of the eight corners, sharing the x and xy prefixes of its chain.
    let (hash_x0, hash_x1) = (hash_combine(seed, x0), hash_combine(seed, x1));
    let (hash_x0y0, hash_x1y0) = (hash_combine(hash_x0, y0), hash_combine(hash_x1, y0));
    let (hash_x0y1, hash_x1y1) = (hash_combine(hash_x0, y1), hash_combine(hash_x1, y1));
    let n000 = perlin_gradient_dot(hash_combine(hash_x0y0, z0), fx, fy, fz);
    let n100 = perlin_gradient_dot(hash_combine(hash_x1y0, z0), gx, fy, fz);
    let n010 = perlin_gradient_dot(hash_combine(hash_x0y1, z0), fx, gy, fz);
    let n110 = perlin_gradient_dot(hash_combine(hash_x1y1, z0), gx, gy, fz);
    let n001 = perlin_gradient_dot(hash_combine(hash_x0y0, z1), fx, fy, gz);
    let n101 = perlin_gradient_dot(hash_combine(hash_x1y0, z1), gx, fy, gz);
    let n011 = perlin_gradient_dot(hash_combine(hash_x0y1, z1), fx, gy, gz);
    let n111 = perlin_gradient_dot(hash_combine(hash_x1y1, z1), gx, gy, gz);
    let (u, v, w) = (perlin_fade(fx), perlin_fade(fy), perlin_fade(fz));
    let nx00 = noise_lerp(n000, n100, u);
    let nx10 = noise_lerp(n010, n110, u);
    let nx01 = noise_lerp(n001, n101, u);
    let nx11 = noise_lerp(n011, n111, u);
    let nxy0 = noise_lerp(nx00, nx10, v);
    let nxy1 = noise_lerp(nx01, nx11, v);
    noise_lerp(nxy0, nxy1, w)
}

/// How far a lower bound of a cell's squared distance may be trusted when deciding to skip
/// the cell in [`worley_noise`]: a cell is skipped only when `WORLEY_SKIP_MARGIN · bound`
/// reaches the best squared distance found. The bound is computed with the same roundings
/// as the distance and is never above it in IEEE arithmetic; the margin keeps the skip
/// safe where a compiler fuses the sums of squares into `fma` (a few ULP of a sum of
/// non-negative terms, far below 1 %). WGSL twin `WORLEY_SKIP_MARGIN`.
const WORLEY_SKIP_MARGIN: f64 = 0.99;

/// One axis of [`worley_noise`]'s 3 × 3 × 3 search around the cell `i` holding a point
/// with fraction `f`: the cell offsets `d` in the order 0, nearer neighbour, farther
/// neighbour, each cell wrapped into the period, and a lower bound of the feature point's
/// `|offset|` along the axis for each, so the bounds ascend.
///
/// The point of cell `i + d` is at `d + u − f` from `p` with `u ∈ [0, 1)`: at least `f`
/// away for `d = −1` (`−1 + u − f < −f`), at least `1 − f` for `d = +1`, and anywhere for
/// `d = 0`. Rounded as [`worley_noise`] rounds it (`(d + u) − f`, each step correctly
/// rounded, so monotonic), the offset is still `≤ −f` for `d = −1` and `≥ fl(1 − f)` for
/// `d = +1`, since `fl(−1 + u) ≤ 0` and `fl(1 + u) ≥ 1`. WGSL twin `worley_axis`.
struct WorleyAxis<F> {
    offset: [F; 3],
    cell: [u32; 3],
    bound: [F; 3],
}

fn worley_axis<F: Real>(i: i32, f: F, period: u32) -> WorleyAxis<F> {
    let here = noise_wrap(i, period);
    let (below, above) = noise_wrap_neighbours(i, here, period);
    let (zero, one) = (F::zero(), F::one());
    let (bound_below, bound_above) = (f, one - f);
    if bound_below <= bound_above {
        WorleyAxis {
            offset: [zero, -one, one],
            cell: [here, below, above],
            bound: [zero, bound_below, bound_above],
        }
    } else {
        WorleyAxis {
            offset: [zero, one, -one],
            cell: [here, above, below],
            bound: [zero, bound_above, bound_below],
        }
    }
}

/// Worley (cellular) noise F1 at `p` (lattice cells) with integer period `period` (≥ 1):
/// the distance in cells to the nearest feature point of the 3×3×3 cells around `p`'s
/// cell. Each cell's point is `cell + (u(h), u(hash(h)), u(hash(hash(h))))` with
/// `h = noise_cell_hash(wrapped cell, seed)` and `u` the top 24 bits in [0, 1).
/// WGSL twin `worley_noise`.
///
/// F1 is the minimum of the 27 squared distances, which does not depend on the order
/// they are visited in, so the search visits `p`'s own cell first and, per axis, the
/// nearer neighbour before the farther one (`WorleyAxis`), and skips every cell whose
/// squared distance cannot be below the best found: the sum of the squared per-axis
/// bounds, accumulated x, then y, then z as the distance is, is a lower bound of the
/// distance as rounded (each rounding is monotonic). Along each axis the bounds ascend,
/// so once a cell is skipped the rest of that row, column or slab is too. A skipped cell
/// is never strictly nearer than the best, so the result is bit for bit the full
/// search's. The cell hash is accumulated axis by axis (`noise_cell_hash` chains x, y, z).
pub fn worley_noise<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
    let (ix, fx) = cell_and_fraction(p[0]);
    let (iy, fy) = cell_and_fraction(p[1]);
    let (iz, fz) = cell_and_fraction(p[2]);
    let x = worley_axis(ix, fx, period);
    let y = worley_axis(iy, fy, period);
    let z = worley_axis(iz, fz, period);
    let margin = F::of(WORLEY_SKIP_MARGIN);
    let mut best = F::of(16.0);
    for a in 0..3 {
        let bound_x = x.bound[a] * x.bound[a];
        if margin * bound_x >= best {
            break;
        }
        let hash_x = hash_combine(seed, x.cell[a]);
        for b in 0..3 {
            let bound_xy = bound_x + y.bound[b] * y.bound[b];
            if margin * bound_xy >= best {
                break;
            }
            let hash_xy = hash_combine(hash_x, y.cell[b]);
            for c in 0..3 {
                let bound_xyz = bound_xy + z.bound[c] * z.bound[c];
                if margin * bound_xyz >= best {
                    break;
                }
                let h0 = hash_combine(hash_xy, z.cell[c]);
                let h1 = hash_u32(h0);
                let h2 = hash_u32(h1);
                let ox = x.offset[a] + noise_unit_from_bits::<F>(h0) - fx;
                let oy = y.offset[b] + noise_unit_from_bits::<F>(h1) - fy;
                let oz = z.offset[c] + noise_unit_from_bits::<F>(h2) - fz;
                best = best.min(ox * ox + oy * oy + oz * oz);
            }
        }
    }
    best.sqrt()
}

/// Three octaves of inverted Worley noise, `Σ wₖ·max(1 − F1(2ᵏp, 2ᵏP, seedₖ), 0)` with
/// Schneider's weights 0.625, 0.25, 0.125 and `seedₖ = noise_octave_seed(seed, k)`;
/// in [0, 1], tileable with period `period`. WGSL twin `worley_fbm`.
pub fn worley_fbm<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
    let mut sum = F::zero();
    let mut frequency = F::one();
    for (k, weight) in WORLEY_FBM_WEIGHTS.iter().enumerate() {
        let q = p.map(|c| c * frequency);
        let f1 = worley_noise(q, period << k, noise_octave_seed(seed, k as u32));
        sum = sum + F::of(*weight) * (F::one() - f1).max(F::zero());
        frequency = frequency * F::of(2.0);
    }
    sum
}

/// Three octaves of Perlin noise at frequencies 1, 2, 4 (weights 1, ½, ¼, seeds
/// `noise_octave_seed(seed, k)`), times 1/1.75 (rounded once), mapped to [0, 1] by
/// `clamp(½ + ½n, 0, 1)`; tileable with period `period`. WGSL twin `perlin_fbm`.
pub fn perlin_fbm<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
    let mut sum = F::zero();
    let mut frequency = F::one();
    let mut amplitude = F::one();
    for k in 0..3u32 {
        let q = p.map(|c| c * frequency);
        sum = sum + amplitude * perlin_noise(q, period << k, noise_octave_seed(seed, k));
        frequency = frequency * F::of(2.0);
        amplitude = amplitude * F::of(0.5);
    }
    let half = F::of(0.5);
    (half + half * (sum * F::of(1.0 / 1.75)))
        .max(F::zero())
        .min(F::one())
}

/// Schneider's Perlin–Worley: the Perlin fBm remapped so the Worley fBm is its floor,
/// `remap(perlin, 0, 1, worley, 1) = worley + perlin·(1 − worley)`, both over the same
/// `p` and period (seeds `noise_octave_seed(seed, 0)` for Perlin, `…(seed, 1)` for
/// Worley). In [0, 1]. WGSL twin `perlin_worley`.
pub fn perlin_worley<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
    let perlin = perlin_fbm(p, period, noise_octave_seed(seed, 0));
    let worley = worley_fbm(p, period, noise_octave_seed(seed, 1));
    worley + perlin * (F::one() - worley)
}

/// The shape (base) noise at `u`, in tiles (one tile = the texture's extent; period 1 on
/// every axis): the four channels of the 128³ base texture,
///
/// * `[0]`: Perlin–Worley with [`SHAPE_CELLS`] cells per tile (seed `noise_octave_seed(seed, 0)`),
/// * `[1]`, `[2]`, `[3]`: inverted Worley `max(1 − F1, 0)` with 4, 8 and 16 cells per
///   tile (seeds `noise_octave_seed(seed, 1…3)`),
///
/// each in [0, 1]. The shell combines `[1..4]` with [`WORLEY_FBM_WEIGHTS`] into the
/// low-frequency fBm that erodes `[0]`. WGSL twin `cloud_shape_noise`.
pub fn cloud_shape_noise<F: Real>(u: [F; 3], seed: u32) -> [F; 4] {
    let cells = F::of(f64::from(SHAPE_CELLS));
    let p = u.map(|c| c * cells);
    let r = perlin_worley(p, SHAPE_CELLS, noise_octave_seed(seed, 0));
    let mut out = [r, F::zero(), F::zero(), F::zero()];
    let mut frequency = F::one();
    for k in 0..3u32 {
        let q = p.map(|c| c * frequency);
        let f1 = worley_noise(q, SHAPE_CELLS << k, noise_octave_seed(seed, 1 + k));
        out[1 + k as usize] = (F::one() - f1).max(F::zero());
        frequency = frequency * F::of(2.0);
    }
    out
}

/// The detail noise at `u`, in tiles (period 1): the three channels of the 32³ detail
/// texture, inverted Worley `max(1 − F1, 0)` with 2, 4 and 8 cells per tile
/// ([`DETAIL_CELLS`] × 1, 2, 4; seeds `noise_octave_seed(seed, 4…6)`), each in [0, 1].
/// WGSL twin `cloud_detail_noise`.
pub fn cloud_detail_noise<F: Real>(u: [F; 3], seed: u32) -> [F; 3] {
    let cells = F::of(f64::from(DETAIL_CELLS));
    let p = u.map(|c| c * cells);
    let mut out = [F::zero(); 3];
    let mut frequency = F::one();
    for k in 0..3u32 {
        let q = p.map(|c| c * frequency);
        let f1 = worley_noise(q, DETAIL_CELLS << k, noise_octave_seed(seed, 4 + k));
        out[k as usize] = (F::one() - f1).max(F::zero());
        frequency = frequency * F::of(2.0);
    }
    out
}

/// `Σ wₖ·channelₖ` with [`WORLEY_FBM_WEIGHTS`]: the fBm of three Worley channels (the
/// shape texture's `[1..4]` or the detail texture's `[0..3]`). WGSL twin `worley_channels_fbm`.
pub fn worley_channels_fbm<F: Real>(c: [F; 3]) -> F {
    F::of(WORLEY_FBM_WEIGHTS[0]) * c[0]
        + F::of(WORLEY_FBM_WEIGHTS[1]) * c[1]
        + F::of(WORLEY_FBM_WEIGHTS[2]) * c[2]
}

/// The tile coordinate of texel `texel` of a `size`³ noise texture: its centre,
/// `(i + ½)/size` on each axis (in [0, 1), period 1). WGSL twin
/// `noise_texel_coordinate` (in `noise_bake_pass.wgsl`).
pub fn noise_texel_coordinate<F: Real>(texel: [u32; 3], size: u32) -> [F; 3] {
    let n = F::of(f64::from(size));
    texel.map(|i| (F::of(f64::from(i)) + F::of(0.5)) / n)
}

/// A texel's value in an 8-bit UNORM texture: `round(clamp(v, 0, 1)·255)` (what the
/// bake pass's `rgba8unorm` store does to the f32 it writes).
pub fn unorm8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The f32 twin of the GPU bake's shape texture: [`cloud_shape_noise`] at every texel
/// centre of a `size`³ tile, x fastest, then y, then z.
pub fn bake_shape_noise(seed: u32, size: u32) -> Vec<[f32; 4]> {
    let mut texels = Vec::with_capacity((size as usize).pow(3));
    for z in 0..size {
        for y in 0..size {
            for x in 0..size {
                let u = noise_texel_coordinate::<f32>([x, y, z], size);
                texels.push(cloud_shape_noise(u, seed));
            }
        }
    }
    texels
}

/// The f32 twin of the GPU bake's detail texture: [`cloud_detail_noise`] at every texel
/// centre of a `size`³ tile, x fastest.
pub fn bake_detail_noise(seed: u32, size: u32) -> Vec<[f32; 3]> {
    let mut texels = Vec::with_capacity((size as usize).pow(3));
    for z in 0..size {
        for y in 0..size {
            for x in 0..size {
                let u = noise_texel_coordinate::<f32>([x, y, z], size);
                texels.push(cloud_detail_noise(u, seed));
            }
        }
    }
    texels
}

/// Where a trilinear lookup at tile coordinate `u` falls along one axis of a `size`-texel
/// repeating texture: the two texels `(i0, i1)` (wrapped) and the weight `t` of `i1`, with
/// texel centres at `(i + ½)/size` (`g = u·size − ½`, `i0 = floor(g)`, `t = g − i0`).
/// The arithmetic of `noise_texture_trilinear` (WGSL), one axis.
pub fn noise_texel_lerp<F: Real>(u: F, size: u32) -> (u32, u32, F) {
    let g = u * F::of(f64::from(size)) - F::of(0.5);
    let (i, t) = cell_and_fraction(g);
    (noise_wrap(i, size), noise_wrap(i.wrapping_add(1), size), t)
}

/// A baked noise texture as the GPU holds it: `size`³ texels (x fastest) of four channels,
/// each `byte/255` of the `rgba8unorm` texel (what `textureLoad` returns). The CPU twin of
/// [`crate::gpu::NoiseBake`]'s textures, for marching the same density on both sides.
#[derive(Debug, Clone, PartialEq)]
pub struct NoiseTexture {
    size: u32,
    texels: Vec<[f32; 4]>,
}

impl NoiseTexture {
    /// The shape texture of `seed` at `size`³ ([`bake_shape_noise`] quantised by
    /// [`unorm8`]). Costs `size`³ evaluations of [`cloud_shape_noise`] (128³: about
    /// 2 million).
    pub fn shape(seed: u32, size: u32) -> Self {
        let texels = bake_shape_noise(seed, size)
            .into_iter()
            .map(|t| t.map(|v| f32::from(unorm8(v)) / 255.0))
            .collect();
        Self { size, texels }
    }

    /// The detail texture of `seed` at `size`³ ([`bake_detail_noise`] quantised; alpha 1).
    pub fn detail(seed: u32, size: u32) -> Self {
        let texels = bake_detail_noise(seed, size)
            .into_iter()
            .map(|t| {
                let q = t.map(|v| f32::from(unorm8(v)) / 255.0);
                [q[0], q[1], q[2], 1.0]
            })
            .collect();
        Self { size, texels }
    }

    /// Edge in texels.
    pub fn size(&self) -> u32 {
        self.size
    }

    /// Texel `(x, y, z)` (each below [`size`](Self::size)).
    pub fn texel(&self, x: u32, y: u32, z: u32) -> [f32; 4] {
        let n = self.size as usize;
        self.texels[x as usize + n * (y as usize + n * z as usize)]
    }

    /// Trilinear lookup at tile coordinate `u` with repeat addressing, channel by channel
    /// `c000 + t·(c100 − c000)` along x, then y, then z ([`noise_texel_lerp`] per axis).
    /// WGSL twin `noise_texture_trilinear` (over `textureLoad`).
    pub fn sample_trilinear<F: Real>(&self, u: [F; 3]) -> [F; 4] {
        let (x0, x1, tx) = noise_texel_lerp(u[0], self.size);
        let (y0, y1, ty) = noise_texel_lerp(u[1], self.size);
        let (z0, z1, tz) = noise_texel_lerp(u[2], self.size);
        let c = |x, y, z| self.texel(x, y, z).map(|v| F::of(f64::from(v)));
        let lerp4 = |a: [F; 4], b: [F; 4], t: F| std::array::from_fn(|k| noise_lerp(a[k], b[k], t));
        let x00 = lerp4(c(x0, y0, z0), c(x1, y0, z0), tx);
        let x10 = lerp4(c(x0, y1, z0), c(x1, y1, z0), tx);
        let x01 = lerp4(c(x0, y0, z1), c(x1, y0, z1), tx);
        let x11 = lerp4(c(x0, y1, z1), c(x1, y1, z1), tx);
        let xy0 = lerp4(x00, x10, ty);
        let xy1 = lerp4(x01, x11, ty);
        lerp4(xy0, xy1, tz)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_neighbours_are_the_wraps_of_the_neighbours() {
        let indices = (-300..300).chain([i32::MIN, i32::MIN + 1, i32::MAX - 1, i32::MAX]);
        let periods = [1, 2, 3, 4, 7, 64, 256, 1 << 30, (1 << 30) + 1, u32::MAX];
        for i in indices {
            for period in periods {
                if period > 1 << 30 && i.unsigned_abs() > 1 << 29 {
                    // noise_wrap's (i % p) + p overflows there (a panic in debug builds).
                    continue;
                }
                let here = noise_wrap(i, period);
                let expected = (
                    noise_wrap(i.wrapping_sub(1), period),
                    noise_wrap(i.wrapping_add(1), period),
                );
                assert_eq!(
                    noise_wrap_neighbours(i, here, period),
                    expected,
                    "i = {i}, period {period}"
                );
            }
        }
    }

    #[test]
    fn wrap_is_modulo_for_negative_indices() {
        assert_eq!(noise_wrap(-1, 4), 3);
        assert_eq!(noise_wrap(-4, 4), 0);
        assert_eq!(noise_wrap(9, 4), 1);
        assert_eq!(noise_wrap(0, 1), 0);
    }

    /// The straightforward F1: all 27 cells, z, y, x from −1 to 1, each with its own
    /// `noise_cell_hash`. `worley_noise` must equal it bit for bit.
    fn worley_noise_full_search<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
        let (ix, fx) = cell_and_fraction(p[0]);
        let (iy, fy) = cell_and_fraction(p[1]);
        let (iz, fz) = cell_and_fraction(p[2]);
        let mut best = F::of(16.0);
        for dz in -1i32..=1 {
            for dy in -1i32..=1 {
                for dx in -1i32..=1 {
                    let cell = [
                        noise_wrap(ix.wrapping_add(dx), period),
                        noise_wrap(iy.wrapping_add(dy), period),
                        noise_wrap(iz.wrapping_add(dz), period),
                    ];
                    let h0 = noise_cell_hash(cell, seed);
                    let h1 = hash_u32(h0);
                    let h2 = hash_u32(h1);
                    let ox = F::of(f64::from(dx)) + noise_unit_from_bits::<F>(h0) - fx;
                    let oy = F::of(f64::from(dy)) + noise_unit_from_bits::<F>(h1) - fy;
                    let oz = F::of(f64::from(dz)) + noise_unit_from_bits::<F>(h2) - fz;
                    best = best.min(ox * ox + oy * oy + oz * oz);
                }
            }
        }
        best.sqrt()
    }

    /// Splitmix64: a seeded stream of 64-bit words.
    struct Stream(u64);

    impl Stream {
        fn next(&mut self) -> u64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^ (z >> 31)
        }

        /// A value in [0, 1) with 53 random bits.
        fn unit(&mut self) -> f64 {
            (self.next() >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The bits of `x` (f32 widens to f64 exactly, so equal bits mean equal f32 bits).
    fn bits<F: Real>(x: F) -> u64 {
        x.to_f64().expect("a float widens to f64").to_bits()
    }

    /// A point of the kind `kind` (0–7): uniform over ±1, ±16, ±300 and ±1e5 cells; within
    /// a few ULP of a lattice plane on every axis (exactly on it for 0 ULP); half way
    /// between lattice planes on every axis (the two neighbours' bounds tie); a cell's
    /// feature point or a few ULP from it (F1 = 0 or nearly).
    fn test_point<F: Real>(stream: &mut Stream, kind: u64, period: u32, seed: u32) -> [F; 3] {
        let cell = [0; 3].map(|_| (stream.next() % 64) as i32 - 32);
        let ulps = [0; 3].map(|_| (stream.next() % 7) as f64 - 3.0);
        let signed = [0; 3].map(|_| 2.0 * stream.unit() - 1.0);
        if kind >= 6 {
            let h0 = noise_cell_hash(cell.map(|i| noise_wrap(i, period)), seed);
            let h = [h0, hash_u32(h0), hash_u32(hash_u32(h0))];
            return std::array::from_fn(|k| {
                let v = F::of(f64::from(cell[k])) + noise_unit_from_bits::<F>(h[k]);
                v + F::of(ulps[k]) * F::epsilon() * v.abs().max(F::one())
            });
        }
        std::array::from_fn(|k| {
            let c = f64::from(cell[k]);
            match kind {
                0 => F::of(signed[k]),
                1 => F::of(16.0 * signed[k]),
                2 => F::of(300.0 * signed[k]),
                3 => F::of(1e5 * signed[k]),
                4 if cell[k] == 0 => F::of(ulps[k] * 1e-30),
                4 => F::of(c) * (F::one() + F::of(ulps[k]) * F::epsilon()),
                _ => F::of(c + 0.5),
            }
        })
    }

    /// `worley_noise` against the full search over 2²⁰ points per precision: nine periods,
    /// five seeds, the point kinds of `test_point`, and non-finite and huge coordinates.
    fn check_worley_against_full_search<F: Real>(stream_seed: u64) {
        const PERIODS: [u32; 9] = [1, 2, 3, 4, 5, 8, 16, 64, 256];
        const SEEDS: [u32; 5] = [0, 1, 7, 0x9e37_79b9, u32::MAX];
        let mut stream = Stream(stream_seed);
        for i in 0..(1u64 << 20) {
            let period = PERIODS[(i % 9) as usize];
            let seed = SEEDS[((i / 9) % 5) as usize];
            let kind = stream.next() % 8;
            let p = test_point::<F>(&mut stream, kind, period, seed);
            let fast = worley_noise(p, period, seed);
            let full = worley_noise_full_search(p, period, seed);
            assert_eq!(
                bits(fast),
                bits(full),
                "p = {p:?}, period {period}, seed {seed}: {fast:?} against {full:?}"
            );
        }
        let specials = [
            F::nan(),
            F::infinity(),
            F::neg_infinity(),
            F::max_value(),
            F::min_positive_value(),
            F::of(-1e-40),
            F::of(3e9),
            F::of(-0.0),
        ];
        for &a in &specials {
            for &b in &specials {
                let p = [a, b, F::of(0.25)];
                let (fast, full) = (worley_noise(p, 4, 3), worley_noise_full_search(p, 4, 3));
                assert_eq!(bits(fast), bits(full), "p = {p:?}");
            }
        }
    }

    #[test]
    fn worley_noise_equals_the_full_search_in_f32() {
        check_worley_against_full_search::<f32>(0x5eed_0f32);
    }

    #[test]
    fn worley_noise_equals_the_full_search_in_f64() {
        check_worley_against_full_search::<f64>(0x5eed_0f64);
    }

    /// Perlin noise with every corner's `noise_cell_hash` and wrap computed on its own:
    /// `perlin_noise` must equal it bit for bit.
    fn perlin_noise_per_corner<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
        let (ix, fx) = cell_and_fraction(p[0]);
        let (iy, fy) = cell_and_fraction(p[1]);
        let (iz, fz) = cell_and_fraction(p[2]);
        let one = F::one();
        let corner = |dx: i32, dy: i32, dz: i32| {
            let cell = [
                noise_wrap(ix.wrapping_add(dx), period),
                noise_wrap(iy.wrapping_add(dy), period),
                noise_wrap(iz.wrapping_add(dz), period),
            ];
            let offset = |f: F, d: i32| if d == 0 { f } else { f - one };
            let (x, y, z) = (offset(fx, dx), offset(fy, dy), offset(fz, dz));
            perlin_gradient_dot(noise_cell_hash(cell, seed), x, y, z)
        };
        let (u, v, w) = (perlin_fade(fx), perlin_fade(fy), perlin_fade(fz));
        let nx00 = noise_lerp(corner(0, 0, 0), corner(1, 0, 0), u);
        let nx10 = noise_lerp(corner(0, 1, 0), corner(1, 1, 0), u);
        let nx01 = noise_lerp(corner(0, 0, 1), corner(1, 0, 1), u);
        let nx11 = noise_lerp(corner(0, 1, 1), corner(1, 1, 1), u);
        noise_lerp(noise_lerp(nx00, nx10, v), noise_lerp(nx01, nx11, v), w)
    }

    fn check_perlin_against_per_corner<F: Real>(stream_seed: u64) {
        const PERIODS: [u32; 9] = [1, 2, 3, 4, 5, 8, 16, 64, 256];
        let mut stream = Stream(stream_seed);
        for i in 0..(1u64 << 18) {
            let period = PERIODS[(i % 9) as usize];
            let seed = (stream.next() >> 32) as u32;
            let kind = stream.next() % 6;
            let p = test_point::<F>(&mut stream, kind, period, seed);
            let (fast, full) = (
                perlin_noise(p, period, seed),
                perlin_noise_per_corner(p, period, seed),
            );
            assert_eq!(bits(fast), bits(full), "p = {p:?}, period {period}");
        }
    }

    #[test]
    fn perlin_noise_equals_the_per_corner_form() {
        check_perlin_against_per_corner::<f32>(0x9e71_0f32);
        check_perlin_against_per_corner::<f64>(0x9e71_0f64);
    }

    #[test]
    fn perlin_is_zero_on_the_lattice() {
        for i in -3..3 {
            let p = [f64::from(i), 1.0, -2.0];
            assert_eq!(perlin_noise(p, 4, 7), 0.0);
        }
    }
}
