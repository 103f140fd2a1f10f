//! Random numbers and the directions the path tracer draws: a counter-based generator,
//! exact sampling of the Rayleigh and Cornette–Shanks phase functions, and the cosine
//! lobe of a Lambertian ground.
//!
//! The generator is SplitMix64 (Steele, Lea & Flood 2014) started from a hash of
//! (seed, query, sample index): every sample has its own stream, so an estimate does not
//! depend on how rayon spreads the samples over threads, and twenty lines need no
//! dependency (the workspace has none for random numbers).

use std::f64::consts::PI;

use glam::DVec3;

const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function: a bijective 64-bit mix.
pub(super) fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// One sample's stream of uniform numbers.
#[derive(Debug, Clone)]
pub(super) struct Random {
    state: u64,
}

impl Random {
    /// The stream of sample `index` of query `query` (a hash) under `seed`.
    pub fn new(seed: u64, query: u64, index: u64) -> Self {
        Self {
            state: mix(mix(seed ^ GOLDEN_GAMMA) ^ mix(query).wrapping_add(index)),
        }
    }

    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        mix(self.state)
    }

    /// Uniform in [0, 1) with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// A unit vector at cosine `cos_theta` from unit `axis`, azimuth `phi` around it.
pub(super) fn direction_around(axis: DVec3, cos_theta: f64, phi: f64) -> DVec3 {
    let (e1, e2) = axis.any_orthonormal_pair();
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let (sin_phi, cos_phi) = phi.sin_cos();
    (cos_theta * axis + sin_theta * (cos_phi * e1 + sin_phi * e2)).normalize()
}

/// Cosine of a Rayleigh scattering angle, pdf ∝ 1 + μ²: the cubic CDF
/// (μ³ + 3μ + 4)/8 = u inverted by Cardano's formula (one real root).
pub(super) fn sample_rayleigh_cosine(u: f64) -> f64 {
    let w = 8.0 * u - 4.0;
    let a = (0.5 * w + (0.25 * w * w + 1.0).sqrt()).cbrt();
    (a - 1.0 / a).clamp(-1.0, 1.0)
}

/// Cosine of a Henyey–Greenstein scattering angle (inverse CDF).
pub(super) fn sample_henyey_greenstein_cosine(g: f64, u: f64) -> f64 {
    if g.abs() < 1e-6 {
        return 2.0 * u - 1.0;
    }
    let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
    ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
}

/// Cosine of a Cornette–Shanks scattering angle: Cornette–Shanks is Henyey–Greenstein
/// times 3(1 + μ²)/(2(2 + g²)), so a Henyey–Greenstein draw accepted with probability
/// (1 + μ²)/2 is distributed exactly as Cornette–Shanks (acceptance ≥ 1/2).
pub(super) fn sample_cornette_shanks_cosine(g: f64, random: &mut Random) -> f64 {
    loop {
        let mu = sample_henyey_greenstein_cosine(g, random.uniform());
        if 2.0 * random.uniform() < 1.0 + mu * mu {
            return mu;
        }
    }
}

/// A direction from the cosine lobe about unit `normal` (pdf cos θ/π).
pub(super) fn sample_cosine_hemisphere(normal: DVec3, random: &mut Random) -> DVec3 {
    let cos_theta = (1.0 - random.uniform()).sqrt();
    direction_around(normal, cos_theta, 2.0 * PI * random.uniform())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::cornette_shanks_legendre_moments;

    fn moments(mut draw: impl FnMut() -> f64, n: usize) -> (f64, f64) {
        let (mut p1, mut p2) = (0.0, 0.0);
        for _ in 0..n {
            let mu = draw();
            assert!((-1.0..=1.0).contains(&mu));
            p1 += mu;
            p2 += 0.5 * (3.0 * mu * mu - 1.0);
        }
        (p1 / n as f64, p2 / n as f64)
    }

    #[test]
    fn uniform_numbers_are_uniform_and_streams_differ() {
        let mut random = Random::new(7, 11, 0);
        let n = 100_000;
        let (mut mean, mut below_tenth) = (0.0, 0);
        for _ in 0..n {
            let u = random.uniform();
            assert!((0.0..1.0).contains(&u));
            mean += u;
            below_tenth += usize::from(u < 0.1);
        }
        // Mean 1/2 ± 3σ (σ = 1/√(12n)); 10 % below 0.1 ± 3σ.
        assert!((mean / n as f64 - 0.5).abs() < 3.0 / (12.0 * n as f64).sqrt());
        assert!((below_tenth as f64 / n as f64 - 0.1).abs() < 3.0 * (0.09 / n as f64).sqrt());
        let first = |seed, query, index| Random::new(seed, query, index).next_u64();
        assert_ne!(first(7, 11, 0), first(7, 11, 1));
        assert_ne!(first(7, 11, 0), first(7, 12, 0));
        assert_ne!(first(7, 11, 0), first(8, 11, 0));
        assert_eq!(first(7, 11, 0), first(7, 11, 0));
    }

    #[test]
    fn phase_samples_have_the_legendre_moments() {
        // Rayleigh: ⟨P1⟩ = 0, ⟨P2⟩ = 1/10. Cornette–Shanks: the moments used by rung 3.
        // 200,000 draws: σ(⟨P1⟩) ≤ 1/√(3n) = 1.3e−3, σ(⟨P2⟩) ≤ 2.3e−3; bound 4σ.
        let n = 200_000;
        let mut random = Random::new(1, 2, 3);
        let (p1, p2) = moments(|| sample_rayleigh_cosine(random.uniform()), n);
        assert!(p1.abs() < 5.2e-3 && (p2 - 0.1).abs() < 9.2e-3, "{p1} {p2}");
        for g in [0.8, -0.5, 0.0] {
            let mut random = Random::new(4, 5, 6);
            let (p1, p2) = moments(|| sample_cornette_shanks_cosine(g, &mut random), n);
            let [m1, m2] = cornette_shanks_legendre_moments(g);
            assert!((p1 - m1).abs() < 5.2e-3, "g {g}: {p1} vs {m1}");
            assert!((p2 - m2).abs() < 9.2e-3, "g {g}: {p2} vs {m2}");
        }
    }

    #[test]
    fn cosine_lobe_and_directions() {
        let mut random = Random::new(9, 9, 9);
        let normal = DVec3::new(0.6, 0.0, 0.8);
        let n = 100_000;
        let mut mean_cos = 0.0;
        for _ in 0..n {
            let d = sample_cosine_hemisphere(normal, &mut random);
            assert!((d.length() - 1.0).abs() < 1e-12);
            let c = d.dot(normal);
            assert!(c >= 0.0);
            mean_cos += c;
        }
        // ⟨cos θ⟩ = 2/3 for the cosine lobe; σ = √(1/2 − 4/9)/√n.
        assert!(
            (mean_cos / n as f64 - 2.0 / 3.0).abs()
                < 4.0 * (0.5f64 - 4.0 / 9.0).sqrt() / (n as f64).sqrt()
        );
        let d = direction_around(DVec3::Z, 0.3, 1.0);
        assert!((d.z - 0.3).abs() < 1e-12);
    }
}
