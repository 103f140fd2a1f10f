//! f64 references of the parameterisation and geometry functions of this rung (same
//! names, arguments and stable forms as [`super::parameterization`] and the pure
//! helpers of [`super::raymarch`]), for `cargo xtask parity`.

use std::f64::consts::PI;

use crate::reference::ray_sphere_intersect;

/// f64 [`super::parameterization::unit_range_to_texel_uv`].
pub fn unit_range_to_texel_uv(x: f64, texel_count: u32) -> f64 {
    let n = f64::from(texel_count);
    0.5 / n + x * (1.0 - 1.0 / n)
}

/// f64 [`super::parameterization::texel_uv_to_unit_range`].
pub fn texel_uv_to_unit_range(u: f64, texel_count: u32) -> f64 {
    let n = f64::from(texel_count);
    (u - 0.5 / n) / (1.0 - 1.0 / n)
}

/// f64 [`super::parameterization::horizon_distance`].
pub fn horizon_distance(a: f64, b: f64) -> f64 {
    ((a - b) * (a + b)).max(0.0).sqrt()
}

/// f64 [`super::parameterization::transmittance_lut_uv`].
pub fn transmittance_lut_uv(
    r: f64,
    mu: f64,
    planet_radius: f64,
    top_radius: f64,
    width: u32,
    height: u32,
) -> [f64; 2] {
    let r = r.clamp(planet_radius, top_radius);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = horizon_distance(r, planet_radius);
    let d = ray_sphere_intersect(r, mu, top_radius)[1].max(0.0);
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let x_mu = ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0);
    [
        unit_range_to_texel_uv(x_mu, width),
        unit_range_to_texel_uv(rho / top_horizon, height),
    ]
}

/// f64 [`super::parameterization::transmittance_lut_r_mu`].
pub fn transmittance_lut_r_mu(
    uv: [f64; 2],
    planet_radius: f64,
    top_radius: f64,
    width: u32,
    height: u32,
) -> [f64; 2] {
    let x_mu = texel_uv_to_unit_range(uv[0], width).clamp(0.0, 1.0);
    let x_r = texel_uv_to_unit_range(uv[1], height).clamp(0.0, 1.0);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = top_horizon * x_r;
    let r = (rho * rho + planet_radius * planet_radius).sqrt();
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let d = d_min + x_mu * (d_max - d_min);
    let mu = if d == 0.0 {
        1.0
    } else {
        ((top_horizon - rho) * (top_horizon + rho) - d * d) / (2.0 * r * d)
    };
    [r, mu.clamp(-1.0, 1.0)]
}

/// f64 [`super::parameterization::multiple_scattering_lut_uv`].
pub fn multiple_scattering_lut_uv(
    r: f64,
    mu_s: f64,
    planet_radius: f64,
    top_radius: f64,
    width: u32,
    height: u32,
) -> [f64; 2] {
    let x_mu_s = (mu_s * 0.5 + 0.5).clamp(0.0, 1.0);
    let x_r = ((r - planet_radius) / (top_radius - planet_radius)).clamp(0.0, 1.0);
    [
        unit_range_to_texel_uv(x_mu_s, width),
        unit_range_to_texel_uv(x_r, height),
    ]
}

/// f64 [`super::parameterization::multiple_scattering_lut_r_mu_s`].
pub fn multiple_scattering_lut_r_mu_s(
    uv: [f64; 2],
    planet_radius: f64,
    top_radius: f64,
    width: u32,
    height: u32,
) -> [f64; 2] {
    let x_mu_s = texel_uv_to_unit_range(uv[0], width).clamp(0.0, 1.0);
    let x_r = texel_uv_to_unit_range(uv[1], height).clamp(0.0, 1.0);
    [
        planet_radius + x_r * (top_radius - planet_radius),
        x_mu_s * 2.0 - 1.0,
    ]
}

/// f64 [`super::parameterization::horizon_zenith_angle`].
pub fn horizon_zenith_angle(r: f64, planet_radius: f64) -> f64 {
    let r = r.max(planet_radius);
    planet_radius.atan2(-horizon_distance(r, planet_radius))
}

/// f64 [`super::parameterization::sky_view_lut_uv`].
pub fn sky_view_lut_uv(
    r: f64,
    mu: f64,
    cos_azimuth: f64,
    planet_radius: f64,
    width: u32,
    height: u32,
) -> [f64; 2] {
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt().atan2(mu);
    let y = if zenith_angle < horizon {
        0.5 * (1.0 - (1.0 - zenith_angle / horizon).max(0.0).sqrt())
    } else {
        0.5 + 0.5
            * ((zenith_angle - horizon) / (PI - horizon))
                .max(0.0)
                .sqrt()
                .min(1.0)
    };
    let x = (0.5 - 0.5 * cos_azimuth).max(0.0).sqrt().min(1.0);
    [
        unit_range_to_texel_uv(x, width),
        unit_range_to_texel_uv(y, height),
    ]
}

/// f64 [`super::parameterization::sky_view_lut_direction`].
pub fn sky_view_lut_direction(
    uv: [f64; 2],
    r: f64,
    planet_radius: f64,
    width: u32,
    height: u32,
) -> [f64; 2] {
    let x = texel_uv_to_unit_range(uv[0], width).clamp(0.0, 1.0);
    let y = texel_uv_to_unit_range(uv[1], height).clamp(0.0, 1.0);
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = if y < 0.5 {
        let coord = 1.0 - 2.0 * y;
        horizon * (1.0 - coord * coord)
    } else {
        let coord = 2.0 * y - 1.0;
        horizon + (PI - horizon) * coord * coord
    };
    [zenith_angle.cos(), 1.0 - 2.0 * x * x]
}

/// f64 [`super::parameterization::view_sun_cos_azimuth`].
pub fn view_sun_cos_azimuth(mu: f64, mu_s: f64, nu: f64) -> f64 {
    let denominator = ((1.0 - mu) * (1.0 + mu) * (1.0 - mu_s) * (1.0 + mu_s))
        .max(0.0)
        .sqrt();
    if denominator < 1e-6 {
        return 1.0;
    }
    ((nu - mu * mu_s) / denominator).clamp(-1.0, 1.0)
}

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
    if ground[0] >= 0.0 {
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

/// f64 [`super::multiple_scattering_moments::sun_frame_direction`].
pub fn sun_frame_direction(mu: f64, mu_s: f64, nu: f64) -> [f64; 3] {
    let horizontal = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let x = if sin_s > 1e-4 {
        ((nu - mu * mu_s) / sin_s).clamp(-horizontal, horizontal)
    } else {
        0.0
    };
    let y = ((horizontal - x) * (horizontal + x)).max(0.0).sqrt();
    [x, y, mu]
}

/// f64 [`super::multiple_scattering_moments::scattered_multiple_scattering`], one
/// channel: `moments` = [Ψ, d_x, d_z, A_xx, A_zz, A_xz].
pub fn scattered_multiple_scattering(
    moments: [f64; 6],
    direction: [f64; 3],
    legendre: [f64; 2],
) -> f64 {
    let [mean, dx, dz, axx, azz, axz] = moments;
    let [x, y, z] = direction;
    let first = dx * x + dz * z;
    let second = axx * (x * x - y * y) + azz * (z * z - y * y) + 2.0 * axz * x * z;
    (mean + 3.0 * legendre[0] * first + 7.5 * legendre[1] * second).max(0.0)
}

/// f64 [`super::multiple_scattering_moments::multiple_scattering_ground_irradiance`],
/// one channel.
pub fn multiple_scattering_ground_irradiance(
    mean: f64,
    first_moment_z: f64,
    anisotropy_zz: f64,
) -> f64 {
    (mean + 2.0 * first_moment_z + 1.875 * anisotropy_zz).max(0.0)
}

/// f64 [`super::multiple_scattering_moments::direction_zenith_sample`].
pub fn direction_zenith_sample(r: f64, planet_radius: f64, i: u32, k: u32) -> [f64; 2] {
    let ratio = (planet_radius / r).min(1.0);
    let mu_h = -((1.0 - ratio) * (1.0 + ratio)).max(0.0).sqrt();
    let ground = k / 2;
    if i < ground {
        let u = (f64::from(i) + 0.5) / f64::from(ground);
        [
            mu_h - (1.0 + mu_h) * u * u,
            (1.0 + mu_h) * 2.0 * u / f64::from(ground),
        ]
    } else {
        let sky = k - ground;
        let u = (f64::from(i - ground) + 0.5) / f64::from(sky);
        [
            mu_h + (1.0 - mu_h) * u * u,
            (1.0 - mu_h) * 2.0 * u / f64::from(sky),
        ]
    }
}
