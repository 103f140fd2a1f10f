//! Building the sky, placing it for an observer and instant, and painting it from an
//! atmos rung.

use atmos::Atmosphere;
use atmos::frame::FrameCamera;
use atmos::ladder::SkyModel;
use glam::DVec3;

use super::*;
use crate::colour::star_colour_from_b_minus_v;
use crate::dome::{SkyDome, spin_from_azimuth};
use crate::draw::star_detection_threshold;
use crate::error::{CelestialError, Result, check_range};
use crate::light::{LuminanceScale, MoonLight};
use crate::moon::moon_position;
use crate::objects::{BackgroundSampling, SkyObjectsBuilder};
use crate::photometry::{
    NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2, illuminance_from_magnitude,
    luminance_from_surface_brightness,
};
use crate::planets::{Planet, planet_position};
use crate::refraction::apparent_direction;
use crate::stars::StarCatalogue;
use crate::sun::sun_position;
use crate::{Angle, Horizontal, Instant, Observer};

/// Stars and planets whose apparent elevation is below this (rad) are not drawn (a
/// viewer high up sees a little below the astronomical horizon).
pub(super) const POINT_LOWEST_ELEVATION_RAD: f64 = -0.05;

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
        self.place(*instant, *observer, sun, moon, planets, stars)
    }

    /// Keeps the bodies' places with what follows from them (the dome's spin, the
    /// photometric scale, the moon's light) as the placement, and forgets the paint.
    pub(super) fn place(
        &mut self,
        instant: Instant,
        observer: Observer,
        sun: SunPosition,
        moon: MoonPosition,
        planets: Vec<PlanetPosition>,
        stars: Vec<SkyStar>,
    ) -> Result<&Placement> {
        let scale = LuminanceScale::new(&self.atmosphere, sun.distance_m)?;
        let moon_light = MoonLight::new(&moon, &sun, &self.atmosphere, &scale)?;
        self.placement = Some(Placement {
            instant,
            observer,
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

    pub(super) fn placed(&self, call: &'static str) -> Result<&Placement> {
        self.placement.as_ref().ok_or(CelestialError::OutOfOrder {
            call,
            missing: "reposition",
        })
    }

    pub(super) fn painted(&self, call: &'static str) -> Result<&Paint> {
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

    pub(super) fn apparent(&self, direction: Horizontal) -> Horizontal {
        match &self.options.air {
            Some(air) => apparent_direction(direction, air),
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
                if apparent.elevation.radians() < POINT_LOWEST_ELEVATION_RAD {
                    return Ok(());
                }
                let mut point = builder.point_source(apparent.to_enu(), illuminance, colour)?;
                let t = f64::from(point.transmittance[1]);
                self.scintillate(&mut point, index, altitude, || {
                    if t > 0.0 && zenith_transmittance < 1.0 {
                        t.ln() / zenith_transmittance.ln()
                    } else {
                        1.0
                    }
                });
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
            layer_light.push(LayerLight::stronger_source(
                (sun_light, sun_irradiance),
                (placement.moon_light.direction, moon_irradiance),
                hemisphere_mean_radiance(&at_layer)?,
            ));
        }
        let angles = [
            placement.sun.airless.zenith_angle(),
            placement.moon.airless.zenith_angle(),
        ];
        self.keep_paint(Paint {
            sky_colour,
            fog_colours,
            dome,
            sun_angle: angles[0],
            moon_angle: angles[1],
            discs,
            points,
            aureole,
            layer_light,
        })
    }

    /// Keeps `paint` as the sky's paint (the layers' light now follows their changes).
    pub(super) fn keep_paint(&mut self, paint: Paint) -> Result<&Paint> {
        self.layers_changed = false;
        self.paint = Some(paint);
        Ok(self.paint.as_ref().expect("set above"))
    }
}

impl Sky {
    /// Sets `point`'s twinkle (the options' scintillation, if any) for the airmass
    /// `airmass()` toward it, seen from `altitude_m`; the index seeds its sequence.
    pub(super) fn scintillate(
        &self,
        point: &mut PointSource,
        index: u32,
        altitude_m: f64,
        airmass: impl FnOnce() -> f64,
    ) {
        if let Some(s) = &self.options.scintillation {
            let sigma = s.relative_deviation(airmass(), altitude_m);
            point.scintillation = s.factor(index, self.clock_s, sigma) as f32;
        }
    }
}

/// Gauss–Legendre nodes and weights of the zenith cosine on [0, 1] (4 points: exact for
/// a sky radiance polynomial of degree 6 in μ at each azimuth).
const SKY_MU_NODES: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];
/// Azimuths of the hemisphere quadrature.
const SKY_AZIMUTHS: usize = 8;

/// The sky's radiance averaged over the upper hemisphere with the cosine weight,
/// `E_sky/π` (E_sky its irradiance on a horizontal surface), seen from `at`: 4 zenith
/// cosines (Gauss–Legendre) × 8 azimuths of the model's radiance. A clear sky is far
/// from isotropic (bright toward the sun and the horizon, darkest near the zenith), so
/// its zenith radiance alone underestimates the light a cloud layer gets from it.
fn hemisphere_mean_radiance(at: &SkyObjectsBuilder<'_>) -> Result<[f64; 3]> {
    let mut sum = [0.0; 3];
    for (mu, weight) in SKY_MU_NODES {
        let horizontal = (1.0 - mu * mu).sqrt();
        for k in 0..SKY_AZIMUTHS {
            let phi = std::f64::consts::TAU * (k as f64 + 0.5) / SKY_AZIMUTHS as f64;
            let radiance = at
                .sky([horizontal * phi.sin(), horizontal * phi.cos(), mu])?
                .radiance;
            for (total, l) in sum.iter_mut().zip(radiance) {
                // E/π = (1/π) ∫∫ L μ dμ dφ; the azimuth step 2π/8 over π.
                *total += 2.0 * weight * mu * l / SKY_AZIMUTHS as f64;
            }
        }
    }
    Ok(sum)
}

impl LayerLight {
    /// A layer lit by the stronger of `sun` and `moon` (each a unit east/north/up
    /// direction and its irradiance at the layer: the one of larger luminance × sine
    /// of elevation), under a sky of cosine-weighted mean radiance `zenith_radiance`
    /// (its irradiance over π; an isotropic sky's radiance).
    pub(super) fn stronger_source(
        sun: ([f64; 3], [f64; 3]),
        moon: ([f64; 3], [f64; 3]),
        zenith_radiance: [f64; 3],
    ) -> Self {
        let strength = |(direction, irradiance): ([f64; 3], [f64; 3])| {
            atmos::ladder::luminance(irradiance) * direction[2].max(0.0)
        };
        let (direction, irradiance) = if strength(sun) >= strength(moon) {
            sun
        } else {
            moon
        };
        LayerLight {
            direction,
            irradiance,
            skylight: zenith_radiance.map(|l| l * std::f64::consts::PI),
        }
    }
}
