//! Multiple-scattering LUT (after Hillaire 2020 §5.5): for a point at radius r lit by
//! the sun at zenith cosine μ_s, Ψ_ms = Σ_{k≥2} Ψ_k, where Ψ_k is the radiance of
//! scattering order k averaged over all directions arriving at the point, per unit sun
//! irradiance. The view raymarch scatters it with an isotropic phase (σ_s·Ψ_ms):
//! Hillaire's approximation, which makes the table 2D.
//!
//! * Ψ₂ = ∮ [∫ T(x→p) (σ_R p_R(ν) + σ_M p_M(ν)) T_sun(p) dt + T(x→g) T_sun(g) max(μ_s,g, 0) ρ/π] dω / 4π
//!   — single-scattered light (with the true Rayleigh and Cornette–Shanks phases of the
//!   sun's scattering angle ν = ω·s, like the view raymarch) and the sun's Lambert bounce
//!   off the ground, arriving from every direction ω;
//! * Ψ_{k+1} = ∮ [∫ T(x→p) σ_s(p) Ψ_k(p) dt + T(x→g) ρ Ψ_k(g)] dω / 4π — the next order
//!   from the previous order's table, looked up where the light scatters (so a point's
//!   neighbourhood is lit as it is, not as the point), and the ground's bounce of that
//!   order (irradiance π Ψ_k(g) of an isotropic field, reflected with albedo ρ).
//!
//! Orders are iterated explicitly up to [`super::LutSettings::multiple_scattering_orders`]
//! (the reference, rung 4, stops at 7; orders 6 and 7 add < 0.1 % of the luminance),
//! one bake pass per order. Hillaire's isotropic first bounce and geometric series
//! Ψ₂/(1 − f_ms) read 3–16 % low (sun 90…10°) against the reference's orders ≥ 2;
//! these orders read 5–9 % low, the cost of the isotropic second scattering (see the
//! atmos README, "Speed against accuracy").
//!
//! The sphere is sampled with n × n stratified directions (zenith cosine and azimuth
//! at stratum midpoints; 8 × 8 = Hillaire's 64), each marched with uniform midpoint
//! steps. Twin of `shaders/atmos/lut_multiple_scattering.wgsl`.

use skyscape_wgsl::common::PI;

use super::parameterization::{
    bilinear_footprint, multiple_scattering_lut_r_mu_s, multiple_scattering_lut_uv,
};
use super::raymarch::{
    LutBindings, medium_at_altitude, radius_along_ray, ray_segment_in_atmosphere,
    scattering_step_fraction, sun_transmittance,
};
use super::{Lut2d, fill_parallel};
use crate::phase::{cornette_shanks_phase, rayleigh_phase};

/// The (r, μ_s) of texel (x, y) of the multiple-scattering LUT.
fn texel_r_mu_s(bindings: &LutBindings<'_>, x: u32, y: u32) -> [f32; 2] {
    let s = bindings.settings;
    let (width, height) = (s.multiple_scattering_width, s.multiple_scattering_height);
    let uv = [
        (x as f32 + 0.5) / width as f32,
        (y as f32 + 0.5) / height as f32,
    ];
    multiple_scattering_lut_r_mu_s(
        uv,
        bindings.atmosphere.planet_radius,
        bindings.atmosphere.top_radius,
        width,
        height,
    )
}

/// One texel of the second order: Ψ₂ per unit sun irradiance (w = 1). Reads only the
/// transmittance LUT.
pub fn multiple_scattering_texel(bindings: &LutBindings<'_>, x: u32, y: u32) -> [f32; 4] {
    let atmosphere = bindings.atmosphere;
    let s = bindings.settings;
    let [r, mu_s] = texel_r_mu_s(bindings, x, y);
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let k = s.multiple_scattering_direction_sqrt;
    let mut second_order = [0.0f32; 3];
    for i in 0..k {
        let mu = -1.0 + (i as f32 + 0.5) * 2.0 / k as f32;
        let sin_v = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
        let segment =
            ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
        let n = s.multiple_scattering_samples;
        let dt = (segment[1] - segment[0]) / n as f32;
        for j in 0..k {
            let azimuth = 2.0 * PI * (j as f32 + 0.5) / k as f32;
            let nu = mu * mu_s + sin_v * sin_s * azimuth.cos();
            // Sunlight scattered at p into −ω turns by the angle whose cosine is ω·s = ν.
            let rayleigh_phase_value = rayleigh_phase(nu);
            let mie_phase_value = cornette_shanks_phase(nu, atmosphere.mie_g);
            let mut throughput = [1.0f32; 3];
            for step in 0..n {
                let t = segment[0] + (step as f32 + 0.5) * dt;
                let r_t = radius_along_ray(r, mu, t);
                let mu_s_t = ((r * mu_s + t * nu) / r_t).clamp(-1.0, 1.0);
                let medium = medium_at_altitude(atmosphere, r_t - atmosphere.planet_radius);
                let sun = sun_transmittance(bindings, r_t, mu_s_t);
                for c in 0..3 {
                    let scattering = medium.rayleigh_scattering[c] * rayleigh_phase_value
                        + medium.mie_scattering[c] * mie_phase_value;
                    let weight = scattering_step_fraction(medium.extinction[c], dt);
                    second_order[c] += throughput[c] * scattering * sun[c] * weight;
                    throughput[c] *= (-medium.extinction[c] * dt).exp();
                }
            }
            if segment[2] > 0.5 {
                // Lambertian ground, lit by the sun at the hit point.
                let r_g = radius_along_ray(r, mu, segment[1]);
                let mu_s_g = ((r * mu_s + segment[1] * nu) / r_g).clamp(-1.0, 1.0);
                let sun = sun_transmittance(bindings, r_g, mu_s_g);
                for c in 0..3 {
                    second_order[c] +=
                        throughput[c] * sun[c] * mu_s_g.max(0.0) * atmosphere.ground_albedo[c] / PI;
                }
            }
        }
    }
    let directions = (k * k) as f32;
    [
        second_order[0] / directions,
        second_order[1] / directions,
        second_order[2] / directions,
        1.0,
    ]
}

/// One texel of the next order: Ψ_{k+1} from the order-k table in
/// `bindings.multiple_scattering` (w = 1).
pub fn multiple_scattering_next_order_texel(
    bindings: &LutBindings<'_>,
    x: u32,
    y: u32,
) -> [f32; 4] {
    let atmosphere = bindings.atmosphere;
    let s = bindings.settings;
    let [r, mu_s] = texel_r_mu_s(bindings, x, y);
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let k = s.multiple_scattering_direction_sqrt;
    let mut next_order = [0.0f32; 3];
    for i in 0..k {
        let mu = -1.0 + (i as f32 + 0.5) * 2.0 / k as f32;
        let sin_v = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
        let segment =
            ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
        let n = s.multiple_scattering_samples;
        let dt = (segment[1] - segment[0]) / n as f32;
        for j in 0..k {
            let azimuth = 2.0 * PI * (j as f32 + 0.5) / k as f32;
            let nu = mu * mu_s + sin_v * sin_s * azimuth.cos();
            let mut throughput = [1.0f32; 3];
            for step in 0..n {
                let t = segment[0] + (step as f32 + 0.5) * dt;
                let r_t = radius_along_ray(r, mu, t);
                let mu_s_t = ((r * mu_s + t * nu) / r_t).clamp(-1.0, 1.0);
                let medium = medium_at_altitude(atmosphere, r_t - atmosphere.planet_radius);
                let previous = lookup_multiple_scattering(bindings, r_t, mu_s_t);
                for c in 0..3 {
                    let scattering = medium.rayleigh_scattering[c] + medium.mie_scattering[c];
                    let weight = scattering_step_fraction(medium.extinction[c], dt);
                    next_order[c] += throughput[c] * scattering * previous[c] * weight;
                    throughput[c] *= (-medium.extinction[c] * dt).exp();
                }
            }
            if segment[2] > 0.5 {
                // The ground under an isotropic field Ψ_k receives π Ψ_k and reflects
                // ρ/π of it as radiance.
                let r_g = radius_along_ray(r, mu, segment[1]);
                let mu_s_g = ((r * mu_s + segment[1] * nu) / r_g).clamp(-1.0, 1.0);
                let previous = lookup_multiple_scattering(bindings, r_g, mu_s_g);
                for c in 0..3 {
                    next_order[c] += throughput[c] * previous[c] * atmosphere.ground_albedo[c];
                }
            }
        }
    }
    let directions = (k * k) as f32;
    [
        next_order[0] / directions,
        next_order[1] / directions,
        next_order[2] / directions,
        1.0,
    ]
}

/// Bakes the whole LUT (threaded): Ψ₂, then each order up to `orders` from the one
/// before, summed. `bindings.multiple_scattering` is not read.
pub fn bake_multiple_scattering_lut(bindings: &LutBindings<'_>, orders: u32) -> Lut2d {
    let (width, height) = (
        bindings.settings.multiple_scattering_width,
        bindings.settings.multiple_scattering_height,
    );
    let count = (width * height) as usize;
    let mut order = Lut2d {
        width,
        height,
        texels: fill_parallel(count, |i| {
            multiple_scattering_texel(bindings, i as u32 % width, i as u32 / width)
        }),
    };
    let mut sum = order.clone();
    for _ in 3..=orders {
        let previous = LutBindings {
            multiple_scattering: &order,
            ..*bindings
        };
        let next = fill_parallel(count, |i| {
            multiple_scattering_next_order_texel(&previous, i as u32 % width, i as u32 / width)
        });
        for (total, texel) in sum.texels.iter_mut().zip(&next) {
            for c in 0..3 {
                total[c] += texel[c];
            }
        }
        order.texels = next;
    }
    sum
}

/// Bilinear lookup of Ψ_ms at (r, μ_s).
pub fn lookup_multiple_scattering(bindings: &LutBindings<'_>, r: f32, mu_s: f32) -> [f32; 3] {
    let s = bindings.settings;
    let uv = multiple_scattering_lut_uv(
        r,
        mu_s,
        bindings.atmosphere.planet_radius,
        bindings.atmosphere.top_radius,
        s.multiple_scattering_width,
        s.multiple_scattering_height,
    );
    let footprint = bilinear_footprint(
        uv,
        s.multiple_scattering_width,
        s.multiple_scattering_height,
        0,
        s.multiple_scattering_height - 1,
    );
    bindings.multiple_scattering.blend(&footprint)
}
