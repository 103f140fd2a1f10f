//! The smooth part of a radiance field that the multiple-scattering LUT stores, and
//! what a phase function and the ground do with it (the theory is in
//! [`super::multiple_scattering_lut`]). Pure functions, no tables: twin of
//! `shaders/atmos/lut_multiple_scattering_moments.wgsl`. The per-channel formulas are
//! generic over [`Real`]; their f64 instantiations are the parity references
//! (re-exported by [`super::reference`]).

use crate::real::{Real, count};

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
#[doc(hidden)]
pub fn sun_frame_direction<F: Real>(mu: F, mu_s: F, nu: F) -> [F; 3] {
    let (zero, one) = (F::zero(), F::one());
    let horizontal = ((one - mu) * (one + mu)).max(zero).sqrt();
    let sin_s = ((one - mu_s) * (one + mu_s)).max(zero).sqrt();
    let x = if sin_s > F::of(1e-4) {
        ((nu - mu * mu_s) / sin_s).clamp(-horizontal, horizontal)
    } else {
        zero
    };
    let y = ((horizontal - x) * (horizontal + x)).max(zero).sqrt();
    [x, y, mu]
}

/// ∮ p(ω·v) F(ω) dω for a phase function with Legendre moments `legendre` = (g₁, g₂)
/// scattering the field `moments` towards the viewer looking along `direction` (sun
/// frame): Ψ + 3 g₁ d·v + (15/2) g₂ vᵀA v, ≥ 0. The floor at 0 is the truncation's:
/// a forward-peaked phase's bands 0–2 dip below zero sideways, and a field far from
/// smooth (none in an Earth-like sky) could follow them; radiance cannot.
#[doc(hidden)]
pub fn scattered_multiple_scattering(
    moments: &MultipleScatteringMoments,
    direction: [f32; 3],
    legendre: [f32; 2],
) -> [f32; 3] {
    std::array::from_fn(|c| {
        scattered_multiple_scattering_channel(
            [
                moments.mean[c],
                moments.first_moment_x[c],
                moments.first_moment_z[c],
                moments.anisotropy_xx[c],
                moments.anisotropy_zz[c],
                moments.anisotropy_xz[c],
            ],
            direction,
            legendre,
        )
    })
}

/// One channel of [`scattered_multiple_scattering`]: `moments` = [Ψ, d_x, d_z, A_xx,
/// A_zz, A_xz] (the f64 instantiation is the parity reference).
#[doc(hidden)]
pub fn scattered_multiple_scattering_channel<F: Real>(
    moments: [F; 6],
    direction: [F; 3],
    legendre: [F; 2],
) -> F {
    let [mean, dx, dz, axx, azz, axz] = moments;
    let [x, y, z] = direction;
    let first = dx * x + dz * z;
    let second = axx * (x * x - y * y) + azz * (z * z - y * y) + F::of(2.0) * axz * x * z;
    (mean + F::of(3.0) * legendre[0] * first + F::of(7.5) * legendre[1] * second).max(F::zero())
}

/// Irradiance over π that a horizontal surface receives from the upper hemisphere of
/// the field: Ψ + 2 d_z + (15/8) A_zz (bands ≤ 2 of the clamped cosine), ≥ 0.
#[doc(hidden)]
pub fn multiple_scattering_ground_irradiance(moments: &MultipleScatteringMoments) -> [f32; 3] {
    std::array::from_fn(|c| {
        multiple_scattering_ground_irradiance_channel(
            moments.mean[c],
            moments.first_moment_z[c],
            moments.anisotropy_zz[c],
        )
    })
}

/// One channel of [`multiple_scattering_ground_irradiance`].
#[doc(hidden)]
pub fn multiple_scattering_ground_irradiance_channel<F: Real>(
    mean: F,
    first_moment_z: F,
    anisotropy_zz: F,
) -> F {
    (mean + F::of(2.0) * first_moment_z + F::of(1.875) * anisotropy_zz).max(F::zero())
}

/// Zenith sample `i` of `k` (k ≥ 2) of the bake's direction quadrature at radius `r`:
/// `[μ, w]`, w the sample's share of dμ (the weights sum to 2). ⌊k/2⌋ samples cover
/// the ground, [−1, μ_h], the rest the sky, [μ_h, 1], μ_h the cosine of the ground's
/// horizon (0 at and below the ground); each part is sampled at midpoints of u with
/// μ − μ_h ∝ ±u², so samples crowd where the field changes fastest: at the horizon,
/// where rays graze the ground and cross the most air, and across the step between
/// sky and ground. Uniform strata in μ (Hillaire's) under-weight the bright grazing
/// rays: at 8 × 8 directions they read orders ≥ 2 about 7 % low.
#[doc(hidden)]
pub fn direction_zenith_sample<F: Real>(r: F, planet_radius: F, i: u32, k: u32) -> [F; 2] {
    let (zero, one, two, half) = (F::zero(), F::one(), F::of(2.0), F::of(0.5));
    let ratio = (planet_radius / r).min(one);
    let mu_h = -((one - ratio) * (one + ratio)).max(zero).sqrt();
    let ground = k / 2;
    if i < ground {
        let u = (count::<F>(i) + half) / count::<F>(ground);
        [
            mu_h - (one + mu_h) * u * u,
            (one + mu_h) * two * u / count::<F>(ground),
        ]
    } else {
        let sky = k - ground;
        let u = (count::<F>(i - ground) + half) / count::<F>(sky);
        [
            mu_h + (one - mu_h) * u * u,
            (one - mu_h) * two * u / count::<F>(sky),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::{
        cornette_shanks_legendre_moments, cornette_shanks_phase, rayleigh_phase,
    };

    /// A fine f64 quadrature of the sphere: (direction, solid angle) pairs, midpoints
    /// in μ and azimuth.
    fn sphere(n: usize) -> Vec<([f64; 3], f64)> {
        let mut out = Vec::with_capacity(n * 2 * n);
        let cell = 2.0 / n as f64 * std::f64::consts::PI / n as f64;
        for i in 0..n {
            let z = -1.0 + (i as f64 + 0.5) * 2.0 / n as f64;
            let s = (1.0 - z * z).sqrt();
            for j in 0..2 * n {
                let phi = std::f64::consts::PI * (j as f64 + 0.5) / n as f64;
                out.push(([s * phi.cos(), s * phi.sin(), z], cell));
            }
        }
        out
    }

    /// The moments of a field, by quadrature (mirror-symmetric fields only: odd
    /// y-terms are dropped by the representation).
    fn moments_of(field: impl Fn([f64; 3]) -> f64, n: usize) -> MultipleScatteringMoments {
        let mut m = [0.0f64; 6];
        for (w, dw) in sphere(n) {
            let f = field(w) * dw / (4.0 * std::f64::consts::PI);
            let terms = [
                1.0,
                w[0],
                w[2],
                w[0] * w[0] - 1.0 / 3.0,
                w[2] * w[2] - 1.0 / 3.0,
                w[0] * w[2],
            ];
            for (k, t) in terms.iter().enumerate() {
                m[k] += f * t;
            }
        }
        MultipleScatteringMoments::from_layers(m.map(|v| [v as f32; 3]))
    }

    /// A smooth, sun-plane-symmetric field of degree ≤ 2: the representation is exact
    /// for it, so scattering it must match the phase integral for any phase function.
    fn degree_two_field(w: [f64; 3]) -> f64 {
        1.0 + 0.3 * w[0] - 0.2 * w[2] + 0.25 * w[0] * w[0] - 0.15 * w[2] * w[2]
            + 0.1 * w[0] * w[2]
            + 0.05 * w[1] * w[1]
    }

    #[test]
    fn scattering_a_degree_two_field_matches_the_phase_integral() {
        let moments = moments_of(degree_two_field, 400);
        type Phase = Box<dyn Fn(f64) -> f64>;
        let phases: [(&str, [f32; 2], Phase); 3] = [
            (
                "rayleigh",
                RAYLEIGH_LEGENDRE_MOMENTS,
                Box::new(rayleigh_phase),
            ),
            (
                "cornette-shanks 0.5",
                cornette_shanks_legendre_moments(0.5).map(|g| g as f32),
                Box::new(|mu| cornette_shanks_phase(mu, 0.5)),
            ),
            (
                "cornette-shanks 0.8",
                cornette_shanks_legendre_moments(0.8).map(|g| g as f32),
                Box::new(|mu| cornette_shanks_phase(mu, 0.8)),
            ),
        ];
        for (name, legendre, phase) in &phases {
            let views: [[f64; 3]; 4] = [
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
                [0.6, 0.0, -0.8],
                [0.48, 0.6, 0.64],
            ];
            for v in views {
                // ∮ p(ω·v) F dω in coordinates around v (μ' = ω·v), so the phase's
                // forward peak is resolved: fine midpoints in μ', and 64 azimuths (F is
                // a trigonometric polynomial of degree 2 in them: exact).
                let t1 = if v[2].abs() < 0.9 {
                    [0.0, 0.0, 1.0]
                } else {
                    [1.0, 0.0, 0.0]
                };
                let dot = t1[0] * v[0] + t1[1] * v[1] + t1[2] * v[2];
                let t1 = [t1[0] - dot * v[0], t1[1] - dot * v[1], t1[2] - dot * v[2]];
                let norm = (t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]).sqrt();
                let t1 = t1.map(|c| c / norm);
                let t2 = [
                    v[1] * t1[2] - v[2] * t1[1],
                    v[2] * t1[0] - v[0] * t1[2],
                    v[0] * t1[1] - v[1] * t1[0],
                ];
                let (n_mu, n_phi) = (20_000, 64);
                let mut exact = 0.0;
                for i in 0..n_mu {
                    let mu = -1.0 + (i as f64 + 0.5) * 2.0 / n_mu as f64;
                    let s = (1.0 - mu * mu).sqrt();
                    let mut ring = 0.0;
                    for j in 0..n_phi {
                        let phi = 2.0 * std::f64::consts::PI * j as f64 / n_phi as f64;
                        let (c, sn) = (phi.cos(), phi.sin());
                        let w: [f64; 3] =
                            std::array::from_fn(|k| mu * v[k] + s * (c * t1[k] + sn * t2[k]));
                        ring += degree_two_field(w);
                    }
                    exact += phase(mu) * ring / n_phi as f64 * 2.0 * std::f64::consts::PI * 2.0
                        / n_mu as f64;
                }
                let direction = v.map(|c| c as f32);
                let got = scattered_multiple_scattering(&moments, direction, *legendre)[0];
                assert!(
                    (f64::from(got) - exact).abs() <= 2e-4 * exact,
                    "{name} towards {v:?}: {got} vs {exact}"
                );
            }
        }
        // An isotropic field scatters as Ψ with any phase function (Hillaire's case).
        let isotropic = moments_of(|_| 2.0, 400);
        for legendre in [RAYLEIGH_LEGENDRE_MOMENTS, [0.84, 0.71]] {
            let got = scattered_multiple_scattering(&isotropic, [0.3, 0.4, 0.866], legendre)[0];
            approx::assert_relative_eq!(got, 2.0, max_relative = 1e-4);
        }
    }

    #[test]
    fn ground_irradiance_of_sky_and_ground_hemispheres_is_the_sky_alone() {
        // Sky radiance 3 above the horizon, ground radiance 0.5 below: E/π = 3 exactly.
        let moments = moments_of(|w| if w[2] > 0.0 { 3.0 } else { 0.5 }, 400);
        approx::assert_relative_eq!(
            multiple_scattering_ground_irradiance(&moments)[0],
            3.0,
            max_relative = 1e-3
        );
        // A degree-2 field: E/π = ∫_{up} F cos dω / π, by quadrature.
        let moments = moments_of(degree_two_field, 400);
        let exact: f64 = sphere(400)
            .iter()
            .filter(|(w, _)| w[2] > 0.0)
            .map(|(w, dw)| degree_two_field(*w) * w[2] * dw)
            .sum::<f64>()
            / std::f64::consts::PI;
        approx::assert_relative_eq!(
            f64::from(multiple_scattering_ground_irradiance(&moments)[0]),
            exact,
            max_relative = 1e-3
        );
    }

    #[test]
    fn sun_frame_direction_is_a_unit_vector_in_the_sun_plane_frame() {
        // Sun 30° above the horizon towards +x; views all around.
        let (mu_s, sin_s) = (0.5f32, 0.75f32.sqrt());
        for (mu, azimuth) in [(0.3f32, 0.0f32), (-0.7, 1.0), (0.0, 3.0), (0.99, 2.0)] {
            let h = (1.0 - mu * mu).sqrt();
            let v = [h * azimuth.cos(), h * azimuth.sin(), mu];
            let nu = v[0] * sin_s + v[2] * mu_s;
            let d = sun_frame_direction(mu, mu_s, nu);
            approx::assert_abs_diff_eq!(d[0], v[0], epsilon = 1e-5);
            approx::assert_abs_diff_eq!(d[1], v[1].abs(), epsilon = 1e-3);
            assert_eq!(d[2], mu);
        }
        // Sun at the zenith: no x, all horizontal in y.
        let d = sun_frame_direction(0.6, 1.0, 0.6);
        assert_eq!(d[0], 0.0);
        approx::assert_abs_diff_eq!(d[1], 0.8, epsilon = 1e-6);
    }

    #[test]
    fn zenith_samples_split_at_the_horizon_and_cover_the_sphere() {
        let planet = 6_360_000.0f32;
        for altitude in [-5.0f32, 0.0, 1_000.0, 50_000.0, 100_000.0] {
            let r = planet + altitude;
            let mu_h = -(1.0 - (planet / r).min(1.0).powi(2)).max(0.0).sqrt();
            for k in [2u32, 3, 8, 17] {
                let samples: Vec<[f32; 2]> = (0..k)
                    .map(|i| direction_zenith_sample(r, planet, i, k))
                    .collect();
                let total: f32 = samples.iter().map(|s| s[1]).sum();
                approx::assert_relative_eq!(total, 2.0, max_relative = 1e-5);
                for (i, s) in samples.iter().enumerate() {
                    assert!((-1.0..=1.0).contains(&s[0]) && s[1] > 0.0, "{s:?}");
                    let below = (i as u32) < k / 2;
                    assert_eq!(s[0] < mu_h, below, "k {k} i {i}: {s:?} vs horizon {mu_h}");
                }
                // Each part runs away from the horizon: the ground's down, the sky's up.
                let (ground, sky) = samples.split_at((k / 2) as usize);
                assert!(ground.windows(2).all(|p| p[0][0] > p[1][0]));
                assert!(sky.windows(2).all(|p| p[0][0] < p[1][0]));
            }
        }
    }
}
