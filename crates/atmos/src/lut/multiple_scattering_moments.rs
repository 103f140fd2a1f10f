//! The smooth part of a radiance field that the multiple-scattering LUT stores, and
//! what a phase function and the ground do with it (the theory is in
//! [`super::multiple_scattering_lut`]). Pure functions, no tables: twin of
//! `shaders/atmos/lut_multiple_scattering_moments.wgsl`; f64 references in
//! [`super::reference`].

/// Layers of the multiple-scattering LUT: Ψ, d_x, d_z, A_xx, A_zz, A_xz.
pub const MULTIPLE_SCATTERING_LAYERS: u32 = 6;

/// Legendre moments (g₁, g₂) of the Rayleigh phase function.
pub const RAYLEIGH_LEGENDRE_MOMENTS: [f32; 2] = [0.0, 0.1];

/// The smooth part (spherical-harmonic bands 0–2) of a radiance field arriving at a
/// point, per unit sun irradiance, in the point's sun frame (z up, x towards the sun's
/// horizontal direction). ⟨·⟩ is the mean over the sphere of directions ω, each
/// direction the way one looks (light travels along −ω). Per channel.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MultipleScatteringMoments {
    /// Ψ = ⟨F⟩, the mean radiance.
    pub mean: [f32; 3],
    /// d_x = ⟨F ω_x⟩.
    pub first_moment_x: [f32; 3],
    /// d_z = ⟨F ω_z⟩.
    pub first_moment_z: [f32; 3],
    /// A_xx = ⟨F (ω_x² − 1/3)⟩.
    pub anisotropy_xx: [f32; 3],
    /// A_zz = ⟨F (ω_z² − 1/3)⟩.
    pub anisotropy_zz: [f32; 3],
    /// A_xz = ⟨F ω_x ω_z⟩.
    pub anisotropy_xz: [f32; 3],
}

impl MultipleScatteringMoments {
    /// The six layers (Ψ, d_x, d_z, A_xx, A_zz, A_xz), the table's order.
    pub fn layers(&self) -> [[f32; 3]; 6] {
        [
            self.mean,
            self.first_moment_x,
            self.first_moment_z,
            self.anisotropy_xx,
            self.anisotropy_zz,
            self.anisotropy_xz,
        ]
    }

    /// From the six layers.
    pub fn from_layers(layers: [[f32; 3]; 6]) -> Self {
        Self {
            mean: layers[0],
            first_moment_x: layers[1],
            first_moment_z: layers[2],
            anisotropy_xx: layers[3],
            anisotropy_zz: layers[4],
            anisotropy_xz: layers[5],
        }
    }
}

/// A view direction in the sun frame of a point: `[v_x, v_y, v_z]` for the direction
/// of zenith cosine `mu` and sun cosine `nu` at a point where the sun's zenith cosine
/// is `mu_s` (v_y ≥ 0: the field is mirror-symmetric in y). With the sun at the zenith
/// the frame's x is arbitrary and v_x = 0.
pub fn sun_frame_direction(mu: f32, mu_s: f32, nu: f32) -> [f32; 3] {
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

/// ∮ p(ω·v) F(ω) dω for a phase function with Legendre moments `legendre` = (g₁, g₂)
/// scattering the field `moments` towards the viewer looking along `direction` (sun
/// frame): Ψ + 3 g₁ d·v + (15/2) g₂ vᵀA v, ≥ 0. The floor at 0 is the truncation's:
/// a forward-peaked phase's bands 0–2 dip below zero sideways, and a field far from
/// smooth (none in an Earth-like sky) could follow them; radiance cannot.
pub fn scattered_multiple_scattering(
    moments: &MultipleScatteringMoments,
    direction: [f32; 3],
    legendre: [f32; 2],
) -> [f32; 3] {
    let [x, y, z] = direction;
    std::array::from_fn(|c| {
        let first = moments.first_moment_x[c] * x + moments.first_moment_z[c] * z;
        let second = moments.anisotropy_xx[c] * (x * x - y * y)
            + moments.anisotropy_zz[c] * (z * z - y * y)
            + 2.0 * moments.anisotropy_xz[c] * x * z;
        (moments.mean[c] + 3.0 * legendre[0] * first + 7.5 * legendre[1] * second).max(0.0)
    })
}

/// Irradiance over π that a horizontal surface receives from the upper hemisphere of
/// the field: Ψ + 2 d_z + (15/8) A_zz (bands ≤ 2 of the clamped cosine), ≥ 0.
pub fn multiple_scattering_ground_irradiance(moments: &MultipleScatteringMoments) -> [f32; 3] {
    std::array::from_fn(|c| {
        (moments.mean[c] + 2.0 * moments.first_moment_z[c] + 1.875 * moments.anisotropy_zz[c])
            .max(0.0)
    })
}

/// Zenith sample `i` of `k` (k ≥ 2) of the bake's direction quadrature at radius `r`:
/// `[μ, w]`, w the sample's share of dμ (the weights sum to 2). ⌊k/2⌋ samples cover
/// the ground, [−1, μ_h], the rest the sky, [μ_h, 1], μ_h the cosine of the ground's
/// horizon (0 at and below the ground); each part is sampled at midpoints of u with
/// μ − μ_h ∝ ±u², so samples crowd where the field changes fastest: at the horizon,
/// where rays graze the ground and cross the most air, and across the step between
/// sky and ground. Uniform strata in μ (Hillaire's) under-weight the bright grazing
/// rays: at 8 × 8 directions they read orders ≥ 2 about 7 % low.
pub fn direction_zenith_sample(r: f32, planet_radius: f32, i: u32, k: u32) -> [f32; 2] {
    let ratio = (planet_radius / r).min(1.0);
    let mu_h = -((1.0 - ratio) * (1.0 + ratio)).max(0.0).sqrt();
    let ground = k / 2;
    if i < ground {
        let u = (i as f32 + 0.5) / ground as f32;
        [
            mu_h - (1.0 + mu_h) * u * u,
            (1.0 + mu_h) * 2.0 * u / ground as f32,
        ]
    } else {
        let sky = k - ground;
        let u = ((i - ground) as f32 + 0.5) / sky as f32;
        [
            mu_h + (1.0 - mu_h) * u * u,
            (1.0 - mu_h) * 2.0 * u / sky as f32,
        ]
    }
}
