//! SGSky's explicit drive: the sky placed and painted from a caller's own simulation,
//! as FlightGear drives SimGear's SGSky (Curtis Olson, SimGear
//! `simgear/scene/sky/sky.cxx`): `reposition` takes the sidereal time and the sun's
//! and moon's right ascensions, declinations and distances; `repaint` takes the sky's
//! and fog's colours and the sun's and moon's angles, from which SGSky derives how the
//! air dims them. Here [`Sky::reposition_explicit`] takes an [`ExplicitPlacement`] and
//! [`Sky::repaint_explicit`] an [`ExplicitPaint`] (with the air's transmittance given
//! outright), and both fill the same [`Placement`] and [`Paint`] as
//! [`Sky::reposition`] and [`Sky::repaint`], so drawing and cloud layers work
//! unchanged.

use glam::DVec3;

use super::place::POINT_LOWEST_ELEVATION_RAD;
use super::*;
use crate::error::{Result, check_range};
use crate::horizontal::parallactic_angle;
use crate::moon::{MOON_RADIUS_M, geocentric_from_topocentric};
use crate::moon_phase::{EquatorialPlace, moon_phase};
use crate::objects::{
    TransmittanceFit, moon_disc_object, ray_hits_ground, sun_disc_object, unit_direction,
};
use crate::photometry::{
    NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2, illuminance_from_magnitude,
    luminance_from_surface_brightness,
};
use crate::planets::Planet;
use crate::sun::ASTRONOMICAL_UNIT_M;
use crate::{Horizontal, colour::star_colour_from_b_minus_v};

/// A planet placed by the caller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitPlanet {
    /// Which planet (its colour).
    pub planet: Planet,
    /// Its apparent topocentric place (true equator and equinox of date, as the viewer
    /// sees it; distance from the viewer).
    pub place: EquatorialPlace,
    /// Its visual magnitude, in [−10, 30].
    pub magnitude: f64,
}

/// Where everything is, as the caller's simulation says: SGSky's `reposition`
/// arguments, typed ([`Sky::reposition_explicit`]).
///
/// Every place is **apparent and topocentric**: right ascension and declination on
/// the true equator and equinox of date as the viewer sees them (parallax included,
/// refraction not: the sky adds its own, [`SkyOptions::air`]), distances from the
/// viewer.
#[derive(Debug, Clone, PartialEq)]
pub struct ExplicitPlacement {
    /// The viewer: latitude, east-positive longitude, elevation (the altitude).
    pub observer: Observer,
    /// Greenwich apparent sidereal time, in [−360°, 360°] (SGSky's `gst`).
    pub greenwich_sidereal_time: Angle,
    /// The sun (distance in [0.9, 1.1] AU).
    pub sun: EquatorialPlace,
    /// The moon (distance in [2, 10⁶] moon radii).
    pub moon: EquatorialPlace,
    /// The planets to draw (none, some or all; SGSky's `planet_data`).
    pub planets: Vec<ExplicitPlanet>,
    /// The instant whose catalogue places the stars take (their apparent places at it,
    /// turned to the horizon by the sidereal time above); also [`Placement::instant`].
    pub star_instant: Instant,
}

/// Horizon (fog) colours for [`ExplicitPaint`]: SGSky's one fog colour
/// ([`HorizonColours::uniform`]) or one per azimuth of the dome's 12 horizon vertices
/// ([`HorizonColours::per_vertex`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HorizonColours([[f64; 3]; DOME_SIDES]);

impl HorizonColours {
    /// One colour all round (SGSky's `fog_color`).
    pub fn uniform(colour: [f64; 3]) -> Self {
        Self([colour; DOME_SIDES])
    }

    /// The colours in the azimuths of the dome's vertices, vertex 0 toward the sun and
    /// then 30° apart from south toward east ([`crate::dome::dome_vertex`]).
    pub fn per_vertex(colours: [[f64; 3]; DOME_SIDES]) -> Self {
        Self(colours)
    }

    /// The colour of each of the dome's 12 horizon vertices.
    pub fn colours(&self) -> [[f64; 3]; DOME_SIDES] {
        self.0
    }
}

/// The sky's colours and the air's transmittance, as the caller's simulation says:
/// SGSky's `repaint` arguments with the transmittance SGSky derives from `sun_angle`
/// and `moon_angle` given outright ([`Sky::repaint_explicit`]).
///
/// Colours are radiances in the unit of the atmosphere's `sun_irradiance` (what
/// [`Paint`] holds), finite and ≥ 0; transmittances are per channel, in [0, 1].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExplicitPaint {
    /// The sky's radiance at the zenith (SGSky's `sky_color`).
    pub sky_colour: [f64; 3],
    /// The horizon's radiance (SGSky's `fog_color`).
    pub fog: HorizonColours,
    /// The air's transmittance from the viewer toward the sun.
    pub sun_transmittance: [f64; 3],
    /// The air's transmittance from the viewer toward the moon.
    pub moon_transmittance: [f64; 3],
    /// The air's transmittance from the viewer toward the zenith: every planet and star
    /// takes its power of the airmass toward it.
    pub zenith_transmittance: [f64; 3],
}

/// The lowest distance of the moon, in moon radii: its disc at most 30° in radius.
const MOON_DISTANCE_MIN_RADII: f64 = 2.0;
/// The largest distance of the moon, in moon radii (1.7 × 10⁹ m).
const MOON_DISTANCE_MAX_RADII: f64 = 1e6;

/// The field names of one equatorial place.
struct PlaceFields {
    right_ascension: &'static str,
    declination: &'static str,
    distance_m: &'static str,
}

macro_rules! place_fields {
    ($name:literal) => {
        PlaceFields {
            right_ascension: concat!($name, ".right_ascension"),
            declination: concat!($name, ".declination"),
            distance_m: concat!($name, ".distance_m"),
        }
    };
}

/// The field names of the planets' places and magnitudes, in [`Planet::ALL`]'s order.
const PLANET_FIELDS: [(PlaceFields, &str); 7] = [
    (
        place_fields!("planets[Mercury].place"),
        "planets[Mercury].magnitude",
    ),
    (
        place_fields!("planets[Venus].place"),
        "planets[Venus].magnitude",
    ),
    (
        place_fields!("planets[Mars].place"),
        "planets[Mars].magnitude",
    ),
    (
        place_fields!("planets[Jupiter].place"),
        "planets[Jupiter].magnitude",
    ),
    (
        place_fields!("planets[Saturn].place"),
        "planets[Saturn].magnitude",
    ),
    (
        place_fields!("planets[Uranus].place"),
        "planets[Uranus].magnitude",
    ),
    (
        place_fields!("planets[Neptune].place"),
        "planets[Neptune].magnitude",
    ),
];

/// An angle's degrees, finite and within `[min, max]`, or the error naming `field`.
fn check_degrees(field: &'static str, angle: Angle, min: f64, max: f64) -> Result<()> {
    check_range(field, angle.degrees(), min, max, "°").map(|_| ())
}

/// A place's right ascension (any turn, [−360°, 360°]), declination ([−90°, 90°]) and
/// distance (`[min, max]` m).
fn check_place(fields: &PlaceFields, place: &EquatorialPlace, min: f64, max: f64) -> Result<()> {
    check_degrees(fields.right_ascension, place.right_ascension, -360.0, 360.0)?;
    check_degrees(fields.declination, place.declination, -90.0, 90.0)?;
    check_range(fields.distance_m, place.distance_m, min, max, "m").map(|_| ())
}

/// Each channel finite and within `[min, max]`, or the error naming `field`.
fn check_channels(field: &'static str, values: [f64; 3], min: f64, max: f64) -> Result<()> {
    for value in values {
        check_range(field, value, min, max, "")?;
    }
    Ok(())
}

impl ExplicitPlacement {
    /// Checks every field: finite, angles in range, distances positive (the sun's in
    /// [0.9, 1.1] AU, the moon's in [2, 10⁶] moon radii), magnitudes in [−10, 30].
    pub fn validate(&self) -> Result<()> {
        check_degrees(
            "greenwich_sidereal_time",
            self.greenwich_sidereal_time,
            -360.0,
            360.0,
        )?;
        check_place(
            &place_fields!("sun"),
            &self.sun,
            0.9 * ASTRONOMICAL_UNIT_M,
            1.1 * ASTRONOMICAL_UNIT_M,
        )?;
        check_place(
            &place_fields!("moon"),
            &self.moon,
            MOON_DISTANCE_MIN_RADII * MOON_RADIUS_M,
            MOON_DISTANCE_MAX_RADII * MOON_RADIUS_M,
        )?;
        for planet in &self.planets {
            let index = Planet::ALL
                .iter()
                .position(|&p| p == planet.planet)
                .expect("Planet::ALL lists every planet");
            let (place, magnitude) = &PLANET_FIELDS[index];
            check_place(place, &planet.place, f64::MIN_POSITIVE, 1e15)?;
            check_range(magnitude, planet.magnitude, -10.0, 30.0, "mag")?;
        }
        Ok(())
    }
}

impl ExplicitPaint {
    /// Checks every field: colours finite and ≥ 0, transmittances in [0, 1].
    pub fn validate(&self) -> Result<()> {
        check_channels("sky_colour", self.sky_colour, 0.0, f64::MAX)?;
        for colour in self.fog.colours() {
            check_channels("fog", colour, 0.0, f64::MAX)?;
        }
        check_channels("sun_transmittance", self.sun_transmittance, 0.0, 1.0)?;
        check_channels("moon_transmittance", self.moon_transmittance, 0.0, 1.0)?;
        check_channels("zenith_transmittance", self.zenith_transmittance, 0.0, 1.0)
    }
}

/// The unit vector of an equatorial place (x toward the equinox, z toward the pole).
fn place_direction(place: &EquatorialPlace) -> DVec3 {
    let (sin_a, cos_a) = place.right_ascension.radians().sin_cos();
    let (sin_d, cos_d) = place.declination.radians().sin_cos();
    DVec3::new(cos_d * cos_a, cos_d * sin_a, sin_d)
}

/// Relative optical airmass toward a body at true (airless) elevation `elevation`:
/// Kasten & Young 1989 (Applied Optics 28, 4735), `1 / (sin γ + 0.50572 (γ +
/// 6.07995°)^−1.6364)` with γ in degrees, within 0.5 % of their tables' path through a
/// model atmosphere up to γ = 0 (airmass ≈ 38); below the true horizon, where the fit
/// was not made, its horizon value.
pub fn kasten_young_airmass(elevation: Angle) -> f64 {
    let gamma = elevation.degrees().clamp(0.0, 90.0);
    1.0 / (gamma.to_radians().sin() + 0.50572 * (gamma + 6.07995).powf(-1.6364))
}

impl Sky {
    /// SGSky's `reposition` with explicit places (FlightGear's drive): every object
    /// placed from `drive` instead of the ephemerides — the sun, moon and planets by
    /// their hour angle (the Greenwich sidereal time + east longitude − α) and
    /// declination at the observer's latitude ([`Horizontal::from_equatorial`]), the
    /// catalogue's stars at their apparent places at `drive.star_instant` turned by the
    /// same sidereal time ([`StarCatalogue::sky_at_sidereal_time`]). Fills the same
    /// [`Placement`] as [`Sky::reposition`]: the dome's spin, the luminance scale, the
    /// moon's phase ([`moon_phase`] from the two given places, as the viewer sees them),
    /// parallactic angle and light. The bodies' geocentric places there are the given
    /// ones less the viewer's parallax ([`geocentric_from_topocentric`]); each
    /// planet's distance from the sun and phase angle come from its place and the
    /// sun's.
    pub fn reposition_explicit(&mut self, drive: &ExplicitPlacement) -> Result<&Placement> {
        drive.validate()?;
        let observer = drive.observer;
        let latitude = observer.latitude();
        let local_sidereal_time =
            (drive.greenwich_sidereal_time + observer.longitude()).wrapped_positive();
        let hour_angle = |place: &EquatorialPlace| local_sidereal_time - place.right_ascension;
        let airless = |place: &EquatorialPlace| {
            Horizontal::from_equatorial(hour_angle(place), place.declination, latitude)
        };
        let geocentric = |place: &EquatorialPlace| {
            geocentric_from_topocentric(place, local_sidereal_time, &observer)
        };

        let sun_geocentric = geocentric(&drive.sun);
        let sun = SunPosition {
            airless: airless(&drive.sun),
            right_ascension: sun_geocentric.right_ascension,
            declination: sun_geocentric.declination,
            distance_m: sun_geocentric.distance_m,
        };
        let moon = MoonPosition {
            airless: airless(&drive.moon),
            geocentric: geocentric(&drive.moon),
            topocentric: drive.moon,
            angular_radius: Angle::from_radians((MOON_RADIUS_M / drive.moon.distance_m).asin()),
            phase: moon_phase(&drive.moon, &drive.sun),
            parallactic_angle: Angle::from_radians(parallactic_angle(
                hour_angle(&drive.moon).radians(),
                drive.moon.declination.radians(),
                latitude.radians(),
            )),
        };
        let to_sun = place_direction(&drive.sun) * drive.sun.distance_m;
        let planets = drive
            .planets
            .iter()
            .map(|p| {
                let to_planet = place_direction(&p.place) * p.place.distance_m;
                let planet_to_sun = to_sun - to_planet;
                PlanetPosition {
                    planet: p.planet,
                    airless: airless(&p.place),
                    geocentric: geocentric(&p.place),
                    heliocentric_distance_m: planet_to_sun.length(),
                    phase_angle: Angle::from_radians(planet_to_sun.angle_between(-to_planet)),
                    magnitude: p.magnitude,
                }
            })
            .collect();
        let stars =
            self.catalogue
                .sky_at_sidereal_time(&drive.star_instant, local_sidereal_time, latitude);
        self.place(drive.star_instant, observer, sun, moon, planets, stars)
    }

    /// SGSky's `repaint` with explicit colours and transmittance (FlightGear's drive):
    /// builds the same [`Paint`] as [`Sky::repaint`] from `paint` instead of a sky
    /// model, for the current placement (either `reposition`):
    /// * the dome: SGSky's weights ([`SkyDome::seed_weights_less_aureole`]) between the
    ///   sky and fog colours, less the aureole, which is drawn per pixel over it (so the
    ///   backdrop shows the given colours at the zenith and on the horizon), whatever
    ///   [`SkyOptions::dome`] says;
    /// * the sun's and moon's discs as `repaint` draws them, through the given
    ///   transmittance, one value across each disc; the aureole through the sun's;
    /// * every planet and star above the horizon through `zenith_transmittance` to the
    ///   power of its airmass ([`kasten_young_airmass`]; 0 where the ray meets the
    ///   ground), against the painted sky's luminance in its direction plus the natural
    ///   night sky's, twinkling as the options say;
    /// * each cloud layer lit by the stronger of the sun and the moon through the given
    ///   transmittance (the viewer's, at every layer: SGSky's one light colour) under
    ///   skylight π × the sky colour.
    pub fn repaint_explicit(&mut self, paint: &ExplicitPaint) -> Result<&Paint> {
        paint.validate()?;
        let placement = self.placed("repaint_explicit")?;
        let atmosphere = &self.atmosphere;
        let altitude = placement.observer.elevation_m();
        // Unit as the model path makes them (the same rounding).
        let drawn_sun = unit_direction(
            "sun disc direction",
            self.apparent(placement.sun.airless).to_enu(),
        )?;
        let drawn_moon = unit_direction(
            "moon disc direction",
            self.apparent(placement.moon_light.horizontal()).to_enu(),
        )?;
        let discs = [
            sun_disc_object(
                atmosphere,
                drawn_sun,
                TransmittanceFit::flat(paint.sun_transmittance, drawn_sun.z),
            ),
            moon_disc_object(&placement.moon_light, drawn_moon, |_| {
                Ok(TransmittanceFit::flat(
                    paint.moon_transmittance,
                    drawn_moon.z,
                ))
            })?,
        ];
        let aureole = Aureole::along(atmosphere, altitude, drawn_sun, paint.sun_transmittance);
        let aureole_radiance =
            |direction: [f64; 3]| aureole.radiance(direction.map(|c| c as f32)).map(f64::from);
        let fog_colours = paint.fog.colours();
        let dome = SkyDome::seed_weights_less_aureole(
            paint.sky_colour,
            fog_colours,
            placement.spin,
            aureole_radiance,
        );

        let floor = luminance_from_surface_brightness(NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2);
        let mut points = Vec::new();
        let mut add = |index: u32, place: Horizontal, illuminance_lx: f64, colour: [f64; 3]| {
            let apparent = self.apparent(place);
            if apparent.elevation.radians() < POINT_LOWEST_ELEVATION_RAD {
                return;
            }
            let direction = apparent.to_enu();
            let airmass = kasten_young_airmass(place.elevation);
            let transmittance =
                if ray_hits_ground(atmosphere, altitude, DVec3::from_array(direction)) {
                    [0.0; 3]
                } else {
                    paint.zenith_transmittance.map(|t| t.powf(airmass))
                };
            let dome_radiance = dome.radiance(direction);
            let aureole = aureole_radiance(direction);
            let sky: [f64; 3] = std::array::from_fn(|i| dome_radiance[i] + aureole[i]);
            let mut point = PointSource {
                direction: direction.map(|c| c as f32),
                illuminance_lux: illuminance_lx as f32,
                colour: colour.map(|c| c as f32),
                background_luminance: (placement.scale.luminance(sky) + floor) as f32,
                transmittance: transmittance.map(|t| t as f32),
                scintillation: 1.0,
            };
            self.scintillate(&mut point, index, altitude, || airmass);
            points.push(point);
        };
        for (i, p) in placement.planets.iter().enumerate() {
            add(
                i as u32,
                p.airless,
                illuminance_from_magnitude(p.magnitude),
                star_colour_from_b_minus_v(p.planet.b_minus_v()),
            );
        }
        for star in &placement.stars {
            add(
                star.hip as u32,
                star.airless,
                star.illuminance_lx,
                star.colour,
            );
        }

        let sun_light = placement.sun.airless.to_enu();
        let moon_light = placement.moon_light;
        let sun_irradiance: [f64; 3] =
            std::array::from_fn(|i| atmosphere.sun_irradiance[i] * paint.sun_transmittance[i]);
        let moon_irradiance: [f64; 3] =
            std::array::from_fn(|i| moon_light.irradiance[i] * paint.moon_transmittance[i]);
        let layer_light = vec![
            LayerLight::stronger_source(
                (sun_light, sun_irradiance),
                (moon_light.direction, moon_irradiance),
                paint.sky_colour,
            );
            self.layers.len()
        ];
        let angles = [
            placement.sun.airless.zenith_angle(),
            placement.moon.airless.zenith_angle(),
        ];
        self.keep_paint(Paint {
            sky_colour: paint.sky_colour,
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
}
