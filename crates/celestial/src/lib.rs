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
//!   angular size and phase; [`planet_position`]: Mercury–Saturn with magnitudes;
//! * [`StarCatalogue`]: the Hipparcos stars to V = 8 precessed to the date, with
//!   illuminance and colour ([`colour`]: B−V → linear sRGB);
//! * [`moon_phase()`]: phase angle, illuminated fraction and bright limb from the sun's
//!   and moon's places (Meeus ch. 48); [`moon_disc_incidence_cosine`] the lit part of
//!   the disc per point;
//! * [`equatorial_to_horizontal`], [`illuminance_from_magnitude`] and
//!   [`moon_disc_incidence_cosine`]: formulas written once over the float type, with
//!   WGSL twins in [`WGSL_MODULES`].
//!
//! Bad input is a [`CelestialError`] naming the field and the value.

pub mod angle;
pub mod clouds;
pub mod colour;
pub mod dome;
pub mod draw;
pub mod error;
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
pub use moon_phase::{EquatorialPlace, MoonPhase, moon_disc_incidence_cosine, moon_phase};
pub use observer::Observer;
pub use photometry::{ZERO_MAGNITUDE_ILLUMINANCE_LX, illuminance_from_magnitude};
pub use planets::{Planet, PlanetPosition, planet_position};
pub use refraction::{AirConditions, apparent_elevation};
pub use sky::{FogModel, Sky, SkyOptions};
pub use stars::{SkyStar, StarCatalogue};
pub use sun::{SunPosition, sun_position};
pub use time::Instant;

/// The crate's WGSL, canonical under `shaders/celestial/`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] = &[
    skyscape_wgsl::Module {
        name: "celestial::coordinates",
        source: include_str!("../shaders/coordinates.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "celestial::moon",
        source: include_str!("../shaders/moon.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "celestial::draw",
        source: include_str!("../shaders/draw.wgsl"),
    },
    skyscape_wgsl::Module {
        name: "celestial::clouds",
        source: include_str!("../shaders/clouds.wgsl"),
    },
];

/// A composer holding the common modules, atmos' modules (the drawing imports its
/// geometry, phase functions and frame camera) and the celestial ones.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = atmos::composer();
    composer
        .add_modules(WGSL_MODULES)
        .expect("celestial WGSL module names are unique and well formed");
    composer
}

#[cfg(test)]
mod tests {
    /// The embedded list is the folder `build.rs` validates: no file left out, none extra.
    #[test]
    fn wgsl_modules_are_the_files_build_rs_validates() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("shaders");
        let mut listed: Vec<_> = super::WGSL_MODULES.iter().map(|m| m.name).collect();
        listed.sort_unstable();
        assert_eq!(
            listed,
            skyscape_wgsl::build::module_names("celestial", &folder).unwrap()
        );
    }

    #[test]
    fn wgsl_modules_compose_and_validate() {
        let composer = super::composer();
        assert_eq!(super::WGSL_MODULES.len(), 4);
        for module in super::WGSL_MODULES {
            assert!(module.name.starts_with("celestial::"));
            let source = composer.compose_module(module.name).unwrap();
            skyscape_wgsl::validate(module.name, &source).unwrap();
        }
    }
}
