//! Sky-irradiance LUT: the irradiance a surface of any normal receives from the sky at
//! any point (Bruneton & Neyret 2008 tabulate it for a horizontal surface; here for
//! every normal). The field arriving at a point depends on its radius r, the sun's
//! zenith cosine μ_s and, in the point's sun frame (z up, x towards the sun's
//! horizontal direction; the field is mirror-symmetric in y), the normal's zenith
//! cosine n_z and azimuth φ_n ∈ [0, π] from the sun: a table over (μ_s, r) per
//! normal, one layer per normal.
//!
//! Each texel marches 32 zenith (split at the horizon and crowding towards it,
//! [`sky_irradiance_direction_zenith`]) × 32 azimuth directions over the half-sphere of
//! azimuths [0, π] (each counted with its mirror image) through this rung's view march
//! (single scattering with the true phase functions, orders ≥ 2 from the
//! multiple-scattering table), adds on rays that meet the ground its Lambertian
//! radiance (the sun's and the sky's irradiance there, the latter from the
//! multiple-scattering table's bands ≤ 2), and integrates every layer's normal
//! against the clamped cosine: E(n) = ∫ L(ω) max(0, n·ω) dω, in the unit of
//! `sun_irradiance`. A band-limited form (the multiple-scattering moments against the
//! clamped cosine's bands 0–2) would miss the sharp horizon and the sun's aureole (`cargo test -p
//! atmos --test sky_irradiance -- --nocapture` measures the per-normal table).
//!
//! Rows are quadratic in altitude (x_r = √((r − R)/(top − R)): 100 m apart at the
//! ground, where the Mie layer's 1.2 km scale height lives), columns linear in μ_s.
//! Normal layers: n_z = −1 + 2 i/31 (32), φ_n = π j/7 (8), layer 8 i + j. Twin of
//! `shaders/atmos/lut_sky_irradiance.wgsl` (the bake) and `lookup_sky_irradiance` in
//! `shaders/atmos/lut_sampling.wgsl`.

use skyscape_wgsl::common::PI;

use super::multiple_scattering_lut::lookup_multiple_scattering;
use super::multiple_scattering_moments::multiple_scattering_ground_irradiance;
use super::parameterization::{
    bilinear_footprint, horizon_zenith_angle, texel_uv_to_unit_range, unit_range_to_texel_uv,
};
use super::raymarch::{
    LutBindings, march_view_segment, radius_along_ray, ray_segment_in_atmosphere, sun_transmittance,
};
use super::{Lut2d, blend_footprint};
use crate::frame::UNLIMITED_DISTANCE;
use rayon::prelude::*;

/// Columns (sun zenith cosine μ_s).
pub const SKY_IRRADIANCE_WIDTH: u32 = 64;
/// Rows (radius, quadratic in altitude).
pub const SKY_IRRADIANCE_HEIGHT: u32 = 32;
/// Normal zenith cosines per table.
pub const SKY_IRRADIANCE_NORMAL_ZENITHS: u32 = 32;
/// Normal azimuths from the sun, over [0, π].
pub const SKY_IRRADIANCE_NORMAL_AZIMUTHS: u32 = 8;
/// Layers: one per normal.
pub const SKY_IRRADIANCE_LAYERS: u32 =
    SKY_IRRADIANCE_NORMAL_ZENITHS * SKY_IRRADIANCE_NORMAL_AZIMUTHS;
/// Zenith samples of the bake's direction quadrature.
pub const SKY_IRRADIANCE_DIRECTION_ZENITHS: u32 = 32;
/// Azimuth samples over [0, π] of the bake's direction quadrature.
pub const SKY_IRRADIANCE_DIRECTION_AZIMUTHS: u32 = 32;
/// Steps of each direction's march.
pub const SKY_IRRADIANCE_SAMPLES: u32 = 24;

/// Texture coordinates of (r, μ_s) in the table.
pub fn sky_irradiance_lut_uv(r: f32, mu_s: f32, planet_radius: f32, top_radius: f32) -> [f32; 2] {
    let x_mu_s = (mu_s * 0.5 + 0.5).clamp(0.0, 1.0);
    let x_r = ((r - planet_radius) / (top_radius - planet_radius))
        .clamp(0.0, 1.0)
        .sqrt();
    [
        unit_range_to_texel_uv(x_mu_s, SKY_IRRADIANCE_WIDTH),
        unit_range_to_texel_uv(x_r, SKY_IRRADIANCE_HEIGHT),
    ]
}

/// Inverse of [`sky_irradiance_lut_uv`]: `[r, μ_s]`.
pub fn sky_irradiance_lut_r_mu_s(uv: [f32; 2], planet_radius: f32, top_radius: f32) -> [f32; 2] {
    let x_mu_s = texel_uv_to_unit_range(uv[0], SKY_IRRADIANCE_WIDTH).clamp(0.0, 1.0);
    let x_r = texel_uv_to_unit_range(uv[1], SKY_IRRADIANCE_HEIGHT).clamp(0.0, 1.0);
    [
        planet_radius + x_r * x_r * (top_radius - planet_radius),
        x_mu_s * 2.0 - 1.0,
    ]
}

/// The normal of `layer` in the sun frame.
pub fn sky_irradiance_layer_normal(layer: u32) -> [f32; 3] {
    let zenith = layer / SKY_IRRADIANCE_NORMAL_AZIMUTHS;
    let azimuth = layer % SKY_IRRADIANCE_NORMAL_AZIMUTHS;
    let n_z = -1.0 + 2.0 * zenith as f32 / (SKY_IRRADIANCE_NORMAL_ZENITHS - 1) as f32;
    let phi = PI * azimuth as f32 / (SKY_IRRADIANCE_NORMAL_AZIMUTHS - 1) as f32;
    let horizontal = ((1.0 - n_z) * (1.0 + n_z)).max(0.0).sqrt();
    [horizontal * phi.cos(), horizontal * phi.sin(), n_z]
}

/// Zenith sample `i` of the bake's direction quadrature at radius `r`: `[μ, w]`, w the
/// sample's share of dμ (the exact μ-length of its cell: the weights sum to 2). Half
/// the samples cover the sky, zenith angles [0, θ_h], half the ground, [θ_h, π] (θ_h
/// the horizon's, 90° at and below the ground), each at θ = θ_h sin(πu/2) (sky) or
/// θ_h + (π − θ_h)(1 − cos(πu/2)) (ground) of midpoints u: cells crowd towards the
/// horizon, where grazing rays brighten fast and the ground's step lies, and stay
/// under 9° at the zenith and the nadir, where a high sun's aureole lies.
pub fn sky_irradiance_direction_zenith(r: f32, planet_radius: f32, i: u32) -> [f32; 2] {
    let horizon = horizon_zenith_angle(r, planet_radius);
    let half = SKY_IRRADIANCE_DIRECTION_ZENITHS / 2;
    let angle = |edge: f32| {
        if i < half {
            horizon * (0.5 * PI * edge / half as f32).sin()
        } else {
            horizon + (PI - horizon) * (1.0 - (0.5 * PI * edge / half as f32).cos())
        }
    };
    let k = (i % half) as f32;
    let (low, high) = (angle(k), angle(k + 1.0));
    [angle(k + 0.5).cos(), low.cos() - high.cos()]
}

/// Direction `index` (zenith `index / 32`, azimuth `index % 32`) of a texel at
/// (r, μ_s): `[w·L_r, w·L_g, w·L_b, μ]`, the radiance arriving from it (air light and,
/// on a ground ray, the ground's Lambertian radiance) times its solid angle, and its
/// zenith cosine.
pub fn sky_irradiance_direction_radiance(
    bindings: &LutBindings<'_>,
    r: f32,
    mu_s: f32,
    index: u32,
) -> [f32; 4] {
    let atmosphere = bindings.atmosphere;
    let zenith = sky_irradiance_direction_zenith(
        r,
        atmosphere.planet_radius,
        index / SKY_IRRADIANCE_DIRECTION_AZIMUTHS,
    );
    let mu = zenith[0];
    let azimuth_count = SKY_IRRADIANCE_DIRECTION_AZIMUTHS as f32;
    let phi = PI * ((index % SKY_IRRADIANCE_DIRECTION_AZIMUTHS) as f32 + 0.5) / azimuth_count;
    let sin_v = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let nu = mu * mu_s + sin_v * sin_s * phi.cos();
    let segment = march_view_segment(
        bindings,
        r,
        mu,
        mu_s,
        nu,
        UNLIMITED_DISTANCE,
        SKY_IRRADIANCE_SAMPLES,
    );
    let mut radiance = segment.radiance;
    let bounds = ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
    if bounds[2] > 0.5 {
        let r_g = radius_along_ray(r, mu, bounds[1]);
        let mu_s_g = ((r * mu_s + bounds[1] * nu) / r_g).clamp(-1.0, 1.0);
        let direct = sun_transmittance(bindings, r_g, mu_s_g);
        let sky = multiple_scattering_ground_irradiance(&lookup_multiple_scattering(
            bindings, r_g, mu_s_g,
        ));
        for c in 0..3 {
            let irradiance_over_pi = direct[c] * mu_s_g.max(0.0) / PI + sky[c];
            radiance[c] += segment.transmittance[c]
                * irradiance_over_pi
                * atmosphere.ground_albedo[c]
                * atmosphere.sun_irradiance[c];
        }
    }
    let weight = zenith[1] * PI / azimuth_count;
    [
        radiance[0] * weight,
        radiance[1] * weight,
        radiance[2] * weight,
        mu,
    ]
}

/// max(0, n·ω) + max(0, n·ω′) for the direction of zenith cosine `mu` and azimuth index
/// `azimuth` and its mirror image ω′ (y negated).
pub fn sky_irradiance_cosines(normal: [f32; 3], mu: f32, azimuth: u32) -> f32 {
    let azimuth_count = SKY_IRRADIANCE_DIRECTION_AZIMUTHS as f32;
    let phi = PI * (azimuth as f32 + 0.5) / azimuth_count;
    let sin_v = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let x = normal[0] * sin_v * phi.cos() + normal[2] * mu;
    let y = normal[1] * sin_v * phi.sin();
    (x + y).max(0.0) + (x - y).max(0.0)
}

/// Every layer of texel (x, y): the irradiance on each layer's normal.
pub fn sky_irradiance_texel(bindings: &LutBindings<'_>, x: u32, y: u32) -> Vec<[f32; 3]> {
    let uv = [
        (x as f32 + 0.5) / SKY_IRRADIANCE_WIDTH as f32,
        (y as f32 + 0.5) / SKY_IRRADIANCE_HEIGHT as f32,
    ];
    let atmosphere = bindings.atmosphere;
    let [r, mu_s] = sky_irradiance_lut_r_mu_s(uv, atmosphere.planet_radius, atmosphere.top_radius);
    let count = SKY_IRRADIANCE_DIRECTION_ZENITHS * SKY_IRRADIANCE_DIRECTION_AZIMUTHS;
    let field: Vec<[f32; 4]> = (0..count)
        .map(|index| sky_irradiance_direction_radiance(bindings, r, mu_s, index))
        .collect();
    (0..SKY_IRRADIANCE_LAYERS)
        .map(|layer| {
            let normal = sky_irradiance_layer_normal(layer);
            let mut irradiance = [0.0f32; 3];
            for (index, entry) in field.iter().enumerate() {
                let azimuth = index as u32 % SKY_IRRADIANCE_DIRECTION_AZIMUTHS;
                let cosines = sky_irradiance_cosines(normal, entry[3], azimuth);
                for c in 0..3 {
                    irradiance[c] += entry[c] * cosines;
                }
            }
            irradiance
        })
        .collect()
}

/// Bakes the whole table (threaded): `width × (layers · height)`, layer m of texel
/// (x, y) at entry x + w·(y + h·m).
pub fn bake_sky_irradiance_lut(bindings: &LutBindings<'_>) -> Lut2d {
    let (width, height) = (SKY_IRRADIANCE_WIDTH, SKY_IRRADIANCE_HEIGHT);
    let texels: Vec<Vec<[f32; 3]>> = (0..width * height)
        .into_par_iter()
        .map(|i| sky_irradiance_texel(bindings, i % width, i / width))
        .collect();
    let mut out = Vec::with_capacity(texels.len() * SKY_IRRADIANCE_LAYERS as usize);
    for layer in 0..SKY_IRRADIANCE_LAYERS as usize {
        out.extend(
            texels
                .iter()
                .map(|t| [t[layer][0], t[layer][1], t[layer][2], 1.0]),
        );
    }
    Lut2d {
        width,
        height: height * SKY_IRRADIANCE_LAYERS,
        texels: out,
    }
}

/// Irradiance (the unit of `sun_irradiance`) from the table at (r, μ_s) on a surface
/// whose normal is `normal` in the point's sun frame: bilinear over (μ_s, r) in each of
/// the four layers around the normal, blended bilinearly over (n_z, φ_n).
pub fn lookup_sky_irradiance(
    bindings: &LutBindings<'_>,
    table: &Lut2d,
    r: f32,
    mu_s: f32,
    normal: [f32; 3],
) -> [f32; 3] {
    let atmosphere = bindings.atmosphere;
    let (width, height) = (SKY_IRRADIANCE_WIDTH, SKY_IRRADIANCE_HEIGHT);
    let uv = sky_irradiance_lut_uv(r, mu_s, atmosphere.planet_radius, atmosphere.top_radius);
    let f = bilinear_footprint(uv, width, height, 0, height - 1);
    let last_zenith = (SKY_IRRADIANCE_NORMAL_ZENITHS - 1) as f32;
    let last_azimuth = (SKY_IRRADIANCE_NORMAL_AZIMUTHS - 1) as f32;
    let z = ((normal[2].clamp(-1.0, 1.0) + 1.0) * 0.5 * last_zenith).clamp(0.0, last_zenith);
    let a = (normal[1].abs().atan2(normal[0]) / PI * last_azimuth).clamp(0.0, last_azimuth);
    let (z0, a0) = (z as u32, a as u32);
    let (z1, a1) = (
        (z0 + 1).min(SKY_IRRADIANCE_NORMAL_ZENITHS - 1),
        (a0 + 1).min(SKY_IRRADIANCE_NORMAL_AZIMUTHS - 1),
    );
    let (fz, fa) = (z - z0 as f32, a - a0 as f32);
    let layer = |zenith: u32, azimuth: u32| {
        let base = (width * height * (zenith * SKY_IRRADIANCE_NORMAL_AZIMUTHS + azimuth)) as usize;
        blend_footprint(&table.texels, &f, |x, y| base + (x + width * y) as usize)
    };
    let (l00, l01, l10, l11) = (layer(z0, a0), layer(z0, a1), layer(z1, a0), layer(z1, a1));
    std::array::from_fn(|c| {
        let low = l00[c] * (1.0 - fa) + l01[c] * fa;
        let high = l10[c] * (1.0 - fa) + l11[c] * fa;
        low * (1.0 - fz) + high * fz
    })
}
