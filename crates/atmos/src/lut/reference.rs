//! f64 references of the parameterisation and geometry functions of this rung, for
//! `cargo xtask parity`. The parameterisations are the generic functions of
//! [`super::parameterization`] re-exported (called with f64 arguments they are the f64
//! instantiation of the twin's formula); the rest are f64 versions of the pure helpers
//! of [`super::raymarch`] and [`super::multiple_scattering_moments`] (same names,
//! arguments and stable forms).

pub use super::multiple_scattering_moments::{
    direction_zenith_sample,
    multiple_scattering_ground_irradiance_channel as multiple_scattering_ground_irradiance,
    scattered_multiple_scattering_channel as scattered_multiple_scattering, sun_frame_direction,
};
pub use super::parameterization::{
    horizon_distance, horizon_zenith_angle, multiple_scattering_lut_r_mu_s,
    multiple_scattering_lut_uv, sky_view_lut_direction, sky_view_lut_uv, texel_uv_to_unit_range,
    transmittance_lut_r_mu, transmittance_lut_uv, unit_range_to_texel_uv, view_sun_cos_azimuth,
};
use crate::reference::ray_sphere_intersect;

/// f64 [`super::raymarch::radius_along_ray`].
pub fn radius_along_ray(r: f64, mu: f64, t: f64) -> f64 {
    (r * r + t * (2.0 * r * mu + t)).max(0.0).sqrt()
}

/// f64 [`super::raymarch::ray_segment_in_atmosphere`].
pub fn ray_segment_in_atmosphere(r: f64, mu: f64, planet_radius: f64, top_radius: f64) -> [f64; 3] {
    let r = r.max(planet_radius);
    let top = ray_sphere_intersect(r, mu, top_radius);
    if top[1] < 0.0 {
        return [0.0; 3];
    }
    let t_start = top[0].max(0.0);
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu < 0.0 && ground[0] >= 0.0 {
        return [t_start, ground[0], 1.0];
    }
    [t_start, top[1], 0.0]
}

/// f64 [`super::transmittance_lut::exponential_step_integral`] (with `exp_m1`).
pub fn exponential_step_integral(x0: f64, x1: f64, dt: f64) -> f64 {
    let delta = x1 - x0;
    let start = (-x0).exp();
    if delta == 0.0 {
        return dt * start;
    }
    dt * start * (-(-delta).exp_m1() / delta)
}
