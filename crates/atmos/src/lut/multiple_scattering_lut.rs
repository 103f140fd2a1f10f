//! Multiple-scattering LUT (after Hillaire 2020 §5.5, made direction-dependent): for
//! a point at radius r lit by the sun at zenith cosine μ_s, the radiance field F of
//! scattering orders 1 … N−1 arriving there (per unit sun irradiance), reduced to its
//! smooth part: the mean Ψ = ⟨F⟩, the first moment d = ⟨F ω⟩ and the traceless second
//! moment A = ⟨F (ω ωᵀ − I/3)⟩, ⟨·⟩ the mean over the sphere of directions ω, in the
//! point's sun frame (z up, x towards the sun's horizontal direction; the field is
//! mirror-symmetric in y, so d_y = A_xy = A_yz = 0 and A_yy = −A_xx − A_zz).
//!
//! Those are F's spherical-harmonic bands 0, 1 and 2, and a phase function with
//! Legendre moments (g₁, g₂) scatters them exactly:
//! ∮ p(ω·v) F(ω) dω = Ψ + 3 g₁ d·v + (15/2) g₂ vᵀA v. Rayleigh's phase has degree 2
//! (g₁ = 0, g₂ = 1/10), so its multiple scattering is exact up to the table's
//! quadrature; Cornette–Shanks' forward peak keeps higher bands, which F (smooth) hardly
//! has. Hillaire's table is band 0 alone: it scatters F as if it were isotropic. On
//! the trade-off set that alone left a 1.10 % day-mean luminance error (errors of both
//! signs by view direction); with bands 0–2, 0.60 %.
//!
//! * F₁ = sunlight single-scattered towards the point (true Rayleigh and
//!   Cornette–Shanks phases of the sun's scattering angle ν = ω·s) and the sun's
//!   Lambert bounce off the ground, arriving from every direction ω;
//! * F_{k+1} = ∫ T(x→p) σ_s(p) ⟨p ∗ F_k⟩(p, ω) dt + T(x→g) ρ E_k(g)/π — the next order
//!   from the previous order's table, scattered towards the point where the light
//!   scatters (so a point's neighbourhood is lit as it is, not as the point), and the
//!   ground's Lambert bounce of the irradiance E_k = π(Ψ + 2 d_z + (15/8) A_zz) of
//!   the previous order's field (its bands ≤ 2 against the clamped cosine: exact for
//!   a field constant over each hemisphere, sky above and ground below).
//!
//! Orders are iterated explicitly up to [`super::LutSettings::multiple_scattering_orders`]
//! (the reference, rung 4, stops at 7; orders 6 and 7 add < 0.1 % of the luminance),
//! one bake pass per order.
//!
//! The sphere is sampled with n zenith × n azimuth directions (8 × 8 = Hillaire's 64):
//! azimuths at stratum midpoints, zenith samples split at the texel's horizon and
//! crowding towards it ([`direction_zenith_sample`]; Hillaire's uniform strata in μ
//! read orders ≥ 2 about 7 % low, the bright grazing rays falling between them), each
//! direction marched with uniform midpoint steps. The moments subtract the quadrature's own means of ω and ω ωᵀ, so an
//! isotropic field gives d = A = 0 exactly. The table is planar: layer m of texel
//! (x, y) is entry x + w·(y + h·m), layers Ψ, d_x, d_z, A_xx, A_zz, A_xz (rgb + 1).
//! Twin of `shaders/atmos/lut_multiple_scattering.wgsl` and the lookups of
//! `shaders/atmos/lut_sampling.wgsl`.

use skyscape_wgsl::common::PI;

use super::multiple_scattering_moments::{
    MULTIPLE_SCATTERING_LAYERS, MultipleScatteringMoments, RAYLEIGH_LEGENDRE_MOMENTS,
    direction_zenith_sample, multiple_scattering_ground_irradiance, scattered_multiple_scattering,
    sun_frame_direction,
};
use super::parameterization::{
    bilinear_footprint, multiple_scattering_lut_r_mu_s, multiple_scattering_lut_uv,
};
use super::raymarch::{
    LutBindings, MediumSample, empty_march, integrate_scattering_step, medium_at_altitude,
    point_along_ray, radius_along_ray, ray_segment_in_atmosphere, sun_transmittance,
};
use super::{Lut2d, blend_footprint, fill_parallel};
use crate::phase::{cornette_shanks_legendre_moments, cornette_shanks_phase, rayleigh_phase};

/// In-scatter source of orders ≥ 2 per metre per unit sun irradiance at a point of
/// radius `r` (sun zenith cosine `mu_s`) towards a viewer looking along (zenith cosine
/// `mu`, sun cosine `nu`): Rayleigh and Mie scattering of the table's field with each
/// phase function's Legendre moments.
pub fn multiple_scattering_source(
    bindings: &LutBindings<'_>,
    medium: &MediumSample,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
) -> [f32; 3] {
    let moments = lookup_multiple_scattering(bindings, r, mu_s);
    let direction = sun_frame_direction(mu, mu_s, nu);
    let rayleigh = scattered_multiple_scattering(&moments, direction, RAYLEIGH_LEGENDRE_MOMENTS);
    let mie = scattered_multiple_scattering(
        &moments,
        direction,
        cornette_shanks_legendre_moments(bindings.atmosphere.mie_g),
    );
    std::array::from_fn(|c| {
        medium.rayleigh_scattering[c] * rayleigh[c] + medium.mie_scattering[c] * mie[c]
    })
}

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

/// Sums over the direction quadrature: of F, F ω and F ω ωᵀ, and of ω and ω ωᵀ alone
/// (the quadrature's own means, subtracted so an isotropic field has no anisotropy).
#[derive(Default)]
struct MomentSums {
    radiance: [f32; 3],
    radiance_x: [f32; 3],
    radiance_z: [f32; 3],
    radiance_xx: [f32; 3],
    radiance_zz: [f32; 3],
    radiance_xz: [f32; 3],
    weight: f32,
    x: f32,
    z: f32,
    xx: f32,
    zz: f32,
}

impl MomentSums {
    fn add(&mut self, radiance: [f32; 3], x: f32, z: f32, weight: f32) {
        for (c, radiance) in radiance.iter().enumerate() {
            let f = radiance * weight;
            self.radiance[c] += f;
            self.radiance_x[c] += f * x;
            self.radiance_z[c] += f * z;
            self.radiance_xx[c] += f * x * x;
            self.radiance_zz[c] += f * z * z;
            self.radiance_xz[c] += f * x * z;
        }
        self.weight += weight;
        self.x += weight * x;
        self.z += weight * z;
        self.xx += weight * x * x;
        self.zz += weight * z * z;
    }

    /// The weighted means, less the quadrature's own means of ω and ω ωᵀ.
    fn moments(&self) -> MultipleScatteringMoments {
        let mean = |sum: f32| sum / self.weight;
        let (x, z, xx, zz) = (mean(self.x), mean(self.z), mean(self.xx), mean(self.zz));
        let psi = self.radiance.map(mean);
        MultipleScatteringMoments {
            mean: psi,
            first_moment_x: std::array::from_fn(|c| mean(self.radiance_x[c]) - x * psi[c]),
            first_moment_z: std::array::from_fn(|c| mean(self.radiance_z[c]) - z * psi[c]),
            anisotropy_xx: std::array::from_fn(|c| mean(self.radiance_xx[c]) - xx * psi[c]),
            anisotropy_zz: std::array::from_fn(|c| mean(self.radiance_zz[c]) - zz * psi[c]),
            anisotropy_xz: self.radiance_xz.map(mean),
        }
    }
}

/// One texel of one order's field moments, per unit sun irradiance: F₁ (sunlight
/// scattered once, and the sun's ground bounce; reads only the transmittance LUT)
/// when `next_order` is false, else F_{k+1} from F_k's table in
/// `bindings.multiple_scattering`. Both integrate the same directions and rays; only
/// the source along a ray and the ground's bounce differ.
pub fn multiple_scattering_order_texel(
    bindings: &LutBindings<'_>,
    x: u32,
    y: u32,
    next_order: bool,
) -> MultipleScatteringMoments {
    let atmosphere = bindings.atmosphere;
    let s = bindings.settings;
    let [r, mu_s] = texel_r_mu_s(bindings, x, y);
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let k = s.multiple_scattering_direction_sqrt;
    let mut sums = MomentSums::default();
    for i in 0..k {
        let [mu, mu_weight] = direction_zenith_sample(r, atmosphere.planet_radius, i, k);
        let sin_v = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
        let segment =
            ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
        let n = s.multiple_scattering_samples;
        let dt = (segment[1] - segment[0]) / n as f32;
        for j in 0..k {
            let azimuth = 2.0 * PI * (j as f32 + 0.5) / k as f32;
            let cos_azimuth = azimuth.cos();
            let nu = mu * mu_s + sin_v * sin_s * cos_azimuth;
            // Sunlight scattered at p into −ω turns by the angle whose cosine is ω·s = ν.
            let rayleigh_phase_value = rayleigh_phase(nu);
            let mie_phase_value = cornette_shanks_phase(nu, atmosphere.mie_g);
            let mut march = empty_march();
            for step in 0..n {
                let t = segment[0] + (step as f32 + 0.5) * dt;
                let [r_t, mu_t, mu_s_t] = point_along_ray(r, mu, mu_s, nu, t);
                let medium = medium_at_altitude(atmosphere, r_t - atmosphere.planet_radius);
                let source = if next_order {
                    multiple_scattering_source(bindings, &medium, r_t, mu_t, mu_s_t, nu)
                } else {
                    let sun = sun_transmittance(bindings, r_t, mu_s_t);
                    std::array::from_fn(|c| {
                        (medium.rayleigh_scattering[c] * rayleigh_phase_value
                            + medium.mie_scattering[c] * mie_phase_value)
                            * sun[c]
                    })
                };
                march = integrate_scattering_step(march, source, medium.extinction, dt);
            }
            let (mut radiance, throughput) = (march.radiance, march.transmittance);
            if segment[2] > 0.5 {
                // A Lambertian ground reflects ρ/π of its irradiance: the sun's at the
                // hit point (F₁), or the previous order's field's (F_{k+1}).
                let r_g = radius_along_ray(r, mu, segment[1]);
                let mu_s_g = ((r * mu_s + segment[1] * nu) / r_g).clamp(-1.0, 1.0);
                let irradiance_over_pi: [f32; 3] = if next_order {
                    let previous = lookup_multiple_scattering(bindings, r_g, mu_s_g);
                    multiple_scattering_ground_irradiance(&previous)
                } else {
                    let sun = sun_transmittance(bindings, r_g, mu_s_g);
                    sun.map(|t| t * mu_s_g.max(0.0) / PI)
                };
                for c in 0..3 {
                    radiance[c] +=
                        throughput[c] * irradiance_over_pi[c] * atmosphere.ground_albedo[c];
                }
            }
            sums.add(radiance, sin_v * cos_azimuth, mu, mu_weight);
        }
    }
    sums.moments()
}

/// One order's texels as the planar table (layer-major, rgb + 1).
fn planar_table(width: u32, height: u32, texels: &[MultipleScatteringMoments]) -> Lut2d {
    let mut out = Vec::with_capacity(texels.len() * MULTIPLE_SCATTERING_LAYERS as usize);
    for layer in 0..MULTIPLE_SCATTERING_LAYERS as usize {
        out.extend(texels.iter().map(|t| {
            let l = t.layers()[layer];
            [l[0], l[1], l[2], 1.0]
        }));
    }
    Lut2d {
        width,
        height: height * MULTIPLE_SCATTERING_LAYERS,
        texels: out,
    }
}

/// Bakes the whole LUT (threaded): F₁'s moments, then each order's up to `orders − 1`
/// from the one before, summed. `bindings.multiple_scattering` is not read. The table
/// is `width × (6 · height)`: the six layers stacked.
pub fn bake_multiple_scattering_lut(bindings: &LutBindings<'_>, orders: u32) -> Lut2d {
    let (width, height) = (
        bindings.settings.multiple_scattering_width,
        bindings.settings.multiple_scattering_height,
    );
    let count = (width * height) as usize;
    let first = fill_parallel(count, |i| {
        multiple_scattering_order_texel(bindings, i as u32 % width, i as u32 / width, false)
    });
    let mut order = planar_table(width, height, &first);
    let mut sum = order.clone();
    for _ in 3..=orders {
        let previous = LutBindings {
            multiple_scattering: &order,
            ..*bindings
        };
        let next = fill_parallel(count, |i| {
            multiple_scattering_order_texel(&previous, i as u32 % width, i as u32 / width, true)
        });
        order = planar_table(width, height, &next);
        for (total, texel) in sum.texels.iter_mut().zip(&order.texels) {
            for c in 0..3 {
                total[c] += texel[c];
            }
        }
    }
    sum
}

/// Bilinear lookup of the field's moments at (r, μ_s).
pub fn lookup_multiple_scattering(
    bindings: &LutBindings<'_>,
    r: f32,
    mu_s: f32,
) -> MultipleScatteringMoments {
    let s = bindings.settings;
    let (width, height) = (s.multiple_scattering_width, s.multiple_scattering_height);
    let uv = multiple_scattering_lut_uv(
        r,
        mu_s,
        bindings.atmosphere.planet_radius,
        bindings.atmosphere.top_radius,
        width,
        height,
    );
    let f = bilinear_footprint(uv, width, height, 0, height - 1);
    let table = &bindings.multiple_scattering.texels;
    let layers = std::array::from_fn(|layer| {
        let base = (width * height) as usize * layer;
        blend_footprint(table, &f, |x, y| base + (x + width * y) as usize)
    });
    MultipleScatteringMoments::from_layers(layers)
}
