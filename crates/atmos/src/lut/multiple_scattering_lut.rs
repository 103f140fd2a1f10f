//! Multiple-scattering LUT (Hillaire 2020 §5.5): for a point at radius r lit by the
//! sun at zenith cosine μ_s, the radiance Ψ_ms of all scattering orders ≥ 2, per unit
//! scattering coefficient, assuming (as Hillaire does) that light reaching the point
//! after the first bounce is isotropic and that its neighbourhood is lit like the
//! point itself:
//!
//! * L₂ = ¼π·∮ [∫ T(x→p) σ_s(p) T_sun(p) dt + T(x→g) T_sun(g) max(μ_s,g, 0) ρ/π] dω / 4π
//!   — second order, with the isotropic phase 1/4π and the ground's Lambert bounce;
//! * f_ms = ∮ ∫ T(x→p) σ_s(p) dt dω / 4π — the fraction re-scattered per order;
//! * Ψ_ms = L₂ · (1 + f_ms + f_ms² + …) = L₂ / (1 − f_ms).
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

/// One texel: Ψ_ms per unit sun irradiance (w = 1). Reads only the transmittance LUT.
pub fn multiple_scattering_texel(bindings: &LutBindings<'_>, x: u32, y: u32) -> [f32; 4] {
    let atmosphere = bindings.atmosphere;
    let s = bindings.settings;
    let (width, height) = (s.multiple_scattering_width, s.multiple_scattering_height);
    let uv = [
        (x as f32 + 0.5) / width as f32,
        (y as f32 + 0.5) / height as f32,
    ];
    let [r, mu_s] = multiple_scattering_lut_r_mu_s(
        uv,
        atmosphere.planet_radius,
        atmosphere.top_radius,
        width,
        height,
    );
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let k = s.multiple_scattering_direction_sqrt;
    let isotropic_phase = 1.0 / (4.0 * PI);
    let mut second_order = [0.0f32; 3];
    let mut transfer = [0.0f32; 3];
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
                let sun = sun_transmittance(bindings, r_t, mu_s_t);
                for c in 0..3 {
                    let scattering = medium.rayleigh_scattering[c] + medium.mie_scattering[c];
                    let weight = scattering_step_fraction(medium.extinction[c], dt);
                    second_order[c] +=
                        throughput[c] * scattering * sun[c] * isotropic_phase * weight;
                    transfer[c] += throughput[c] * scattering * weight;
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
    let mut texel = [0.0f32, 0.0, 0.0, 1.0];
    for c in 0..3 {
        let l2 = second_order[c] / directions;
        let f_ms = (transfer[c] / directions).min(0.999);
        texel[c] = l2 / (1.0 - f_ms);
    }
    texel
}

/// Bakes the whole LUT (threaded); `bindings.multiple_scattering` is not read.
pub fn bake_multiple_scattering_lut(bindings: &LutBindings<'_>) -> Lut2d {
    let (width, height) = (
        bindings.settings.multiple_scattering_width,
        bindings.settings.multiple_scattering_height,
    );
    let texels = fill_parallel((width * height) as usize, |i| {
        multiple_scattering_texel(bindings, i as u32 % width, i as u32 / width)
    });
    Lut2d {
        width,
        height,
        texels,
    }
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
