//! f64 twins of [`crate::single_scattering`] (same names, arguments, algorithm), from
//! the f64 [`Atmosphere`]. Used by the parity cases (same sample counts: the difference
//! is floating-point error) and, at high sample counts, as the single-scattering part of
//! the Reference ([`super::ReferenceSky`]).

use super::{
    altitude_along_ray, cornette_shanks_phase, exponential_density, one_minus_exp_neg,
    ray_sphere_intersect, rayleigh_phase, tent_density, transmittance_from_optical_depth,
};
use crate::{Atmosphere, SkySample};

/// f64 [`crate::single_scattering::density_profile`].
pub fn density_profile(atmosphere: &Atmosphere, altitude: f64) -> [f64; 3] {
    [
        exponential_density(altitude, atmosphere.rayleigh_scale_height),
        exponential_density(altitude, atmosphere.mie_scale_height),
        tent_density(
            altitude,
            atmosphere.ozone_center_altitude,
            atmosphere.ozone_half_width,
        ),
    ]
}

/// f64 [`crate::single_scattering::extinction_from_densities`].
pub fn extinction_from_densities(atmosphere: &Atmosphere, densities: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| {
        atmosphere.rayleigh_scattering[i] * densities[0]
            + atmosphere.mie_extinction[i] * densities[1]
            + atmosphere.ozone_absorption[i] * densities[2]
    })
}

/// f64 [`crate::single_scattering::ray_sample_distance`].
pub fn ray_sample_distance(s: f64, t_split: f64, ray_length: f64) -> f64 {
    let s_split = t_split / ray_length;
    if s <= s_split && s_split > 0.0 {
        let x = (s_split - s) / s_split;
        return t_split - t_split * x * x;
    }
    let x = (s - s_split) / (1.0 - s_split);
    t_split + (ray_length - t_split) * x * x
}

/// f64 [`crate::single_scattering::lowest_point_distance`].
pub fn lowest_point_distance(r: f64, mu: f64, ray_length: f64) -> f64 {
    (-r * mu).clamp(0.0, ray_length)
}

/// f64 [`crate::single_scattering::optical_lengths`].
pub fn optical_lengths(
    atmosphere: &Atmosphere,
    r: f64,
    mu: f64,
    ray_length: f64,
    sample_count: u32,
) -> [f64; 3] {
    if ray_length <= 0.0 {
        return [0.0; 3];
    }
    let n = sample_count.max(1);
    let t_split = lowest_point_distance(r, mu, ray_length);
    let mut sum = [0.0; 3];
    let mut t_start = 0.0;
    for i in 0..n {
        let t_end = ray_sample_distance(f64::from(i + 1) / f64::from(n), t_split, ray_length);
        let t = ray_sample_distance((f64::from(i) + 0.5) / f64::from(n), t_split, ray_length);
        let d = density_profile(
            atmosphere,
            altitude_along_ray(r, mu, t, atmosphere.planet_radius),
        );
        for k in 0..3 {
            sum[k] += d[k] * (t_end - t_start);
        }
        t_start = t_end;
    }
    sum
}

/// f64 [`crate::single_scattering::light_path_transmittance`].
pub fn light_path_transmittance(
    atmosphere: &Atmosphere,
    altitude: f64,
    mu_s: f64,
    light_samples: u32,
) -> [f64; 3] {
    let planet_radius = atmosphere.planet_radius;
    let r = planet_radius + altitude;
    if mu_s < 0.0 && mu_s * mu_s * (r * r) > altitude * (r + planet_radius) {
        return [0.0; 3];
    }
    let top = ray_sphere_intersect(r, mu_s, atmosphere.top_radius);
    let length = top[1].max(0.0);
    let lengths = optical_lengths(atmosphere, r, mu_s, length, light_samples);
    transmittance_from_optical_depth(extinction_from_densities(atmosphere, lengths))
}

/// f64 [`crate::single_scattering::mean_transmittance_over_segment`].
pub fn mean_transmittance_over_segment(optical_depth: [f64; 3]) -> [f64; 3] {
    optical_depth.map(|x| {
        if x == 0.0 {
            1.0
        } else {
            one_minus_exp_neg(x) / x
        }
    })
}

/// f64 [`crate::single_scattering::single_scattering_inside`].
#[allow(clippy::too_many_arguments)] // mirrors the WGSL signature
pub fn single_scattering_inside(
    atmosphere: &Atmosphere,
    r: f64,
    mu: f64,
    mu_s: f64,
    nu: f64,
    max_distance: f64,
    view_samples: u32,
    light_samples: u32,
) -> SkySample {
    let planet_radius = atmosphere.planet_radius;
    let r0 = r.max(planet_radius);
    let ground = ray_sphere_intersect(r0, mu, planet_radius);
    let top = ray_sphere_intersect(r0, mu, atmosphere.top_radius);
    let mut end = top[1].max(0.0);
    if mu < 0.0 && ground[0] >= 0.0 {
        end = ground[0];
    }
    let limit = end.min(max_distance.max(0.0));
    let n = view_samples.max(1);
    let t_split = lowest_point_distance(r0, mu, end);
    let rayleigh = rayleigh_phase(nu);
    let mie = cornette_shanks_phase(nu, atmosphere.mie_g);
    let mut optical_depth = [0.0f64; 3];
    let mut radiance = [0.0; 3];
    let mut t_start = 0.0;
    for i in 0..n {
        if t_start >= limit {
            break;
        }
        let t_end = ray_sample_distance(f64::from(i + 1) / f64::from(n), t_split, end);
        let dt = t_end.min(limit) - t_start;
        let t = ray_sample_distance((f64::from(i) + 0.5) / f64::from(n), t_split, end);
        t_start = t_end;
        let altitude = altitude_along_ray(r0, mu, t, planet_radius);
        let r_t = planet_radius + altitude;
        let mu_s_t = ((r0 * mu_s + t * nu) / r_t).clamp(-1.0, 1.0);
        let densities = density_profile(atmosphere, altitude);
        let extinction = extinction_from_densities(atmosphere, densities);
        let sun = light_path_transmittance(atmosphere, altitude, mu_s_t, light_samples);
        let segment_depth = extinction.map(|e| e * dt);
        let weight = mean_transmittance_over_segment(segment_depth);
        for k in 0..3 {
            let scattering = atmosphere.rayleigh_scattering[k] * (densities[0] * rayleigh)
                + atmosphere.mie_scattering[k] * (densities[1] * mie);
            radiance[k] += (-optical_depth[k]).exp() * sun[k] * scattering * weight[k] * dt;
            optical_depth[k] += segment_depth[k];
        }
    }
    SkySample {
        radiance: std::array::from_fn(|k| radiance[k] * atmosphere.sun_irradiance[k]),
        transmittance: transmittance_from_optical_depth(optical_depth),
    }
}

/// f64 [`crate::single_scattering::single_scattering`].
#[allow(clippy::too_many_arguments)] // mirrors the WGSL signature
pub fn single_scattering(
    atmosphere: &Atmosphere,
    r: f64,
    mu: f64,
    mu_s: f64,
    nu: f64,
    max_distance: f64,
    view_samples: u32,
    light_samples: u32,
) -> SkySample {
    let top_radius = atmosphere.top_radius;
    if r <= top_radius {
        return single_scattering_inside(
            atmosphere,
            r,
            mu,
            mu_s,
            nu,
            max_distance,
            view_samples,
            light_samples,
        );
    }
    let hit = ray_sphere_intersect(r, mu, top_radius);
    if mu >= 0.0 || hit[0] < 0.0 {
        return SkySample {
            radiance: [0.0; 3],
            transmittance: [1.0; 3],
        };
    }
    let entry = hit[0];
    let b = r * mu;
    let c = (r - top_radius) * (r + top_radius);
    let mu_entry = -(b * b - c).max(0.0).sqrt() / top_radius;
    let mu_s_entry = ((r * mu_s + entry * nu) / top_radius).clamp(-1.0, 1.0);
    single_scattering_inside(
        atmosphere,
        top_radius,
        mu_entry,
        mu_s_entry,
        nu,
        max_distance - entry,
        view_samples,
        light_samples,
    )
}
