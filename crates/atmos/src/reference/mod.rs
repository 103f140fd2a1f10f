//! f64 references for every f32 twin in this crate: the same names, arguments and
//! algorithms, evaluated in double precision. `cargo xtask parity` measures both the
//! f32 twin and the WGSL against these, so the reported error is floating-point error
//! (the discretisation, where there is one, is shared and is measured separately
//! against analytic results in the unit tests).

use std::f64::consts::PI;

/// f64 [`crate::phase::rayleigh_phase`].
pub fn rayleigh_phase(cos_theta: f64) -> f64 {
    3.0 / (16.0 * PI) * (1.0 + cos_theta * cos_theta)
}

/// f64 [`crate::phase::phase_denominator_base`].
pub fn phase_denominator_base(cos_theta: f64, g: f64) -> f64 {
    if g >= 0.0 {
        (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - cos_theta)
    } else {
        (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + cos_theta)
    }
}

/// f64 [`crate::phase::henyey_greenstein_phase`].
pub fn henyey_greenstein_phase(cos_theta: f64, g: f64) -> f64 {
    let base = phase_denominator_base(cos_theta, g);
    (1.0 - g) * (1.0 + g) / (4.0 * PI * base * base.sqrt())
}

/// f64 [`crate::phase::cornette_shanks_phase`].
pub fn cornette_shanks_phase(cos_theta: f64, g: f64) -> f64 {
    let base = phase_denominator_base(cos_theta, g);
    3.0 / (8.0 * PI) * (1.0 - g) * (1.0 + g) * (1.0 + cos_theta * cos_theta)
        / ((2.0 + g * g) * base * base.sqrt())
}

/// f64 [`crate::phase::cornette_shanks_legendre_moments`].
pub fn cornette_shanks_legendre_moments(g: f64) -> [f64; 2] {
    let g2 = g * g;
    let normalisation = 3.0 / (2.0 * (2.0 + g2));
    [
        normalisation * g * (8.0 + 2.0 * g2) / 5.0,
        normalisation * (2.0 / 15.0 + 32.0 / 21.0 * g2 + 12.0 / 35.0 * g2 * g2),
    ]
}

/// f64 [`crate::geometry::ray_sphere_intersect`] (miss: both `-1`).
pub fn ray_sphere_intersect(r: f64, mu: f64, sphere_radius: f64) -> [f64; 2] {
    let b = r * mu;
    let c = (r - sphere_radius) * (r + sphere_radius);
    let discriminant = b * b - c;
    if discriminant < 0.0 {
        return [-1.0, -1.0];
    }
    let q = -(b + b.signum() * discriminant.sqrt());
    if q == 0.0 {
        return [0.0, 0.0];
    }
    let (t0, t1) = (q, c / q);
    [t0.min(t1), t0.max(t1)]
}

/// f64 [`crate::geometry::altitude_along_ray`].
pub fn altitude_along_ray(r: f64, mu: f64, t: f64, planet_radius: f64) -> f64 {
    let excess = (r - planet_radius) * (r + planet_radius) + t * (2.0 * r * mu + t);
    let r_t = (r * r + t * (2.0 * r * mu + t)).max(0.0).sqrt();
    excess / (r_t + planet_radius)
}

/// f64 [`crate::optical_depth::optical_length_exponential`].
pub fn optical_length_exponential(
    r: f64,
    mu: f64,
    ray_length: f64,
    planet_radius: f64,
    scale_height: f64,
    sample_count: u32,
) -> f64 {
    let n = sample_count.max(1);
    let dt = ray_length / f64::from(n);
    let sum: f64 = (0..n)
        .map(|i| {
            let t = (f64::from(i) + 0.5) * dt;
            (-altitude_along_ray(r, mu, t, planet_radius) / scale_height).exp()
        })
        .sum();
    sum * dt
}

/// f64 [`crate::transmittance::transmittance_from_optical_depth`].
pub fn transmittance_from_optical_depth(optical_depth: [f64; 3]) -> [f64; 3] {
    optical_depth.map(|tau| (-tau).exp())
}

/// 1 − exp(−x) exactly rounded in f64 (via `exp_m1`).
pub fn one_minus_exp_neg(x: f64) -> f64 {
    -(-x).exp_m1()
}

/// f64 [`crate::closed_form::closed_form_extinction`].
pub fn closed_form_extinction(
    beta_rayleigh: [f64; 3],
    beta_mie: [f64; 3],
    path_length: f64,
) -> [f64; 3] {
    std::array::from_fn(|i| (-(beta_rayleigh[i] + beta_mie[i]) * path_length).exp())
}

/// f64 [`crate::closed_form::closed_form_inscatter`].
pub fn closed_form_inscatter(
    beta_rayleigh: [f64; 3],
    beta_mie: [f64; 3],
    cos_theta: f64,
    g: f64,
    path_length: f64,
) -> [f64; 3] {
    let p_r = rayleigh_phase(cos_theta);
    let p_m = henyey_greenstein_phase(cos_theta, g);
    std::array::from_fn(|i| {
        let extinction = beta_rayleigh[i] + beta_mie[i];
        if extinction <= 0.0 {
            return 0.0;
        }
        (beta_rayleigh[i] * p_r + beta_mie[i] * p_m) * one_minus_exp_neg(extinction * path_length)
            / extinction
    })
}

/// f64 [`crate::atmosphere::exponential_density`].
pub fn exponential_density(altitude: f64, scale_height: f64) -> f64 {
    (-altitude / scale_height).exp()
}

/// f64 [`crate::atmosphere::tent_density`].
pub fn tent_density(altitude: f64, center: f64, half_width: f64) -> f64 {
    (1.0 - (altitude - center).abs() / half_width).max(0.0)
}

/// f64 [`crate::atmosphere::extinction_at_altitude`], from the f64 parameters.
pub fn extinction_at_altitude(atmosphere: &crate::Atmosphere, altitude: f64) -> [f64; 3] {
    let rayleigh = exponential_density(altitude, atmosphere.rayleigh_scale_height);
    let mie = exponential_density(altitude, atmosphere.mie_scale_height);
    let ozone = tent_density(
        altitude,
        atmosphere.ozone_center_altitude,
        atmosphere.ozone_half_width,
    );
    std::array::from_fn(|i| {
        atmosphere.rayleigh_scattering[i] * rayleigh
            + atmosphere.mie_extinction[i] * mie
            + atmosphere.ozone_absorption[i] * ozone
    })
}

mod single_scattering;
pub use single_scattering::{
    density_profile, extinction_from_densities, light_path_transmittance, lowest_point_distance,
    mean_transmittance_over_segment, optical_lengths, ray_sample_distance, single_scattering,
    single_scattering_inside,
};

pub mod multiple_scattering;
mod transmittance_table;
pub use multiple_scattering::{ReferenceSettings, ReferenceSky};
pub mod path_tracer;
pub use path_tracer::{FreePaths, PathTracedSample, PathTracedSky, PathTracerSettings};
pub mod spectral;
pub use spectral::SpectralReferenceSky;
pub use transmittance_table::TransmittanceTable;
