//! The light of a march without `atmos`.

use atmos::real::Real;

use super::*;

/// The light of a march without `atmos`: explicit sun direction and irradiance, ambient
/// radiance and the up direction of the ambient visibility (field frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lighting<F> {
    pub(super) sun_direction: [F; 3],
    pub(super) sun_irradiance: [F; 3],
    pub(super) ambient_radiance: [F; 3],
    pub(super) up: [F; 3],
}

fn check_unit(field: &'static str, v: [f64; 3]) -> Result<[f64; 3], MarchError> {
    for c in v {
        if !c.is_finite() {
            return Err(invalid(field, c, "components must be finite"));
        }
    }
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if (n - 1.0).abs() > 1e-3 {
        return Err(invalid(field, n, "length must be 1 (within 1e-3)"));
    }
    Ok(v.map(|c| c / n))
}

fn check_colour(field: &'static str, v: [f64; 3]) -> Result<(), MarchError> {
    for c in v {
        if !(c >= 0.0 && c.is_finite()) {
            return Err(invalid(field, c, "components must be finite and ≥ 0"));
        }
    }
    Ok(())
}

impl<F: Real> Lighting<F> {
    /// `sun_direction` (unit, toward the sun; may point below the horizon),
    /// `sun_irradiance` (per channel, ≥ 0, on a surface facing the sun, at the cloud),
    /// `ambient_radiance` (isotropic sky radiance per channel, ≥ 0, same unit per sr),
    /// `up` (unit; the direction the ambient light is taken to come from).
    /// Directions are renormalised; errors name the field and value.
    pub fn new(
        sun_direction: [f64; 3],
        sun_irradiance: [f64; 3],
        ambient_radiance: [f64; 3],
        up: [f64; 3],
    ) -> Result<Self, MarchError> {
        let sun_direction = check_unit("sun_direction", sun_direction)?;
        let up = check_unit("up", up)?;
        check_colour("sun_irradiance", sun_irradiance)?;
        check_colour("ambient_radiance", ambient_radiance)?;
        Ok(Self {
            sun_direction: sun_direction.map(F::of),
            sun_irradiance: sun_irradiance.map(F::of),
            ambient_radiance: ambient_radiance.map(F::of),
            up: up.map(F::of),
        })
    }

    /// A white sun of irradiance 1 along `sun_direction`, no ambient light (the Monte
    /// Carlo reference's lighting).
    pub fn white_sun(sun_direction: [f64; 3]) -> Result<Self, MarchError> {
        Self::new(sun_direction, [1.0; 3], [0.0; 3], [0.0, 0.0, 1.0])
    }

    /// Unit vector toward the sun.
    pub fn sun_direction(&self) -> [F; 3] {
        self.sun_direction
    }

    /// Sun irradiance per channel.
    pub fn sun_irradiance(&self) -> [F; 3] {
        self.sun_irradiance
    }

    /// Ambient radiance per channel.
    pub fn ambient_radiance(&self) -> [F; 3] {
        self.ambient_radiance
    }

    /// Unit up direction of the ambient visibility.
    pub fn up(&self) -> [F; 3] {
        self.up
    }
}
