//! `terrain`: heightfields, normal maps and horizon maps for self-shadowed terrain.
//!
//! Hoffman & Preetham (2002) shade terrain with `(N·L) · terrain_color · self_shadow · cloud_shadow`,
//! the self-shadow coming from a *horizon angle* stored in the alpha channel of the
//! normal map — one map for the sun in the east, one for the west. This crate bakes
//! those maps from a [`Heightfield`] (loaded from PNG / raw `f32`, or
//! [generated](generate::generate)), exactly and fast:
//!
//! * [`NormalMap`]: central differences over the true spacing;
//! * [`horizon`]: the horizon angle (definition and sampling documented there), by
//!   brute force or by the exact convex-hull sweep of Timonen & Westerholm (2010),
//!   east/west or `N` azimuths, with Earth curvature and a maximum distance;
//! * [`shadow`]: hard and soft (sun-disc) shadow queries and the
//!   `(N·L) · albedo · self_shadow · cloud_shadow` shading term, each with a WGSL twin in [`WGSL_MODULES`];
//! * [`tilted`]: variant (c), east/west measured in the tilted plane of the sun's
//!   daily path at a latitude;
//! * [`HorizonEncoding`]: how an angle is stored (u8, u16 unorm or f32), exactly;
//! * [`intersect`]: the first hit of a ray on the bilinear surface (exact per cell,
//!   block maxima skip empty space), for CPU ray-cast rendering;
//! * [`raycast`]: the exact ray-cast horizon over the bilinear surface (`f64`), the
//!   reference the trade-off (`cargo xtask tradeoff terrain`) measures maps against;
//! * `gpu` (default feature): horizon bakes in WGSL compute (east/west, or any azimuth
//!   with the CPU's sampling) that record into the caller's encoder;
//! * [`prelude`]: the types and bakes a typical program needs, in one `use`;
//! * [`twins`]: the shader helpers only `cargo xtask parity` calls on their own.
//!
//! Frames and units: SI, radians; heightfields row-major with `x` east and rows
//! south; normals and sun directions in east–north–up; azimuths clockwise from north.
//!
//! ```
//! use terrain::{Heightfield, HorizonOptions, Algorithm, bake_east_west};
//! // A 10 m wall 20 m east of texel 0 of a 1 m-spaced row.
//! let hf = Heightfield::from_fn(32, 1, 1.0, |x, _| if x == 20 { 10.0 } else { 0.0 })?;
//! let maps = bake_east_west(&hf, &HorizonOptions::flat(), Algorithm::HullSweep)?;
//! assert!((maps.east.angle(0, 0)? - (10.0f32 / 20.0).atan()).abs() < 1e-6);
//! # Ok::<(), terrain::TerrainError>(())
//! ```

mod encoding;
mod error;
pub mod generate;
#[cfg(feature = "gpu")]
pub mod gpu;
mod heightfield;
pub mod horizon;
pub mod horizon_stack;
#[cfg(feature = "gpu")]
pub mod horizon_texture;
pub mod intersect;
mod normal;
pub mod raycast;
pub mod shadow;
pub mod tilted;

/// The types and entry points a typical program needs: `use terrain::prelude::*;`.
///
/// ```
/// use terrain::prelude::*;
/// let hf = Heightfield::from_fn(16, 16, 30.0, |x, y| (x + y) as f32)?;
/// let normals = NormalMap::from_heightfield(&hf);
/// let maps = bake_east_west(&hf, &HorizonOptions::flat(), Algorithm::HullSweep)?;
/// let lit = shadow::self_shadow_east_west(
///     maps.east.angle(3, 3)?,
///     maps.west.angle(3, 3)?,
///     glam::Vec3::new(0.6, 0.0, 0.8),
///     shadow::SUN_ANGULAR_RADIUS,
/// );
/// assert!(lit > 0.99 && normals.normal(3, 3)?[2] > 0.9);
/// # Ok::<(), TerrainError>(())
/// ```
pub mod prelude {
    pub use crate::shadow;
    pub use crate::{
        Algorithm, AzimuthHorizonMaps, BitDepth, EastWestHorizon, Heightfield, HorizonEncoding,
        HorizonMap, HorizonOptions, NormalMap, TerrainError, bake_azimuths, bake_east_west,
        bake_horizon,
    };
}

/// Rust twins of WGSL helpers that only `cargo xtask parity` (and this crate's tests)
/// call on their own, with their `f64` references.
///
/// They are public so that the parity harness can compare each one with its WGSL
/// twin, but a program does not need them: [`shadow::soft_shadow`] and
/// [`shadow::self_shadow_east_west`] compose them, and
/// [`decode_horizon_unorm8`]/[`decode_horizon_unorm16`] decode stored texels. They
/// stay defined beside their siblings in [`shadow`] (which mirrors
/// `shaders/terrain/shadow.wgsl` function for function) and are hidden there.
pub mod twins {
    #[doc(inline)]
    pub use crate::shadow::reference::{soft_shadow_f64, sun_disc_visible_fraction_f64};
    #[doc(inline)]
    pub use crate::shadow::{decode_horizon_angle, hard_shadow, sun_disc_visible_fraction};
}

pub use encoding::{
    HorizonEncoding, decode_horizon_unorm8, decode_horizon_unorm16, encode_horizon_unorm8,
    encode_horizon_unorm16,
};
pub use error::TerrainError;
pub use heightfield::{Heightfield, MAX_SIDE, MAX_TEXELS};
pub use horizon::{
    Algorithm, AzimuthHorizonMaps, EastWestHorizon, HorizonMap, HorizonOptions, bake_azimuths,
    bake_east_west, bake_horizon, horizon_angle,
};
pub use normal::{BitDepth, NormalMap, encode_horizon_angle};

/// The crates whose types appear in this crate's public API, re-exported so that a
/// dependent names the very versions this crate was built with (no pinning by hand):
/// `glam` (vectors and matrices), `skyscape_wgsl` (the WGSL `Composer` and `Module`), and with
/// feature `gpu` `wgpu` (devices, queues, encoders).
pub use glam;
pub use skyscape_wgsl;
#[cfg(feature = "gpu")]
pub use wgpu;

/// The WGSL modules of this crate, importable as `#import terrain::<name>`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] =
    include!(concat!(env!("OUT_DIR"), "/wgsl_modules.rs"));

/// A composer that knows the common modules and every `terrain` module.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer
        .add_modules(WGSL_MODULES)
        .expect("terrain WGSL module names are unique and well formed");
    composer
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

#[cfg(test)]
mod wgsl_tests {
    #[test]
    fn every_module_composes_and_validates() {
        let composer = super::composer();
        assert_eq!(super::WGSL_MODULES.len(), 4);
        for module in super::WGSL_MODULES {
            assert!(module.name.starts_with("terrain::"));
            let source = composer.compose_module(module.name).unwrap();
            skyscape_wgsl::validate(module.name, &source).unwrap();
        }
    }

    #[test]
    fn broken_wgsl_is_caught_by_validation() {
        // The validation above can fail: a type error in a composed terrain module is reported.
        let composer = super::composer();
        let bad = "#import terrain::shadow\nfn f() -> f32 { return hard_shadow(1.0, 2u); }\n";
        let source = composer.compose("bad", bad).unwrap();
        assert!(skyscape_wgsl::validate("bad", &source).is_err());
    }
}
