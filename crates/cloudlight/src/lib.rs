//! `cloudlight`: lighting of cloud volumes, once in Rust and once in WGSL.
//!
//! Implemented so far (each function has a same-named WGSL twin under
//! `shaders/cloudlight/`, embedded as [`WGSL_MODULES`], and a case in
//! `cargo xtask parity`):
//!
//! * [`slice::slice_attenuation`]: seed 002's slice-by-slice light attenuation step;
//! * [`jitter::bayer_jitter_4x4`]: seed 003's ordered (Bayer) ray-march jitter.
//!
//! [`CloudVolume`] holds a density grid placed in metres (cloudsim's axis order) with its
//! extinction per unit density; [`reference`](mod@reference) integrates its trilinear density exactly along
//! a ray (f64 optical depth and transmittance); [`propagate`](mod@propagate) is seed 002's
//! slice propagation (physical and faithful modes) written once over the float type, with
//! its WGSL pass [`gpu::SlicePropagation`] (feature `gpu`).
//!
//! ```
//! // A fully dense slice passing 60 % of the light, after one that passed 80 %.
//! let light = cloudlight::slice::slice_attenuation(0.8, 1.0, 0.6);
//! assert!((light - 0.48).abs() < 1e-6);
//! ```

pub mod cone;
pub mod jitter;
pub mod propagate;
pub mod reference;
pub mod slice;
pub mod volume;

#[cfg(feature = "gpu")]
pub mod gpu;

pub use volume::{CloudVolume, VolumeError};

/// The WGSL modules of this crate, importable as `#import cloudlight::<name>`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] = &[
    skyscape_wgsl::Module {
        name: "cloudlight::slice_attenuation",
        source: include_str!("../shaders/slice_attenuation.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "cloudlight::jitter",
        source: include_str!("../shaders/jitter.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "cloudlight::cone",
        source: include_str!("../shaders/cone.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "cloudlight::slice_propagation",
        source: include_str!("../shaders/slice_propagation.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "cloudlight::slice_propagation_pass",
        source: include_str!("../shaders/slice_propagation_pass.wgsl"),
    },
];

/// A composer with the common, `atmos` and `cloudlight` modules.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = atmos::composer();
    composer
        .add_modules(WGSL_MODULES)
        .expect("cloudlight WGSL module names are unique and well formed");
    composer
}

#[cfg(test)]
mod wgsl_tests {
    /// The embedded list is the folder `build.rs` validates: no file left out, none extra.
    #[test]
    fn wgsl_modules_are_the_files_build_rs_validates() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let mut listed: Vec<_> = super::WGSL_MODULES.iter().map(|m| m.name).collect();
        listed.sort_unstable();
        assert_eq!(
            listed,
            skyscape_wgsl::build::module_names("cloudlight", &folder).unwrap()
        );
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
