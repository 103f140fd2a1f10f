//! The raymarch shared by every bake of this rung: the medium at a point, the sun's
//! transmittance there, and Hillaire's energy-conserving step. Twin of the functions
//! of the same names in `shaders/atmos/lut_sampling.wgsl`.
//!
//! The WGSL side reads the atmosphere, the settings and the LUTs from module-scope
//! bindings; the CPU twin passes them as a [`LutBindings`] first argument.

use crate::AtmosphereParameters;
use crate::atmosphere::{exponential_density, tent_density};
use crate::geometry::ray_sphere_intersect;
use crate::phase::{cornette_shanks_phase, rayleigh_phase};
use crate::real::Real;

use super::multiple_scattering_lut::multiple_scattering_source;
use super::transmittance_lut::{lookup_transmittance, transmittance_to_boundary};
use super::{Lut2d, LutSettingsUniform};

/// What the WGSL passes see as bindings: the atmosphere, the settings and the two
/// static LUTs (the multiple-scattering one may be absent while it is being baked).
#[derive(Debug, Clone, Copy)]
pub struct LutBindings<'a> {
    /// The atmosphere uniform.
    pub atmosphere: &'a AtmosphereParameters,
    /// The settings uniform.
    pub settings: &'a LutSettingsUniform,
    /// Transmittance LUT.
    pub transmittance: &'a Lut2d,
    /// Multiple-scattering LUT.
    pub multiple_scattering: &'a Lut2d,
}

/// Scattering and extinction coefficients (1/m) at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MediumSample {
    /// Rayleigh scattering per channel.
    pub rayleigh_scattering: [f32; 3],
    /// Mie scattering per channel.
    pub mie_scattering: [f32; 3],
    /// Total extinction (Rayleigh + Mie extinction + ozone absorption).
    pub extinction: [f32; 3],
}

/// The medium at an altitude (m).
pub fn medium_at_altitude(atmosphere: &AtmosphereParameters, altitude: f32) -> MediumSample {
    let rayleigh = exponential_density(altitude, atmosphere.rayleigh_scale_height);
    let mie = exponential_density(altitude, atmosphere.mie_scale_height);
    let ozone = tent_density(
        altitude,
        atmosphere.ozone_center_altitude,
        atmosphere.ozone_half_width,
    );
    MediumSample {
        rayleigh_scattering: atmosphere.rayleigh_scattering.map(|b| b * rayleigh),
        mie_scattering: atmosphere.mie_scattering.map(|b| b * mie),
        extinction: std::array::from_fn(|i| {
            atmosphere.rayleigh_scattering[i] * rayleigh
                + atmosphere.mie_extinction[i] * mie
                + atmosphere.ozone_absorption[i] * ozone
        }),
    }
}

/// Distance from the planet centre of the point `t` metres along the ray (generic:
/// the f64 instantiation is the reference).
#[doc(hidden)]
pub fn radius_along_ray<F: Real>(r: F, mu: F, t: F) -> F {
    (r * r + t * (F::of(2.0) * r * mu + t))
        .max(F::zero())
        .sqrt()
}

/// 1 when the sun (zenith cosine `mu_s` at radius `r`) is above the planet's
/// geometric horizon, 0 when the planet shadows it (Hillaire's "earth shadow").
pub fn sun_visibility(r: f32, mu_s: f32, planet_radius: f32) -> f32 {
    let horizon_mu = -super::parameterization::horizon_distance(r, planet_radius) / r;
    if mu_s >= horizon_mu { 1.0 } else { 0.0 }
}

/// Transmittance from a point to the sun, 0 in the planet's shadow.
pub fn sun_transmittance(bindings: &LutBindings<'_>, r: f32, mu_s: f32) -> [f32; 3] {
    let visibility = sun_visibility(r, mu_s, bindings.atmosphere.planet_radius);
    lookup_transmittance(bindings, r, mu_s).map(|t| t * visibility)
}

/// ∫₀^dt e^{−σ s} ds = (1 − e^{−σ dt})/σ, and dt where σ = 0: the weight of a
/// constant source over one step (Hillaire 2020 §5.6.3's energy-conserving step).
#[doc(hidden)]
pub fn scattering_step_fraction<F: Real>(extinction: F, dt: F) -> F {
    if extinction > F::zero() {
        F::one_minus_exp_neg(extinction * dt) / extinction
    } else {
        dt
    }
}

/// The part of a ray inside the atmosphere: `[t_start, t_end, hits_ground]`
/// (`hits_ground` is 1 when the segment ends on the ground). Both ends are 0 when the
/// ray misses the atmosphere. `r` is clamped to ≥ planet_radius (a viewer below the
/// ground is treated as on it).
/// Generic: the f64 instantiation is the reference.
#[doc(hidden)]
pub fn ray_segment_in_atmosphere<F: Real>(r: F, mu: F, planet_radius: F, top_radius: F) -> [F; 3] {
    let zero = F::zero();
    let r = r.max(planet_radius);
    let top = ray_sphere_intersect(r, mu, top_radius);
    if top[1] < zero {
        // Outside and looking away (or missing the shell entirely).
        return [zero; 3];
    }
    let t_start = top[0].max(zero);
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu < zero && ground[0] >= zero {
        return [t_start, ground[0], F::one()];
    }
    [t_start, top[1], zero]
}

/// Radiance and transmittance of a segment (or of a march so far), in `f32` (the twin)
/// or `f64` (the reference of the generic helpers).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ScatteringSegment<F = f32> {
    /// In-scattered radiance (unit of `sun_irradiance` per sr).
    pub radiance: [F; 3],
    /// Transmittance of the segment.
    pub transmittance: [F; 3],
}

/// The point `t` metres along the ray (`r`, `mu`) whose sun zenith cosine is `mu_s` and
/// view–sun cosine `nu`: `[r_t, mu_t, mu_s_t]` there (generic: the f64 instantiation is
/// the reference).
#[doc(hidden)]
pub fn point_along_ray<F: Real>(r: F, mu: F, mu_s: F, nu: F, t: F) -> [F; 3] {
    let one = F::one();
    let r_t = radius_along_ray(r, mu, t);
    [
        r_t,
        ((r * mu + t) / r_t).clamp(-one, one),
        ((r * mu_s + t * nu) / r_t).clamp(-one, one),
    ]
}

/// One step of every march of this rung (Hillaire 2020 §5.6.3's energy-conserving
/// step): `source` (per metre) integrated over `dt` against the step's `extinction`,
/// seen through the march's transmittance so far, is added to its radiance; the
/// transmittance is multiplied by the step's (generic: the f64 instantiation is the
/// reference).
#[doc(hidden)]
pub fn integrate_scattering_step<F: Real>(
    march: ScatteringSegment<F>,
    source: [F; 3],
    extinction: [F; 3],
    dt: F,
) -> ScatteringSegment<F> {
    let weight = extinction.map(|e| scattering_step_fraction(e, dt));
    ScatteringSegment {
        radiance: std::array::from_fn(|c| {
            march.radiance[c] + march.transmittance[c] * source[c] * weight[c]
        }),
        transmittance: std::array::from_fn(|c| {
            march.transmittance[c] * (-extinction[c] * dt).exp()
        }),
    }
}

/// The start of every march: no radiance, full transmittance.
pub fn empty_march<F: Real>() -> ScatteringSegment<F> {
    ScatteringSegment {
        radiance: [F::zero(); 3],
        transmittance: [F::one(); 3],
    }
}

/// In-scatter source (per metre, per unit sun irradiance) at a point of radius `r`
/// towards a viewer looking along (zenith cosine `mu`, sun cosine `nu`; sun zenith
/// cosine `mu_s` there): single scattering lit by the sun through the transmittance
/// LUT plus all higher orders from the multiple-scattering LUT.
#[allow(clippy::too_many_arguments)]
pub fn scattering_source(
    bindings: &LutBindings<'_>,
    medium: &MediumSample,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    rayleigh_phase_value: f32,
    mie_phase_value: f32,
) -> [f32; 3] {
    let sun = sun_transmittance(bindings, r, mu_s);
    let multiple = multiple_scattering_source(bindings, medium, r, mu, mu_s, nu);
    std::array::from_fn(|i| {
        sun[i]
            * (medium.rayleigh_scattering[i] * rayleigh_phase_value
                + medium.mie_scattering[i] * mie_phase_value)
            + multiple[i]
    })
}

/// Marches the ray (origin at radius `r`, zenith cosine `mu`, sun cosine `mu_s`,
/// view–sun cosine `nu`) from `t_start` to `t_end` with `sample_count` steps spaced
/// quadratically (t = t_start + (t_end − t_start)(i/n)², fine near the viewer, where
/// the air is densest for a ground viewer), sampling each step at its midpoint.
/// Radiance includes the sun irradiance.
#[allow(clippy::too_many_arguments)]
pub fn raymarch_scattering(
    bindings: &LutBindings<'_>,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    t_start: f32,
    t_end: f32,
    sample_count: u32,
) -> ScatteringSegment {
    let atmosphere = bindings.atmosphere;
    let rayleigh_phase_value = rayleigh_phase(nu);
    let mie_phase_value = cornette_shanks_phase(nu, atmosphere.mie_g);
    let length = (t_end - t_start).max(0.0);
    let n = sample_count as f32;
    let mut march = empty_march();
    let mut t_previous = t_start;
    for i in 0..sample_count {
        let s = (i as f32 + 1.0) / n;
        let t_next = t_start + length * s * s;
        let dt = t_next - t_previous;
        let t = t_previous + 0.5 * dt;
        t_previous = t_next;
        let [r_t, mu_t, mu_s_t] = point_along_ray(r, mu, mu_s, nu, t);
        let medium = medium_at_altitude(atmosphere, r_t - atmosphere.planet_radius);
        let source = scattering_source(
            bindings,
            &medium,
            r_t,
            mu_t,
            mu_s_t,
            nu,
            rayleigh_phase_value,
            mie_phase_value,
        );
        march = integrate_scattering_step(march, source, medium.extinction, dt);
    }
    ScatteringSegment {
        radiance: std::array::from_fn(|c| march.radiance[c] * atmosphere.sun_irradiance[c]),
        transmittance: march.transmittance,
    }
}

/// The per-pixel path of this rung without the sky-view and aerial-perspective tables:
/// the ray's segment inside the atmosphere up to `max_distance` (≥ 1e30: unlimited),
/// with the origin moved to where the ray enters the shell for a viewer above the
/// atmosphere (Hillaire's space views). Transmittance of an unlimited segment comes
/// from the transmittance LUT; a limited one from the march itself.
#[allow(clippy::too_many_arguments)]
pub fn march_view_segment(
    bindings: &LutBindings<'_>,
    r: f32,
    mu: f32,
    mu_s: f32,
    nu: f32,
    max_distance: f32,
    sample_count: u32,
) -> ScatteringSegment {
    let atmosphere = bindings.atmosphere;
    let r = r.max(atmosphere.planet_radius);
    let segment = ray_segment_in_atmosphere(r, mu, atmosphere.planet_radius, atmosphere.top_radius);
    let t_start = segment[0];
    let t_end = segment[1].min(max_distance);
    if t_end <= t_start {
        return ScatteringSegment {
            radiance: [0.0; 3],
            transmittance: [1.0; 3],
        };
    }
    // Move the origin to the segment's start (exactly r when inside).
    let r_0 = radius_along_ray(r, mu, t_start);
    let mu_0 = ((r * mu + t_start) / r_0).clamp(-1.0, 1.0);
    let mu_s_0 = ((r * mu_s + t_start * nu) / r_0).clamp(-1.0, 1.0);
    let mut result = raymarch_scattering(
        bindings,
        r_0,
        mu_0,
        mu_s_0,
        nu,
        0.0,
        t_end - t_start,
        sample_count,
    );
    if max_distance >= crate::frame::UNLIMITED_DISTANCE {
        result.transmittance = transmittance_to_boundary(bindings, r_0, mu_0);
    }
    result
}
