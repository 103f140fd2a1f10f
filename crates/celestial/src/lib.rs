//! skyscape `celestial`: where things are in the sky for a date, time and place, and
//! how bright they are.
//!
//! * [`Instant`]: a UTC instant in 1950–2100 parsed from ISO 8601, with ΔT, Julian
//!   days and centuries in UT and TT;
//! * [`Observer`]: latitude, longitude (east positive), elevation, validated;
//! * [`Angle`]: every angle at the API is typed, so degrees/radians mix-ups do not
//!   compile;
//! * [`sidereal`]: nutation, obliquity, Greenwich and local mean/apparent sidereal
//!   time (Meeus ch. 12, 22);
//! * [`sun_position`]: the sun by NREL SPA (crate `solar-positioning`), topocentric,
//!   airless; [`refraction`] the separate Sæmundsson step to the apparent elevation;
//! * [`moon_position`]: the moon (Schlyter + parallax), topocentric, with distance,
//!   angular size and phase; [`planet_position`]: Mercury–Neptune with magnitudes;
//!   every body's `apparent` direction through the one refraction step
//!   [`apparent_direction`];
//! * [`StarCatalogue`]: the Hipparcos stars to V = 8 at their apparent places
//!   ([`astrometry`]: proper motion, parallax, aberration, precession, nutation), with
//!   illuminance, colour ([`colour`]: B−V → linear sRGB) and IAU names
//!   ([`StarCatalogue::find`]);
//! * [`moon_phase()`]: phase angle, illuminated fraction and bright limb from the sun's
//!   and moon's places (Meeus ch. 48), [`geocentric_moon_phase`] the same from an
//!   instant in one call; [`moon_disc_incidence_cosine`] the lit part of the disc per
//!   point;
//! * [`equatorial_to_horizontal`], [`illuminance_from_magnitude`] and
//!   [`moon_disc_incidence_cosine`]: formulas written once over the float type, with
//!   WGSL twins in [`WGSL_MODULES`].
//!
//! * drawing ([`draw`], [`objects`], the `gpu` module): the sun's limb-darkened disc and Mie
//!   aureole, the moon's lit sphere, stars and planets as sprites fading in by contrast
//!   against the sky, all through `atmos`' transmittance; [`light`]: the moon as a light
//!   source and the photometric scale of atmos' unit;
//! * SimGear's SGSky SGSky: the [`Sky`] facade, [`dome`] (the 12-sided dome), [`clouds`]
//!   (cloud layers) and [`visibility`] (Koschmieder and exp² fog).
//!
//! Bad input is a [`CelestialError`] naming the field and the value. [`prelude`] holds
//! the types a typical program needs; [`twins`] the drawing helpers that only
//! `cargo xtask parity` calls on their own.

pub mod angle;
pub mod astrometry;
pub mod clouds;
pub mod colour;
pub mod dome;
pub mod dome_sky;
pub mod draw;
pub mod error;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod horizontal;
pub mod light;
pub mod moon;
pub mod moon_phase;
pub mod objects;
pub mod observer;
pub mod photometry;
pub mod planets;
pub mod refraction;
pub mod scintillation;
pub mod sidereal;
pub mod sky;
pub mod stars;
pub mod sun;
pub mod time;
pub mod visibility;

pub use angle::Angle;
pub use error::{CelestialError, Result};
pub use horizontal::{Horizontal, equatorial_to_horizontal, parallactic_angle};
pub use light::{LuminanceScale, MoonLight};
pub use moon::{MoonPosition, moon_position};
pub use moon_phase::{
    EquatorialPlace, MoonPhase, geocentric_moon_phase, moon_disc_incidence_cosine, moon_phase,
};
pub use observer::Observer;
pub use photometry::{ZERO_MAGNITUDE_ILLUMINANCE_LX, illuminance_from_magnitude};
pub use planets::{Planet, PlanetPosition, planet_position};
pub use refraction::{AirConditions, apparent_direction, apparent_elevation};
pub use sky::{
    ExplicitPaint, ExplicitPlacement, ExplicitPlanet, FogModel, HorizonColours, Sky, SkyOptions,
};
pub use stars::{CatalogueStar, SkyStar, StarCatalogue};
pub use sun::{SunPosition, sun_position};
pub use time::Instant;

/// The crates whose types appear in this crate's public API, re-exported so that a
/// dependent names the very versions this crate was built with (no pinning by hand):
/// `glam` (vectors and matrices), `skyscape_wgsl` (the WGSL `Composer` and `Module`), and with
/// feature `gpu` `wgpu` (devices, queues, encoders).
pub use glam;
pub use skyscape_wgsl;
#[cfg(feature = "gpu")]
pub use wgpu;

/// The types and entry points a typical program needs: `use celestial::prelude::*;`.
/// ([`crate::Result`] is left out so that it does not shadow `std`'s.)
///
/// ```
/// use celestial::prelude::*;
/// let observer = Observer::new(Angle::from_degrees(52.0), Angle::from_degrees(5.0), 0.0)?;
/// let noon = Instant::parse("2024-06-21T11:40:00Z")?;
/// let sun = sun_position(&noon, &observer)?;
/// // Near the June solstice's noon at 52° N the sun stands about 61.4° high, due south.
/// assert!((sun.airless.elevation.degrees() - 61.4).abs() < 0.2);
/// assert!((sun.airless.azimuth.degrees() - 180.0).abs() < 5.0);
/// # Ok::<(), CelestialError>(())
/// ```
pub mod prelude {
    pub use crate::clouds::{CloudKind, CloudLayer};
    pub use crate::{
        AirConditions, Angle, CelestialError, FogModel, Horizontal, Instant, LuminanceScale,
        MoonLight, MoonPhase, MoonPosition, Observer, Planet, PlanetPosition, Sky, SkyOptions,
        SkyStar, StarCatalogue, SunPosition, apparent_elevation, moon_phase, moon_position,
        planet_position, sun_position,
    };
}

/// Rust twins of WGSL drawing helpers that only `cargo xtask parity` calls on their
/// own, and the f64 reference of the aureole.
///
/// The drawing composes them: [`draw::disc_object_radiance`] shades the sun's disc
/// with [`sun_disc_limb_factor`](twins::sun_disc_limb_factor) and the moon's with
/// [`moon_disc_lommel_seeliger`](twins::moon_disc_lommel_seeliger), the sprites are
/// splatted with [`point_sprite_weight`](twins::point_sprite_weight), and a cloud
/// layer's [`clouds::cloud_layer_radiance`] is built from
/// [`cloud_layer_distance`](twins::cloud_layer_distance),
/// [`cloud_column`](twins::cloud_column) and
/// [`cloud_optical_thickness`](twins::cloud_optical_thickness) (the texture of
/// [`cloud_density`](twins::cloud_density), over [`cloud_fbm`](twins::cloud_fbm) and
/// [`cloud_value_noise`](twins::cloud_value_noise)),
/// [`cloud_sun_scattering`](twins::cloud_sun_scattering) and
/// [`cloud_reflectance`](twins::cloud_reflectance); a program draws through those,
/// the `Sky` facade or the `gpu` pass. They stay defined in [`draw`] and [`clouds`],
/// which mirror `shaders/celestial/draw.wgsl` and `clouds.wgsl` function for
/// function, and are hidden there.
pub mod twins {
    #[doc(inline)]
    pub use crate::clouds::{
        cloud_column, cloud_density, cloud_fbm, cloud_layer_distance, cloud_optical_thickness,
        cloud_reflectance, cloud_sun_scattering, cloud_value_noise,
    };
    #[doc(inline)]
    pub use crate::draw::{
        moon_disc_lommel_seeliger, point_sprite_weight, sun_aureole_radiance_f64,
        sun_disc_limb_factor,
    };
}

/// The crate's WGSL, canonical under `shaders/celestial/`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] =
    include!(concat!(env!("OUT_DIR"), "/wgsl_modules.rs"));

/// A composer holding the common modules, atmos' modules (the drawing imports its
/// geometry, phase functions and frame camera) and the celestial ones.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = atmos::composer();
    composer
        .add_modules(WGSL_MODULES)
        .expect("celestial WGSL module names are unique and well formed");
    composer
}

/// The README's examples, compiled as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

#[cfg(test)]
mod tests {
    /// Every `#[repr(C)]` block shared with WGSL has its struct's size and offsets.
    #[test]
    fn uniform_twins_match_their_wgsl_layouts() {
        use crate::clouds::CloudLayerUniforms;
        use crate::draw::{DiscObject, PointSource};
        use crate::objects::SkyObjectsUniforms;
        let composer = super::composer();
        let wgsl = |module: &str, name: &str| {
            let source = composer.compose_module(module).unwrap();
            let parsed = skyscape_wgsl::validate(module, &source).unwrap();
            skyscape_wgsl::struct_layout(&parsed, name)
                .unwrap_or_else(|| panic!("no struct {name} in {module}"))
        };
        let twins = [
            (
                skyscape_wgsl::rust_layout!(DiscObject {
                    direction,
                    sin_radius,
                    radiance,
                    kind,
                    shading,
                    mu_centre,
                    log_transmittance,
                    padding0,
                    log_transmittance_slope,
                    padding1,
                    log_transmittance_curvature,
                    padding2,
                }),
                wgsl("celestial::draw", "DiscObject"),
            ),
            (
                skyscape_wgsl::rust_layout!(PointSource {
                    direction,
                    illuminance_lux,
                    colour,
                    background_luminance,
                    transmittance,
                    scintillation,
                }),
                wgsl("celestial::draw", "PointSource"),
            ),
            (
                skyscape_wgsl::rust_layout!(SkyObjectsUniforms {
                    camera,
                    planet_radius,
                    lux_per_unit,
                    sprite_sigma_px,
                    far_depth,
                }),
                wgsl("celestial::sky_objects", "SkyObjectsUniforms"),
            ),
            (
                skyscape_wgsl::rust_layout!(CloudLayerUniforms {
                    base_radius,
                    top_radius,
                    planet_radius,
                    curved,
                    feature_size,
                    stretch,
                    octaves,
                    seed,
                    threshold,
                    softness,
                    optical_thickness,
                    asymmetry,
                    offset,
                    half_span,
                    fog_extinction,
                    sun_direction,
                    exp2_fog,
                    sunlight,
                    core_depth,
                    skylight,
                    padding1,
                    fog_colour,
                    padding2,
                }),
                wgsl("celestial::clouds", "CloudLayerUniforms"),
            ),
        ];
        for (rust, wgsl) in twins {
            rust.check_twin_of(&wgsl).unwrap_or_else(|e| panic!("{e}"));
        }
    }

    #[test]
    fn wgsl_modules_compose_and_validate() {
        let composer = super::composer();
        assert_eq!(super::WGSL_MODULES.len(), 7);
        for module in super::WGSL_MODULES {
            assert!(module.name.starts_with("celestial::"));
            let source = composer.compose_module(module.name).unwrap();
            skyscape_wgsl::validate(module.name, &source).unwrap();
        }
    }
}
