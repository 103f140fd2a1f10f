//! [`Sky`]: SGSky's interface (seed 004) in typed Rust, driven by the ephemerides and
//! any atmos rung where SGSky used hand-picked colours.
//!
//! | SGSky | here |
//! |---|---|
//! | `build(sun_size, moon_size, planets, stars…)` | [`Sky::build`] (the sizes are the atmosphere's and the ephemerides'; the stars are the catalogue's) |
//! | `reposition(view_pos, lon, lat, alt, spin, gst, sun/moon ra, dec…)` | [`Sky::reposition`]: an [`Observer`] (latitude, longitude, altitude) and an [`Instant`] place every object and the dome's spin |
//! | `repaint(sky_color, fog_color, sun_angle, moon_angle, planets, stars)` | [`Sky::repaint`]: sky and fog colours, sun and moon angles, star and planet brightness, all from an atmos [`SkyModel`] |
//! | `add_cloud_layer` / change / remove | [`Sky::add_cloud_layer`], [`Sky::change_cloud_layer`], [`Sky::remove_cloud_layer`] |
//! | `set_visibility`, `modify_vis(alt, time_factor)`, `get_visibility` | [`Sky::set_visibility`], [`Sky::modify_vis`], [`Sky::visibility`] |
//! | `get_num_layers`, `get_cloud_layer(i)` | [`Sky::num_layers`], [`Sky::cloud_layer`] |
//! | `preDraw` / `postDraw(alt)` | stage 1, the backdrop: [`Sky::render_backdrop_cpu`] (dome, aureole, sun, moon, planets, stars) or, over a per-pixel atmos sky, [`Sky::sky_objects_frame`] (CPU: [`crate::objects::render_sky_objects_cpu`]; GPU: `celestial::gpu::SkyObjectsPass`); stage 2 after the scene: [`Sky::render_clouds_cpu`] / [`Sky::cloud_layers_in_draw_order`], farthest to nearest |
//!
//! Frame: the viewer's east/north/up axes, the planet-centred viewer on +z
//! ([`Sky::viewer_position`]); cameras are `atmos::frame::FrameCamera`s there
//! ([`Sky::camera`]).

use atmos::Atmosphere;
use atmos::frame::FrameCamera;
use atmos::ladder::SkyModel;
use glam::DVec3;

use crate::clouds::{CloudLayer, CloudLayerFrame, CloudLayerUniforms, draw_order, no_layer};
use crate::colour::star_colour_from_b_minus_v;
use crate::dome::{DOME_SIDES, DomeColouring, SkyDome, spin_from_azimuth};
use crate::draw::{DiscObject, PointSource, star_detection_threshold};
use crate::error::{CelestialError, Result, check_range};
use crate::light::{LuminanceScale, MoonLight};
use crate::moon::{MoonPosition, moon_position};
use crate::objects::{
    Aureole, BackgroundSampling, SkyObjectsBuilder, SkyObjectsFrame, render_sky_objects_cpu,
};
use crate::photometry::{
    NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2, illuminance_from_magnitude,
    luminance_from_surface_brightness,
};
use crate::planets::{Planet, PlanetPosition, planet_position};
use crate::refraction::{AirConditions, apparent_elevation};
use crate::scintillation::Scintillation;
use crate::stars::{SkyStar, StarCatalogue};
use crate::sun::{SunPosition, sun_position};
use crate::visibility::{
    KOSCHMIEDER_CONTRAST, VisibilityAerosol, aerosol_for_visibility, check_visibility,
    exp2_fog_factor, koschmieder_fog_factor,
};
use crate::{Angle, Horizontal, Instant, Observer};

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
    /// Mercury–Saturn.
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
    /// The sky's irradiance on a horizontal surface at the layer (π × its zenith
    /// radiance: an isotropic sky), per channel.
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
#[derive(Debug)]
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

/// Slot length of the "puffy" variation (s): SGSky's ramp.
const PUFF_SLOT_S: f64 = 0.15;
/// Longest puff (s), SGSky's.
const PUFF_MAX_S: f64 = 2.0;

/// The puff envelope in [0, 1] at time `t` for a layer seeded `seed`: SGSky's disabled
/// effect, made frame-rate independent. Each 0.15 s slot starts a puff when a hashed
/// uniform u satisfies u³ > 0.95 (SGSky's test, there per frame), lasting up to 2 s
/// with 0.15 s ramps; overlapping puffs take the largest envelope.
pub fn puff_envelope(seed: u32, t: f64) -> f64 {
    use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};
    let last = (t / PUFF_SLOT_S).floor() as i64;
    let first = ((t - PUFF_MAX_S) / PUFF_SLOT_S).floor() as i64;
    let mut envelope = 0.0f64;
    for slot in first..=last {
        let h = hash_combine(hash_combine(seed, slot as u32), (slot >> 32) as u32);
        let u = f64::from(unit_float_from_bits(h));
        if u * u * u <= 0.95 {
            continue;
        }
        let duration = PUFF_MAX_S * f64::from(unit_float_from_bits(hash_combine(h, 1)));
        let local = t - slot as f64 * PUFF_SLOT_S;
        if local < 0.0 || local > duration {
            continue;
        }
        let ramp = (local / PUFF_SLOT_S)
            .min((duration - local) / PUFF_SLOT_S)
            .clamp(0.0, 1.0);
        envelope = envelope.max(ramp);
    }
    envelope
}

fn atmos_error(field: &'static str) -> impl Fn(atmos::AtmosError) -> CelestialError {
    move |source| CelestialError::Atmos { field, source }
}

impl Sky {
    /// SGSky's `build`: a sky over `atmosphere` (which owns the sun's size and
    /// irradiance) with the catalogue loaded to the options' limit. Visibility starts
    /// at the atmosphere's own (clear air, 1000 km asked).
    pub fn build(atmosphere: Atmosphere, options: SkyOptions) -> Result<Self> {
        atmosphere.validate().map_err(atmos_error("atmosphere"))?;
        check_range(
            "sprite_sigma_px",
            f64::from(options.sprite_sigma_px),
            f64::from(crate::draw::MIN_SPRITE_SIGMA_PX),
            64.0,
            "px",
        )?;
        if let Some(s) = &options.scintillation {
            s.validate()?;
        }
        let limit = match options.star_limit_magnitude {
            Some(m) => m,
            None => {
                let floor = luminance_from_surface_brightness(NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2);
                -2.5 * (star_detection_threshold(floor) / crate::ZERO_MAGNITUDE_ILLUMINANCE_LX)
                    .log10()
            }
        };
        let catalogue = StarCatalogue::hipparcos(limit)?;
        Ok(Self {
            atmosphere,
            options,
            catalogue,
            layers: Vec::new(),
            layers_changed: false,
            visibility_m: crate::visibility::MAX_VISIBILITY_M,
            effective_visibility_m: crate::visibility::MAX_VISIBILITY_M,
            clock_s: 0.0,
            placement: None,
            paint: None,
        })
    }

    /// The atmosphere.
    pub fn atmosphere(&self) -> &Atmosphere {
        &self.atmosphere
    }

    /// The options.
    pub fn options(&self) -> &SkyOptions {
        &self.options
    }

    /// The catalogue's stars.
    pub fn catalogue(&self) -> &StarCatalogue {
        &self.catalogue
    }

    /// SGSky's `reposition`: places the sun, moon, planets and stars for `observer`
    /// (whose elevation is the viewer's altitude) at `instant`, and the dome's spin.
    pub fn reposition(&mut self, observer: &Observer, instant: &Instant) -> Result<&Placement> {
        let sun = sun_position(instant, observer)?;
        let moon = moon_position(instant, observer)?;
        let planets = Planet::ALL
            .iter()
            .map(|&p| planet_position(p, instant, observer))
            .collect::<Result<Vec<_>>>()?;
        let stars = self.catalogue.sky(instant, observer);
        let scale = LuminanceScale::new(&self.atmosphere, sun.distance_m)?;
        let moon_light = MoonLight::new(&moon, &sun, &self.atmosphere, &scale)?;
        self.placement = Some(Placement {
            instant: *instant,
            observer: *observer,
            sun,
            moon,
            planets,
            stars,
            spin: spin_from_azimuth(sun.airless.azimuth),
            scale,
            moon_light,
        });
        self.paint = None;
        Ok(self.placement.as_ref().expect("set above"))
    }

    /// Where everything is, if repositioned.
    pub fn placement(&self) -> Option<&Placement> {
        self.placement.as_ref()
    }

    /// The colours and brightness, if repainted since the last reposition.
    pub fn paint(&self) -> Option<&Paint> {
        self.paint.as_ref()
    }

    /// The viewer's altitude (m): the observer's elevation.
    pub fn altitude_m(&self) -> Result<f64> {
        Ok(self.placed("altitude_m")?.observer.elevation_m())
    }

    fn placed(&self, call: &'static str) -> Result<&Placement> {
        self.placement.as_ref().ok_or(CelestialError::OutOfOrder {
            call,
            missing: "reposition",
        })
    }

    fn painted(&self, call: &'static str) -> Result<&Paint> {
        if self.layers_changed {
            return Err(CelestialError::OutOfOrder {
                call,
                missing: "repaint after the cloud layers changed",
            });
        }
        self.paint.as_ref().ok_or(CelestialError::OutOfOrder {
            call,
            missing: "repaint",
        })
    }

    /// The planet-centred viewer position (m) in the east/north/up axes.
    pub fn viewer_position(&self) -> Result<DVec3> {
        let altitude = self.altitude_m()?;
        Ok(DVec3::new(
            0.0,
            0.0,
            self.atmosphere.planet_radius + altitude,
        ))
    }

    /// A camera at the viewer looking along `forward` (east/north/up), rolled by
    /// `up_hint`, with vertical field of view `fov_y`, lit by the sun (airless).
    pub fn camera(
        &self,
        forward: [f64; 3],
        up_hint: [f64; 3],
        fov_y: Angle,
        width: u32,
        height: u32,
    ) -> Result<FrameCamera> {
        let placement = self.placed("camera")?;
        FrameCamera::look_at(
            self.viewer_position()?,
            DVec3::from_array(forward),
            DVec3::from_array(up_hint),
            fov_y.radians(),
            width,
            height,
            DVec3::from_array(placement.sun.airless.to_enu()),
            None,
        )
        .map_err(atmos_error("camera"))
    }

    fn apparent(&self, direction: Horizontal) -> Horizontal {
        match &self.options.air {
            Some(air) => Horizontal {
                azimuth: direction.azimuth,
                elevation: apparent_elevation(direction.elevation, air),
            },
            None => direction,
        }
    }

    /// SGSky's `repaint`: the sky's and fog's colours, the sun and moon (their discs
    /// through the air), every planet's and visible star's brightness against the sky,
    /// the dome's vertex colours and the cloud layers' light, from `model` — any atmos
    /// rung built from this sky's atmosphere (its radiance must be in the unit of the
    /// atmosphere's `sun_irradiance`).
    pub fn repaint(&mut self, model: &dyn SkyModel) -> Result<&Paint> {
        let placement = self.placed("repaint")?;
        let altitude = placement.observer.elevation_m();
        let sun_light = placement.sun.airless.to_enu();
        let drawn_sun = self.apparent(placement.sun.airless).to_enu();
        let drawn_moon = self.apparent(placement.moon_light.horizontal()).to_enu();
        // Objects are drawn at their apparent places; the air is lit from the true ones.
        let builder = SkyObjectsBuilder::new(
            &self.atmosphere,
            model,
            altitude,
            sun_light,
            placement.sun.distance_m,
            Some(placement.moon_light),
            self.options.background,
        )?;
        let discs = [
            builder.sun_disc_towards(drawn_sun)?,
            builder.moon_disc_towards(drawn_moon)?,
        ];
        let aureole = builder.aureole_towards(drawn_sun)?;
        // Stars and planets above the horizon, at their apparent places.
        let zenith_transmittance = builder.transmittance([0.0, 0.0, 1.0])?[1];
        let mut points = Vec::new();
        let mut add =
            |index: u32, place: Horizontal, illuminance: f64, colour: [f64; 3]| -> Result<()> {
                let apparent = self.apparent(place);
                if apparent.elevation.radians() < -0.05 {
                    return Ok(());
                }
                let mut point = builder.point_source(apparent.to_enu(), illuminance, colour)?;
                if let Some(s) = &self.options.scintillation {
                    let t = f64::from(point.transmittance[1]);
                    let airmass = if t > 0.0 && zenith_transmittance < 1.0 {
                        t.ln() / zenith_transmittance.ln()
                    } else {
                        1.0
                    };
                    let sigma = s.relative_deviation(airmass, altitude);
                    point.scintillation = s.factor(index, self.clock_s, sigma) as f32;
                }
                points.push(point);
                Ok(())
            };
        for (i, p) in placement.planets.iter().enumerate() {
            add(
                i as u32,
                p.airless,
                illuminance_from_magnitude(p.magnitude),
                star_colour_from_b_minus_v(p.planet.b_minus_v()),
            )?;
        }
        for star in &placement.stars {
            add(
                star.hip as u32,
                star.airless,
                star.illuminance_lx,
                star.colour,
            )?;
        }
        // Sky and fog colours, the dome (13 or 49 model queries per light source).
        let painted = SkyDome::paint(
            self.options.dome,
            placement.spin,
            |direction| Ok(builder.sky_exact(direction)?.radiance),
            |direction| aureole.radiance(direction.map(|c| c as f32)).map(f64::from),
        )?;
        let (dome, sky_colour, fog_colours) =
            (painted.dome, painted.sky_colour, painted.fog_colours);
        // Each layer's light: the stronger of sun and moon at its altitude.
        let mut layer_light = Vec::with_capacity(self.layers.len());
        for layer in &self.layers {
            let at_layer = SkyObjectsBuilder::new(
                &self.atmosphere,
                model,
                layer.base_m.max(altitude.min(layer.top_m())),
                sun_light,
                placement.sun.distance_m,
                Some(placement.moon_light),
                BackgroundSampling::PerObject,
            )?;
            let sun_t = at_layer.transmittance(sun_light)?;
            let sun_irradiance: [f64; 3] =
                std::array::from_fn(|i| self.atmosphere.sun_irradiance[i] * sun_t[i]);
            let moon_t = at_layer.transmittance(placement.moon_light.direction)?;
            let moon_irradiance: [f64; 3] =
                std::array::from_fn(|i| placement.moon_light.irradiance[i] * moon_t[i]);
            let lum = atmos::ladder::luminance;
            let sun_strength = lum(sun_irradiance) * sun_light[2].max(0.0);
            let moon_strength = lum(moon_irradiance) * placement.moon_light.direction[2].max(0.0);
            let (direction, irradiance) = if sun_strength >= moon_strength {
                (sun_light, sun_irradiance)
            } else {
                (placement.moon_light.direction, moon_irradiance)
            };
            let zenith = at_layer.sky([0.0, 0.0, 1.0])?.radiance;
            layer_light.push(LayerLight {
                direction,
                irradiance,
                skylight: zenith.map(|l| l * std::f64::consts::PI),
            });
        }
        let sun_angle = placement.sun.airless.zenith_angle();
        let moon_angle = placement.moon.airless.zenith_angle();
        self.layers_changed = false;
        self.paint = Some(Paint {
            sky_colour,
            fog_colours,
            dome,
            sun_angle,
            moon_angle,
            discs,
            points,
            aureole,
            layer_light,
        });
        Ok(self.paint.as_ref().expect("set above"))
    }

    /// SGSky's `add_cloud_layer`: checks and appends `layer`; returns its index.
    pub fn add_cloud_layer(&mut self, layer: CloudLayer) -> Result<usize> {
        layer.validate()?;
        self.layers.push(layer);
        self.layers_changed = true;
        Ok(self.layers.len() - 1)
    }

    /// Replaces layer `index`.
    pub fn change_cloud_layer(&mut self, index: usize, layer: CloudLayer) -> Result<()> {
        layer.validate()?;
        let count = self.layers.len();
        let slot = self
            .layers
            .get_mut(index)
            .ok_or_else(|| no_layer(index, count))?;
        *slot = layer;
        self.layers_changed = true;
        Ok(())
    }

    /// Removes and returns layer `index` (later ones move down by one).
    pub fn remove_cloud_layer(&mut self, index: usize) -> Result<CloudLayer> {
        if index >= self.layers.len() {
            return Err(no_layer(index, self.layers.len()));
        }
        self.layers_changed = true;
        Ok(self.layers.remove(index))
    }

    /// SGSky's `get_num_layers`.
    pub fn num_layers(&self) -> usize {
        self.layers.len()
    }

    /// SGSky's `get_cloud_layer(i)`.
    pub fn cloud_layer(&self, index: usize) -> Option<&CloudLayer> {
        self.layers.get(index)
    }

    /// SGSky's `set_visibility` (m, in [1 m, 1000 km]; SGSky clamps below 25 m, this
    /// rejects what is not a visibility). The effective visibility is reset to it.
    pub fn set_visibility(&mut self, visibility_m: f64) -> Result<()> {
        let v = check_visibility("visibility_m", visibility_m)?;
        self.visibility_m = v;
        self.effective_visibility_m = v;
        Ok(())
    }

    /// SGSky's `modify_vis(alt, time_factor)`: advances the sky's clock by `dt_s` and
    /// closes the visibility in around a viewer at `altitude_m` inside or near cloud
    /// layers. Extinctions add: the clear air's 3.912/V plus, per layer, its immersion
    /// (smooth across the transition zones, raised toward 1 by the deterministic
    /// "puffy" envelope while in a transition zone) × coverage × 3.912/in-cloud
    /// visibility. Returns the effective visibility ([`Sky::visibility`]).
    pub fn modify_vis(&mut self, altitude_m: f64, dt_s: f64) -> Result<f64> {
        check_range("altitude_m", altitude_m, -500.0, 1.0e6, "m")?;
        check_range("dt_s", dt_s, 0.0, 1.0e6, "s")?;
        self.clock_s += dt_s;
        let k = -KOSCHMIEDER_CONTRAST.ln();
        let mut extinction = k / self.visibility_m;
        for layer in &self.layers {
            let mut immersion = layer.immersion(altitude_m);
            if immersion > 0.0 && immersion < 1.0 {
                immersion += (1.0 - immersion) * puff_envelope(layer.seed, self.clock_s);
            }
            extinction += immersion * layer.coverage * k / layer.in_cloud_visibility_m;
        }
        self.effective_visibility_m = k / extinction;
        Ok(self.effective_visibility_m)
    }

    /// SGSky's `get_visibility`: the visibility as modified by [`Sky::modify_vis`] (m).
    pub fn visibility(&self) -> f64 {
        self.effective_visibility_m
    }

    /// The sky's clock (s): the sum of `modify_vis`'s `dt`.
    pub fn clock_s(&self) -> f64 {
        self.clock_s
    }

    /// The fog's extinction coefficient (1/m) at the effective visibility.
    pub fn fog_extinction(&self) -> f64 {
        -KOSCHMIEDER_CONTRAST.ln() / self.effective_visibility_m
    }

    /// The fraction of an object's contrast left at `distance_m` by the fog model.
    pub fn fog_factor(&self, distance_m: f64) -> f64 {
        match self.options.fog {
            FogModel::Koschmieder => {
                koschmieder_fog_factor(distance_m, self.effective_visibility_m)
            }
            FogModel::Exp2 => exp2_fog_factor(distance_m, self.effective_visibility_m),
        }
    }

    /// The fog's colour toward horizontal `view` (the dome's horizon colour there).
    pub fn fog_colour(&self, view: [f64; 3]) -> Result<[f64; 3]> {
        let paint = self.painted("fog_colour")?;
        let horizontal = [view[0], view[1], 0.0];
        Ok(paint.dome.radiance(horizontal))
    }

    /// The effective visibility as a physical aerosol for atmos at the viewer's
    /// altitude (Koschmieder).
    pub fn aerosol_atmosphere(&self) -> Result<VisibilityAerosol> {
        aerosol_for_visibility(
            &self.atmosphere,
            self.effective_visibility_m,
            self.altitude_m()?,
        )
    }

    /// Stage 1's objects for `camera` (made by [`Sky::camera`]): what
    /// [`render_sky_objects_cpu`] and `celestial::gpu::SkyObjectsPass` draw over a sky.
    pub fn sky_objects_frame(&self, camera: &FrameCamera) -> Result<SkyObjectsFrame> {
        let placement = self.placed("sky_objects_frame")?;
        let paint = self.painted("sky_objects_frame")?;
        SkyObjectsFrame::new(
            *camera,
            self.atmosphere.planet_radius,
            &placement.scale,
            self.options.sprite_sigma_px,
            paint.discs,
            paint.points.clone(),
        )
    }

    /// SGSky's stage 1 on the CPU with the cheap sky: per pixel the dome's colour and
    /// the sun's aureole (which the dome cannot resolve), then the sun, moon, planets
    /// and stars. Row-major radiance in the atmosphere's unit.
    pub fn render_backdrop_cpu(&self, camera: &FrameCamera) -> Result<Vec<[f32; 3]>> {
        let paint = self.painted("render_backdrop_cpu")?;
        let mut radiance = vec![[0.0f32; 3]; camera.pixel_count()];
        for y in 0..camera.height {
            for x in 0..camera.width {
                let view = atmos::frame::frame_view_direction([x, y], camera);
                let dome = paint.dome.radiance(view.map(f64::from));
                let aureole = paint.aureole.radiance(view);
                radiance[(y * camera.width + x) as usize] =
                    std::array::from_fn(|i| dome[i] as f32 + aureole[i]);
            }
        }
        render_sky_objects_cpu(&self.sky_objects_frame(camera)?, &mut radiance)?;
        Ok(radiance)
    }

    /// The uniform blocks of the cloud layers for a viewer at `altitude_m`, farthest
    /// first (SGSky's `postDraw` order); a layer the viewer is inside is left out
    /// (its effect is the closed-in visibility). Pairs of (layer index, uniforms).
    pub fn cloud_layers_in_draw_order(
        &self,
        altitude_m: f64,
    ) -> Result<Vec<(usize, CloudLayerUniforms)>> {
        let paint = self.painted("cloud_layers_in_draw_order")?;
        let fog_colour = {
            let mut sum = [0.0; 3];
            for f in &paint.fog_colours {
                for i in 0..3 {
                    sum[i] += f[i] / DOME_SIDES as f64;
                }
            }
            sum
        };
        Ok(draw_order(&self.layers, altitude_m)
            .into_iter()
            .map(|i| {
                let light = &paint.layer_light[i];
                let frame = CloudLayerFrame {
                    planet_radius_m: self.atmosphere.planet_radius,
                    offset_m: [0.0, 0.0],
                    fog_extinction_per_m: self.fog_extinction(),
                    exp2_fog: self.options.fog == FogModel::Exp2,
                    sun_direction: light.direction,
                    sunlight: light.irradiance,
                    skylight: light.skylight,
                    fog_colour,
                };
                (i, self.layers[i].uniforms(&frame))
            })
            .collect())
    }

    /// SGSky's stage 2 on the CPU: composites every cloud layer over `radiance` (the
    /// scene already drawn, row-major for `camera`), farthest first; then the in-cloud
    /// fog of the layers the viewer is in or near (those are not drawn as sheets when
    /// the viewer is inside; in their transition zones both) (the extinction `modify_vis` uses,
    /// integrated along each view: [`crate::clouds::in_cloud_transmittance`]) toward
    /// the nearest such layer's interior colour. Puffs change the reported visibility,
    /// not this image.
    pub fn render_clouds_cpu(&self, camera: &FrameCamera, radiance: &mut [[f32; 3]]) -> Result<()> {
        let p = camera.position;
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let altitude = f64::from(r) - self.atmosphere.planet_radius;
        let layers = self.cloud_layers_in_draw_order(altitude)?;
        if radiance.len() != camera.pixel_count() {
            return Err(CelestialError::OutOfRange {
                field: "radiance.len()",
                value: radiance.len() as f64,
                min: camera.pixel_count() as f64,
                max: camera.pixel_count() as f64,
                unit: "pixels",
            });
        }
        // The layer whose fog the viewer is in (the most immersed), with its colour.
        let paint = self.painted("render_clouds_cpu")?;
        let fog_layer = (0..self.layers.len())
            .filter(|&i| self.layers[i].immersion(altitude) > 0.0)
            .max_by(|&a, &b| {
                self.layers[a]
                    .immersion(altitude)
                    .total_cmp(&self.layers[b].immersion(altitude))
            });
        let interior = fog_layer.map(|i| {
            let light = &paint.layer_light[i];
            let frame = CloudLayerFrame {
                planet_radius_m: self.atmosphere.planet_radius,
                offset_m: [0.0, 0.0],
                fog_extinction_per_m: 0.0,
                exp2_fog: false,
                sun_direction: light.direction,
                sunlight: light.irradiance,
                skylight: light.skylight,
                fog_colour: [0.0; 3],
            };
            crate::clouds::cloud_interior_radiance(&self.layers[i].uniforms(&frame))
        });
        for y in 0..camera.height {
            for x in 0..camera.width {
                let view = atmos::frame::frame_view_direction([x, y], camera);
                let out = &mut radiance[(y * camera.width + x) as usize];
                for (_, layer) in &layers {
                    *out = crate::clouds::cloud_layer_radiance(view, r, layer, *out);
                }
                if let Some(colour) = interior {
                    let t = crate::clouds::in_cloud_transmittance(
                        &self.layers,
                        altitude,
                        f64::from(view[2]),
                    ) as f32;
                    for i in 0..3 {
                        out[i] = t * out[i] + (1.0 - t) * colour[i];
                    }
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clouds::CloudKind;

    #[test]
    fn puffs_are_deterministic_and_frame_rate_independent() {
        let mut active = 0;
        for k in 0..20_000 {
            let t = f64::from(k) * 0.05;
            let e = puff_envelope(3, t);
            assert!((0.0..=1.0).contains(&e));
            active += usize::from(e > 0.0);
            assert_eq!(e, puff_envelope(3, t));
        }
        // Puffs happen, but not all the time.
        assert!(active > 100 && active < 19_000, "{active}");
        assert_ne!(
            (0..2000)
                .map(|k| puff_envelope(3, f64::from(k) * 0.05))
                .sum::<f64>(),
            (0..2000)
                .map(|k| puff_envelope(4, f64::from(k) * 0.05))
                .sum::<f64>()
        );
    }

    #[test]
    fn visibility_closes_in_and_reopens_whatever_the_step() {
        let mut coarse = Sky::build(Atmosphere::earth(), SkyOptions::default()).unwrap();
        coarse.set_visibility(20_000.0).unwrap();
        let layer = CloudLayer::new(1000.0, 500.0, 200.0, 40_000.0, CloudKind::Stratus).unwrap();
        coarse.add_cloud_layer(layer).unwrap();
        let mut fine = Sky::build(Atmosphere::earth(), SkyOptions::default()).unwrap();
        fine.set_visibility(20_000.0).unwrap();
        fine.add_cloud_layer(coarse.cloud_layer(0).unwrap().clone())
            .unwrap();
        // Far below: the clear visibility; inside: the cloud's 25 m (coverage 1).
        assert!((coarse.modify_vis(0.0, 0.0).unwrap() - 20_000.0).abs() < 1e-6);
        let inside = coarse.modify_vis(1200.0, 0.0).unwrap();
        assert!(
            (inside - 1.0 / (1.0 / 20_000.0 + 1.0 / 25.0)).abs() < 1e-9,
            "{inside}"
        );
        // The same accumulated time in 1 step or 100 gives the same visibility.
        let a = coarse.modify_vis(900.0, 10.0).unwrap();
        for _ in 0..100 {
            fine.modify_vis(900.0, 0.1).unwrap();
        }
        assert!((fine.visibility() - a).abs() < 1e-9 * a);
        // Bad input names the field.
        assert!(
            coarse
                .modify_vis(f64::NAN, 0.1)
                .unwrap_err()
                .to_string()
                .contains("altitude_m")
        );
        assert!(
            coarse
                .modify_vis(0.0, -1.0)
                .unwrap_err()
                .to_string()
                .contains("dt_s")
        );
        assert!(
            coarse
                .set_visibility(0.0)
                .unwrap_err()
                .to_string()
                .contains("visibility_m")
        );
        assert!(
            coarse
                .remove_cloud_layer(3)
                .unwrap_err()
                .to_string()
                .contains("cloud layer index")
        );
    }
}
