//! Shading a layer: its frame uniforms, texture, shadow, reflectance and radiance
//! (the WGSL twins).

use atmos::real::Real;
use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};

/// What a layer needs from the frame: the planet, the fog, the light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudLayerFrame {
    /// Ground radius (m).
    pub planet_radius_m: f64,
    /// Texture offset (m, east and north): the viewer's travel plus wind drift.
    pub offset_m: [f64; 2],
    /// Fog extinction (1/m) between the viewer and the layer: 3.912 / visibility.
    pub fog_extinction_per_m: f64,
    /// SGSky's exp² fog instead of the exponential one.
    pub exp2_fog: bool,
    /// Unit direction toward the sun (east/north/up).
    pub sun_direction: [f64; 3],
    /// The sun's irradiance at the layer (after the atmosphere), per channel.
    pub sunlight: [f64; 3],
    /// The sky's irradiance on a horizontal surface at the layer, per channel.
    pub skylight: [f64; 3],
    /// Radiance of the fog the layer fades into (the horizon sky), per channel.
    pub fog_colour: [f64; 3],
}

/// A layer's uniform block; layout identical to WGSL `CloudLayerUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs)]
pub struct CloudLayerUniforms {
    pub base_radius: f32,
    pub top_radius: f32,
    pub planet_radius: f32,
    pub curved: u32,
    pub feature_size: f32,
    pub stretch: f32,
    pub octaves: u32,
    pub seed: u32,
    pub threshold: f32,
    pub softness: f32,
    pub optical_thickness: f32,
    pub asymmetry: f32,
    pub offset: [f32; 2],
    pub half_span: f32,
    pub fog_extinction: f32,
    pub sun_direction: [f32; 3],
    pub exp2_fog: u32,
    pub sunlight: [f32; 3],
    /// [`CloudLayer::core_depth`](super::CloudLayer::core_depth).
    pub core_depth: f32,
    pub skylight: [f32; 3],
    pub padding1: f32,
    pub fog_colour: [f32; 3],
    pub padding2: f32,
}

/// −ln 0.02: the optical depth at which Koschmieder's contrast threshold is reached.
const KOSCHMIEDER_OPTICAL_DEPTH: f32 = 3.912_023;

/// Value noise in [0, 1) at (x, y) (lattice units): the four corners' hashes (seed,
/// cell x, cell y) blended with the smoothstep of the fractional position.
#[doc(hidden)]
pub fn cloud_value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i32, fy as i32);
    let (tx, ty) = (x - fx, y - fy);
    let corner = |dx: i32, dy: i32| {
        unit_float_from_bits(hash_combine(
            hash_combine(seed, ix.wrapping_add(dx) as u32),
            iy.wrapping_add(dy) as u32,
        ))
    };
    let sx = tx * tx * (3.0 - 2.0 * tx);
    let sy = ty * ty * (3.0 - 2.0 * ty);
    let bottom = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    let top = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

/// fBm: `octaves` octaves of [`cloud_value_noise`], each twice the frequency and half
/// the amplitude of the previous (with its own seed), normalised to [0, 1).
#[doc(hidden)]
pub fn cloud_fbm(x: f32, y: f32, octaves: u32, seed: u32) -> f32 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0f32, 1.0f32, 0.0f32, 1.0f32);
    for octave in 0..octaves {
        sum +=
            amplitude * cloud_value_noise(x * frequency, y * frequency, hash_combine(seed, octave));
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total
}

/// Cloud density in [0, 1] at horizontal position (`u`, `v`) metres on the layer:
/// fBm at the layer's scale, stretched along u, through the coverage threshold with
/// the kind's soft edge (a smoothstep of width `softness` centred on `threshold`).
#[doc(hidden)]
pub fn cloud_density(u: f32, v: f32, layer: &CloudLayerUniforms) -> f32 {
    let x = u / (layer.feature_size * layer.stretch);
    let y = v / layer.feature_size;
    let n = cloud_fbm(x, y, layer.octaves, layer.seed);
    let t = ((n - layer.threshold) / layer.softness + 0.5).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Fraction of the direct sun that reaches a point under the layer: the sun's ray from
/// the point crosses the layer's base where the texture has density ρ, and the
/// element's vertical optical thickness τ along the slant leaves exp(−τρ/μ☉) — the
/// `direct` term `cloud_layer_radiance` lights the layer with. `point` is east/north/up
/// metres from the viewer (on the +z axis at radius `r`), the sun the layer's
/// `sun_direction`. 1 for a point at or above the layer's top, outside its patch, or
/// with the sun at or below the horizon (no direct sun for the layer to block). The
/// base is taken flat over the point (the layer's curvature over a shadow's reach is
/// left out: 0.2 m at 1.6 km).
pub fn cloud_shadow(point: [f32; 3], r: f32, layer: &CloudLayerUniforms) -> f32 {
    let sun = layer.sun_direction;
    let mu_sun = sun[2];
    let point_radius = r + point[2];
    if mu_sun <= 0.0 || point_radius >= layer.top_radius {
        return 1.0;
    }
    let distance = (layer.base_radius - point_radius).max(0.0) / mu_sun;
    let x = point[0] + sun[0] * distance;
    let y = point[1] + sun[1] * distance;
    if (x * x + y * y).sqrt() >= layer.half_span {
        return 1.0;
    }
    let density = cloud_density(x + layer.offset[0], y + layer.offset[1], layer);
    (-layer.optical_thickness * density / mu_sun).exp()
}

/// Eddington two-stream reflectance of a conservative layer of optical thickness
/// `optical_thickness` and asymmetry `asymmetry`, lit at cosine `mu_sun` (Lacis &
/// Hansen 1974); the sun below the layer's horizon (μ₀ ≤ 0) reflects nothing. One
/// formula: the f64 instantiation is the reference.
#[doc(hidden)]
pub fn cloud_reflectance<F: Real>(optical_thickness: F, asymmetry: F, mu_sun: F) -> F {
    if mu_sun <= F::zero() {
        return F::zero();
    }
    let scaled = (F::one() - asymmetry) * optical_thickness;
    let direct = F::one() - (-optical_thickness / mu_sun).exp();
    ((scaled + (F::of(2.0 / 3.0) - mu_sun) * direct) / (F::of(4.0 / 3.0) + scaled))
        .max(F::zero())
        .min(F::one())
}

/// The cloud at horizontal position (`u`, `v`) metres on the layer, as
/// `[coverage, optical_thickness]`: the fraction of the area the cloud covers there (the
/// coverage noise's smoothstep across the edge, [`cloud_density`]'s) and the vertical
/// optical thickness of the cloud where it is: the kind's τ × the noise's height above
/// the edge's foot (threshold − softness/2), floored at the edge's middle (the
/// threshold), over the layer's `core_depth` (that height's mean over the covered area,
/// noise above the threshold). An element's edge is partial cover of a finite column —
/// a cloud's edge is sharp at the scale of a pixel, not a sheet thinning to nothing —
/// and its core is thick; τ is the covered area's mean (ISCCP's τ is a mean over cloudy
/// pixels: Rossow & Schiffer 1999).
#[doc(hidden)]
pub fn cloud_column(u: f32, v: f32, layer: &CloudLayerUniforms) -> [f32; 2] {
    let x = u / (layer.feature_size * layer.stretch);
    let y = v / layer.feature_size;
    let n = cloud_fbm(x, y, layer.octaves, layer.seed);
    let height = (n - layer.threshold) / layer.softness + 0.5;
    let t = height.clamp(0.0, 1.0);
    let coverage = t * t * (3.0 - 2.0 * t);
    [
        coverage,
        layer.optical_thickness * (height.max(0.5) * layer.softness / layer.core_depth),
    ]
}

/// The area-mean vertical optical thickness at (`u`, `v`): coverage × the column's
/// ([`cloud_column`]), what a volume of the same layer holds there.
#[doc(hidden)]
pub fn cloud_optical_thickness(u: f32, v: f32, layer: &CloudLayerUniforms) -> f32 {
    let [coverage, column] = cloud_column(u, v, layer);
    coverage * column
}

/// (1 − e^{−y})/y for y ≥ 0 (1 at y = 0): the mean of e^{−y s} over s ∈ [0, 1].
fn mean_attenuation<F: Real>(y: F) -> F {
    if y < F::of(1e-6) {
        return F::one() - F::of(0.5) * y;
    }
    F::one_minus_exp_neg(y) / y
}

/// Radiance (1/sr, per unit of the sun's irradiance normal to its beam) that a
/// horizontally uniform conservative column of vertical optical thickness
/// `optical_thickness` and Henyey–Greenstein asymmetry `asymmetry`, lit from above at
/// `mu_sun`, sends toward a viewer at zenith-cosine magnitude `mu_view` (> 0) and
/// scattering-angle cosine `cos_scattering`, reflected from its top (`transmitted` 0)
/// or transmitted through its base (1).
///
/// Two parts (the single-scattering split of Nakajima & Tanaka 1988, with a two-stream
/// multiple-scattering part as in Liou 2002 §6.5):
/// * single scattering, exact for the column (Chandrasekhar 1960 §§ 10–11; Liou 2002
///   eq. 6.4.4): `P(Θ)·(τ/μ)·⟨e^{−…}⟩` with `P` Henyey–Greenstein, which makes the
///   forward glow around the sun through thin cloud (the silver lining) and the weak
///   side-scatter of thin cloud away from it;
/// * the rest of Eddington's two-stream flux (reflectance R of [`cloud_reflectance`],
///   diffuse transmittance `1 − R − e^{−τ/μ₀}`) less the singly scattered flux (the
///   Eddington backscatter fraction `β₀ = 1/2 − 3gμ₀/4` of Meador & Weaver 1980, each
///   half escaping along the diffusivity path 1/1.66), spread as a uniform source seen
///   through the column's opacity `(1 − e^{−τ/μ})/(1 − e^{−1.66τ})` (Lambertian for a
///   thick column). A thick core's base is dark because its diffuse transmittance
///   falls as τ grows.
///
/// The two parts together send out Eddington's flux (the single part exactly its own
/// escaping flux where the β₀ estimate holds), so no column scatters more than it
/// receives. 0 with the sun at or below the horizon or no cloud.
#[doc(hidden)]
pub fn cloud_sun_scattering<F: Real>(
    optical_thickness: F,
    asymmetry: F,
    mu_sun: F,
    mu_view: F,
    cos_scattering: F,
    transmitted: u32,
) -> F {
    let tau = optical_thickness;
    if mu_sun <= F::zero() || tau <= F::zero() {
        return F::zero();
    }
    let diffusivity = F::of(f64::from(DIFFUSIVITY));
    let phase = atmos::phase::henyey_greenstein_phase(cos_scattering, asymmetry);
    let backscatter = (F::of(0.5) - F::of(0.75) * asymmetry * mu_sun)
        .max(F::zero())
        .min(F::one());
    let reflectance = cloud_reflectance(tau, asymmetry, mu_sun);
    let (single, flux) = if transmitted != 0 {
        // ∫₀^τ e^{−t/μ₀} e^{−(τ−t)/μ} dt/μ = (τ/μ)·e^{−τ/max(μ₀, μ)}·⟨e^{−τ|1/μ − 1/μ₀|s}⟩.
        let single = tau / mu_view
            * (-tau / mu_sun.max(mu_view)).exp()
            * mean_attenuation(tau * (F::one() / mu_view - F::one() / mu_sun).abs());
        let single_flux = (F::one() - backscatter) * tau / mu_sun
            * (-tau / mu_sun.max(F::one() / diffusivity)).exp()
            * mean_attenuation(tau * (diffusivity - F::one() / mu_sun).abs());
        let diffuse = F::one() - reflectance - (-tau / mu_sun).exp();
        (single, (diffuse - single_flux).max(F::zero()))
    } else {
        // ∫₀^τ e^{−t/μ₀} e^{−t/μ} dt/μ = (τ/μ)·⟨e^{−τ(1/μ₀ + 1/μ)s}⟩.
        let single =
            tau / mu_view * mean_attenuation(tau * (F::one() / mu_sun + F::one() / mu_view));
        let single_flux =
            backscatter * tau / mu_sun * mean_attenuation(tau * (F::one() / mu_sun + diffusivity));
        (single, (reflectance - single_flux).max(F::zero()))
    };
    let opacity = F::one_minus_exp_neg(tau / mu_view);
    let emissivity = F::one_minus_exp_neg(diffusivity * tau);
    phase * single + flux * mu_sun * F::of(std::f64::consts::FRAC_1_PI) * opacity / emissivity
}

/// Distance (m) along a view from radius `r` with zenith cosine `mu` to the layer
/// surface of radius `layer_radius`: the sphere (curved) or the plane at that altitude
/// (flat); −1 when the view does not reach it (or the viewer is on it).
#[doc(hidden)]
pub fn cloud_layer_distance(r: f32, mu: f32, layer_radius: f32, curved: u32) -> f32 {
    if curved != 0 {
        let hit = atmos::geometry::ray_sphere_intersect(r, mu, layer_radius);
        if r < layer_radius {
            return hit[1];
        }
        if hit[0] >= 0.0 && mu < 0.0 {
            return hit[0];
        }
        return -1.0;
    }
    let height = layer_radius - r;
    if (height > 0.0 && mu > 0.0) || (height < 0.0 && mu < 0.0) {
        return height / mu;
    }
    -1.0
}

/// The diffusivity factor: a slab's diffuse transmission of its own uniform source,
/// `1 − 2E₃(τ)`, is close to `1 − exp(−1.66 τ)` (Elsasser 1942; Liou 2002, An
/// Introduction to Atmospheric Radiation, §4.4).
pub const DIFFUSIVITY: f32 = 1.66;

/// The layer seen along `view` (unit, east/north/up) from a viewer at radius `r` on
/// the +z axis, composited over `background` (the radiance behind it, per channel):
/// the layer's surface facing the viewer (its base from below, its top from above;
/// nothing from inside), the cloud's cover and column there ([`cloud_column`]), the
/// column's opacity `1 − exp(−τ/|μ_layer|)` over the background on the covered part,
/// and its own radiance: the sun's light it reflects (seen from above) or
/// transmits (from below) toward the view ([`cloud_sun_scattering`], at the scattering
/// angle between view and sun) and the sky's (Eddington's flux for diffuse light at
/// μ = 1/2, seen as a uniform source through the opacity), faded into the fog colour by
/// the fog over the distance and toward the patch's rim (linearly over its outer half).
/// Returns the composited radiance.
pub fn cloud_layer_radiance(
    view: [f32; 3],
    r: f32,
    layer: &CloudLayerUniforms,
    background: [f32; 3],
) -> [f32; 3] {
    let mu = view[2];
    let inside = r >= layer.base_radius && r <= layer.top_radius;
    if inside {
        return background;
    }
    let below = r < layer.base_radius;
    let surface = if below {
        layer.base_radius
    } else {
        layer.top_radius
    };
    let distance = cloud_layer_distance(r, mu, surface, layer.curved);
    if distance < 0.0 {
        return background;
    }
    let horizontal = [view[0] * distance, view[1] * distance];
    let reach = (horizontal[0] * horizontal[0] + horizontal[1] * horizontal[1]).sqrt();
    if reach >= layer.half_span {
        return background;
    }
    let rim = (2.0 * (1.0 - reach / layer.half_span)).min(1.0);
    // Zenith cosine of the view at the hit point (the local vertical there for a
    // curved layer) and of the sun.
    let hit_z = r + mu * distance;
    let hit_radius = if layer.curved != 0 { surface } else { hit_z };
    let mu_hit = if layer.curved != 0 {
        (view[0] * horizontal[0] + view[1] * horizontal[1] + view[2] * hit_z) / hit_radius
    } else {
        mu
    };
    let slant = mu_hit.abs().max(0.01);
    let [coverage, tau] = cloud_column(
        horizontal[0] + layer.offset[0],
        horizontal[1] + layer.offset[1],
        layer,
    );
    if coverage <= 0.0 {
        return background;
    }
    let opacity = atmos::transmittance::one_minus_exp_neg(tau / slant);
    let sun = layer.sun_direction;
    // The sun's zenith cosine at the hit point (the layer's local vertical: the
    // viewer's, the layer's curvature over the patch tilting it by under 0.2°).
    let mu_sun = sun[2];
    let cos_scattering = view[0] * sun[0] + view[1] * sun[1] + view[2] * sun[2];
    let sun_scattering = cloud_sun_scattering(
        tau,
        layer.asymmetry,
        mu_sun,
        slant,
        cos_scattering,
        u32::from(below),
    );
    // The sky: an isotropic sky above the layer lighting its top, the Eddington flux
    // for diffuse light (μ = 1/2) seen as a uniform source through the opacity.
    let sky_factor = if below {
        (1.0 - cloud_reflectance(tau, layer.asymmetry, 0.5) - (-tau / 0.5).exp()).max(0.0)
    } else {
        cloud_reflectance(tau, layer.asymmetry, 0.5)
    };
    let emissivity = atmos::transmittance::one_minus_exp_neg(DIFFUSIVITY * tau);
    let fog = if layer.exp2_fog != 0 {
        // SGSky's exp² fog with the same 2 % at the visibility: exp(−(βd)²/3.912).
        let x = layer.fog_extinction * distance;
        (-(x * x) / KOSCHMIEDER_OPTICAL_DEPTH).exp()
    } else {
        (-layer.fog_extinction * distance).exp()
    };
    std::array::from_fn(|i| {
        let lit = sun_scattering * layer.sunlight[i]
            + sky_factor * layer.skylight[i] * skyscape_wgsl::common::INV_PI * opacity / emissivity;
        let faded = fog * lit + (1.0 - fog) * opacity * layer.fog_colour[i];
        background[i] + rim * coverage * (faded - opacity * background[i])
    })
}
