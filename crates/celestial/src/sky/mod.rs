//! [`Sky`]: SimGear's SGSky interface in typed Rust, driven by the ephemerides and any
//! atmos rung where SGSky used hand-picked colours.
//!
//! | SGSky | here |
//! |---|---|
//! | `build(sun_size, moon_size, planets, stars…)` | [`Sky::build`] (the sizes are the atmosphere's and the ephemerides'; the stars are the catalogue's) |
//! | `reposition(view_pos, lon, lat, alt, spin, gst, sun/moon ra, dec…)` | [`Sky::reposition`]: an [`Observer`] (latitude, longitude, altitude) and an [`Instant`] place every object and the dome's spin; or, driven by your own simulation as FlightGear drives SGSky, [`Sky::reposition_explicit`]: an [`ExplicitPlacement`] (observer, Greenwich sidereal time, the sun's, moon's and planets' apparent topocentric α, δ and distances, the stars' instant) |
//! | `repaint(sky_color, fog_color, sun_angle, moon_angle, planets, stars)` | [`Sky::repaint`]: sky and fog colours, sun and moon angles, star and planet brightness, all from an atmos [`SkyModel`](atmos::ladder::SkyModel); or [`Sky::repaint_explicit`]: an [`ExplicitPaint`] (sky and fog colours, the air's transmittance toward the sun, the moon and the zenith) |
//! | `add_cloud_layer` / change / remove | [`Sky::add_cloud_layer`], [`Sky::change_cloud_layer`], [`Sky::remove_cloud_layer`] |
//! | `set_visibility`, `modify_vis(alt, time_factor)`, `get_visibility` | [`Sky::set_visibility`], [`Sky::modify_vis`], [`Sky::visibility`] |
//! | `get_num_layers`, `get_cloud_layer(i)` | [`Sky::num_layers`], [`Sky::cloud_layer`] |
//! | `preDraw` / `postDraw(alt)` | stage 1, the backdrop: [`Sky::render_backdrop_cpu`] (dome, aureole, sun, moon, planets, stars) or, over a per-pixel atmos sky, [`Sky::sky_objects_frame`] (CPU: [`crate::objects::render_sky_objects_cpu`]; GPU: `celestial::gpu::SkyObjectsPass`); stage 2 after the scene: [`Sky::render_clouds_cpu`] / [`Sky::cloud_layers_in_draw_order`], farthest to nearest |
//!
//! Frame: the viewer's east/north/up axes, the planet-centred viewer on +z
//! ([`Sky::viewer_position`]); cameras are `atmos::frame::FrameCamera`s there
//! ([`Sky::camera`]).

mod explicit;
mod place;
mod render;
#[cfg(test)]
mod tests;
mod weather;

pub use explicit::{
    ExplicitPaint, ExplicitPlacement, ExplicitPlanet, HorizonColours, kasten_young_airmass,
};
pub use render::InCloudFog;
pub use weather::puff_envelope;

use atmos::Atmosphere;

use crate::clouds::CloudLayer;
use crate::dome::{DOME_SIDES, DomeColouring, SkyDome};
use crate::draw::{DiscObject, PointSource};
use crate::error::CelestialError;
use crate::light::{LuminanceScale, MoonLight};
use crate::moon::MoonPosition;
use crate::objects::{Aureole, BackgroundSampling};
use crate::planets::PlanetPosition;
use crate::refraction::AirConditions;
use crate::scintillation::Scintillation;
use crate::stars::{SkyStar, StarCatalogue};
use crate::sun::SunPosition;
use crate::{Angle, Instant, Observer};

/// Fog between the viewer and the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FogModel {
    /// `exp(−3.912 d/V)`: what the air does (the physical option).
    #[default]
    Koschmieder,
    /// SGSky's `exp(−(ρd)²)`, equal at d = V (the cheap option).
    Exp2,
}

/// How the sky is built.
#[derive(Debug, Clone, PartialEq)]
pub struct SkyOptions {
    /// How the sky behind stars is sampled.
    pub background: BackgroundSampling,
    /// The dome's colouring.
    pub dome: DomeColouring,
    /// Point-sprite width σ (pixels, ≥ 0.75).
    pub sprite_sigma_px: f32,
    /// Twinkling (off by default).
    pub scintillation: Option<Scintillation>,
    /// The fog model.
    pub fog: FogModel,
    /// Refraction of the drawn objects (the reference air by default; `None`: airless).
    pub air: Option<AirConditions>,
    /// Faintest catalogue star loaded; `None`: the faintest the eye can detect against
    /// the natural night sky with no extinction (the detection threshold at
    /// 21.9 mag/arcsec², magnitude 6.6) — fainter ones can never be drawn.
    pub star_limit_magnitude: Option<f64>,
}

impl Default for SkyOptions {
    fn default() -> Self {
        Self {
            background: BackgroundSampling::default(),
            dome: DomeColouring::default(),
            sprite_sigma_px: 1.0,
            scintillation: None,
            fog: FogModel::default(),
            air: Some(AirConditions::REFERENCE),
            star_limit_magnitude: None,
        }
    }
}

/// Where everything is (after [`Sky::reposition`]).
#[derive(Debug, Clone)]
pub struct Placement {
    /// The instant.
    pub instant: Instant,
    /// The viewer (its elevation is the viewer's altitude).
    pub observer: Observer,
    /// The sun.
    pub sun: SunPosition,
    /// The moon.
    pub moon: MoonPosition,
    /// Mercury–Neptune.
    pub planets: Vec<PlanetPosition>,
    /// The catalogue's stars in this sky.
    pub stars: Vec<SkyStar>,
    /// The dome's rotation: the sun's azimuth from south toward east.
    pub spin: Angle,
    /// Lux per unit of the atmosphere's irradiance today.
    pub scale: LuminanceScale,
    /// The moon as a light source.
    pub moon_light: MoonLight,
}

/// The light a cloud layer gets (after [`Sky::repaint`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerLight {
    /// Unit direction of the stronger source at the layer (sun or moon).
    pub direction: [f64; 3],
    /// Its irradiance at the layer, per channel (after the atmosphere above).
    pub irradiance: [f64; 3],
    /// The sky's irradiance on a horizontal surface at the layer, per channel: the
    /// model's radiance over the upper hemisphere (4 × 8 directions) after `repaint`,
    /// π × the given sky colour after `repaint_explicit`.
    pub skylight: [f64; 3],
}

/// The sky's colours and the objects' brightness (after [`Sky::repaint`]).
#[derive(Debug, Clone)]
pub struct Paint {
    /// Radiance at the zenith (sunlit + moonlit), the atmosphere's unit.
    pub sky_colour: [f64; 3],
    /// Radiance at the horizon in the azimuths of the dome's 12 vertices (vertex 0
    /// toward the sun).
    pub fog_colours: [[f64; 3]; DOME_SIDES],
    /// The coloured dome (the model's radiance minus the aureole at each vertex: the
    /// aureole is drawn per pixel over it).
    pub dome: SkyDome,
    /// The sun's angle from the zenith (SGSky's `sun_angle`).
    pub sun_angle: Angle,
    /// The moon's angle from the zenith.
    pub moon_angle: Angle,
    /// The sun and moon discs.
    pub discs: [DiscObject; 2],
    /// Planets, then stars above the horizon.
    pub points: Vec<PointSource>,
    /// The aureole's inputs (drawn with the dome backdrop only: per-pixel rungs
    /// already contain it).
    pub aureole: Aureole,
    /// The light of each cloud layer, in the layers' order at repaint time.
    pub layer_light: Vec<LayerLight>,
}

/// SGSky's sky.
#[derive(Debug, Clone)]
pub struct Sky {
    atmosphere: Atmosphere,
    options: SkyOptions,
    catalogue: StarCatalogue,
    layers: Vec<CloudLayer>,
    layers_changed: bool,
    visibility_m: f64,
    effective_visibility_m: f64,
    clock_s: f64,
    placement: Option<Placement>,
    paint: Option<Paint>,
}

fn atmos_error(field: &'static str) -> impl Fn(atmos::AtmosError) -> CelestialError {
    move |source| CelestialError::Atmos { field, source }
}
