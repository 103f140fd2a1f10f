//! f64 references of the parameterisation and geometry functions of this rung, for
//! `cargo xtask parity`. The parameterisations are the generic functions of
//! [`super::parameterization`] re-exported (called with f64 arguments they are the f64
//! instantiation of the twin's formula), as are the pure helpers of
//! [`super::raymarch`], [`super::transmittance_lut`] and
//! [`super::multiple_scattering_moments`].

#[doc(inline)]
pub use super::multiple_scattering_moments::{
    direction_zenith_sample,
    multiple_scattering_ground_irradiance_channel as multiple_scattering_ground_irradiance,
    scattered_multiple_scattering_channel as scattered_multiple_scattering, sun_frame_direction,
};
#[doc(inline)]
pub use super::parameterization::{
    horizon_distance, horizon_zenith_angle, multiple_scattering_lut_r_mu_s,
    multiple_scattering_lut_uv, sky_view_lut_direction, sky_view_lut_uv, texel_uv_to_unit_range,
    transmittance_lut_r_mu, transmittance_lut_uv, unit_range_to_texel_uv, view_sun_cos_azimuth,
};
#[doc(inline)]
pub use super::raymarch::{
    integrate_scattering_step, point_along_ray, radius_along_ray, ray_segment_in_atmosphere,
    scattering_step_fraction,
};
#[doc(inline)]
pub use super::transmittance_lut::exponential_step_integral;
