//! Sky-view LUT (Hillaire 2020 §5.3): radiance of the whole sky for one viewer
//! altitude and one sun zenith angle, per (azimuth from the sun, view zenith angle),
//! baked per frame. With [`super::ViewTransmittance::SkyViewLut`] (the default) each
//! texel also holds the transmittance of its view ray (to the ground or space, from
//! the transmittance LUT): a pixel then reads one footprint for both, instead of a
//! ray–sphere test and one or two transmittance lookups (half of a CPU query's cost).
//! Layers ([`super::LutSettingsUniform::sky_view_entries_per_texel`]: 2 or 1), planar
//! like the GPU's texture array: radiance (layer 0) of texel (x, y) at
//! x + width·y, transmittance (layer 1) at x + width·(y + height). Its rows are mapped non-linearly so
//! the horizon, where radiance changes fastest, gets the most texels; the horizon
//! itself lies between the two middle rows, and lookups never blend a sky row with a
//! ground row.
//!
//! Valid for viewers inside the atmosphere (r ≤ top); above it the renderer marches
//! each pixel from where its ray enters the shell
//! ([`super::raymarch::march_view_segment`]). Twin of
//! `shaders/atmos/lut_sky_view.wgsl` (bake) and `lut_sampling.wgsl` (lookup).

use crate::frame::FrameCamera;

use super::parameterization::{bilinear_footprint, sky_view_lut_direction, sky_view_lut_uv};
use super::raymarch::{
    LutBindings, ScatteringSegment, ray_segment_in_atmosphere, raymarch_scattering,
};
use super::transmittance_lut::transmittance_to_boundary;
use super::{Lut2d, blend_footprint, fill_parallel};

/// The viewer radius (clamped to the atmosphere) and sun zenith cosine a sky-view LUT
/// is baked for, from a frame camera.
pub fn sky_view_r_mu_s(camera: &FrameCamera, planet_radius: f32, top_radius: f32) -> [f32; 2] {
    let p = camera.position;
    let length = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let mu_s = (camera.sun[0] * p[0] + camera.sun[1] * p[1] + camera.sun[2] * p[2]) / length;
    [
        length.clamp(planet_radius, top_radius),
        mu_s.clamp(-1.0, 1.0),
    ]
}

/// One texel: radiance along the view ray of this texel's direction and, when the
/// table stores it, the ray's transmittance to the ground or space (`None` for a
/// radiance-only table: no transmittance lookup is made).
pub fn sky_view_texel(
    bindings: &LutBindings<'_>,
    r: f32,
    mu_s: f32,
    x: u32,
    y: u32,
) -> ([f32; 3], Option<[f32; 3]>) {
    let atmosphere = bindings.atmosphere;
    let s = bindings.settings;
    let (width, height) = (s.sky_view_width, s.sky_view_height);
    let uv = [
        (x as f32 + 0.5) / width as f32,
        (y as f32 + 0.5) / height as f32,
    ];
    let [mu, cos_azimuth] = sky_view_lut_direction(uv, r, atmosphere.planet_radius, width, height);
    let sin_v = ((1.0 - mu) * (1.0 + mu)).max(0.0).sqrt();
    let sin_s = ((1.0 - mu_s) * (1.0 + mu_s)).max(0.0).sqrt();
    let nu = (mu * mu_s + sin_v * sin_s * cos_azimuth).clamp(-1.0, 1.0);
    let segment = ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
    let result = raymarch_scattering(
        bindings,
        r,
        mu,
        mu_s,
        nu,
        segment[0],
        segment[1],
        s.sky_view_samples,
    );
    let transmittance =
        (s.sky_view_transmittance != 0).then(|| transmittance_to_boundary(bindings, r, mu));
    (result.radiance, transmittance)
}

/// Bakes the LUT for a viewer at radius `r` with the sun at zenith cosine `mu_s`.
pub fn bake_sky_view_lut(bindings: &LutBindings<'_>, r: f32, mu_s: f32) -> Lut2d {
    let (width, height) = (
        bindings.settings.sky_view_width,
        bindings.settings.sky_view_height,
    );
    let entries = fill_parallel((width * height) as usize, |i| {
        sky_view_texel(bindings, r, mu_s, i as u32 % width, i as u32 / width)
    });
    let texel = |[r, g, b]: [f32; 3]| [r, g, b, 1.0];
    let radiance = entries.iter().map(|&(radiance, _)| texel(radiance));
    let transmittance = entries
        .iter()
        .filter_map(|&(_, transmittance)| transmittance.map(texel));
    let texels = radiance.chain(transmittance).collect();
    Lut2d {
        width,
        height,
        texels,
    }
}

/// Radiance and transmittance of the whole view ray towards (μ, cos φ) for a viewer at
/// radius `r` (the radius the LUT was baked for): the radiance by a bilinear lookup
/// (sky directions read only sky rows, ground directions only ground rows), the
/// transmittance from the same footprint or from the transmittance LUT, as
/// [`super::ViewTransmittance`] chose.
pub fn lookup_sky_view(
    bindings: &LutBindings<'_>,
    sky_view: &Lut2d,
    r: f32,
    mu: f32,
    cos_azimuth: f32,
) -> ScatteringSegment {
    let settings = bindings.settings;
    let (width, height) = (settings.sky_view_width, settings.sky_view_height);
    let uv = sky_view_lut_uv(
        r,
        mu,
        cos_azimuth,
        bindings.atmosphere.planet_radius,
        width,
        height,
    );
    let half = height / 2;
    // At the horizon both halves meet at v = ½; a viewer on the ground looking along
    // (or above) the tangent plane sees the sky (docs/architecture.md, "Rays at the
    // ground"), so it reads the sky rows.
    let sky_rows = uv[1] < 0.5 || (mu >= 0.0 && r <= bindings.atmosphere.planet_radius);
    let f = if sky_rows {
        bilinear_footprint(uv, width, height, 0, half - 1)
    } else {
        bilinear_footprint(uv, width, height, half, height - 1)
    };
    let blend = |layer: u32| {
        blend_footprint(&sky_view.texels, &f, |x, y| {
            (x + width * (y + height * layer)) as usize
        })
    };
    let transmittance = if settings.sky_view_transmittance != 0 {
        blend(1)
    } else {
        transmittance_to_boundary(bindings, r, mu)
    };
    ScatteringSegment {
        radiance: blend(0),
        transmittance,
    }
}
