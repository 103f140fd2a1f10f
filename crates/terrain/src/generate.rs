//! A seeded, deterministic procedural heightfield generator (fBm and ridged noise).
//!
//! Only integer hashing and IEEE `f64` `+ - * /` are used (no transcendental
//! functions), so the output is bit-identical on every platform for a given
//! [`GeneratorParams`].

use crate::{Heightfield, TerrainError};

/// The lattice noise summed by the fractal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Noise {
    /// Value noise: random values at lattice points, quintic interpolation. Range [-1, 1].
    Value,
    /// Gradient (Perlin-style) noise: random unit-ish gradients at lattice points,
    /// quintic interpolation. Range about [-1, 1].
    Gradient,
}

/// How octaves are combined.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fractal {
    /// Fractional Brownian motion: `sum gain^i * noise(lacunarity^i * p)`.
    Fbm,
    /// Ridged multifractal: `sum gain^i * (1 - |noise|)^2`, giving sharp crests.
    Ridged,
}

/// Parameters of [`generate`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneratorParams {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Metres per texel.
    pub spacing: f64,
    /// Seed: different seeds give unrelated terrains.
    pub seed: u64,
    /// Number of octaves (1..=24).
    pub octaves: u32,
    /// Wavelength of the first octave, metres (> 0).
    pub wavelength: f64,
    /// Peak-to-peak scale of the result, metres (>= 0): the output spans
    /// roughly `[0, amplitude]`.
    pub amplitude: f64,
    /// Frequency ratio between octaves (typically 2).
    pub lacunarity: f64,
    /// Amplitude ratio between octaves (typically 0.5).
    pub gain: f64,
    /// Lattice noise.
    pub noise: Noise,
    /// Octave combination.
    pub fractal: Fractal,
}

impl GeneratorParams {
    /// Sensible defaults for a `width × height` map at `spacing` m: 8 octaves of
    /// gradient fBm, first wavelength a quarter of the map, 1,000 m relief.
    pub fn new(width: usize, height: usize, spacing: f64, seed: u64) -> Self {
        Self {
            width,
            height,
            spacing,
            seed,
            octaves: 8,
            wavelength: 0.25 * (width.max(height) as f64) * spacing,
            amplitude: 1000.0,
            lacunarity: 2.0,
            gain: 0.5,
            noise: Noise::Gradient,
            fractal: Fractal::Fbm,
        }
    }
}

/// SplitMix64 finaliser: a good 64-bit integer hash.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

fn lattice_hash(seed: u64, octave: u32, ix: i64, iy: i64) -> u64 {
    mix(
        mix(mix(seed ^ u64::from(octave).wrapping_mul(0xA24B_AED4_963E_E407)) ^ ix as u64)
            ^ iy as u64,
    )
}

/// Uniform in [-1, 1) from the top 53 bits.
fn unit(h: u64) -> f64 {
    (h >> 11) as f64 * (2.0 / (1u64 << 53) as f64) - 1.0
}

fn quintic(t: f64) -> f64 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

fn lattice_noise(kind: Noise, seed: u64, octave: u32, x: f64, y: f64) -> f64 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i64, fy as i64);
    let (tx, ty) = (x - fx, y - fy);
    let corner = |dx: i64, dy: i64| -> f64 {
        let h = lattice_hash(seed, octave, ix + dx, iy + dy);
        match kind {
            Noise::Value => unit(h),
            Noise::Gradient => {
                // Gradient components in [-1, 1); dot with the offset to the corner.
                let gx = unit(h);
                let gy = unit(mix(h));
                gx * (tx - dx as f64) + gy * (ty - dy as f64)
            }
        }
    };
    let (sx, sy) = (quintic(tx), quintic(ty));
    let top = corner(0, 0) + sx * (corner(1, 0) - corner(0, 0));
    let bottom = corner(0, 1) + sx * (corner(1, 1) - corner(0, 1));
    top + sy * (bottom - top)
}

/// The largest lattice coordinate [`generate`] accepts at its finest octave (2^40).
const MAX_LATTICE_COORDINATE: f64 = (1u64 << 40) as f64;

/// Generates a heightfield. Deterministic in `params`; errors on invalid parameters.
pub fn generate(params: &GeneratorParams) -> Result<Heightfield, TerrainError> {
    let p = params;
    crate::heightfield::check_dimensions(p.width as u64, p.height as u64)?;
    let positive = |field: &'static str, v: f64| {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(TerrainError::param(field, v, "must be finite and > 0"))
        }
    };
    positive("spacing", p.spacing)?;
    positive("wavelength", p.wavelength)?;
    positive("lacunarity", p.lacunarity)?;
    positive("gain", p.gain)?;
    if !(p.amplitude.is_finite() && p.amplitude >= 0.0) {
        return Err(TerrainError::param(
            "amplitude",
            p.amplitude,
            "must be finite and >= 0",
        ));
    }
    if !(1..=24).contains(&p.octaves) {
        return Err(TerrainError::param(
            "octaves",
            f64::from(p.octaves),
            "must be in 1..=24",
        ));
    }
    // The finest octave's lattice coordinate must keep a fractional part in f64 and
    // fit the lattice hash's i64 corners: beyond 2^40 lattice cells the noise would be
    // evaluated at rounded coordinates (and the corner index could overflow).
    let extent = (p.width.max(p.height) as f64) * p.spacing;
    let finest = extent / p.wavelength * p.lacunarity.max(1.0).powi(p.octaves as i32 - 1);
    if finest.is_nan() || finest > MAX_LATTICE_COORDINATE {
        return Err(TerrainError::param(
            "wavelength",
            p.wavelength,
            "with lacunarity^(octaves - 1), gives more than 2^40 lattice cells across the \
             map at the finest octave (extent / wavelength x lacunarity^(octaves - 1))",
        ));
    }
    let mut raw = vec![0.0f64; p.width * p.height];
    let mut total_weight = 0.0;
    let mut weight = 1.0;
    for _ in 0..p.octaves {
        total_weight += weight;
        weight *= p.gain;
    }
    for y in 0..p.height {
        for x in 0..p.width {
            let mut frequency = 1.0 / p.wavelength;
            let mut weight = 1.0;
            let mut sum = 0.0;
            for octave in 0..p.octaves {
                let px = x as f64 * p.spacing * frequency;
                let py = y as f64 * p.spacing * frequency;
                let n = lattice_noise(p.noise, p.seed, octave, px, py);
                sum += weight
                    * match p.fractal {
                        // Map [-1, 1] to [0, 1].
                        Fractal::Fbm => 0.5 * (n + 1.0),
                        Fractal::Ridged => {
                            let r = 1.0 - n.abs();
                            r * r
                        }
                    };
                frequency *= p.lacunarity;
                weight *= p.gain;
            }
            raw[y * p.width + x] = sum / total_weight;
        }
    }
    let samples = raw
        .into_iter()
        .map(|v| (v.clamp(0.0, 1.0) * p.amplitude) as f32)
        .collect();
    Heightfield::new(p.width, p.height, p.spacing, 1.0, samples)
}
