//! Atmospheric refraction: the separate step from the airless ("true") elevation to
//! the apparent one.
//!
//! Sæmundsson's formula (Sky & Telescope 72, 70, 1986; Meeus eq. 16.4), the one NREL
//! SPA uses (Reda & Andreas 2004, eq. 42):
//!
//! R = 1.02′ / tan(h + 10.3°/(h + 5.11°)) · (P / 1010 hPa) · (283 K / T)
//!
//! with h the airless elevation in degrees. It agrees with Bennett's inverse formula
//! to 0.07′ for h ≥ 0 and is the standard 34′ at the horizon. Like SPA, refraction
//! is applied only while the airless elevation is above −0.83337° (SPA's cutoff:
//! the sun's upper limb on the horizon with 34′ + 16′); below it the body is set
//! and refraction is 0. The formula diverges near h = −4.6°, which the cutoff keeps
//! away from.

use crate::angle::Angle;
use crate::error::{Result, check_range};
use crate::horizontal::Horizontal;

/// Airless elevation below which refraction is not applied (degrees, as in SPA).
pub const REFRACTION_CUTOFF_DEGREES: f64 = -0.83337;

/// Air at the observer: pressure and temperature.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AirConditions {
    pressure_pa: f64,
    temperature_k: f64,
}

impl AirConditions {
    /// Sæmundsson's reference air, for which the formula gives its nominal values:
    /// 1010 hPa, 10 °C.
    pub const REFERENCE: AirConditions = AirConditions {
        pressure_pa: 101_000.0,
        temperature_k: 283.15,
    };

    /// Air at `pressure_pa` ∈ [0, 120 000] Pa (0: no atmosphere, no refraction) and
    /// `temperature_k` ∈ [150, 350] K.
    pub fn new(pressure_pa: f64, temperature_k: f64) -> Result<Self> {
        check_range("pressure_pa", pressure_pa, 0.0, 120_000.0, "Pa")?;
        check_range("temperature_k", temperature_k, 150.0, 350.0, "K")?;
        Ok(AirConditions {
            pressure_pa,
            temperature_k,
        })
    }

    /// Pressure (Pa).
    pub fn pressure_pa(&self) -> f64 {
        self.pressure_pa
    }

    /// Temperature (K).
    pub fn temperature_k(&self) -> f64 {
        self.temperature_k
    }
}

/// Refraction R (apparent − airless elevation) for a body at airless elevation
/// `true_elevation` in `air`; zero below [`REFRACTION_CUTOFF_DEGREES`].
pub fn refraction(true_elevation: Angle, air: &AirConditions) -> Angle {
    let h = true_elevation.degrees();
    if h.is_nan() || h <= REFRACTION_CUTOFF_DEGREES {
        return Angle::ZERO;
    }
    let arcminutes = 1.02 / Angle::from_degrees(h + 10.3 / (h + 5.11)).radians().tan()
        * (air.pressure_pa / 101_000.0)
        * (283.0 / (air.temperature_k - 0.15));
    Angle::from_degrees(arcminutes / 60.0)
}

/// Apparent elevation: `true_elevation` lifted by [`refraction`].
pub fn apparent_elevation(true_elevation: Angle, air: &AirConditions) -> Angle {
    true_elevation + refraction(true_elevation, air)
}

/// The direction a body at airless direction `airless` is seen in through `air`:
/// azimuth unchanged, elevation lifted by [`refraction`]. The one step every body's
/// `apparent` takes (sun, moon, planets, stars).
pub fn apparent_direction(airless: Horizontal, air: &AirConditions) -> Horizontal {
    Horizontal {
        azimuth: airless.azimuth,
        elevation: apparent_elevation(airless.elevation, air),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form at the horizon (28.99′ for the reference air), the zenith
    /// limit, monotonicity over the applied range, and the cutoff.
    #[test]
    fn magnitudes_and_limits() {
        let air = AirConditions::REFERENCE;
        let at = |deg: f64| refraction(Angle::from_degrees(deg), &air).degrees() * 60.0;
        // h = 0: 1.02 / tan(10.3/5.11 °) = 28.99′.
        let expected = 1.02 / (10.3_f64 / 5.11).to_radians().tan();
        assert!((at(0.0) - expected).abs() < 1e-12 && (at(0.0) - 28.99).abs() < 0.01);
        // h = 90°: tan(90.108°) = −530 → R = −0.0019′ (the formula's known zenith
        // residue, 3·10⁻⁵°; Meeus p. 106).
        assert!((at(90.0) + 0.0019).abs() < 1e-4, "{}", at(90.0));
        // Monotone decreasing from the cutoff to 89°.
        let mut previous = f64::INFINITY;
        for tenth in -8..890 {
            let r = at(f64::from(tenth) / 10.0);
            assert!(r < previous && r > 0.0, "{tenth}");
            previous = r;
        }
        assert_eq!(at(-1.0), 0.0);
        assert_eq!(at(f64::NAN), 0.0);
        let vacuum = AirConditions::new(0.0, 288.0).unwrap();
        assert_eq!(refraction(Angle::from_degrees(10.0), &vacuum), Angle::ZERO);
    }

    #[test]
    fn rejects_bad_air() {
        use crate::error::CelestialError;
        assert!(matches!(
            AirConditions::new(-1.0, 288.0),
            Err(CelestialError::OutOfRange {
                field: "pressure_pa",
                ..
            })
        ));
        assert!(matches!(
            AirConditions::new(101_325.0, f64::NAN),
            Err(CelestialError::NotFinite {
                field: "temperature_k",
                ..
            })
        ));
    }
}
