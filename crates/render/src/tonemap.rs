//! Display encoding. Twin of `shaders/render/tonemap.wgsl`.

use crate::RenderError;
use atmos::transmittance::one_minus_exp_neg;
use serde::Deserialize;
use skyscape_wgsl::common::{hash_combine, hash_u32};

/// How exposed radiance becomes a display value in [0, 1]³ (`[output]
/// display_transform`, `--display-transform`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DisplayTransform {
    /// [`tonemap_neutral`]: the brightest channel follows a curve and the others keep
    /// their ratios to it, so a colour keeps its hue; a bounded path to white.
    #[default]
    Neutral,
    /// [`tonemap_exposure`]: 1 − exp(−x) on each channel alone (O'Neil 2005's tone map):
    /// bright saturated colours drift towards the primaries' mixtures and white.
    PerChannel,
}

impl DisplayTransform {
    /// As the scene file and `--display-transform` spell it.
    pub fn name(self) -> &'static str {
        match self {
            DisplayTransform::Neutral => "neutral",
            DisplayTransform::PerChannel => "per-channel",
        }
    }

    /// The WGSL encoding (`DISPLAY_NEUTRAL`, `DISPLAY_PER_CHANNEL` in
    /// `render::tonemap`).
    pub fn code(self) -> u32 {
        match self {
            DisplayTransform::Neutral => 0,
            DisplayTransform::PerChannel => 1,
        }
    }

    /// The transform a WGSL code stands for (any code but 1 is the neutral one, as in
    /// the WGSL).
    pub fn from_code(code: u32) -> Self {
        if code == 1 {
            DisplayTransform::PerChannel
        } else {
            DisplayTransform::Neutral
        }
    }
}

/// The tone map of O'Neil's planet shader (GPU Gems 2, ch. 16, 2005): 1 − exp(−radiance·exposure) per channel.
pub fn tonemap_exposure(radiance: [f32; 3], exposure: f32) -> [f32; 3] {
    radiance.map(|c| one_minus_exp_neg(c * exposure))
}

/// The largest finite value of the GPU's HDR target (f16). The sky passes scale a
/// brighter colour (the sun's disc) down as a whole to fit it, keeping its hue;
/// [`tonemap_neutral`] does the same, so that the CPU's f32 radiance displays as the
/// GPU's target does.
pub const HDR_LARGEST: f32 = 65_504.0;
/// Where the neutral curve leaves the identity: Khronos PBR Neutral's
/// `startCompression` (0.8 − 0.04).
pub const NEUTRAL_COMPRESSION_START: f32 = 0.76;
/// Khronos PBR Neutral's `desaturation`: how fast compressed light moves towards white.
pub const NEUTRAL_DESATURATION: f32 = 0.15;
/// The most white mixed into an infinitely bright colour: a bright light keeps three
/// quarters of its saturation, so a reddened sun stays red (its displayed R/B is
/// above 2 for any linear R/B above 4.7, the smallest the f16 target leaves it at
/// sunset), while Khronos' unbounded path turns every light far above display white
/// into white.
pub const NEUTRAL_WHITE_MIX_LIMIT: f32 = 0.25;

/// Hue-preserving display transform after Khronos PBR Neutral (Khronos 3D Commerce
/// "PBR Neutral" tone mapper specification, 2024): the peak channel `p` of the exposed
/// radiance follows the identity up to 0.76 and then the shoulder
/// `1 − 0.24² / (p − 0.52)` (slope 1 and value 0.76 at the start, approaching 1); the
/// colour is scaled with it, keeping its channel ratios (hue and saturation); then a
/// fraction `0.25 · (1 − 1 / (0.15 (p − p′) + 1))` of the way to white at the new peak
/// `p′`, so very bright light pales. Two departures from the specification, both for
/// hue: no toe (its offset, subtracted from every channel alike, turns dark
/// saturated colours' hue), and a bounded path to white ([`NEUTRAL_WHITE_MIX_LIMIT`]).
/// A colour brighter than [`HDR_LARGEST`] is first scaled down to it as a whole (an
/// infinite channel, which a GPU target may hold, counts as `f32::MAX`).
pub fn tonemap_neutral(radiance: [f32; 3], exposure: f32) -> [f32; 3] {
    let unfitted = radiance.map(|c| (c * exposure).clamp(0.0, f32::MAX));
    let brightest = unfitted[0].max(unfitted[1]).max(unfitted[2]);
    let fit = if brightest > HDR_LARGEST {
        HDR_LARGEST / brightest
    } else {
        1.0
    };
    let exposed = unfitted.map(|c| c * fit);
    let peak = exposed[0].max(exposed[1]).max(exposed[2]);
    if peak < NEUTRAL_COMPRESSION_START {
        return exposed;
    }
    // 1 − d² / (p + d − start) with d = 1 − start = 0.24: d² = 0.0576, d − start = −0.52.
    let new_peak = 1.0 - 0.0576 / (peak - 0.52);
    let scale = new_peak / peak;
    let white_mix =
        NEUTRAL_WHITE_MIX_LIMIT * (1.0 - 1.0 / (NEUTRAL_DESATURATION * (peak - new_peak) + 1.0));
    exposed.map(|c| c * scale * (1.0 - white_mix) + new_peak * white_mix)
}

/// The scene's display transform of exposed radiance: [`tonemap_neutral`] or
/// [`tonemap_exposure`]. WGSL takes `transform` as [`DisplayTransform::code`].
pub fn display_transform(
    radiance: [f32; 3],
    exposure: f32,
    transform: DisplayTransform,
) -> [f32; 3] {
    match transform {
        DisplayTransform::PerChannel => tonemap_exposure(radiance, exposure),
        DisplayTransform::Neutral => tonemap_neutral(radiance, exposure),
    }
}

/// The sRGB transfer function (IEC 61966-2-1) for one channel in [0, 1].
pub fn linear_to_srgb(linear: f32) -> f32 {
    if linear <= 0.003_130_8 {
        12.92 * linear
    } else {
        1.055 * linear.powf(1.0 / 2.4) - 0.055
    }
}

/// Triangular-PDF dither in (−1, 1) LSB for a pixel: two 23-bit draws summed in
/// integers and converted once, exactly (bit-identical to the WGSL).
pub fn dither_offset(pixel: [u32; 2], seed: u32) -> f32 {
    let h = hash_combine(hash_combine(seed, pixel[0]), pixel[1]);
    let sum = (h >> 9) + (hash_u32(h ^ 0x5bd1_e995) >> 9);
    (sum as i32 - 8_388_608) as f32 * (1.0 / 8_388_608.0)
}

/// sRGB-encodes, dithers and quantises a display value to 8-bit code values.
pub fn quantize_srgb8(display: [f32; 3], pixel: [u32; 2], seed: u32) -> [f32; 3] {
    let offset = dither_offset(pixel, seed);
    display.map(|c| {
        (linear_to_srgb(c) * 255.0 + offset + 0.5)
            .floor()
            .clamp(0.0, 255.0)
    })
}

/// Packs code values into RGBA8 (alpha 255), R in the low byte.
pub fn pack_rgba8(code: [f32; 3]) -> u32 {
    let [r, g, b] = code.map(|c| c as u32);
    r | (g << 8) | (b << 16) | (255 << 24)
}

/// Fraction of RGBA8 pixels (as packed by [`pack_rgba8`]) whose channels all differ
/// by at most `lsb` code values between two images of the same size; 1 for two empty
/// images; an error when the sizes differ. Used to compare the GPU pass with its
/// CPU twin.
pub fn fraction_within_lsb(a: &[u32], b: &[u32], lsb: u8) -> Result<f64, RenderError> {
    if a.len() != b.len() {
        return Err(RenderError::InvalidParameter {
            field: "b",
            value: format!("{} pixels", b.len()),
            reason: "must have as many pixels as `a`",
        });
    }
    if a.is_empty() {
        return Ok(1.0);
    }
    let close = a
        .iter()
        .zip(b)
        .filter(|(x, y)| {
            x.to_le_bytes()
                .iter()
                .zip(y.to_le_bytes())
                .all(|(p, q)| p.abs_diff(q) <= lsb)
        })
        .count();
    Ok(close as f64 / a.len() as f64)
}

/// Fraction of pixels of `a` that have a pixel within `lsb` code values (every
/// channel) somewhere in the `(2 radius + 1)²` neighbourhood of the same place in `b`,
/// and the other way round (the smaller of the two). A comparison for images whose
/// geometry may land a pixel apart: the GPU rasterises the terrain as triangles, the
/// CPU reference renderer ray casts the bilinear surface, so where the terrain is
/// finer than a pixel the two sample neighbouring points of it. `width` is the row
/// length; errors as [`fraction_within_lsb`], and when `width` does not divide the
/// pixel count.
pub fn fraction_within_lsb_of_neighbourhood(
    a: &[u32],
    b: &[u32],
    width: usize,
    lsb: u8,
    radius: usize,
) -> Result<f64, RenderError> {
    fraction_within_lsb(a, b, lsb)?;
    if a.is_empty() {
        return Ok(1.0);
    }
    if width == 0 || !a.len().is_multiple_of(width) {
        return Err(RenderError::InvalidParameter {
            field: "width",
            value: width.to_string(),
            reason: "must divide the pixel count",
        });
    }
    let height = a.len() / width;
    let close = |p: u32, q: u32| {
        p.to_le_bytes()
            .iter()
            .zip(q.to_le_bytes())
            .all(|(x, y)| x.abs_diff(y) <= lsb)
    };
    let one_way = |from: &[u32], to: &[u32]| {
        let mut matched = 0usize;
        for y in 0..height {
            for x in 0..width {
                let pixel = from[y * width + x];
                let rows = y.saturating_sub(radius)..(y + radius + 1).min(height);
                let found = rows.into_iter().any(|yy| {
                    (x.saturating_sub(radius)..(x + radius + 1).min(width))
                        .any(|xx| close(pixel, to[yy * width + xx]))
                });
                matched += usize::from(found);
            }
        }
        matched as f64 / from.len() as f64
    };
    Ok(one_way(a, b).min(one_way(b, a)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbourhood_agreement_forgives_a_one_pixel_shift_only() {
        // A bright column one pixel apart: strict agreement fails on two columns,
        // the 3×3 neighbourhood forgives it, a two-pixel shift is not forgiven.
        let image = |column: usize| -> Vec<u32> {
            (0..8 * 4)
                .map(|i| {
                    if i % 8 == column {
                        0xffff_ffff
                    } else {
                        0xff00_0000
                    }
                })
                .collect()
        };
        let (a, b, c) = (image(3), image(4), image(5));
        assert_eq!(fraction_within_lsb(&a, &b, 2).unwrap(), 0.75);
        assert_eq!(
            fraction_within_lsb_of_neighbourhood(&a, &b, 8, 2, 1).unwrap(),
            1.0
        );
        assert!(fraction_within_lsb_of_neighbourhood(&a, &c, 8, 2, 1).unwrap() < 1.0);
        assert_eq!(
            fraction_within_lsb_of_neighbourhood(&a, &a, 8, 0, 0).unwrap(),
            1.0
        );
        assert!(fraction_within_lsb_of_neighbourhood(&a, &b, 7, 2, 1).is_err());
    }

    #[test]
    fn srgb_endpoints_and_continuity() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        approx::assert_abs_diff_eq!(linear_to_srgb(1.0), 1.0, epsilon = 1e-6);
        let below = linear_to_srgb(0.003_130_8);
        let above = linear_to_srgb(0.003_130_9);
        assert!((above - below).abs() < 1e-5);
    }

    #[test]
    fn dither_is_triangular_and_centred() {
        let n = 200_000u32;
        let samples: Vec<f32> = (0..n)
            .map(|i| dither_offset([i % 1000, i / 1000], 7))
            .collect();
        let mean = samples.iter().map(|&s| f64::from(s)).sum::<f64>() / f64::from(n);
        let variance = samples.iter().map(|&s| f64::from(s).powi(2)).sum::<f64>() / f64::from(n);
        assert!(samples.iter().all(|s| s.abs() < 1.0));
        assert!(mean.abs() < 0.01, "mean {mean}");
        // Triangular on (−1, 1) has variance 1/6.
        assert!((variance - 1.0 / 6.0).abs() < 0.005, "variance {variance}");
    }

    #[test]
    fn dithering_breaks_banding_on_a_smooth_gradient() {
        // A slow ramp over 1024 pixels spans ~4 code values: without dither each
        // value would hold for ~250 pixels; with it the longest run is short while
        // the local mean still tracks the ramp.
        let width = 1024u32;
        let codes: Vec<f32> = (0..width)
            .map(|x| quantize_srgb8([0.2 + 0.002 * x as f32 / width as f32; 3], [x, 0], 1)[0])
            .collect();
        let longest = codes
            .chunk_by(|a, b| a == b)
            .map(<[f32]>::len)
            .max()
            .unwrap();
        assert!(longest < 40, "longest run of one code value: {longest}");
    }

    #[test]
    fn tonemap_is_monotonic_and_bounded() {
        let mut last = -1.0;
        for i in 0..1000 {
            let v = tonemap_exposure([i as f32 * 0.01; 3], 3.0)[0];
            assert!(v >= last && (0.0..=1.0).contains(&v));
            last = v;
        }
    }

    #[test]
    fn agreement_counts_pixels_with_every_channel_close() {
        let a = [pack_rgba8([10.0, 20.0, 30.0]), pack_rgba8([0.0, 0.0, 0.0])];
        let b = [pack_rgba8([12.0, 18.0, 30.0]), pack_rgba8([0.0, 3.0, 0.0])];
        assert_eq!(fraction_within_lsb(&a, &b, 2).unwrap(), 0.5);
        assert_eq!(fraction_within_lsb(&a, &b, 3).unwrap(), 1.0);
        assert_eq!(fraction_within_lsb(&a, &a, 0).unwrap(), 1.0);
        assert!(fraction_within_lsb(&a, &b[..1], 0).is_err());
    }

    #[test]
    fn packing_puts_red_in_the_low_byte() {
        assert_eq!(pack_rgba8([1.0, 2.0, 3.0]).to_le_bytes(), [1, 2, 3, 255]);
    }
}
