//! The terrain's procedural materials: rock, grass and snow weighted by slope, altitude
//! and aspect, a value-noise detail band-limited by the pixel's footprint on the
//! ground, and the bilinear taps of a colour texture. Each function is one formula
//! generic over the float type: the `f32` instance is the twin of its WGSL namesake in
//! `shaders/render/terrain_materials.wgsl` (operation for operation), the `f64` instance
//! the parity reference.
//!
//! The weights: snow above the snow line (lowered on slopes facing the pole, which see
//! less of the sun's mean path, by `snow_line_aspect` per unit of the normal's
//! horizontal component toward the pole), sliding off slopes steeper than the snow
//! slope; rock on slopes steeper than the rock slope and above the grass line; grass
//! elsewhere. Every transition is a smoothstep; the altitude lines are moved by the
//! detail noise so they follow no contour.

use num_traits::Float;
use skyscape_wgsl::common::{hash_combine, hash_u32, unit_float_from_bits};

/// Octaves of the detail noise: wavelengths from [`DETAIL_LONGEST_WAVELENGTH`] halving.
pub const DETAIL_OCTAVES: u32 = 10;
/// The detail noise's longest wavelength (m); a power of two, so every octave's lattice
/// coordinate `east × frequency` is exact in any precision.
pub const DETAIL_LONGEST_WAVELENGTH: f64 = 256.0;

/// The materials' parameters in the float type `F` (layout of WGSL `MaterialParams`
/// for `f32`: [`MaterialsUniform`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MaterialParams<F> {
    /// Linear RGB albedo of rock.
    pub rock_albedo: [F; 3],
    /// Elevation of the snow line on flat ground (m).
    pub snow_line: F,
    /// Linear RGB albedo of grass.
    pub grass_albedo: [F; 3],
    /// Metres the snow line lies lower per unit of the normal's horizontal component
    /// toward the pole.
    pub snow_line_aspect: F,
    /// Linear RGB albedo of snow.
    pub snow_albedo: [F; 3],
    /// Elevation above which grass gives way to rock and scree (m).
    pub grass_line: F,
    /// Width of the altitude transitions (m).
    pub transition: F,
    /// cos of the slope where rock starts.
    pub cos_rock_gentle: F,
    /// cos of the slope where rock is complete.
    pub cos_rock_steep: F,
    /// cos of the slope where snow starts to slide off.
    pub cos_snow_gentle: F,
    /// cos of the slope where snow is gone.
    pub cos_snow_steep: F,
    /// Metres by which the detail noise moves the altitude lines.
    pub line_noise: F,
    /// Relative albedo variation of the detail noise.
    pub albedo_noise: F,
    /// The noise's seed.
    pub seed: u32,
    /// +1: the pole is north (northern hemisphere), −1: south.
    pub pole_north: F,
}

/// [`MaterialParams`] as the GPU's uniform (layout identical to WGSL `MaterialParams`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MaterialsUniform {
    /// Rock albedo.
    pub rock_albedo: [f32; 3],
    /// Snow line (m).
    pub snow_line: f32,
    /// Grass albedo.
    pub grass_albedo: [f32; 3],
    /// Snow line's lowering toward the pole (m).
    pub snow_line_aspect: f32,
    /// Snow albedo.
    pub snow_albedo: [f32; 3],
    /// Grass line (m).
    pub grass_line: f32,
    /// Transition width (m).
    pub transition: f32,
    /// cos where rock starts.
    pub cos_rock_gentle: f32,
    /// cos where rock is complete.
    pub cos_rock_steep: f32,
    /// cos where snow starts to slide.
    pub cos_snow_gentle: f32,
    /// cos where snow is gone.
    pub cos_snow_steep: f32,
    /// Line noise (m).
    pub line_noise: f32,
    /// Albedo noise.
    pub albedo_noise: f32,
    /// Seed.
    pub seed: u32,
    /// +1 north, −1 south.
    pub pole_north: f32,
    /// Alignment.
    pub padding0: f32,
    /// Alignment.
    pub padding1: f32,
    /// Alignment.
    pub padding2: f32,
}

impl MaterialParams<f32> {
    /// The GPU uniform of these parameters.
    pub fn uniform(&self) -> MaterialsUniform {
        MaterialsUniform {
            rock_albedo: self.rock_albedo,
            snow_line: self.snow_line,
            grass_albedo: self.grass_albedo,
            snow_line_aspect: self.snow_line_aspect,
            snow_albedo: self.snow_albedo,
            grass_line: self.grass_line,
            transition: self.transition,
            cos_rock_gentle: self.cos_rock_gentle,
            cos_rock_steep: self.cos_rock_steep,
            cos_snow_gentle: self.cos_snow_gentle,
            cos_snow_steep: self.cos_snow_steep,
            line_noise: self.line_noise,
            albedo_noise: self.albedo_noise,
            seed: self.seed,
            pole_north: self.pole_north,
            padding0: 0.0,
            padding1: 0.0,
            padding2: 0.0,
        }
    }
}

impl<F: Float> MaterialParams<F> {
    /// These parameters in another float type (each value rounded once).
    pub fn cast<G: Float>(&self) -> MaterialParams<G> {
        let c = |x: F| G::from(x).unwrap_or_else(G::nan);
        MaterialParams {
            rock_albedo: self.rock_albedo.map(c),
            snow_line: c(self.snow_line),
            grass_albedo: self.grass_albedo.map(c),
            snow_line_aspect: c(self.snow_line_aspect),
            snow_albedo: self.snow_albedo.map(c),
            grass_line: c(self.grass_line),
            transition: c(self.transition),
            cos_rock_gentle: c(self.cos_rock_gentle),
            cos_rock_steep: c(self.cos_rock_steep),
            cos_snow_gentle: c(self.cos_snow_gentle),
            cos_snow_steep: c(self.cos_snow_steep),
            line_noise: c(self.line_noise),
            albedo_noise: c(self.albedo_noise),
            seed: self.seed,
            pole_north: c(self.pole_north),
        }
    }
}

/// The constant `x` in `F`.
fn of<F: Float>(x: f64) -> F {
    F::from(x).unwrap_or_else(F::nan)
}

/// `t²(3 − 2t)` of `t` clamped to [0, 1]. Twin of WGSL `smooth_unit`.
pub fn smooth_unit<F: Float>(t: F) -> F {
    let c = t.max(F::zero()).min(F::one());
    c * c * (of::<F>(3.0) - of::<F>(2.0) * c)
}

/// A lattice value in [−1, 1) at integer point (ix, iy). Twin of WGSL `lattice_value`
/// (the hash is integer arithmetic; the value is exact in `f32`).
pub fn lattice_value<F: Float>(ix: i32, iy: i32, seed: u32) -> F {
    let h = hash_combine(hash_combine(hash_u32(seed), ix as u32), iy as u32);
    of::<F>(2.0) * of::<F>(f64::from(unit_float_from_bits(h))) - F::one()
}

/// Value noise of unit lattice spacing at (x, y), smoothly interpolated, in [−1, 1].
/// Twin of WGSL `value_noise`.
pub fn value_noise<F: Float>(x: F, y: F, seed: u32) -> F {
    let fx = x.floor();
    let fy = y.floor();
    let ix = fx.to_i32().unwrap_or(0);
    let iy = fy.to_i32().unwrap_or(0);
    let sx = smooth_unit(x - fx);
    let sy = smooth_unit(y - fy);
    let a = lattice_value::<F>(ix, iy, seed);
    let b = lattice_value::<F>(ix.wrapping_add(1), iy, seed);
    let c = lattice_value::<F>(ix, iy.wrapping_add(1), seed);
    let d = lattice_value::<F>(ix.wrapping_add(1), iy.wrapping_add(1), seed);
    let bottom = a + (b - a) * sx;
    let top = c + (d - c) * sx;
    bottom + (top - bottom) * sy
}

/// Detail noise at map position (`east`, `south`) in metres, in [−1, 1]: octaves of
/// value noise of halving wavelength and amplitude, each faded out as its wavelength
/// drops from eight to four footprints (m): twice the Nyquist limit of two footprints, as
/// a pixel's footprint is no ideal low-pass filter; the faded detail is left at its mean,
/// 0, instead of aliasing. Twin of WGSL `detail_noise`.
pub fn detail_noise<F: Float>(east: F, south: F, footprint: F, seed: u32) -> F {
    let inverse_quadruple_footprint = F::one() / (of::<F>(4.0) * footprint);
    let mut sum = F::zero();
    let mut norm = F::zero();
    let mut wavelength = of::<F>(DETAIL_LONGEST_WAVELENGTH);
    let mut frequency = of::<F>(1.0 / DETAIL_LONGEST_WAVELENGTH);
    let mut amplitude = F::one();
    for k in 0..DETAIL_OCTAVES {
        let fade = (wavelength * inverse_quadruple_footprint - F::one())
            .max(F::zero())
            .min(F::one());
        if fade > F::zero() {
            sum = sum
                + amplitude
                    * fade
                    * value_noise(east * frequency, south * frequency, seed.wrapping_add(k));
        }
        norm = norm + amplitude;
        wavelength = wavelength * of::<F>(0.5);
        frequency = frequency * of::<F>(2.0);
        amplitude = amplitude * of::<F>(0.5);
    }
    sum / norm
}

/// Weights `[rock, grass, snow]`, summing to 1, of a surface with unit normal `normal`
/// (east, north, up) at `elevation` (m), its altitude lines moved by `detail` × the line
/// noise. Twin of WGSL `material_weights`.
pub fn material_weights<F: Float>(
    normal: [F; 3],
    elevation: F,
    detail: F,
    params: &MaterialParams<F>,
) -> [F; 3] {
    let one = F::one();
    let half = of::<F>(0.5);
    let perturbed = elevation + detail * params.line_noise;
    let poleward = params.pole_north * normal[1];
    let snow_line = params.snow_line - params.snow_line_aspect * poleward;
    let inverse_transition = one / params.transition;
    let snow_by_altitude = smooth_unit((perturbed - snow_line) * inverse_transition + half);
    let snow_slides = smooth_unit(
        (params.cos_snow_gentle - normal[2]) / (params.cos_snow_gentle - params.cos_snow_steep),
    );
    let snow = snow_by_altitude * (one - snow_slides);
    let rock_by_slope = smooth_unit(
        (params.cos_rock_gentle - normal[2]) / (params.cos_rock_gentle - params.cos_rock_steep),
    );
    let rock_by_altitude = smooth_unit((perturbed - params.grass_line) * inverse_transition + half);
    let rock = one - (one - rock_by_slope) * (one - rock_by_altitude);
    [(one - snow) * rock, (one - snow) * (one - rock), snow]
}

/// Albedo of the procedural materials: the weights' mix of rock, `ground_albedo` (the
/// grass's, or a colour texture's) and snow, its brightness varied by the detail. Twin
/// of WGSL `procedural_albedo`.
pub fn procedural_albedo<F: Float>(
    normal: [F; 3],
    elevation: F,
    detail: F,
    ground_albedo: [F; 3],
    params: &MaterialParams<F>,
) -> [F; 3] {
    let w = material_weights(normal, elevation, detail, params);
    let brightness = F::one() + params.albedo_noise * detail;
    std::array::from_fn(|c| {
        let mixed =
            params.rock_albedo[c] * w[0] + ground_albedo[c] * w[1] + params.snow_albedo[c] * w[2];
        (mixed * brightness).min(F::one())
    })
}

/// The pixel's footprint on the ground (m) at `distance` (m) for a pixel of
/// `pixel_angle` (rad), seen at cosine `cos_incidence` from the normal: stretched by
/// 1/cos, at most tenfold. Twin of WGSL `pixel_footprint`.
pub fn pixel_footprint<F: Float>(distance: F, pixel_angle: F, cos_incidence: F) -> F {
    distance * pixel_angle / cos_incidence.abs().max(of::<F>(0.1))
}

/// Bilinear taps of a colour texel position `texel` (texels from texel (0, 0)'s
/// centre) in a `size` texture (at least 2×2): the four flat indices (x fastest) and
/// their weights, clamped to the texture. Twin of WGSL `colour_taps`.
pub fn colour_taps(texel: [f32; 2], size: [u32; 2]) -> ([u32; 4], [f32; 4]) {
    let t = [
        texel[0].clamp(0.0, (size[0] - 1) as f32),
        texel[1].clamp(0.0, (size[1] - 1) as f32),
    ];
    let i = (t[0].floor() as u32).min(size[0] - 2);
    let j = (t[1].floor() as u32).min(size[1] - 2);
    let fx = t[0] - i as f32;
    let fy = t[1] - j as f32;
    (
        [
            j * size[0] + i,
            j * size[0] + i + 1,
            (j + 1) * size[0] + i,
            (j + 1) * size[0] + i + 1,
        ],
        [
            (1.0 - fx) * (1.0 - fy),
            fx * (1.0 - fy),
            (1.0 - fx) * fy,
            fx * fy,
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn params() -> MaterialParams<f64> {
        crate::scene::ProceduralMaterialsSection::default()
            .params(1.0)
            .unwrap()
            .cast()
    }

    fn normal_at_slope(slope_deg: f64, toward_north: f64) -> [f64; 3] {
        let s = slope_deg.to_radians();
        [0.0, s.sin() * toward_north, s.cos()]
    }

    #[test]
    fn the_noise_stays_in_range_and_is_continuous() {
        let mut previous = value_noise(0.0f64, 0.3, 5);
        for k in 1..20_000 {
            let x = k as f64 * 1e-3;
            let v = value_noise(x, 0.3, 5);
            assert!((-1.0..=1.0).contains(&v));
            assert!((v - previous).abs() < 0.01, "jump at x = {x}");
            previous = v;
        }
    }

    #[test]
    fn the_detail_fades_to_its_mean_when_the_footprint_exceeds_its_wavelengths() {
        // A footprint of a quarter of the longest wavelength or more shows no detail.
        for k in 0..100 {
            let east = 37.0 * k as f64;
            assert_eq!(detail_noise(east, 11.0, 64.0, 3), 0.0);
        }
        let near: Vec<f64> = (0..100)
            .map(|k| detail_noise(3.7 * k as f64, 11.0, 0.1, 3))
            .collect();
        assert!(near.iter().any(|v| v.abs() > 0.05));
    }

    #[test]
    fn snow_lies_above_the_snow_line_and_lower_on_the_shaded_side() {
        let p = params();
        let flat = [0.0, 0.0, 1.0];
        let [_, _, snow] = material_weights(flat, p.snow_line + p.transition, 0.0, &p);
        assert_eq!(snow, 1.0);
        let [_, _, snow] = material_weights(flat, p.snow_line - p.transition, 0.0, &p);
        assert_eq!(snow, 0.0);
        // A 25° slope just below the flat snow line: snow facing the pole, none facing
        // the equator.
        let elevation = p.snow_line - 0.4 * p.snow_line_aspect * 25f64.to_radians().sin();
        let poleward = material_weights(normal_at_slope(25.0, 1.0), elevation, 0.0, &p)[2];
        let sunward = material_weights(normal_at_slope(25.0, -1.0), elevation, 0.0, &p)[2];
        assert!(poleward > 0.5 && sunward < 0.01, "{poleward} {sunward}");
    }

    #[test]
    fn steep_slopes_are_rock_and_gentle_valleys_grass() {
        let p = params();
        let valley = p.grass_line - 2.0 * p.transition;
        let [rock, grass, snow] = material_weights(normal_at_slope(60.0, 0.3), valley, 0.0, &p);
        assert_eq!([rock, grass, snow], [1.0, 0.0, 0.0]);
        let [rock, grass, _] = material_weights(normal_at_slope(5.0, 0.3), valley, 0.0, &p);
        assert_eq!([rock, grass], [0.0, 1.0]);
        // Snow slides off cliffs above the snow line: rock again.
        let high = p.snow_line + 2.0 * p.transition;
        let [rock, _, snow] = material_weights(normal_at_slope(70.0, 1.0), high, 0.0, &p);
        assert_eq!([rock, snow], [1.0, 0.0]);
    }

    #[test]
    fn colour_taps_weigh_the_four_neighbours_and_clamp_at_the_edges() {
        let (index, weight) = colour_taps([1.25, 0.5], [4, 3]);
        assert_eq!(index, [1, 2, 5, 6]);
        assert_eq!(weight, [0.375, 0.125, 0.375, 0.125]);
        let (index, weight) = colour_taps([9.0, -2.0], [4, 3]);
        assert_eq!(index, [2, 3, 6, 7]);
        assert_eq!(weight, [0.0, 1.0, 0.0, 0.0]);
    }
}
