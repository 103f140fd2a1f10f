//! The sky's light sources in the atmosphere's units: how many lux one unit of
//! [`atmos::Atmosphere::sun_irradiance`] is ([`LuminanceScale`]), and the moon as a
//! light source ([`MoonLight`]) — its irradiance for atmos (a moonlit sky is the same
//! scattering with the moon's irradiance from the moon's direction) and its illuminance
//! for terrain.
//!
//! The atmosphere owns the sun's irradiance and angular radius; nothing here defines a
//! second one. The photometric scale comes from the sun's apparent magnitude
//! ([`crate::photometry::SUN_V_MAGNITUDE_AT_1_AU`]) at its distance of the day, so stars,
//! planets, the moon and the sky share one luminance scale.

use atmos::Atmosphere;
use atmos::ladder::luminance;

use crate::colour::star_colour_from_b_minus_v;
use crate::error::{CelestialError, Result};
use crate::moon::MoonPosition;
use crate::photometry::{illuminance_from_magnitude, moon_magnitude, sun_illuminance_lx};
use crate::sun::SunPosition;
use crate::{Angle, Horizontal};

/// Converts the atmosphere's radiance unit to photometric units: `lux_per_unit` lux per
/// unit of `sun_irradiance`'s luminance, so radiance × `lux_per_unit` is cd·m⁻².
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LuminanceScale {
    lux_per_unit: f64,
}

impl LuminanceScale {
    /// The scale at which `atmosphere.sun_irradiance` is the sun's illuminance at
    /// `sun_distance_m` (its magnitude, [`sun_illuminance_lx`]).
    pub fn new(atmosphere: &Atmosphere, sun_distance_m: f64) -> Result<Self> {
        crate::error::check_range(
            "sun_distance_m",
            sun_distance_m,
            0.9 * crate::sun::ASTRONOMICAL_UNIT_M,
            1.1 * crate::sun::ASTRONOMICAL_UNIT_M,
            "m",
        )?;
        let sun = luminance(atmosphere.sun_irradiance);
        if !(sun.is_finite() && sun > 0.0) {
            return Err(CelestialError::OutOfRange {
                field: "atmosphere.sun_irradiance (luminance)",
                value: sun,
                min: f64::MIN_POSITIVE,
                max: f64::MAX,
                unit: "atmos units",
            });
        }
        Ok(Self {
            lux_per_unit: sun_illuminance_lx(sun_distance_m) / sun,
        })
    }

    /// Lux per unit of the atmosphere's irradiance (and cd·m⁻² per unit of radiance).
    pub fn lux_per_unit(&self) -> f64 {
        self.lux_per_unit
    }

    /// Luminance (cd·m⁻²) of a radiance in the atmosphere's unit.
    pub fn luminance(&self, radiance: [f64; 3]) -> f64 {
        luminance(radiance) * self.lux_per_unit
    }
}

/// B−V colour index of the moon (Allen's *Astrophysical Quantities*, 4th ed., Cox
/// 2000, §12.4): redder than the sunlight it reflects.
pub const MOON_B_MINUS_V: f64 = 0.92;
/// B−V of the sun (Ramírez et al. 2012, ApJ 752, 5: 0.653 ± 0.003).
pub const SUN_B_MINUS_V: f64 = 0.653;

/// The moon as a light source for one observer at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoonLight {
    /// Unit east/north/up direction of the moon (topocentric, airless).
    pub direction: [f64; 3],
    /// Illuminance outside the atmosphere (lux), from the moon's magnitude.
    pub illuminance_lx: f64,
    /// The same in the atmosphere's irradiance unit, per channel, with the moon's
    /// colour (the sun's irradiance reddened from B−V 0.653 to 0.92 at equal luminance).
    pub irradiance: [f64; 3],
    /// Angular radius of the disc.
    pub angular_radius: Angle,
    /// Phase angle (sun–moon–observer).
    pub phase_angle: Angle,
    /// Unit east/north/up direction from the moon toward the sun.
    pub toward_sun: [f64; 3],
}

impl MoonLight {
    /// The moon at `moon`, lit by the sun at `sun`, in the units of `atmosphere`'s
    /// irradiance (`scale` relates them to lux).
    pub fn new(
        moon: &MoonPosition,
        sun: &SunPosition,
        atmosphere: &Atmosphere,
        scale: &LuminanceScale,
    ) -> Result<Self> {
        let magnitude = moon_magnitude(
            moon.phase.phase_angle,
            moon.topocentric.distance_m,
            sun.distance_m,
        );
        let illuminance_lx = illuminance_from_magnitude(magnitude);
        let moon_colour = star_colour_from_b_minus_v(MOON_B_MINUS_V);
        let sun_colour = star_colour_from_b_minus_v(SUN_B_MINUS_V);
        let tint: [f64; 3] = std::array::from_fn(|i| moon_colour[i] / sun_colour[i]);
        let tinted: [f64; 3] = std::array::from_fn(|i| atmosphere.sun_irradiance[i] * tint[i]);
        let tinted_luminance = luminance(tinted);
        let unit = illuminance_lx / scale.lux_per_unit();
        let irradiance = tinted.map(|e| e * unit / tinted_luminance);
        let direction = moon.airless.to_enu();
        let sun_direction = sun.airless.to_enu();
        let toward: [f64; 3] = std::array::from_fn(|i| {
            sun_direction[i] * sun.distance_m - direction[i] * moon.topocentric.distance_m
        });
        let length = toward.iter().map(|c| c * c).sum::<f64>().sqrt();
        Ok(Self {
            direction,
            illuminance_lx,
            irradiance,
            angular_radius: moon.angular_radius,
            phase_angle: moon.phase.phase_angle,
            toward_sun: toward.map(|c| c / length),
        })
    }

    /// `atmosphere` lit by the moon instead of the sun: its `sun_irradiance` is the
    /// moon's and its `sun_angular_radius` the moon's. Any atmos rung built from it and
    /// queried with the moon's direction as the "sun" is the moonlit sky.
    pub fn atmosphere(&self, atmosphere: &Atmosphere) -> Atmosphere {
        Atmosphere {
            sun_irradiance: self.irradiance,
            sun_angular_radius: self.angular_radius.radians(),
            ..atmosphere.clone()
        }
    }

    /// Per channel, the moon's irradiance over the sun's: a sky computed for the sun's
    /// irradiance from the moon's direction, times this, is the moonlit sky (radiance is
    /// linear in the source; 0 where the atmosphere's sun irradiance is 0).
    pub fn sky_scale(&self, atmosphere: &Atmosphere) -> [f64; 3] {
        std::array::from_fn(|i| {
            let sun = atmosphere.sun_irradiance[i];
            if sun > 0.0 {
                self.irradiance[i] / sun
            } else {
                0.0
            }
        })
    }

    /// Illuminance (lux) the moon gives a surface at `cos_incidence` to it, through the
    /// atmosphere's `transmittance` toward the moon (per channel; luminance-weighted
    /// with the moon's colour): for terrain lighting. Below the surface's horizon, 0.
    pub fn ground_illuminance_lx(&self, transmittance: [f64; 3], cos_incidence: f64) -> f64 {
        let seen: [f64; 3] = std::array::from_fn(|i| self.irradiance[i] * transmittance[i]);
        let fraction = luminance(seen) / luminance(self.irradiance);
        self.illuminance_lx * fraction * cos_incidence.max(0.0)
    }

    /// The moon's direction as azimuth and elevation.
    pub fn horizontal(&self) -> Horizontal {
        Horizontal::from_enu(self.direction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Instant, Observer, moon_position, sun_position};

    #[test]
    fn scale_makes_the_sun_its_magnitude() {
        let atmosphere = Atmosphere::earth();
        let au = crate::sun::ASTRONOMICAL_UNIT_M;
        let scale = LuminanceScale::new(&atmosphere, au).unwrap();
        assert!((scale.luminance(atmosphere.sun_irradiance) - sun_illuminance_lx(au)).abs() < 1e-6);
        let dark = Atmosphere {
            sun_irradiance: [0.0; 3],
            ..Atmosphere::earth()
        };
        let error = LuminanceScale::new(&dark, au).unwrap_err().to_string();
        assert!(error.contains("sun_irradiance"), "{error}");
        let error = LuminanceScale::new(&atmosphere, f64::NAN)
            .unwrap_err()
            .to_string();
        assert!(error.contains("sun_distance_m"), "{error}");
    }

    /// A full moon (2024-04-23 23:49 UTC) gives ~0.3 lx, a quarter ~0.03 lx; the
    /// moonlit atmosphere keeps every other constant and the moon is redder.
    #[test]
    fn moon_light_full_and_quarter() {
        let atmosphere = Atmosphere::earth();
        let observer =
            Observer::new(Angle::from_degrees(0.0), Angle::from_degrees(0.0), 0.0).unwrap();
        let full = Instant::parse("2024-04-23T23:49:00Z").unwrap();
        let quarter = Instant::parse("2024-04-15T19:13:00Z").unwrap();
        let light = |instant: &Instant| {
            let sun = sun_position(instant, &observer).unwrap();
            let moon = moon_position(instant, &observer).unwrap();
            let scale = LuminanceScale::new(&atmosphere, sun.distance_m).unwrap();
            (
                MoonLight::new(&moon, &sun, &atmosphere, &scale).unwrap(),
                scale,
            )
        };
        let (full_light, scale) = light(&full);
        assert!(
            (0.2..0.4).contains(&full_light.illuminance_lx),
            "{}",
            full_light.illuminance_lx
        );
        assert!((scale.luminance(full_light.irradiance) - full_light.illuminance_lx).abs() < 1e-9);
        assert!(full_light.irradiance[0] / full_light.irradiance[2] > 1.0);
        let (quarter_light, _) = light(&quarter);
        assert!(
            (0.02..0.05).contains(&quarter_light.illuminance_lx),
            "{}",
            quarter_light.illuminance_lx
        );
        let moonlit = full_light.atmosphere(&atmosphere);
        assert_eq!(moonlit.sun_irradiance, full_light.irradiance);
        assert_eq!(moonlit.rayleigh_scattering, atmosphere.rayleigh_scattering);
        moonlit.validate().unwrap();
        // The moon's direction toward the sun is ~opposite the observer at full moon.
        let away: f64 = full_light
            .toward_sun
            .iter()
            .zip(full_light.direction)
            .map(|(a, b)| a * b)
            .sum();
        assert!(away < -0.99, "{away}");
        assert!(
            (full_light.ground_illuminance_lx([1.0; 3], 1.0) - full_light.illuminance_lx).abs()
                < 1e-12
        );
        assert_eq!(full_light.ground_illuminance_lx([1.0; 3], -0.5), 0.0);
    }
}
