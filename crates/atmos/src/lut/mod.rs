//! Rung 3 of the ladder: precomputed multiple scattering after Hillaire 2020 ("A
//! Scalable and Production Ready Sky and Atmosphere Rendering Technique"), with
//! Bruneton 2017's parameterisations.
//!
//! Four tables, each baked on the CPU (f32 twins here, threaded) and on the GPU
//! (`crate::gpu::luts`, one WGSL file per pass in `shaders/atmos/lut_*.wgsl`):
//!
//! | table | default size | depends on | what a texel holds |
//! |---|---|---|---|
//! | transmittance | 256 × 64, 40 log-linear steps | atmosphere | transmittance to the top of the atmosphere for (r, μ) |
//! | multiple scattering | 32 × 32 × 6 layers, 64 directions × 20 samples, orders 2…5 | atmosphere | the field of orders 1…4 arriving at (altitude, μ_s): its mean, first moment and traceless second moment (bands 0–2), per unit sun irradiance |
//! | sky view | 192 × 108, 30 samples | camera altitude, sun zenith | radiance and transmittance of the view ray for (view elevation, azimuth from the sun) |
//! | aerial perspective | 32 × 32 × 32 over 32 km, 2 steps per slice | camera frame | in-scatter and transmittance per froxel |
//!
//! The first two are *static* (bake once per atmosphere); the last two are *per
//! frame* ([`precomputed_sky::PrecomputedSky::prepare`] on the CPU, the renderer's
//! frame passes on the GPU); a pixel then costs a few lookups.
//!
//! All LUTs store `[f32; 4]` texels (rgb + 1) in row-major order (the multiple-scattering
//! table as six planar layers, the sky view and aerial perspective as two entries per
//! texel), the layout of the GPU's `array<vec4<f32>>` storage buffers: lookups filter manually (bilinear /
//! trilinear), so they work on adapters without float32 filtering (llvmpipe GL) and
//! the CPU twin reads exactly what the GPU reads.

pub mod aerial_perspective;
pub mod drop_in;
pub mod marched_sky;
pub mod multiple_scattering_lut;
pub mod multiple_scattering_moments;
pub mod parameterization;
pub mod precomputed_sky;
pub mod raymarch;
pub mod reference;
pub mod sky_irradiance;
pub mod sky_view_lut;
pub mod transmittance_lut;

pub use marched_sky::MarchedPrecomputedSky;
pub use precomputed_sky::{FrameLuts, PrecomputedSky, StaticLuts};

use crate::AtmosError;

/// The WGSL modules of this rung (`#import atmos::lut_*`), composed by
/// [`crate::composer`].
pub const WGSL_MODULES: &[skyscape_wgsl::Module] = &[
    skyscape_wgsl::Module {
        name: "atmos::lut_parameterization",
        source: include_str!("../../shaders/lut_parameterization.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_multiple_scattering_moments",
        source: include_str!("../../shaders/lut_multiple_scattering_moments.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_bindings",
        source: include_str!("../../shaders/lut_bindings.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_sampling",
        source: include_str!("../../shaders/lut_sampling.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_transmittance",
        source: include_str!("../../shaders/lut_transmittance.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_multiple_scattering",
        source: include_str!("../../shaders/lut_multiple_scattering.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_sky_view",
        source: include_str!("../../shaders/lut_sky_view.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_sky_irradiance",
        source: include_str!("../../shaders/lut_sky_irradiance.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_aerial_perspective",
        source: include_str!("../../shaders/lut_aerial_perspective.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_shading",
        source: include_str!("../../shaders/lut_shading.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::lut_render",
        source: include_str!("../../shaders/lut_render.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::aerial_perspective",
        source: include_str!("../../shaders/aerial_perspective.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::sky_pass",
        source: include_str!("../../shaders/sky_pass.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::aerial_perspective_pass",
        source: include_str!("../../shaders/aerial_perspective_pass.wgsl"),
    },
];

/// Where the precomputed rung takes the transmittance of a whole view ray (to the
/// ground or to space) for a viewer inside the atmosphere: a speed-for-accuracy choice.
///
/// Measured against the default-settings reference on 2,304 queries (viewers 0 – 50 km,
/// suns −6° … 90°; `cargo test -p atmos --test luts -- --nocapture
/// view_transmittance_against_the_reference`); see `docs/atmos-methods.md` for
/// the figures and the per-query cost of each choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ViewTransmittance {
    /// Stored in the sky-view LUT beside each texel's radiance (two entries per
    /// texel): a pixel reads one footprint for both. Coarser than the transmittance
    /// LUT just below the horizon seen from high up, where the sky view's rows are
    /// sparser.
    #[default]
    SkyViewLut,
    /// Looked up per pixel in the transmittance LUT (a ray–sphere test and one or two
    /// lookups): more accurate at the horizon, dearer per pixel; the sky-view LUT then
    /// holds radiance only (half the memory, no transmittance lookup in its bake).
    TransmittanceLut,
}

/// Sizes and sample counts of the precomputed rung.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LutSettings {
    /// Transmittance LUT size (μ, r).
    pub transmittance_size: [u32; 2],
    /// Uniform steps of the optical-depth integral per transmittance texel.
    pub transmittance_samples: u32,
    /// Multiple-scattering LUT size (μ_s, altitude).
    pub multiple_scattering_size: [u32; 2],
    /// Raymarch samples per direction in the multiple-scattering bake.
    pub multiple_scattering_samples: u32,
    /// √(directions) of the multiple-scattering bake, ≥ 2 (8 → Hillaire's 64): that
    /// many zenith samples (half below the horizon, crowding at it) × azimuths.
    pub multiple_scattering_direction_sqrt: u32,
    /// Highest scattering order in the multiple-scattering LUT (≥ 2): one bake pass per
    /// order from 2 on (host side only: the passes are the same shader).
    pub multiple_scattering_orders: u32,
    /// Sky-view LUT size (azimuth, elevation); the height must be even (the horizon
    /// lies between the two middle rows).
    pub sky_view_size: [u32; 2],
    /// Raymarch samples per sky-view texel (quadratically spaced).
    pub sky_view_samples: u32,
    /// Where a view ray's transmittance comes from (sky-view LUT or transmittance LUT).
    pub view_transmittance: ViewTransmittance,
    /// Aerial-perspective froxels (screen x, screen y, depth slices).
    pub aerial_perspective_size: [u32; 3],
    /// Depth covered by the aerial-perspective volume (m).
    pub aerial_perspective_range: f32,
    /// Raymarch steps per depth slice of the aerial-perspective volume.
    pub aerial_perspective_steps_per_slice: u32,
    /// Raymarch samples of the per-pixel fallback (viewer above the atmosphere, or a
    /// finite segment beyond the aerial-perspective range).
    pub pixel_samples: u32,
}

impl Default for LutSettings {
    fn default() -> Self {
        Self {
            transmittance_size: [256, 64],
            transmittance_samples: 40,
            // 128 μ_s texels (Hillaire: 32): across the terminator the multiple
            // scattering falls by orders of magnitude within a few degrees, and 32
            // texels (3.7° apart at the horizon) read it too bright in twilight:
            // against the path tracer, twilight mean 17.8 % with 32, 6.2 % with 64,
            // 2.2 % with 128 (`precomputed_against_the_path_tracer` in
            // tests/path_tracer.rs). A static bake: no per-frame cost.
            multiple_scattering_size: [128, 32],
            multiple_scattering_samples: 20,
            multiple_scattering_direction_sqrt: 8,
            multiple_scattering_orders: 5,
            sky_view_size: [192, 108],
            sky_view_samples: 30,
            view_transmittance: ViewTransmittance::SkyViewLut,
            aerial_perspective_size: [32, 32, 32],
            aerial_perspective_range: 32_000.0,
            aerial_perspective_steps_per_slice: 2,
            // 32 read 0.25 % (day mean) worse for viewers at 100 km and above, whose
            // rays are marched from the top of the atmosphere per pixel.
            pixel_samples: 64,
        }
    }
}

impl LutSettings {
    /// Small tables for tests on software adapters (debug builds, lavapipe).
    pub fn small() -> Self {
        Self {
            transmittance_size: [64, 16],
            transmittance_samples: 40,
            multiple_scattering_size: [16, 16],
            multiple_scattering_samples: 20,
            multiple_scattering_direction_sqrt: 8,
            multiple_scattering_orders: 5,
            sky_view_size: [48, 28],
            sky_view_samples: 30,
            view_transmittance: ViewTransmittance::SkyViewLut,
            aerial_perspective_size: [8, 8, 16],
            aerial_perspective_range: 32_000.0,
            aerial_perspective_steps_per_slice: 2,
            pixel_samples: 32,
        }
    }

    /// Checks every size and count; the error names the field.
    pub fn validate(&self) -> Result<(), AtmosError> {
        let invalid = |field: &str, value: f64, reason: &'static str| {
            Err(AtmosError::InvalidLutSettings {
                field: field.to_owned(),
                value,
                reason,
            })
        };
        // Each table stays far below the 128 MiB storage-binding minimum of wgpu.
        const MAX_SIDE: u32 = 4096;
        let sides: [(&str, u32); 9] = [
            ("transmittance_size[0]", self.transmittance_size[0]),
            ("transmittance_size[1]", self.transmittance_size[1]),
            (
                "multiple_scattering_size[0]",
                self.multiple_scattering_size[0],
            ),
            (
                "multiple_scattering_size[1]",
                self.multiple_scattering_size[1],
            ),
            ("sky_view_size[0]", self.sky_view_size[0]),
            ("sky_view_size[1]", self.sky_view_size[1]),
            (
                "aerial_perspective_size[0]",
                self.aerial_perspective_size[0],
            ),
            (
                "aerial_perspective_size[1]",
                self.aerial_perspective_size[1],
            ),
            (
                "aerial_perspective_size[2]",
                self.aerial_perspective_size[2],
            ),
        ];
        for (field, side) in sides {
            if !(2..=MAX_SIDE).contains(&side) {
                return invalid(field, f64::from(side), "must be in 2..=4096 texels");
            }
        }
        if !self.sky_view_size[1].is_multiple_of(2) {
            return invalid(
                "sky_view_size[1]",
                f64::from(self.sky_view_size[1]),
                "must be even (sky and ground rows meet at the horizon)",
            );
        }
        let ap = self.aerial_perspective_size;
        if u64::from(ap[0]) * u64::from(ap[1]) * u64::from(ap[2]) > 1 << 22 {
            return invalid(
                "aerial_perspective_size",
                f64::from(ap[0]) * f64::from(ap[1]) * f64::from(ap[2]),
                "must hold at most 2^22 froxels",
            );
        }
        let counts: [(&str, u32); 6] = [
            ("transmittance_samples", self.transmittance_samples),
            (
                "multiple_scattering_samples",
                self.multiple_scattering_samples,
            ),
            (
                "multiple_scattering_direction_sqrt",
                self.multiple_scattering_direction_sqrt,
            ),
            ("sky_view_samples", self.sky_view_samples),
            (
                "aerial_perspective_steps_per_slice",
                self.aerial_perspective_steps_per_slice,
            ),
            ("pixel_samples", self.pixel_samples),
        ];
        for (field, count) in counts {
            if !(1..=1024).contains(&count) {
                return invalid(field, f64::from(count), "must be in 1..=1024 samples");
            }
        }
        if self.multiple_scattering_direction_sqrt < 2 {
            return invalid(
                "multiple_scattering_direction_sqrt",
                f64::from(self.multiple_scattering_direction_sqrt),
                "must be ≥ 2 (the zenith samples are split between the ground and the sky)",
            );
        }
        if !(2..=16).contains(&self.multiple_scattering_orders) {
            return invalid(
                "multiple_scattering_orders",
                f64::from(self.multiple_scattering_orders),
                "must be in 2..=16 scattering orders",
            );
        }
        let range = self.aerial_perspective_range;
        if !(range.is_finite() && range > 0.0) {
            return invalid(
                "aerial_perspective_range",
                f64::from(range),
                "must be a finite distance > 0 m",
            );
        }
        Ok(())
    }

    /// Validates and converts to the uniform block of `shaders/atmos/lut_sampling.wgsl`.
    pub fn to_uniforms(&self) -> Result<LutSettingsUniform, AtmosError> {
        self.validate()?;
        Ok(LutSettingsUniform {
            transmittance_width: self.transmittance_size[0],
            transmittance_height: self.transmittance_size[1],
            transmittance_samples: self.transmittance_samples,
            multiple_scattering_width: self.multiple_scattering_size[0],
            multiple_scattering_height: self.multiple_scattering_size[1],
            multiple_scattering_samples: self.multiple_scattering_samples,
            multiple_scattering_direction_sqrt: self.multiple_scattering_direction_sqrt,
            sky_view_width: self.sky_view_size[0],
            sky_view_height: self.sky_view_size[1],
            sky_view_samples: self.sky_view_samples,
            sky_view_transmittance: u32::from(
                self.view_transmittance == ViewTransmittance::SkyViewLut,
            ),
            aerial_perspective_width: self.aerial_perspective_size[0],
            aerial_perspective_height: self.aerial_perspective_size[1],
            aerial_perspective_depth: self.aerial_perspective_size[2],
            aerial_perspective_steps_per_slice: self.aerial_perspective_steps_per_slice,
            aerial_perspective_range: self.aerial_perspective_range,
            pixel_samples: self.pixel_samples,
        })
    }
}

/// The settings as WGSL `LutSettings` (68 bytes, scalars only).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs)]
pub struct LutSettingsUniform {
    pub transmittance_width: u32,
    pub transmittance_height: u32,
    pub transmittance_samples: u32,
    pub multiple_scattering_width: u32,
    pub multiple_scattering_height: u32,
    pub multiple_scattering_samples: u32,
    pub multiple_scattering_direction_sqrt: u32,
    pub sky_view_width: u32,
    pub sky_view_height: u32,
    pub sky_view_samples: u32,
    /// 1: the sky-view LUT stores each texel's transmittance
    /// ([`ViewTransmittance::SkyViewLut`]); 0: radiance only.
    pub sky_view_transmittance: u32,
    pub aerial_perspective_width: u32,
    pub aerial_perspective_height: u32,
    pub aerial_perspective_depth: u32,
    pub aerial_perspective_steps_per_slice: u32,
    pub aerial_perspective_range: f32,
    pub pixel_samples: u32,
}

impl LutSettingsUniform {
    /// Entries per sky-view texel: radiance at `entries · i`, and with
    /// [`ViewTransmittance::SkyViewLut`] the transmittance at `entries · i + 1`
    /// (i = x + width · y). Twin: `sky_view_entries_per_texel` in `lut_sampling.wgsl`.
    pub fn sky_view_entries_per_texel(&self) -> u32 {
        1 + self.sky_view_transmittance
    }
}

/// A 2D table of `[f32; 4]` texels, row-major (`x + width · y`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Lut2d {
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
    /// `width · height` texels.
    pub texels: Vec<[f32; 4]>,
}

impl Lut2d {
    /// The texel at column `x`, row `y`.
    pub fn texel(&self, x: u32, y: u32) -> [f32; 4] {
        self.texels[(x + self.width * y) as usize]
    }

    /// Bilinear interpolation over a footprint (same arithmetic as the WGSL
    /// `bilinear_blend`).
    pub fn blend(&self, f: &parameterization::BilinearFootprint) -> [f32; 3] {
        blend_footprint(&self.texels, f, |x, y| (x + self.width * y) as usize)
    }

    /// All texels flattened (`[r, g, b, 1]` each), as uploaded to the GPU.
    pub fn as_floats(&self) -> &[f32] {
        bytemuck::cast_slice(&self.texels)
    }
}

/// Bilinear interpolation over a footprint of a table whose texel (x, y) is entry
/// `index(x, y)` (planar layers, interleaved entries): the four reads and
/// [`bilinear_blend`] per channel.
pub fn blend_footprint(
    texels: &[[f32; 4]],
    f: &parameterization::BilinearFootprint,
    index: impl Fn(u32, u32) -> usize,
) -> [f32; 3] {
    let a = texels[index(f.x0, f.y0)];
    let b = texels[index(f.x1, f.y0)];
    let c = texels[index(f.x0, f.y1)];
    let d = texels[index(f.x1, f.y1)];
    std::array::from_fn(|i| bilinear_blend(a[i], b[i], c[i], d[i], f.fx, f.fy))
}

/// (1 − fy)·((1 − fx)·a + fx·b) + fy·((1 − fx)·c + fx·d): twin of WGSL `mix(mix(a, b,
/// fx), mix(c, d, fx), fy)` written out (WGSL's mix is x·(1 − t) + y·t).
pub fn bilinear_blend(a: f32, b: f32, c: f32, d: f32, fx: f32, fy: f32) -> f32 {
    let top = a * (1.0 - fx) + b * fx;
    let bottom = c * (1.0 - fx) + d * fx;
    top * (1.0 - fy) + bottom * fy
}

/// Evaluates `texel(index)` for `0..count` on all cores (`std::thread::scope`, one
/// contiguous chunk per thread).
pub fn fill_parallel<T, F>(count: usize, texel: F) -> Vec<T>
where
    T: Copy + Default + Send,
    F: Fn(usize) -> T + Sync,
{
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(count.max(1));
    let mut out = vec![T::default(); count];
    if threads <= 1 || count < 64 {
        for (i, t) in out.iter_mut().enumerate() {
            *t = texel(i);
        }
        return out;
    }
    let chunk = count.div_ceil(threads);
    std::thread::scope(|scope| {
        for (c, slice) in out.chunks_mut(chunk).enumerate() {
            let texel = &texel;
            scope.spawn(move || {
                for (i, t) in slice.iter_mut().enumerate() {
                    *t = texel(c * chunk + i);
                }
            });
        }
    });
    out
}
