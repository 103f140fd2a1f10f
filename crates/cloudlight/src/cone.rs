//! Light sampling toward the sun (Schneider 2015's 6 cone samples + 1 far sample),
//! Beer–Lambert, the powder term and dual-lobe Henyey–Greenstein scattering, written once
//! over the float type: the f32 instantiations mirror `shaders/cloudlight/cone.wgsl`
//! operation for operation, the f64 ones are the parity references.
//!
//! A light estimate at a point is an optical depth `τ = σ_t Σ wᵢ ρ(p + offsetᵢ)` over seven
//! samples ([`cone_sample`] gives each offset and weight), turned into light by
//! [`beer_lambert`]. Two weightings ([`ConeWeights`]):
//!
//! * [`ConeWeights::Raw`]: Schneider as published: six samples at `(i + 1)·Δ`
//!   spreading sideways in a cone, one far sample at `9Δ`, every weight `Δ`. The samples
//!   cover `7Δ` of the path whatever its length, so the light is biased bright wherever
//!   the cloud extends past the cone.
//! * [`ConeWeights::Partitioned`]: the same 6 + 1 layout made a quadrature of the whole
//!   path to the volume's exit `L`: `Δ = min(step, L/7)`, six samples at the midpoints
//!   `(i + ½)Δ` with weight `Δ`, the far sample at the midpoint of `[6Δ, L]` with weight
//!   `L − 6Δ` (a corrected far sample: it stands for the rest of the path).
//!
//! [`march_optical_depth`] is the accurate option: `n` midpoint steps over `[0, L]`.
//! All three are measured against the exact transmittance ([`crate::reference`]) by
//! `cargo xtask tradeoff cloudlight` (`docs/tradeoffs/cloudlight.md`).

use atmos::real::Real;

/// The six cone directions (Schneider's noise kernel, here fixed unit vectors in
/// all directions), scaled by the cone's spread and the sample's distance.
pub const CONE_KERNEL: [[f64; 3]; 6] = [
    [0.38051305, 0.92453450, -0.02111345],
    [-0.50625799, -0.03590792, -0.86163418],
    [-0.32509218, -0.94557439, 0.01428793],
    [0.09026238, -0.27376545, 0.95755166],
    [0.28128598, 0.42443639, -0.86065786],
    [-0.16852403, 0.14748697, 0.97460107],
];

/// How the seven light samples are placed and weighted (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConeWeights {
    /// Schneider's published layout: weights `Δ`, far sample at `9Δ`.
    Raw,
    /// A quadrature of the whole path to the exit (corrected far sample).
    Partitioned,
}

/// Sample `i` (0–5 cone, 6 far) of a light estimate: `[offset x, y, z, weight]` in metres,
/// the offset from the shaded point. `to_sun` is a unit vector, `step` the cone's step Δ
/// (metres), `exit_distance` the path length to the volume's exit `L` (metres; used by
/// the partitioned weighting), `spread` the cone's half-width per metre of distance
/// (0 = a straight line). WGSL twin `cone_sample`.
pub fn cone_sample<F: Real>(
    i: u32,
    to_sun: [F; 3],
    step: F,
    exit_distance: F,
    spread: F,
    weights: ConeWeights,
) -> [F; 4] {
    let half = F::of(0.5);
    let seven = F::of(7.0);
    let six = F::of(6.0);
    let (distance, weight, lateral) = match weights {
        ConeWeights::Raw => {
            if i < 6 {
                (atmos::real::count::<F>(i + 1) * step, step, spread)
            } else {
                (F::of(9.0) * step, step, F::zero())
            }
        }
        ConeWeights::Partitioned => {
            let delta = step.min(exit_distance / seven);
            if i < 6 {
                ((atmos::real::count::<F>(i) + half) * delta, delta, spread)
            } else {
                let near = six * delta;
                (
                    half * (near + exit_distance),
                    (exit_distance - near).max(F::zero()),
                    F::zero(),
                )
            }
        }
    };
    let k = CONE_KERNEL[(i.min(5)) as usize].map(F::of);
    let side = lateral * distance;
    [
        to_sun[0] * distance + side * k[0],
        to_sun[1] * distance + side * k[1],
        to_sun[2] * distance + side * k[2],
        weight,
    ]
}

/// Beer–Lambert: the transmittance `exp(−τ)` of optical depth `τ`. WGSL twin
/// `beer_lambert`.
pub fn beer_lambert<F: Real>(optical_depth: F) -> F {
    (-optical_depth).exp()
}

/// Schneider's "powder" darkening `1 − exp(−2τ)` (GPU Pro 7): dark edges where the light
/// has not yet been in-scattered. Not physical (no radiative-transfer law gives it); an
/// art-directed option, off by default. WGSL twin `powder`.
pub fn powder<F: Real>(optical_depth: F) -> F {
    F::one() - (F::of(-2.0) * optical_depth).exp()
}

/// Dual-lobe Henyey–Greenstein: `(1 − w)·HG(g_forward) + w·HG(g_back)` (1/sr), with
/// `atmos`' Henyey–Greenstein (imported, not copied: `#import atmos::phase` in WGSL).
/// WGSL twin `dual_lobe_henyey_greenstein`.
pub fn dual_lobe_henyey_greenstein<F: Real>(
    cos_theta: F,
    g_forward: F,
    g_back: F,
    back_weight: F,
) -> F {
    let forward = atmos::phase::henyey_greenstein_phase(cos_theta, g_forward);
    let back = atmos::phase::henyey_greenstein_phase(cos_theta, g_back);
    (F::one() - back_weight) * forward + back_weight * back
}

/// Distance (metres) from `p` along unit `dir` to where the ray leaves the axis-aligned
/// box `[lo, hi]` (0 when `p` is outside and moving away; the largest finite float for a
/// zero direction). WGSL twin `box_exit_distance`.
pub fn box_exit_distance<F: Real>(p: [F; 3], dir: [F; 3], lo: [F; 3], hi: [F; 3]) -> F {
    let mut exit = F::max_value();
    for a in 0..3 {
        if dir[a] > F::zero() {
            exit = exit.min((hi[a] - p[a]) / dir[a]);
        } else if dir[a] < F::zero() {
            exit = exit.min((lo[a] - p[a]) / dir[a]);
        }
    }
    exit.max(F::zero())
}

/// The 6 + 1 optical depth at `p` toward unit `to_sun`: `σ_t Σ wᵢ ρ(p + offsetᵢ)` with
/// `density` any density field (metres → density) and `exit_distance` the path to the
/// volume's exit.
#[allow(clippy::too_many_arguments)]
pub fn cone_optical_depth<F: Real>(
    density: impl Fn([F; 3]) -> F,
    sigma_t: F,
    p: [F; 3],
    to_sun: [F; 3],
    step: F,
    exit_distance: F,
    spread: F,
    weights: ConeWeights,
) -> F {
    let mut sum = F::zero();
    for i in 0..7 {
        let s = cone_sample(i, to_sun, step, exit_distance, spread, weights);
        sum = sum + s[3] * density([p[0] + s[0], p[1] + s[1], p[2] + s[2]]);
    }
    sigma_t * sum
}

/// The full light march: `σ_t Σ ρ(p + (j + ½)h·l)·h` with `h = exit_distance / steps`
/// (`steps` ≥ 1 by its type: no silent clamp of a zero).
pub fn march_optical_depth<F: Real>(
    density: impl Fn([F; 3]) -> F,
    sigma_t: F,
    p: [F; 3],
    to_sun: [F; 3],
    exit_distance: F,
    steps: std::num::NonZeroU32,
) -> F {
    let h = exit_distance / atmos::real::count::<F>(steps.get());
    let mut sum = F::zero();
    for j in 0..steps.get() {
        let t = (atmos::real::count::<F>(j) + F::of(0.5)) * h;
        sum = sum
            + density([
                p[0] + t * to_sun[0],
                p[1] + t * to_sun[1],
                p[2] + t * to_sun[2],
            ]);
    }
    sigma_t * sum * h
}

/// Bad input to the light-estimate API ([`ConeSettings`], [`FullMarchSettings`],
/// [`LightRay`]), naming the field and its value. The per-sample functions above mirror
/// WGSL and stay infallible; these constructors validate at the API edge.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ConeError {
    /// A field is out of its domain.
    #[error("{field} = {value}: {requirement}")]
    BadParameter {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
}

fn bad(field: &'static str, value: f64, requirement: &'static str) -> ConeError {
    ConeError::BadParameter {
        field,
        value,
        requirement,
    }
}

/// Validated settings of a 6 + 1 light estimate: the cone's step Δ (metres, > 0), its
/// spread (half-width per metre of distance, ≥ 0) and the weighting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConeSettings {
    step: f64,
    spread: f64,
    weights: ConeWeights,
}

impl ConeSettings {
    /// Refuses a step outside (0, [`MAX_LENGTH`]] and a spread outside [0, 100] (f32 keeps
    /// every offset finite within them).
    pub fn new(step: f64, spread: f64, weights: ConeWeights) -> Result<Self, ConeError> {
        if !(step > 0.0 && step <= MAX_LENGTH) {
            return Err(bad("step", step, "must be in (0, 1e8] (metres)"));
        }
        if !(0.0..=100.0).contains(&spread) {
            return Err(bad(
                "spread",
                spread,
                "must be in [0, 100] (half-width per metre)",
            ));
        }
        Ok(Self {
            step,
            spread,
            weights,
        })
    }

    /// Schneider's 6 + 1 light samples (Schneider & Vos 2015, "The Real-Time Volumetric
    /// Cloudscapes of Horizon Zero Dawn", SIGGRAPH Advances in Real-Time Rendering;
    /// Schneider 2016, GPU Pro 7, "Real-Time Volumetric Cloudscapes") laid out as a
    /// quadrature of the whole light path: [`ConeWeights::Partitioned`] with a step of
    /// [`MAX_LENGTH`], so the step used is `Δ = min(MAX_LENGTH, L/7) = L/7` for every
    /// path `L` (metres) the API accepts (six samples at `(i + ½)·L/7`, the far sample at
    /// `13L/14`, every weight `L/7`), and no spread (a straight line toward the sun). The
    /// cone that `cargo xtask tradeoff cloudlight` measures as "cone 6+1, partitioned,
    /// Δ = L/7"; [`crate::march::LightMarch::cone_sevenths`] is the same for the march.
    pub const fn sevenths() -> Self {
        Self {
            step: MAX_LENGTH,
            spread: 0.0,
            weights: ConeWeights::Partitioned,
        }
    }

    /// The step Δ, metres.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// The spread, half-width per metre of distance.
    pub fn spread(&self) -> f64 {
        self.spread
    }

    /// The weighting.
    pub fn weights(&self) -> ConeWeights {
        self.weights
    }
}

/// Validated settings of the full light march: its midpoint steps (1 to 65 536).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FullMarchSettings {
    steps: std::num::NonZeroU32,
}

impl FullMarchSettings {
    /// Refuses 0 steps and more than 65 536.
    pub fn new(steps: u32) -> Result<Self, ConeError> {
        match std::num::NonZeroU32::new(steps) {
            Some(n) if steps <= 65_536 => Ok(Self { steps: n }),
            _ => Err(bad(
                "steps",
                f64::from(steps),
                "must be in 1..=65536 (midpoint steps)",
            )),
        }
    }

    /// The steps.
    pub fn steps(&self) -> std::num::NonZeroU32 {
        self.steps
    }
}

/// The largest coordinate, exit distance or step the light-estimate API accepts: 1e8 m
/// (100 000 km, past any cloud in a planet-centred frame), so every f32 offset and
/// weight stays finite.
pub const MAX_LENGTH: f64 = 1e8;

/// A validated light ray: a point (|coordinates| ≤ [`MAX_LENGTH`]), the unit direction
/// toward the sun (normalised from any finite non-zero vector) and the path length to
/// the cloud's exit (in [0, [`MAX_LENGTH`]], metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightRay {
    point: [f64; 3],
    to_sun: [f64; 3],
    exit_distance: f64,
}

impl LightRay {
    /// Errors name the field: a non-finite point or direction component, a zero
    /// direction, a negative or non-finite exit distance.
    pub fn new(point: [f64; 3], to_sun: [f64; 3], exit_distance: f64) -> Result<Self, ConeError> {
        for (field, value) in ["point.x", "point.y", "point.z"].into_iter().zip(point) {
            if value.is_nan() || value.abs() > MAX_LENGTH {
                return Err(bad(field, value, "must be in [-1e8, 1e8] (metres)"));
            }
        }
        for (field, value) in ["to_sun.x", "to_sun.y", "to_sun.z"].into_iter().zip(to_sun) {
            if !value.is_finite() {
                return Err(bad(field, value, "must be finite"));
            }
        }
        let norm = to_sun.iter().map(|c| c * c).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(bad("|to_sun|", norm, "must be non-zero and finite"));
        }
        if !(0.0..=MAX_LENGTH).contains(&exit_distance) {
            return Err(bad(
                "exit_distance",
                exit_distance,
                "must be in [0, 1e8] (metres)",
            ));
        }
        Ok(Self {
            point,
            to_sun: to_sun.map(|c| c / norm),
            exit_distance,
        })
    }

    /// The ray from `point` toward the sun to where it last leaves `field` (its last
    /// span's exit; 0 when it misses): the path the light estimates integrate.
    pub fn through<D: crate::DensityField<f64> + ?Sized>(
        field: &D,
        point: [f64; 3],
        to_sun: [f64; 3],
    ) -> Result<Self, ConeError> {
        let checked = Self::new(point, to_sun, 0.0)?;
        let spans = field.ray_spans(checked.point, checked.to_sun);
        let exit = spans.as_slice().last().map_or(0.0, |&(_, exit)| exit);
        Self::new(point, to_sun, exit)
    }

    /// The point, metres.
    pub fn point(&self) -> [f64; 3] {
        self.point
    }

    /// The unit direction toward the sun.
    pub fn to_sun(&self) -> [f64; 3] {
        self.to_sun
    }

    /// The path length to the exit, metres.
    pub fn exit_distance(&self) -> f64 {
        self.exit_distance
    }

    /// The 6 + 1 optical depth ([`cone_optical_depth`]) through `field` in precision `F`,
    /// NaN-free for any valid field: densities and σ_t saturate at 1e30 (the f32 lookup of
    /// an `f32::MAX` density may round to ∞), σ_t = 0 gives 0, and the depth saturates at
    /// [`TAU_SATURATION`](crate::propagate::TAU_SATURATION). Otherwise the free function's
    /// operations exactly (σ_t times the weighted sum).
    pub fn cone_optical_depth<F: Real, D: crate::DensityField<F> + ?Sized>(
        &self,
        field: &D,
        settings: &ConeSettings,
    ) -> F {
        let saturation = F::of(crate::propagate::TAU_SATURATION);
        let sigma = field.extinction_per_density().min(saturation);
        if sigma == F::zero() {
            return F::zero();
        }
        let sum = cone_optical_depth(
            |q| field.density(q).min(saturation),
            F::one(),
            self.point.map(F::of),
            self.to_sun.map(F::of),
            F::of(settings.step),
            F::of(self.exit_distance),
            F::of(settings.spread),
            settings.weights,
        );
        (sigma * sum).min(saturation)
    }

    /// The full light march's optical depth ([`march_optical_depth`]) through `field`,
    /// NaN-free like [`LightRay::cone_optical_depth`] (the march runs with σ_t = 1 and is
    /// scaled after: the free function's value up to one rounding).
    pub fn march_optical_depth<F: Real, D: crate::DensityField<F> + ?Sized>(
        &self,
        field: &D,
        settings: &FullMarchSettings,
    ) -> F {
        let saturation = F::of(crate::propagate::TAU_SATURATION);
        let sigma = field.extinction_per_density().min(saturation);
        if sigma == F::zero() {
            return F::zero();
        }
        let depth = march_optical_depth(
            |q| field.density(q).min(saturation),
            F::one(),
            self.point.map(F::of),
            self.to_sun.map(F::of),
            F::of(self.exit_distance),
            settings.steps,
        );
        (sigma * depth.min(saturation)).min(saturation)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CloudVolume;
    use crate::reference::transmittance;

    #[test]
    fn kernel_is_unit_vectors() {
        for k in CONE_KERNEL {
            let n = k.iter().map(|c| c * c).sum::<f64>().sqrt();
            assert!((n - 1.0).abs() < 1e-6, "{n}");
        }
    }

    #[test]
    fn partitioned_weights_cover_the_path() {
        for exit in [10.0, 70.0, 700.0, 5000.0] {
            let total: f64 = (0..7)
                .map(|i| {
                    cone_sample(
                        i,
                        [0.0, 0.0, 1.0],
                        50.0,
                        exit,
                        0.0,
                        ConeWeights::Partitioned,
                    )[3]
                })
                .sum();
            assert!((total - exit).abs() < 1e-9 * exit, "{exit}: {total}");
        }
        let raw: f64 = (0..7)
            .map(|i| cone_sample(i, [0.0, 0.0, 1.0], 50.0, 5000.0, 0.3, ConeWeights::Raw)[3])
            .sum();
        assert_eq!(raw, 350.0);
    }

    #[test]
    fn homogeneous_slab_partitioned_is_exact() {
        // A constant density: the partition integrates it exactly; raw covers 7Δ only.
        let v = CloudVolume::new([4, 4, 4], [0.0; 3], 100.0, 0.004, vec![1.0; 64]).unwrap();
        let p = [200.0, 200.0, 50.0];
        let l = [0.0, 0.0, 1.0];
        let exit = box_exit_distance(p, l, [0.0; 3], [400.0; 3]);
        assert_eq!(exit, 350.0);
        let d = |q: [f64; 3]| v.density_at(q);
        let tau = cone_optical_depth(d, 0.004, p, l, 40.0, exit, 0.0, ConeWeights::Partitioned);
        let exact = -transmittance(&v, p, l, f64::INFINITY).unwrap().ln();
        assert!((tau - exact).abs() < 1e-12, "{tau} vs {exact}");
        let steps = std::num::NonZeroU32::new(5).unwrap();
        let marched = march_optical_depth(d, 0.004, p, l, exit, steps);
        assert!((marched - exact).abs() < 1e-12, "{marched} vs {exact}");
        let raw = cone_optical_depth(d, 0.004, p, l, 40.0, exit, 0.0, ConeWeights::Raw);
        assert!(raw < exact, "raw {raw} is biased bright against {exact}");
    }

    #[test]
    fn bad_light_inputs_are_named() {
        let err = ConeSettings::new(0.0, 0.2, ConeWeights::Raw).unwrap_err();
        assert!(err.to_string().starts_with("step = 0"), "{err}");
        let err = ConeSettings::new(-3.0, 0.2, ConeWeights::Raw).unwrap_err();
        assert!(err.to_string().starts_with("step = -3"), "{err}");
        let err = ConeSettings::new(10.0, f64::NAN, ConeWeights::Raw).unwrap_err();
        assert!(err.to_string().starts_with("spread = NaN"), "{err}");
        let err = FullMarchSettings::new(0).unwrap_err();
        assert!(err.to_string().starts_with("steps = 0"), "{err}");
        let err = LightRay::new([0.0; 3], [f64::NAN, 0.0, 1.0], 1.0).unwrap_err();
        assert!(err.to_string().starts_with("to_sun.x = NaN"), "{err}");
        let err = LightRay::new([0.0; 3], [0.0; 3], 1.0).unwrap_err();
        assert!(err.to_string().starts_with("|to_sun| = 0"), "{err}");
        let err = LightRay::new([0.0; 3], [0.0, 0.0, 1.0], -1.0).unwrap_err();
        assert!(err.to_string().starts_with("exit_distance = -1"), "{err}");
        let err = LightRay::new([0.0, f64::INFINITY, 0.0], [0.0, 0.0, 1.0], 1.0).unwrap_err();
        assert!(err.to_string().starts_with("point.y = inf"), "{err}");
    }

    #[test]
    fn a_light_ray_through_a_field_matches_the_free_functions() {
        let v = CloudVolume::new([4, 4, 4], [0.0; 3], 100.0, 0.004, vec![1.0; 64]).unwrap();
        let ray = LightRay::through(&v, [200.0, 200.0, 50.0], [0.0, 0.0, 2.0]).unwrap();
        assert_eq!(ray.exit_distance(), 350.0);
        let march = FullMarchSettings::new(5).unwrap();
        let tau: f64 = ray.march_optical_depth(&v, &march);
        assert!((tau - 0.004 * 350.0).abs() < 1e-12, "{tau}");
        let cone = ConeSettings::new(40.0, 0.0, ConeWeights::Partitioned).unwrap();
        let tau32: f32 = ray.cone_optical_depth(&v, &cone);
        assert!((f64::from(tau32) - 1.4).abs() < 1e-6, "{tau32}");
    }

    /// The sevenths preset is seven equal steps of `L/7` over the path (six midpoints and
    /// the far sample at the midpoint of the last seventh), whatever `L`, and the march's
    /// preset carries the same values.
    #[test]
    fn sevenths_preset_is_seven_equal_steps_over_the_path() {
        let cone = ConeSettings::sevenths();
        assert_eq!(
            ConeSettings::new(cone.step(), cone.spread(), cone.weights()),
            Ok(cone)
        );
        for exit in [1.0, 350.0, 12_000.0, MAX_LENGTH] {
            let seventh = exit / 7.0;
            for i in 0..7u32 {
                let [x, y, z, weight] = cone_sample(
                    i,
                    [0.0, 0.0, 1.0],
                    cone.step(),
                    exit,
                    cone.spread(),
                    cone.weights(),
                );
                let midpoint = (f64::from(i) + 0.5) * seventh;
                assert_eq!([x, y], [0.0, 0.0]);
                assert!(
                    (z - midpoint).abs() <= 1e-12 * exit,
                    "{exit} {i}: {z} vs {midpoint}"
                );
                assert!(
                    (weight - seventh).abs() <= 1e-12 * exit,
                    "{exit} {i}: {weight}"
                );
            }
        }
        assert_eq!(
            crate::march::LightMarch::cone_sevenths(),
            crate::march::LightMarch::Cone {
                step: cone.step(),
                spread: cone.spread(),
                weights: cone.weights(),
            }
        );
    }

    #[test]
    fn powder_and_beer_limits() {
        assert_eq!(beer_lambert(0.0f64), 1.0);
        assert_eq!(powder(0.0f64), 0.0);
        assert!((powder(50.0f64) - 1.0).abs() < 1e-15);
        let p = dual_lobe_henyey_greenstein(0.3f64, 0.8, -0.3, 0.0);
        assert_eq!(p, atmos::phase::henyey_greenstein_phase(0.3, 0.8));
    }
}
