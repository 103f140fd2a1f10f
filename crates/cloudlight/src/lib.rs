//! `cloudlight`: the light that reaches the inside of a cloud volume from the sun, once in
//! Rust and once in WGSL. What exists (the crate README is a short guide to choosing;
//! `docs/tradeoffs/cloudlight.md` the measured trade):
//!
//! * [`CloudVolume`]: an f32 density grid placed in metres (cloudsim's axis order, x
//!   fastest) with its extinction per unit density σ_t (1/m); typed errors name the field.
//! * [`reference`](mod@reference): the exact f64 optical depth and transmittance of the
//!   volume's trilinear density along a ray (Simpson on each cubic piece: no
//!   discretisation error); single scattering of a directional sun with the exact light
//!   path at every point of an adaptive view quadrature
//!   ([`reference::single_scattering`]); every order by an unbiased Monte Carlo path
//!   tracer (delta tracking, phase sampling, next-event estimation, standard errors:
//!   [`reference::path_tracer`]), all validated on closed forms
//!   (`tests/reference_closed_forms.rs`). Everything else is measured against it.
//! * [`propagate`](mod@propagate): Dobashi et al. 2000's slice propagation, light at every cell in one
//!   sweep of slices toward the sun — physical mode (Beer–Lambert over the true spacing,
//!   the optical depth resampled by a clamped Catmull–Rom or bilinearly) and faithful mode
//!   (Dobashi et al. 2000's `1 − (1 − r)·ρ̄`, 5-tap smoothing, whole-texel shifts). Written once over
//!   the float type: `propagate::<f64>` is the reference, `propagate::<f32>` the twin of the
//!   WGSL pass [`gpu::SlicePropagation`] (feature `gpu`, on by default; bring your own
//!   device).
//! * [`cone`]: Schneider's (GPU Pro 7) light samples toward the sun (6 cone + 1 far, raw or as a
//!   partitioned quadrature of the path), the full light march, Beer–Lambert, the powder
//!   term, dual-lobe Henyey–Greenstein on `atmos`' lobe. The per-sample functions have
//!   WGSL twins (`shaders/cloudlight/cone.wgsl`); no GPU pass samples a volume with them
//!   yet.
//! * [`billboard`]: Dobashi et al. 2000's billboards, the volume's dense cells as soft splats lit by
//!   the propagation, sorted back to front; a CPU rasteriser twin of the GPU pass
//!   [`gpu::billboard::BillboardPass`].
//! * [`shadow_map`](mod@shadow_map): the ground's cloud shadow map (Hoffman and Preetham's
//!   `clouds_shadow`), the sun's transmittance through any [`DensityField`] from every
//!   texel of a ground grid, at any sun elevation: the march written once over the float
//!   type (f32: the twin of the GPU pass [`gpu::ShadowMapPass`], an R32Float texture) and
//!   the exact f64 map of a volume.
//! * [`shell_shadow`](mod@shell_shadow): the same map over a procedural [`CloudShell`]
//!   (its density evaluated per sample), twin of the GPU pass
//!   [`gpu::ShellShadowMapPass`] (a storage buffer), equal bit for bit to the generic
//!   march on the shell.
//! * [`shell`](mod@shell) and [`noise`]: Schneider's (GPU Pro 7) procedural cloud shell about the
//!   planet ([`CloudShell`], a [`DensityField`]): tileable Perlin, Worley and
//!   Perlin–Worley noise, a procedural or user weather map, height profiles per cloud
//!   type, Schneider's coverage remap and detail erosion, the ray's spans from `atmos`'
//!   ray–sphere roots, the horizon fade; WGSL twins (`noise.wgsl`, `shell.wgsl`), the GPU
//!   bake of the noise into 128³ and 32³ textures ([`gpu::NoiseBake`]) and the density
//!   over the baked textures ([`shell::BakedShell`]).
//! * [`march`](mod@march): Schneider's (GPU Pro 7) view ray-march through any [`DensityField`] (a
//!   volume or the shell), written once over the float type: jittered steps (Bayer,
//!   interleaved gradient noise), the 6 + 1 cone or a full light march at every sample,
//!   dual-lobe Henyey–Greenstein octaves, powder (optional, not physical), ambient light,
//!   Hillaire's energy-conserving step; sun and sky light and aerial perspective from
//!   `atmos`; the GPU passes [`gpu::MarchPass`] (a volume) and [`gpu::MarchShellPass`]
//!   (the procedural shell), whose twin is `march::render_image::<f32>`.
//! * [`union::UnionField`]: two density fields (a volume and the shell, each in its own
//!   frame and σ_t) as one, so one march interleaves them and lights each through both;
//!   `render`'s `cloud_overlap` test measures its two-cloud composite against it.
//! * [`slice::slice_attenuation`] (Dobashi et al. 2000's per-texel attenuation) and
//!   [`jitter::bayer_jitter_4x4`] (Schneider's (GPU Pro 7) ordered march jitter).
//!
//! Every WGSL function with a Rust twin is a case of `cargo xtask parity`; the WGSL is
//! embedded as [`WGSL_MODULES`] (`#import cloudlight::<name>`) and validated with naga at
//! build time.
//!
//! What each method costs and how wrong it is: `cargo xtask tradeoff cloudlight`
//! (`docs/tradeoffs/cloudlight.md`).
//!
//! ```
//! use cloudlight::CloudVolume;
//! use cloudlight::propagate::{SliceMode, SlicePlan, propagate};
//!
//! // A 4×4×4 cube of 50 m cells, density 1, σ_t 0.01 /m, lit from straight above.
//! let volume = CloudVolume::new([4, 4, 4], [0.0, 0.0, 1000.0], 50.0, 0.01, vec![1.0; 64])?;
//! let plan = SlicePlan::new(&volume, [0.0, 0.0, 1.0], SliceMode::Physical)?;
//! let light = propagate::<f32>(&volume, &plan)?;
//! // The bottom centres are 175 m deep: exp(−0.01 · 175).
//! assert!((light[0] - (-1.75f32).exp()).abs() < 1e-6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod billboard;
pub mod cone;
pub mod density;
pub mod jitter;
pub mod march;
pub mod noise;
pub mod propagate;
pub mod reference;
pub mod shadow_map;
pub mod shell;
pub mod shell_shadow;
pub mod slice;
pub mod union;
pub mod volume;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use density::{DensityField, RaySpans};
pub use shell::{CloudShell, ShellError, ShellSettings};
pub use volume::{CloudVolume, VolumeError};

/// The crates whose types appear in this crate's public API, re-exported so that a
/// dependent names the very versions this crate was built with (no pinning by hand):
/// `glam` (vectors and matrices), `skyscape_wgsl` (the WGSL `Composer` and `Module`), and with
/// feature `gpu` `wgpu` (devices, queues, encoders).
pub use glam;
pub use skyscape_wgsl;
#[cfg(feature = "gpu")]
pub use wgpu;

/// What a typical user needs: the volume, the slice propagation (reference and twin)
/// and its settings, the cone and march helpers.
///
/// ```
/// use cloudlight::prelude::*;
/// // A 4³ block of unit density, 25 m cells, lit from straight above.
/// let volume = CloudVolume::new([4, 4, 4], [0.0; 3], 25.0, 0.02, vec![1.0; 64]).unwrap();
/// let light = propagate_f64(&volume, [0.0, 0.0, 1.0], SliceMode::Physical).unwrap();
/// assert_eq!(light.len(), 64);
/// ```
pub mod prelude {
    pub use crate::cone::{ConeError, ConeSettings, FullMarchSettings, LightRay};
    pub use crate::cone::{
        ConeWeights, beer_lambert, box_exit_distance, cone_optical_depth, cone_sample,
        dual_lobe_henyey_greenstein, march_optical_depth, powder,
    };
    #[cfg(feature = "gpu")]
    pub use crate::gpu::ShadowMapPass;
    #[cfg(feature = "gpu")]
    pub use crate::gpu::SlicePropagation;
    pub use crate::propagate::{
        Resampling, SliceError, SliceMode, SlicePlan, propagate, propagate_f32, propagate_f64,
    };
    pub use crate::shadow_map::{
        ShadowGrid, ShadowMapError, ShadowMapPlan, shadow_map, shadow_map_reference,
    };
    pub use crate::shell::{
        CloudShell, ProceduralWeather, ShellError, ShellSettings, WeatherGrid, WeatherMap,
    };
    pub use crate::volume::{CloudVolume, VolumeError};
}

/// The WGSL modules of this crate, importable as `#import cloudlight::<name>`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] =
    include!(concat!(env!("OUT_DIR"), "/wgsl_modules.rs"));

/// A composer with the common, `atmos` and `cloudlight` modules.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = atmos::composer();
    composer
        .add_modules(WGSL_MODULES)
        .expect("cloudlight WGSL module names are unique and well formed");
    composer
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

#[cfg(test)]
mod wgsl_tests {
    /// Each pass composed as it runs, its `cloudlight::density_source` bound to its
    /// field's module, validates (on its own each composes with the empty field).
    #[test]
    fn every_pass_validates_over_its_density_source() {
        let composer = super::composer();
        for (entry, source) in [
            ("cloudlight::march_pass", "cloudlight::density_grid"),
            ("cloudlight::march_shell_pass", "cloudlight::density_shell"),
            ("cloudlight::shadow_map_pass", "cloudlight::density_grid"),
            (
                "cloudlight::shell_shadow_map_pass",
                "cloudlight::density_shell",
            ),
        ] {
            let wgsl = composer
                .compose_module_bound(entry, &[("cloudlight::density_source", source)])
                .unwrap();
            assert!(
                !wgsl.contains("begin cloudlight::density_source"),
                "{entry}"
            );
            skyscape_wgsl::validate(entry, &wgsl).unwrap();
        }
    }

    #[test]
    fn every_module_composes_and_validates() {
        let composer = super::composer();
        for module in super::WGSL_MODULES {
            let source = composer.compose_module(module.name).unwrap();
            skyscape_wgsl::validate(module.name, &source).unwrap();
        }
    }
}
