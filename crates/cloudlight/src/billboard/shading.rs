//! A particle's radiance toward the eye: phase, albedo and sky light.

use atmos::real::Real;

/// One light of a particle ([`particle_radiance`]): the sun, or the moon at night.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleLight<F> {
    /// Unit direction toward the light, in the volume's frame.
    pub direction: [F; 3],
    /// The light's irradiance at the cloud on a surface facing it (linear RGB).
    pub irradiance: [F; 3],
    /// The fraction of it that reaches the particle: the cell's light from the slice
    /// propagation toward this light ([`propagate`](crate::propagate::propagate)).
    pub transmittance: F,
}

/// How a particle scatters ([`particle_radiance`]): the single-scattering albedo, the
/// dual-lobe Henyey–Greenstein phase and the multiple-scattering octaves of the ray-march
/// ([`crate::march::MarchConfig`]'s `albedo`, `g_forward`, `g_back`, `back_weight`,
/// `octaves`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParticleScattering {
    /// σ_s/σ_t, in [0, 1].
    pub albedo: f64,
    /// Forward lobe anisotropy, in (−1, 1).
    pub g_forward: f64,
    /// Backward lobe anisotropy, in (−1, 1).
    pub g_back: f64,
    /// Weight of the backward lobe, in [0, 1].
    pub back_weight: f64,
    /// The march's octaves (`count = 1`: single scattering).
    pub octaves: crate::march::Octaves,
}

impl ParticleScattering {
    /// The march's albedo and phase (validated by [`crate::march::MarchSettings::new`]).
    pub fn of_march(settings: &crate::march::MarchSettings) -> Self {
        let c = settings.config();
        Self {
            albedo: c.albedo,
            g_forward: c.g_forward,
            g_back: c.g_back,
            back_weight: c.back_weight,
            octaves: c.octaves,
        }
    }
}

impl Default for ParticleScattering {
    /// [`crate::march::MarchConfig::default`]'s: albedo 1, lobes 0.8 and −0.3, back
    /// weight 0.2, single scattering.
    fn default() -> Self {
        Self::of_march(&crate::march::MarchSettings::default())
    }
}

/// The radiance a particle scatters toward the eye, the ray-march's source term with the
/// slices' light in place of the light march (Dobashi 2000: the sunlight attenuated to
/// the particle times the phase function, plus the sky light):
///
/// `L = albedo · (Σ_k E_k · P(τ_k, view · ω_k) + L_amb · V_amb)`
///
/// with `E_k` a light's irradiance, `ω_k` its direction, `τ_k = −ln T_k` the optical
/// depth that the particle's transmittance toward it (the slice propagation) stands for,
/// `P` the march's [`octave_scattering`](crate::march::octave_scattering) (one octave:
/// `T_k · p(view · ω_k)`, `p` the dual-lobe Henyey–Greenstein phase of
/// [`crate::cone::dual_lobe_henyey_greenstein`], 1/sr; `view · ω = 1` looking straight
/// at the light: forward scattering), `L_amb` the isotropic sky radiance and `V_amb` its
/// visibility at the particle ([`crate::march::ambient_visibility`]). `T_k = 0` is taken
/// as the smallest positive `F` (`τ` finite, so that an octave factor `a = 0` still sees
/// `e^0 = 1` as its limit does). A splat of opacity `α` then adds `α · L`: the march's
/// `(S/σ_t) · (1 − e^{−σ_t·d})` over a slab of the cell's density. `view` is the unit
/// direction from the eye to the particle.
pub fn particle_radiance<F: Real>(
    view: [F; 3],
    lights: &[ParticleLight<F>],
    ambient_radiance: [F; 3],
    ambient_visibility: F,
    scattering: &ParticleScattering,
) -> [F; 3] {
    let mut sum = [F::zero(); 3];
    let s = scattering;
    let o = s.octaves;
    for light in lights {
        let d = light.direction;
        let cos_theta = view[0] * d[0] + view[1] * d[1] + view[2] * d[2];
        let optical_depth = -light.transmittance.max(F::min_positive_value()).ln();
        let scattered = crate::march::octave_scattering(
            optical_depth,
            cos_theta,
            F::of(s.g_forward),
            F::of(s.g_back),
            F::of(s.back_weight),
            o.count,
            F::of(o.a),
            F::of(o.b),
            F::of(o.c),
        );
        for (sum, e) in sum.iter_mut().zip(light.irradiance) {
            *sum = *sum + e * scattered;
        }
    }
    let albedo = F::of(s.albedo);
    std::array::from_fn(|k| albedo * (sum[k] + ambient_radiance[k] * ambient_visibility))
}
