//! Irradiance on a horizontal surface (terrain lighting) from any rung of the ladder:
//! the direct sun, attenuated along its path and projected on the surface, plus the
//! sky's radiance integrated over the upper hemisphere with the cosine weight.
//!
//! Units: those of `sun_irradiance` (the surface's outgoing Lambertian radiance is
//! `albedo/π ×` the sum). The sun is treated as a point (its disc's partial setting
//! behind the horizon is not modelled), as in every rung's single scattering.
//!
//! ```
//! use atmos::ground_irradiance::{ground_irradiance, HemisphereQuadrature};
//! use atmos::single_scattering::{SingleScatteringSettings, SingleScatteringSky};
//! use atmos::Atmosphere;
//! use glam::DVec3;
//!
//! let earth = Atmosphere::earth();
//! let sky = SingleScatteringSky::new(&earth, SingleScatteringSettings::default()).unwrap();
//! let here = DVec3::new(0.0, 0.0, earth.planet_radius);
//! let sun = DVec3::new(0.5, 0.0, 0.75f64.sqrt()); // 60° elevation
//! let e = ground_irradiance(&sky, &earth, here, sun, HemisphereQuadrature::default()).unwrap();
//! assert!(e.direct[0] > e.sky[0] && e.sky[2] > e.sky[0]); // the sky is blue
//! ```

use glam::DVec3;

use crate::reference::ray_sphere_intersect;
use crate::{AtmosError, Atmosphere, SkyModel, SkyQuery};

/// Irradiance on a horizontal surface, per channel (unit of `sun_irradiance`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GroundIrradiance {
    /// From the sun disc: transmittance × cos(sun zenith) × sun irradiance.
    pub direct: [f64; 3],
    /// From the sky: ∫ L cos θ dω over the upper hemisphere.
    pub sky: [f64; 3],
}

impl GroundIrradiance {
    /// direct + sky.
    pub fn total(&self) -> [f64; 3] {
        std::array::from_fn(|k| self.direct[k] + self.sky[k])
    }
}

/// Cells of the hemisphere integral: `zenith_cells` equal steps in zenith angle over
/// [0, π/2] times `azimuth_cells` equal steps in azimuth, each sampled at its angular
/// centre and weighted by its exact cosine-weighted solid angle
/// (sin²θ_b − sin²θ_a)/2 · Δφ, so a uniform sky of radiance L gives exactly πL. Equal
/// angle steps (rather than equal cosine-weighted areas) keep the bright horizon, where
/// radiance grows like the path length ~ 1/cos θ, resolved: the cosine weight cancels
/// that growth inside each cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct HemisphereQuadrature {
    /// Steps in sin²θ over [0, 1].
    pub zenith_cells: u32,
    /// Steps in azimuth over [0, 2π).
    pub azimuth_cells: u32,
}

impl Default for HemisphereQuadrature {
    /// 16 × 32 = 512 sky evaluations.
    fn default() -> Self {
        Self {
            zenith_cells: 16,
            azimuth_cells: 32,
        }
    }
}

/// Irradiance on a horizontal surface at `position` (planet-centred, m) with the sun
/// along `sun` (unit), from `model`'s radiance and transmittance.
pub fn ground_irradiance(
    model: &impl SkyModel,
    atmosphere: &Atmosphere,
    position: DVec3,
    sun: DVec3,
    quadrature: HemisphereQuadrature,
) -> Result<GroundIrradiance, AtmosError> {
    atmosphere.validate()?;
    for (field, cells) in [
        ("zenith_cells", quadrature.zenith_cells),
        ("azimuth_cells", quadrature.azimuth_cells),
    ] {
        if cells == 0 || cells > 4096 {
            return Err(AtmosError::InvalidSetting {
                setting: "irradiance quadrature",
                field: field.to_owned(),
                value: f64::from(cells),
                reason: "must be in 1..=4096",
            });
        }
    }
    let planet = atmosphere.planet_radius;
    let sun_query = SkyQuery::new(planet, position, sun, sun)?;
    let zenith = position.normalize();
    // Direct: zero when the sun is below the surface's horizon or behind the planet.
    let mu_s = sun_query.mu_s();
    let r = sun_query.r().max(planet);
    let behind_planet = mu_s < 0.0 && ray_sphere_intersect(r, mu_s, planet)[1] > 0.0;
    let direct = if mu_s <= 0.0 || behind_planet {
        [0.0; 3]
    } else {
        let t = model.evaluate(&sun_query).transmittance;
        std::array::from_fn(|k| t[k] * mu_s * atmosphere.sun_irradiance[k])
    };
    // A tangent frame at the point.
    let helper = if zenith.x.abs() < 0.9 {
        DVec3::X
    } else {
        DVec3::Y
    };
    let east = helper.cross(zenith).normalize();
    let north = zenith.cross(east);
    let (n_zenith, n_azimuth) = (quadrature.zenith_cells, quadrature.azimuth_cells);
    let d_theta = std::f64::consts::FRAC_PI_2 / f64::from(n_zenith);
    let d_phi = std::f64::consts::TAU / f64::from(n_azimuth);
    let mut sky = [0.0; 3];
    for i in 0..n_zenith {
        let (theta_a, theta_b) = (f64::from(i) * d_theta, f64::from(i + 1) * d_theta);
        let weight = 0.5 * (theta_b.sin().powi(2) - theta_a.sin().powi(2)) * d_phi;
        let (sin_theta, cos_theta) = ((f64::from(i) + 0.5) * d_theta).sin_cos();
        for j in 0..n_azimuth {
            let phi = std::f64::consts::TAU * (f64::from(j) + 0.5) / f64::from(n_azimuth);
            let view = zenith * cos_theta + (east * phi.cos() + north * phi.sin()) * sin_theta;
            let query = SkyQuery::new(planet, position, view, sun)?;
            let radiance = model.evaluate(&query).radiance;
            for k in 0..3 {
                sky[k] += weight * radiance[k];
            }
        }
    }
    Ok(GroundIrradiance { direct, sky })
}
