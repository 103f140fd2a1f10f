//! Rung 1 of the ladder: seed 000's closed form in spherical geometry, per pixel
//! ([`ClosedFormSky`]) or per vertex of a dome ([`crate::dome::DomeInterpolated`]).
//! Twin of `shaders/atmos/closed_form_sky.wgsl`.
//!
//! The closed form assumes constant density. Earth's exponential layers become one
//! homogeneous shell of thickness `H_R` (the Rayleigh scale height) above the ground,
//! with the Mie coefficient scaled by `H_M / H_R`, so that both constituents keep their
//! true vertical optical depth; ozone is not modelled. In-scatter along the view path
//! is driven by sunlight attenuated by the transmittance *averaged* over the sun's path
//! through the shell, `(1 − e^{−τ})/τ`: the closed form needs one value for the whole
//! path, and most scattering happens above the viewer where the sun is less dimmed.

use crate::closed_form::{closed_form_extinction, closed_form_inscatter};
use crate::geometry::ray_sphere_intersect;
use crate::ladder::{SkyModel, SkyQuery, SkySample};
use crate::transmittance::one_minus_exp_neg;
use crate::{AtmosError, Atmosphere};

/// The closed form's parameters; layout identical to WGSL `ClosedFormSkyParameters`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ClosedFormSkyParameters {
    /// Rayleigh scattering (1/m).
    pub beta_rayleigh: [f32; 3],
    /// Mie anisotropy (Henyey–Greenstein, as in seed 000).
    pub mie_g: f32,
    /// Homogeneous-equivalent Mie scattering, `β_M · H_M / H_R` (1/m).
    pub beta_mie: [f32; 3],
    /// Planet radius (m).
    pub planet_radius: f32,
    /// Sun irradiance above the atmosphere (sets the radiance unit).
    pub sun_irradiance: [f32; 3],
    /// `planet_radius + H_R` (m).
    pub shell_radius: f32,
}

impl ClosedFormSkyParameters {
    /// The homogeneous shell equivalent to `atmosphere` (validated first).
    pub fn from_atmosphere(atmosphere: &Atmosphere) -> Result<Self, AtmosError> {
        atmosphere.validate()?;
        let f = |v: [f64; 3]| v.map(|x| x as f32);
        let mie_scale = atmosphere.mie_scale_height / atmosphere.rayleigh_scale_height;
        Ok(Self {
            beta_rayleigh: f(atmosphere.rayleigh_scattering),
            mie_g: atmosphere.mie_g as f32,
            beta_mie: f(atmosphere.mie_scattering.map(|b| b * mie_scale)),
            planet_radius: atmosphere.planet_radius as f32,
            sun_irradiance: f(atmosphere.sun_irradiance),
            shell_radius: (atmosphere.planet_radius + atmosphere.rayleigh_scale_height) as f32,
        })
    }
}

/// Sunlight driving the in-scatter at a viewer at radius `r` with sun zenith cosine
/// `mu_s`: irradiance × `(1 − e^{−τ})/τ` over the sun's path through the shell; 0 when
/// the planet hides the sun's centre.
pub fn closed_form_sunlight(r: f32, mu_s: f32, params: &ClosedFormSkyParameters) -> [f32; 3] {
    let sun_ground = ray_sphere_intersect(r, mu_s, params.planet_radius);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu_s < 0.0 && sun_ground[0] >= 0.0 {
        return [0.0; 3];
    }
    let sun_shell = ray_sphere_intersect(r, mu_s, params.shell_radius);
    let path = (sun_shell[1] - sun_shell[0].max(0.0)).max(0.0);
    std::array::from_fn(|i| {
        let optical_depth = (params.beta_rayleigh[i] + params.beta_mie[i]) * path;
        let average = if optical_depth > 0.0 {
            one_minus_exp_neg(optical_depth) / optical_depth
        } else {
            1.0
        };
        params.sun_irradiance[i] * average
    })
}

/// Length (m) of the view ray's segment inside the shell, from the viewer (or where
/// the ray enters the shell) to where it leaves it, hits the ground, or `max_distance`.
pub fn closed_form_path_length(
    r: f32,
    mu: f32,
    max_distance: f32,
    params: &ClosedFormSkyParameters,
) -> f32 {
    let shell = ray_sphere_intersect(r, mu, params.shell_radius);
    if shell[1] < 0.0 {
        return 0.0;
    }
    let ground = ray_sphere_intersect(r, mu, params.planet_radius);
    let mut end = shell[1].min(max_distance);
    if mu < 0.0 && ground[0] >= 0.0 {
        end = end.min(ground[0]);
    }
    (end - shell[0].max(0.0)).max(0.0)
}

/// In-scattered radiance along the view ray `(r, mu)` with view–sun cosine `nu`,
/// given the sunlight from [`closed_form_sunlight`].
pub fn closed_form_sky_radiance(
    r: f32,
    mu: f32,
    nu: f32,
    max_distance: f32,
    sunlight: [f32; 3],
    params: &ClosedFormSkyParameters,
) -> [f32; 3] {
    let path = closed_form_path_length(r, mu, max_distance, params);
    let inscatter = closed_form_inscatter(
        params.beta_rayleigh,
        params.beta_mie,
        nu,
        params.mie_g,
        path,
    );
    std::array::from_fn(|i| sunlight[i] * inscatter[i])
}

/// Transmittance of the same segment.
pub fn closed_form_sky_transmittance(
    r: f32,
    mu: f32,
    max_distance: f32,
    params: &ClosedFormSkyParameters,
) -> [f32; 3] {
    let path = closed_form_path_length(r, mu, max_distance, params);
    closed_form_extinction(params.beta_rayleigh, params.beta_mie, path)
}

/// Rung 1 per pixel: the closed form evaluated for every query.
#[derive(Debug, Clone, PartialEq)]
pub struct ClosedFormSky {
    params: ClosedFormSkyParameters,
}

impl ClosedFormSky {
    /// The closed form for `atmosphere` (validated).
    pub fn new(atmosphere: &Atmosphere) -> Result<Self, AtmosError> {
        Ok(Self {
            params: ClosedFormSkyParameters::from_atmosphere(atmosphere)?,
        })
    }

    /// The uniform block shared with WGSL.
    pub fn parameters(&self) -> &ClosedFormSkyParameters {
        &self.params
    }
}

impl SkyModel for ClosedFormSky {
    fn label(&self) -> String {
        "closed form, per pixel".into()
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        let r = query.r() as f32;
        let (mu, mu_s, nu) = (query.mu() as f32, query.mu_s() as f32, query.nu() as f32);
        let max_distance = query.max_distance().min(f64::from(f32::MAX)) as f32;
        let sunlight = closed_form_sunlight(r, mu_s, &self.params);
        let radiance = closed_form_sky_radiance(r, mu, nu, max_distance, sunlight, &self.params);
        let transmittance = closed_form_sky_transmittance(r, mu, max_distance, &self.params);
        SkySample {
            radiance: radiance.map(f64::from),
            transmittance: transmittance.map(f64::from),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn query(altitude: f64, view_elevation: f64, sun_elevation: f64) -> SkyQuery {
        let r = 6_360_000.0 + altitude;
        let dir = |e: f64, a: f64| DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin());
        SkyQuery::new(
            6_360_000.0,
            DVec3::new(0.0, 0.0, r),
            dir(view_elevation, 0.0),
            dir(sun_elevation, 1.0),
        )
        .unwrap()
    }

    #[test]
    fn zenith_path_is_the_shell_thickness_and_sunlight_is_the_column_average() {
        let sky = ClosedFormSky::new(&Atmosphere::earth()).unwrap();
        let p = sky.parameters();
        let r = p.planet_radius;
        assert!((closed_form_path_length(r, 1.0, f32::MAX, p) - 8_000.0).abs() < 1.0);
        let light = closed_form_sunlight(r, 1.0, p);
        let tau = (p.beta_rayleigh[2] + p.beta_mie[2]) * 8_000.0;
        assert!((light[2] - (1.0 - (-tau).exp()) / tau).abs() < 1e-5);
        // Sun below the horizon: no sunlight.
        assert_eq!(closed_form_sunlight(r, -0.1, p), [0.0; 3]);
    }

    #[test]
    fn rayleigh_only_noon_zenith_is_blue_and_horizon_brighter() {
        let mut earth = Atmosphere::earth();
        earth.mie_scattering = [0.0; 3];
        earth.mie_extinction = [0.0; 3];
        let sky = ClosedFormSky::new(&earth).unwrap();
        let zenith = sky.evaluate(&query(2.0, 1.5, 1.5)).radiance;
        assert!(zenith[2] > zenith[1] && zenith[1] > zenith[0], "{zenith:?}");
        let horizon = sky.evaluate(&query(2.0, 0.02, 1.5)).radiance;
        assert!(crate::ladder::luminance(horizon) > crate::ladder::luminance(zenith));
    }

    #[test]
    fn viewer_above_the_shell_sees_through_it_and_space_is_dark() {
        let sky = ClosedFormSky::new(&Atmosphere::earth()).unwrap();
        let down = sky.evaluate(&query(100_000.0, -1.5, 0.5));
        assert!(down.radiance[2] > 0.0 && down.transmittance[2] < 1.0);
        let up = sky.evaluate(&query(100_000.0, 1.0, 0.5));
        assert_eq!(up.radiance, [0.0; 3]);
        assert_eq!(up.transmittance, [1.0; 3]);
    }

    #[test]
    fn bad_atmosphere_is_rejected() {
        let mut a = Atmosphere::earth();
        a.mie_g = 1.0;
        assert!(
            ClosedFormSky::new(&a)
                .unwrap_err()
                .to_string()
                .contains("mie_g")
        );
    }
}
