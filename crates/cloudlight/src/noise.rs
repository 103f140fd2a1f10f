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
    let (x0, x1) = (
        noise_wrap(ix, period),
        noise_wrap(ix.wrapping_add(1), period),
    );
    let (y0, y1) = (
        noise_wrap(iy, period),
        noise_wrap(iy.wrapping_add(1), period),
    );
    let (z0, z1) = (
        noise_wrap(iz, period),
        noise_wrap(iz.wrapping_add(1), period),
    );
    let one = F::one();
    let (gx, gy, gz) = (fx - one, fy - one, fz - one);
    let n000 = perlin_gradient_dot(noise_cell_hash([x0, y0, z0], seed), fx, fy, fz);
    let n100 = perlin_gradient_dot(noise_cell_hash([x1, y0, z0], seed), gx, fy, fz);
    let n010 = perlin_gradient_dot(noise_cell_hash([x0, y1, z0], seed), fx, gy, fz);
    let n110 = perlin_gradient_dot(noise_cell_hash([x1, y1, z0], seed), gx, gy, fz);
    let n001 = perlin_gradient_dot(noise_cell_hash([x0, y0, z1], seed), fx, fy, gz);
    let n101 = perlin_gradient_dot(noise_cell_hash([x1, y0, z1], seed), gx, fy, gz);
    let n011 = perlin_gradient_dot(noise_cell_hash([x0, y1, z1], seed), fx, gy, gz);
    let n111 = perlin_gradient_dot(noise_cell_hash([x1, y1, z1], seed), gx, gy, gz);
    let (u, v, w) = (perlin_fade(fx), perlin_fade(fy), perlin_fade(fz));
    let nx00 = noise_lerp(n000, n100, u);
    let nx10 = noise_lerp(n010, n110, u);
    let nx01 = noise_lerp(n001, n101, u);
    let nx11 = noise_lerp(n011, n111, u);
    let nxy0 = noise_lerp(nx00, nx10, v);
    let nxy1 = noise_lerp(nx01, nx11, v);
    noise_lerp(nxy0, nxy1, w)
}

/// Worley (cellular) noise F1 at `p` (lattice cells) with integer period `period` (≥ 1):
/// the distance in cells to the nearest feature point of the 3×3×3 cells around `p`'s
/// cell. Each cell's point is `cell + (u(h), u(hash(h)), u(hash(hash(h))))` with
/// `h = noise_cell_hash(wrapped cell, seed)` and `u` the top 24 bits in [0, 1).
/// WGSL twin `worley_noise`.
pub fn worley_noise<F: Real>(p: [F; 3], period: u32, seed: u32) -> F {
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
    fn wrap_is_modulo_for_negative_indices() {
        assert_eq!(noise_wrap(-1, 4), 3);
        assert_eq!(noise_wrap(-4, 4), 0);
        assert_eq!(noise_wrap(9, 4), 1);
        assert_eq!(noise_wrap(0, 1), 0);
    }

    #[test]
    fn perlin_is_zero_on_the_lattice() {
        for i in -3..3 {
            let p = [f64::from(i), 1.0, -2.0];
            assert_eq!(perlin_noise(p, 4, 7), 0.0);
        }
    }
}
