//! `atmos`: atmospheric scattering math, once in Rust and once in WGSL.
//!
//! Every public function here has a WGSL twin of the same name, arguments and units in
//! `shaders/atmos/` (embedded as [`WGSL_MODULES`]); [`reference`](mod@reference) holds f64 versions
//! used as ground truth by `cargo xtask parity`. Conventions (SI units, `r`/`mu`
//! naming) are in `docs/architecture.md`.
//!
//! [`prelude`] holds the types a typical program needs (the atmosphere, the rungs of
//! the ladder, the camera, and with feature `gpu` the renderers); [`twins`] the
//! helpers that only `cargo xtask parity` and the tests call on their own.
//!
//! ```
//! use atmos::phase::{henyey_greenstein_phase, rayleigh_phase};
//! // Forward scattering by haze dominates the Rayleigh lobe near the sun.
//! assert!(henyey_greenstein_phase(1.0, 0.8) > 10.0 * rayleigh_phase(1.0));
//! ```

pub mod atmosphere;
pub mod closed_form;
pub mod closed_form_sky;
pub mod dome;
pub mod frame;
pub mod geometry;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod ground_irradiance;
pub mod ladder;
pub mod lut;
pub mod optical_depth;
pub mod phase;
pub mod real;
pub mod reference;
pub mod single_scattering;
pub mod transmittance;
pub mod view;

pub use atmosphere::{AtmosError, Atmosphere, AtmosphereParameters, GpuError, SUN_ANGULAR_RADIUS};
pub use ladder::{SkyModel, SkyQuery, SkySample};
pub use skyscape_wgsl::common::PI;

/// The crates whose types appear in this crate's public API, re-exported so that a
/// dependent names the very versions this crate was built with (no pinning by hand):
/// `glam` (vectors and matrices), `skyscape_wgsl` (the WGSL `Composer` and `Module`), and with
/// feature `gpu` `wgpu` (devices, queues, encoders).
pub use glam;
pub use skyscape_wgsl;
#[cfg(feature = "gpu")]
pub use wgpu;

/// The types a typical program needs: `use atmos::prelude::*;`.
///
/// ```
/// use atmos::prelude::*;
/// let earth = Atmosphere::earth();
/// let sky = ClosedFormSky::new(&earth)?; // any rung implements SkyModel
/// let viewer = glam::DVec3::new(0.0, 0.0, earth.planet_radius + 2.0);
/// let sun = glam::DVec3::new(0.6, 0.0, 0.8);
/// let query = SkyQuery::new(earth.planet_radius, viewer, glam::DVec3::Z, sun)?;
/// let zenith: SkySample = sky.evaluate(&query);
/// assert!(zenith.radiance[2] > zenith.radiance[0]); // a blue sky
/// # Ok::<(), AtmosError>(())
/// ```
pub mod prelude {
    pub use crate::closed_form_sky::ClosedFormSky;
    pub use crate::dome::{DomeInterpolated, DomeResolution};
    pub use crate::frame::{FrameCamera, LocalFrame};
    #[cfg(feature = "gpu")]
    pub use crate::gpu::{
        AtmosphereLuts, ClosedFormRenderer, FrameOutput, PrecomputedRenderer,
        SingleScatteringRenderer, SkyPass, SkyPassDescriptor,
    };
    pub use crate::lut::PrecomputedSky;
    pub use crate::reference::{ReferenceSettings, ReferenceSky};
    pub use crate::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
    pub use crate::{
        AtmosError, Atmosphere, AtmosphereParameters, GpuError, SUN_ANGULAR_RADIUS, SkyModel,
        SkyQuery, SkySample,
    };
}

/// Rust twins of WGSL helpers that only `cargo xtask parity` and the tests call on
/// their own.
///
/// Each is a step of a public model (the density profile and the optical lengths of
/// the single-scattering march, one ray-march step of the LUT bakes, the
/// multiple-scattering moments' per-direction terms, the dome's row placement, the
/// drop-in camera's projection), public so that the parity harness can compare it with
/// its WGSL twin; a program goes through the models instead ([`SkyModel`], the LUT
/// bakes and lookups, the `gpu` renderers). The generic ones are also the f64
/// references (instantiated at f64, re-exported in [`reference`](mod@reference) and
/// [`lut::reference`]). They stay defined beside their siblings, in the files that
/// mirror their WGSL modules function for function, and are hidden there.
pub mod twins {
    #[doc(inline)]
    pub use crate::atmosphere::{exponential_density, tent_density};
    #[doc(inline)]
    pub use crate::dome::{dome_horizon_mu, dome_row_coordinate, dome_row_mu};
    #[doc(inline)]
    pub use crate::lut::drop_in::frame_screen_position;
    #[doc(inline)]
    pub use crate::lut::multiple_scattering_moments::{
        direction_zenith_sample, multiple_scattering_ground_irradiance,
        multiple_scattering_ground_irradiance_channel, scattered_multiple_scattering,
        scattered_multiple_scattering_channel, sun_frame_direction,
    };
    #[doc(inline)]
    pub use crate::lut::raymarch::{
        integrate_scattering_step, point_along_ray, radius_along_ray, ray_segment_in_atmosphere,
        scattering_step_fraction,
    };
    #[doc(inline)]
    pub use crate::lut::transmittance_lut::exponential_step_integral;
    #[doc(inline)]
    pub use crate::single_scattering::{
        density_profile, extinction_from_densities, light_path_transmittance,
        lowest_point_distance, mean_transmittance_over_segment, optical_lengths,
        ray_sample_distance, single_scattering_inside,
    };
}

/// The WGSL modules of this crate, importable as `#import atmos::<name>`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] = &[
    skyscape_wgsl::Module {
        name: "atmos::atmosphere",
        source: include_str!("../shaders/atmosphere.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::phase",
        source: include_str!("../shaders/phase.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::geometry",
        source: include_str!("../shaders/geometry.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::optical_depth",
        source: include_str!("../shaders/optical_depth.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::transmittance",
        source: include_str!("../shaders/transmittance.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::closed_form_sky",
        source: include_str!("../shaders/closed_form_sky.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::dome",
        source: include_str!("../shaders/dome.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::render_closed_form",
        source: include_str!("../shaders/render_closed_form.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::frame",
        source: include_str!("../shaders/frame.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::closed_form",
        source: include_str!("../shaders/closed_form.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "atmos::single_scattering",
        source: include_str!("../shaders/single_scattering.wgsl"),
    },
];

/// A composer that knows the common modules and every `atmos` module.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer
        .add_modules(WGSL_MODULES)
        .expect("atmos WGSL module names are unique and well formed");
    composer
        .add_modules(lut::WGSL_MODULES)
        .expect("atmos LUT WGSL module names are unique and well formed");
    composer
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

#[cfg(test)]
mod wgsl_tests {
    /// The embedded list is the folder `build.rs` validates: no file left out, none extra.
    #[test]
    fn wgsl_modules_are_the_files_build_rs_validates() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let mut listed: Vec<_> = super::WGSL_MODULES
            .iter()
            .chain(super::lut::WGSL_MODULES)
            .map(|m| m.name)
            .collect();
        listed.sort_unstable();
        assert_eq!(
            listed,
            skyscape_wgsl::build::module_names("atmos", &folder).unwrap()
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

    /// Every `#[repr(C)]` uniform twin has the size and the field offsets of its WGSL
    /// struct (a field added, removed or reordered on one side only would shift the
    /// data the GPU reads).
    #[test]
    fn uniform_twins_match_their_wgsl_layouts() {
        use crate::AtmosphereParameters;
        use crate::closed_form_sky::ClosedFormSkyParameters;
        use crate::frame::FrameCamera;
        use crate::lut::LutSettingsUniform;
        let composer = super::composer();
        let wgsl = |module: &str, name: &str| {
            let source = composer.compose_module(module).unwrap();
            let parsed = skyscape_wgsl::validate(module, &source).unwrap();
            skyscape_wgsl::struct_layout(&parsed, name)
                .unwrap_or_else(|| panic!("no struct {name} in {module}"))
        };
        let twins = [
            (
                skyscape_wgsl::rust_layout!(AtmosphereParameters {
                    rayleigh_scattering,
                    rayleigh_scale_height,
                    mie_scattering,
                    mie_scale_height,
                    mie_extinction,
                    mie_g,
                    ozone_absorption,
                    ozone_center_altitude,
                    ground_albedo,
                    ozone_half_width,
                    sun_irradiance,
                    sun_angular_radius,
                    planet_radius,
                    top_radius,
                    padding,
                }),
                wgsl("atmos::atmosphere", "AtmosphereParameters"),
            ),
            (
                skyscape_wgsl::rust_layout!(LutSettingsUniform {
                    transmittance_width,
                    transmittance_height,
                    transmittance_samples,
                    multiple_scattering_width,
                    multiple_scattering_height,
                    multiple_scattering_samples,
                    multiple_scattering_direction_sqrt,
                    sky_view_width,
                    sky_view_height,
                    sky_view_samples,
                    sky_view_transmittance,
                    aerial_perspective_width,
                    aerial_perspective_height,
                    aerial_perspective_depth,
                    aerial_perspective_steps_per_slice,
                    aerial_perspective_range,
                    pixel_samples,
                }),
                wgsl("atmos::lut_bindings", "LutSettings"),
            ),
            (
                skyscape_wgsl::rust_layout!(FrameCamera {
                    position,
                    width,
                    right,
                    height,
                    up,
                    tan_half_fov_y,
                    forward,
                    max_distance,
                    sun,
                    padding,
                }),
                wgsl("atmos::frame", "FrameCamera"),
            ),
            (
                skyscape_wgsl::rust_layout!(ClosedFormSkyParameters {
                    beta_rayleigh,
                    mie_g,
                    beta_mie,
                    planet_radius,
                    sun_irradiance,
                    shell_radius,
                }),
                wgsl("atmos::closed_form_sky", "ClosedFormSkyParameters"),
            ),
        ];
        for (rust, wgsl) in twins {
            rust.check_twin_of(&wgsl).unwrap_or_else(|e| panic!("{e}"));
        }
    }
}
