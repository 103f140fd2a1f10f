//! Every scattering order by Monte Carlo: an unbiased path tracer for a [`ReferenceField`]
//! lit by a directional [`Sun`], no ground, black background.
//!
//! A path starts at a camera ray and walks the medium backwards:
//!
//! * **Free flights** by delta tracking (Woodcock) with the majorant
//!   `σ̄ = extinction_per_density × density_bound` (for a
//!   [`CloudVolume`](crate::CloudVolume) its largest cell) over each of the ray's spans:
//!   tentative collisions at exponential distances of rate `σ̄`, each real with probability
//!   `σ_t ρ(x)/σ̄`. The collision point is then distributed as `σ_t(x)·T(0, x)` exactly.
//! * At the `k`-th real collision the weight is multiplied by the single-scattering albedo
//!   ϖ (collision estimator: `σ_s/σ_t`), and **next-event estimation** adds
//!   `weight · p(cos θ) · E · T_sun(x)` to order `k`, with `T_sun` by ratio tracking toward
//!   the sun (`Π (1 − σ_t ρ/σ̄)` over tentative collisions, Russian roulette below 0.1; or
//!   the field's reference optical depth, exact for a volume).
//! * The next direction is drawn from the phase function (Henyey–Greenstein inversion; a
//!   dual lobe picks its lobe first), so the phase/pdf ratio is 1. The sun is a delta
//!   light: a path that escapes adds nothing.
//!
//! Each sample's random numbers come from its own SplitMix64 stream keyed by
//! `(seed, sample index)`: results do not depend on the thread count. Samples run in
//! blocks across rayon's threads; means and standard errors (√(variance/n)) are reported
//! for single scattering (order 1), multiple scattering (orders ≥ 2) and their sum.
//! [`radiance_image`] traces every pixel of a [`PinholeCamera`](crate::march::PinholeCamera).

use rayon::prelude::*;

use super::{Phase, ReferenceError, ReferenceField, Sun, unit};

mod image;
pub use image::radiance_image;

const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// SplitMix64 (Steele, Lea & Flood 2014): one stream per sample.
#[derive(Debug, Clone)]
pub struct Random {
    state: u64,
}

impl Random {
    /// The stream of sample `index` under `seed`.
    pub fn new(seed: u64, index: u64) -> Self {
        Self {
            state: mix(mix(seed ^ GOLDEN_GAMMA).wrapping_add(mix(index))),
        }
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        (mix(self.state) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// An exponential distance of rate `rate` (> 0).
    fn exponential(&mut self, rate: f64) -> f64 {
        -(1.0 - self.uniform()).ln() / rate
    }
}

/// How next-event estimation gets the transmittance toward the sun.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SunTransmittance {
    /// Ratio tracking with the majorant (unbiased for any field), Russian roulette below 0.1.
    RatioTracking,
    /// `exp(−τ)` of [`ReferenceField::reference_optical_depth`] (exact for a volume) to
    /// within `tolerance` of optical depth.
    Reference {
        /// Absolute optical-depth tolerance for fields without an exact one.
        tolerance: f64,
    },
}

/// Settings of the path tracer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTracerSettings {
    /// Single-scattering albedo ϖ, [0, 1] (clouds: 0.99–1).
    pub albedo: f64,
    /// Paths traced (≥ 2 for a standard error).
    pub samples: u64,
    /// Seed of every sample's stream.
    pub seed: u64,
    /// Highest scattering order traced (`None`: all; `Some(1)`: single scattering only).
    pub max_order: Option<u32>,
    /// Next-event transmittance.
    pub sun_transmittance: SunTransmittance,
}

impl Default for PathTracerSettings {
    /// Albedo 1, 4096 samples, seed 2026, every order, ratio tracking.
    fn default() -> Self {
        Self {
            albedo: 1.0,
            samples: 4096,
            seed: 2026,
            max_order: None,
            sun_transmittance: SunTransmittance::RatioTracking,
        }
    }
}

impl PathTracerSettings {
    /// Checks every field's domain, naming the field.
    pub fn validate(&self) -> Result<(), ReferenceError> {
        let bad = |field, value, requirement| {
            Err(ReferenceError::BadParameter {
                field,
                value,
                requirement,
            })
        };
        if !(0.0..=1.0).contains(&self.albedo) {
            return bad("albedo", self.albedo, "must lie in [0, 1]");
        }
        if self.samples < 2 {
            return bad(
                "samples",
                self.samples as f64,
                "must be ≥ 2 (a standard error needs two)",
            );
        }
        if self.max_order == Some(0) {
            return bad("max_order", 0.0, "must be ≥ 1 (or None for every order)");
        }
        if let SunTransmittance::Reference { tolerance } = self.sun_transmittance
            && !(tolerance > 0.0 && tolerance.is_finite())
        {
            return bad(
                "sun_transmittance.tolerance",
                tolerance,
                "must be finite and > 0",
            );
        }
        Ok(())
    }
}

/// A Monte Carlo mean with its standard error, RGB.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Sample mean.
    pub mean: [f64; 3],
    /// Standard error of the mean, √(s²/n).
    pub standard_error: [f64; 3],
}

/// What [`estimate`] returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathTracerResult {
    /// Every traced order.
    pub total: Estimate,
    /// Order 1 (single scattering).
    pub single: Estimate,
    /// Orders ≥ 2.
    pub multiple: Estimate,
    /// Paths traced.
    pub samples: u64,
    /// Mean real collisions per path.
    pub mean_collisions: f64,
}

/// One camera ray drawn by a sampler: `weight × radiance(origin, direction)` is what a
/// sample contributes (1 for a uniform pick among pixels; π/cos-weighted for a flux).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RaySample {
    /// Camera position, metres.
    pub origin: [f64; 3],
    /// View direction (away from the camera), any non-zero vector.
    pub direction: [f64; 3],
    /// The sample's weight.
    pub weight: f64,
}

/// Running sums of one tally.
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    sum: f64,
    sum_sq: f64,
}

impl Sums {
    fn push(&mut self, x: f64) {
        self.sum += x;
        self.sum_sq += x * x;
    }

    fn merge(self, o: Sums) -> Sums {
        Sums {
            sum: self.sum + o.sum,
            sum_sq: self.sum_sq + o.sum_sq,
        }
    }

    fn estimate(&self, n: u64, irradiance: [f64; 3]) -> Estimate {
        let n = n as f64;
        let mean = self.sum / n;
        let variance = ((self.sum_sq / n - mean * mean) * n / (n - 1.0)).max(0.0);
        let se = (variance / n).sqrt();
        Estimate {
            mean: irradiance.map(|e| e * mean),
            standard_error: irradiance.map(|e| e * se),
        }
    }
}

#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    single: Sums,
    multiple: Sums,
    total: Sums,
    collisions: u64,
    /// Largest density / bound met (> 1: the majorant was not one).
    worst: (f64, f64),
}

impl Tally {
    fn merge(self, o: Tally) -> Tally {
        Tally {
            single: self.single.merge(o.single),
            multiple: self.multiple.merge(o.multiple),
            total: self.total.merge(o.total),
            collisions: self.collisions + o.collisions,
            worst: if o.worst.0 > self.worst.0 {
                o.worst
            } else {
                self.worst
            },
        }
    }
}

/// The fixed problem of one estimate.
struct Problem<'a, F: ?Sized> {
    field: &'a F,
    to_sun: [f64; 3],
    phase: Phase,
    settings: PathTracerSettings,
    bound: f64,
    majorant: f64,
}

fn at(o: [f64; 3], d: [f64; 3], t: f64) -> [f64; 3] {
    [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]]
}

impl<F: ReferenceField + ?Sized> Problem<'_, F> {
    /// Density at `x`, recording any excess over the bound.
    fn density(&self, x: [f64; 3], worst: &mut (f64, f64)) -> f64 {
        let rho = self.field.density(x);
        if rho > worst.0 {
            *worst = (rho, self.bound);
        }
        rho
    }

    /// Delta tracking: distance to the next real collision, `None` on escape.
    fn free_flight(
        &self,
        x: [f64; 3],
        d: [f64; 3],
        rng: &mut Random,
        worst: &mut (f64, f64),
    ) -> Option<f64> {
        if self.majorant <= 0.0 {
            return None;
        }
        let spans = self.field.ray_spans(x, d);
        for &(a, b) in spans.as_slice() {
            let mut t = a;
            loop {
                t += rng.exponential(self.majorant);
                if t >= b {
                    break;
                }
                let rho = self.density(at(x, d, t), worst);
                if rng.uniform() * self.bound < rho {
                    return Some(t);
                }
            }
        }
        None
    }

    /// Transmittance from `x` toward the sun.
    fn sun_transmittance(
        &self,
        x: [f64; 3],
        rng: &mut Random,
        worst: &mut (f64, f64),
    ) -> Result<f64, ReferenceError> {
        match self.settings.sun_transmittance {
            SunTransmittance::Reference { tolerance } => Ok((-self
                .field
                .reference_optical_depth(x, self.to_sun, f64::INFINITY, tolerance)?
                .value)
                .exp()),
            SunTransmittance::RatioTracking => {
                if self.majorant <= 0.0 {
                    return Ok(1.0);
                }
                let mut tr = 1.0;
                let spans = self.field.ray_spans(x, self.to_sun);
                for &(a, b) in spans.as_slice() {
                    let mut t = a;
                    loop {
                        t += rng.exponential(self.majorant);
                        if t >= b {
                            break;
                        }
                        let rho = self.density(at(x, self.to_sun, t), worst);
                        tr *= 1.0 - rho / self.bound;
                        if tr < 0.1 {
                            if rng.uniform() < 0.5 {
                                return Ok(0.0);
                            }
                            tr *= 2.0;
                        }
                    }
                }
                Ok(tr)
            }
        }
    }

    /// One path from a camera ray; the scalar (unit irradiance) contributions of order 1
    /// and orders ≥ 2, and the real collisions.
    fn path(
        &self,
        origin: [f64; 3],
        direction: [f64; 3],
        rng: &mut Random,
        worst: &mut (f64, f64),
    ) -> Result<(f64, f64, u64), ReferenceError> {
        let (mut x, mut d) = (origin, direction);
        let (mut single, mut multiple) = (0.0, 0.0);
        let mut weight = 1.0;
        let mut order = 0u32;
        while let Some(t) = self.free_flight(x, d, rng, worst) {
            order += 1;
            x = at(x, d, t);
            weight *= self.settings.albedo;
            if weight == 0.0 {
                break;
            }
            let cos = d[0] * self.to_sun[0] + d[1] * self.to_sun[1] + d[2] * self.to_sun[2];
            let tr = self.sun_transmittance(x, rng, worst)?;
            let contribution = weight * self.phase.value(cos) * tr;
            if order == 1 {
                single += contribution;
            } else {
                multiple += contribution;
            }
            if self.settings.max_order.is_some_and(|m| order >= m) {
                break;
            }
            let cos_theta = self.phase.sample_cosine(rng.uniform(), rng.uniform());
            d = around(d, cos_theta, std::f64::consts::TAU * rng.uniform());
        }
        Ok((single, multiple, u64::from(order)))
    }
}

/// A unit vector at cosine `cos_theta` from unit `axis`, azimuth `phi` around it.
fn around(axis: [f64; 3], cos_theta: f64, phi: f64) -> [f64; 3] {
    let a = glam::DVec3::from_array(axis);
    let (e1, e2) = a.any_orthonormal_pair();
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (s, c) = phi.sin_cos();
    (cos_theta * a + sin_theta * (c * e1 + s * e2))
        .normalize()
        .to_array()
}

/// Samples per rayon block (results do not depend on it: each sample has its own stream).
const BLOCK: u64 = 256;

/// The mean over `settings.samples` paths of `weight × radiance` of the rays `sampler`
/// draws from two uniforms in [0, 1) (a random pixel, a cosine-weighted direction…),
/// through `field` lit by `sun`, scattered by `phase`.
pub fn estimate<F: ReferenceField + ?Sized>(
    field: &F,
    sun: &Sun,
    phase: &Phase,
    settings: &PathTracerSettings,
    sampler: impl Fn([f64; 2]) -> RaySample + Sync,
) -> Result<PathTracerResult, ReferenceError> {
    let problem = Problem::new(field, sun, phase, settings)?;
    let n = settings.samples;
    let blocks = n.div_ceil(BLOCK);
    let tally = (0..blocks)
        .into_par_iter()
        .map(|b| problem.trace(settings.seed, b * BLOCK..((b + 1) * BLOCK).min(n), &sampler))
        .try_reduce(Tally::default, |a, b| Ok(a.merge(b)))?;
    problem.result(tally, sun)
}

impl<'a, F: ReferenceField + ?Sized> Problem<'a, F> {
    /// Validates the settings, the phase function and the field's density bound.
    fn new(
        field: &'a F,
        sun: &Sun,
        phase: &Phase,
        settings: &PathTracerSettings,
    ) -> Result<Self, ReferenceError> {
        settings.validate()?;
        phase.validate()?;
        let sigma = field.extinction_per_density();
        let bound = field.density_bound();
        if !(bound.is_finite() && bound >= 0.0) {
            return Err(ReferenceError::BadParameter {
                field: "density_bound",
                value: bound,
                requirement: "must be finite and ≥ 0",
            });
        }
        Ok(Problem {
            field,
            to_sun: sun.to_sun(),
            phase: *phase,
            settings: *settings,
            bound,
            majorant: sigma * bound,
        })
    }

    /// The tally of samples `indices`, each with its own stream under `seed`.
    fn trace(
        &self,
        seed: u64,
        indices: std::ops::Range<u64>,
        sampler: &(impl Fn([f64; 2]) -> RaySample + ?Sized),
    ) -> Result<Tally, ReferenceError> {
        let mut tally = Tally::default();
        for i in indices {
            let mut rng = Random::new(seed, i);
            let ray = sampler([rng.uniform(), rng.uniform()]);
            for (field_name, value) in ["origin.x", "origin.y", "origin.z"]
                .into_iter()
                .zip(ray.origin)
            {
                if !value.is_finite() {
                    return Err(ReferenceError::BadRay {
                        field: field_name,
                        value,
                        requirement: "must be finite (metres)",
                    });
                }
            }
            let d = unit(
                ray.direction,
                ["direction.x", "direction.y", "direction.z"],
                "direction",
            )?;
            let (s, m, k) = self.path(ray.origin, d, &mut rng, &mut tally.worst)?;
            tally.single.push(ray.weight * s);
            tally.multiple.push(ray.weight * m);
            tally.total.push(ray.weight * (s + m));
            tally.collisions += k;
        }
        Ok(tally)
    }

    /// The estimates of a tally of all `settings.samples` paths.
    fn result(&self, tally: Tally, sun: &Sun) -> Result<PathTracerResult, ReferenceError> {
        if tally.worst.0 > self.bound {
            return Err(ReferenceError::MajorantExceeded {
                density: tally.worst.0,
                bound: self.bound,
            });
        }
        let n = self.settings.samples;
        let e = sun.irradiance();
        Ok(PathTracerResult {
            total: tally.total.estimate(n, e),
            single: tally.single.estimate(n, e),
            multiple: tally.multiple.estimate(n, e),
            samples: n,
            mean_collisions: tally.collisions as f64 / n as f64,
        })
    }
}

/// The radiance along one view ray (every sample on the same ray).
pub fn radiance<F: ReferenceField + ?Sized>(
    field: &F,
    origin: [f64; 3],
    direction: [f64; 3],
    sun: &Sun,
    phase: &Phase,
    settings: &PathTracerSettings,
) -> Result<PathTracerResult, ReferenceError> {
    estimate(field, sun, phase, settings, |_| RaySample {
        origin,
        direction,
        weight: 1.0,
    })
}

/// Transmittance along `origin + t·direction`, `t ∈ [0, length]`, by delta tracking: the
/// fraction of `samples` free flights (stream `seed`) with no real collision before
/// `length`, with its binomial standard error `(mean, standard_error)`.
pub fn transmittance<F: ReferenceField + ?Sized>(
    field: &F,
    origin: [f64; 3],
    direction: [f64; 3],
    length: f64,
    samples: u64,
    seed: u64,
) -> Result<(f64, f64), ReferenceError> {
    if samples < 2 {
        return Err(ReferenceError::BadParameter {
            field: "samples",
            value: samples as f64,
            requirement: "must be ≥ 2",
        });
    }
    let d = unit(
        direction,
        ["direction.x", "direction.y", "direction.z"],
        "direction",
    )?;
    let bound = field.density_bound();
    let sigma = field.extinction_per_density();
    let problem = Problem {
        field,
        to_sun: d,
        phase: Phase::HenyeyGreenstein { g: 0.0 },
        settings: PathTracerSettings::default(),
        bound,
        majorant: sigma * bound,
    };
    let blocks = samples.div_ceil(BLOCK);
    let (escaped, worst) = (0..blocks)
        .into_par_iter()
        .map(|b| {
            let mut worst = (0.0, bound);
            let mut escaped = 0u64;
            for i in b * BLOCK..((b + 1) * BLOCK).min(samples) {
                let mut rng = Random::new(seed, i);
                match problem.free_flight(origin, d, &mut rng, &mut worst) {
                    Some(t) if t <= length => {}
                    _ => escaped += 1,
                }
            }
            (escaped, worst)
        })
        .reduce(
            || (0, (0.0, bound)),
            |a, b| (a.0 + b.0, if b.1.0 > a.1.0 { b.1 } else { a.1 }),
        );
    if worst.0 > bound {
        return Err(ReferenceError::MajorantExceeded {
            density: worst.0,
            bound,
        });
    }
    let p = escaped as f64 / samples as f64;
    Ok((p, (p * (1.0 - p) / samples as f64).sqrt()))
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::CloudVolume;
    use crate::reference::single_scattering::{SingleScatteringSettings, single_scattering};

    fn direction() -> impl Strategy<Value = [f64; 3]> {
        (-1.0f64..1.0, 0.0f64..std::f64::consts::TAU).prop_map(|(z, phi)| {
            let s = (1.0 - z * z).sqrt();
            [s * phi.cos(), s * phi.sin(), z]
        })
    }

    fn volume() -> impl Strategy<Value = CloudVolume> {
        (
            (1u32..=4, 1u32..=4, 1u32..=4),
            prop_oneof![Just(0.0f64), 1e-4f64..1.0],
            prop_oneof![Just(0.0f32), 0.0f32..2.0, Just(1e6f32)],
            any::<u64>(),
        )
            .prop_map(|((nx, ny, nz), sigma, scale, seed)| {
                let n = (nx * ny * nz) as u64;
                let density = (0..n)
                    .map(|i| {
                        let mut r = Random::new(seed, i);
                        scale * r.uniform() as f32
                    })
                    .collect();
                CloudVolume::new([nx, ny, nz], [-20.0, -20.0, -20.0], 10.0, sigma, density).unwrap()
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]

        /// Densities 0 to 1e6, σ_t 0 to 1 /m, grids 1³ to 4³, any sun (below the horizon
        /// too), cameras inside and outside: no NaN or Inf, transmittance in [0, 1],
        /// radiance ≥ 0, from both the single-scattering reference and the path tracer.
        #[test]
        fn outputs_are_finite_and_in_range(
            v in volume(),
            to_sun in direction(),
            view in direction(),
            origin in prop::array::uniform3(-60.0f64..60.0),
            albedo in 0.0f64..=1.0,
        ) {
            let sun = Sun::new(to_sun, [1.0, 0.5, 2.0]).unwrap();
            let phase = Phase::DualLobe { g_forward: 0.8, g_back: -0.3, back_weight: 0.2 };
            let t = crate::reference::transmittance(&v, origin, view, f64::INFINITY).unwrap();
            prop_assert!((0.0..=1.0).contains(&t), "{}", t);
            let ss = single_scattering(
                &v,
                origin,
                view,
                &sun,
                &phase,
                &SingleScatteringSettings { albedo, max_evaluations: 20_000, ..Default::default() },
            )
            .unwrap();
            for c in ss.radiance {
                prop_assert!(c.is_finite() && c >= 0.0, "{:?}", ss);
            }
            prop_assert!(ss.integral.error_estimate.is_finite());
            let settings = PathTracerSettings {
                albedo,
                samples: 32,
                max_order: Some(16),
                ..Default::default()
            };
            let mc = radiance(&v, origin, view, &sun, &phase, &settings).unwrap();
            for c in 0..3 {
                prop_assert!(mc.total.mean[c].is_finite() && mc.total.mean[c] >= 0.0, "{:?}", mc);
                prop_assert!(mc.total.standard_error[c].is_finite());
            }
            let (tr, se) = transmittance(&v, origin, view, f64::INFINITY, 32, 1).unwrap();
            prop_assert!((0.0..=1.0).contains(&tr) && se.is_finite());
        }
    }

    #[test]
    fn bad_settings_are_named() {
        let v = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, 0.1, vec![1.0]).unwrap();
        let sun = Sun::new([0.0, 0.0, 1.0], [1.0; 3]).unwrap();
        let phase = Phase::HenyeyGreenstein { g: 0.5 };
        let run = |settings: PathTracerSettings| {
            radiance(&v, [0.0; 3], [1.0, 0.0, 0.0], &sun, &phase, &settings)
                .unwrap_err()
                .to_string()
        };
        let base = PathTracerSettings::default();
        assert!(run(PathTracerSettings { samples: 1, ..base }).starts_with("samples = 1"));
        assert!(
            run(PathTracerSettings {
                albedo: -0.1,
                ..base
            })
            .starts_with("albedo = -0.1")
        );
        assert!(
            run(PathTracerSettings {
                max_order: Some(0),
                ..base
            })
            .starts_with("max_order = 0")
        );
        let err = radiance(&v, [0.0; 3], [0.0; 3], &sun, &phase, &base).unwrap_err();
        assert!(err.to_string().starts_with("direction = 0"), "{err}");
    }
}
