//! Optional stellar scintillation (twinkling), off by default: each star's brightness
//! varies from one exposure to the next with a log-normal distribution of unit mean
//! whose variance follows Young's approximation (Young 1967, AJ 72, 747, as given by
//! Dravins et al. 1998, PASP 110, 610, eq. 10): `σ = 0.09 D^{−2/3} X^{1.75}
//! e^{−h/8000 m} (2t)^{−1/2}` (D the aperture in cm, X the airmass, h the observatory's
//! altitude, t the exposure in s). The airmass comes from atmos' transmittance,
//! `X = ln T(view) / ln T(zenith)`. Draws are deterministic: hashed from the seed, the
//! star and the exposure's index, so a frame can be reproduced.

use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};

use crate::error::{Result, check_range};

/// Scintillation settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scintillation {
    /// Aperture (m): the dark-adapted pupil is 7 mm.
    pub aperture_m: f64,
    /// Integration time of one exposure (s): the eye's is ≈ 0.1 s.
    pub exposure_s: f64,
    /// Seed of the draws.
    pub seed: u32,
}

impl Scintillation {
    /// The naked eye: a 7 mm pupil integrating for 0.1 s.
    pub const NAKED_EYE: Scintillation = Scintillation {
        aperture_m: 0.007,
        exposure_s: 0.1,
        seed: 0,
    };

    /// Checks the settings, naming the bad field.
    pub fn validate(&self) -> Result<()> {
        check_range("aperture_m", self.aperture_m, 1e-4, 100.0, "m")?;
        check_range("exposure_s", self.exposure_s, 1e-4, 1e4, "s")?;
        Ok(())
    }

    /// Young's σ (relative standard deviation of the intensity) at airmass `airmass`
    /// for an observer `altitude_m` up.
    pub fn relative_deviation(&self, airmass: f64, altitude_m: f64) -> f64 {
        let d_cm = self.aperture_m * 100.0;
        0.09 * d_cm.powf(-2.0 / 3.0) * airmass.max(1.0).powf(1.75) * (-altitude_m / 8000.0).exp()
            / (2.0 * self.exposure_s).sqrt()
    }

    /// The brightness factor (mean 1, log-normal) of star `star` at time `time_s` for a
    /// relative deviation `sigma`.
    pub fn factor(&self, star: u32, time_s: f64, sigma: f64) -> f64 {
        let exposure = (time_s / self.exposure_s).floor() as i64 as u64;
        let h = hash_combine(
            hash_combine(hash_combine(self.seed, star), exposure as u32),
            (exposure >> 32) as u32,
        );
        let u1 = f64::from(unit_float_from_bits(h)).max(1e-12);
        let u2 = f64::from(unit_float_from_bits(hash_combine(h, 1)));
        // Box–Muller: a standard normal deviate.
        let normal = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        let log_variance = (1.0 + sigma * sigma).ln();
        (log_variance.sqrt() * normal - 0.5 * log_variance).exp()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_mean_and_young_scaling() {
        let s = Scintillation::NAKED_EYE;
        s.validate().unwrap();
        let sigma = s.relative_deviation(1.0, 0.0);
        // 0.09 · 0.7^(−2/3) / √0.2 = 0.255 at the zenith, sea level.
        assert!((sigma - 0.2552).abs() < 1e-3, "{sigma}");
        assert!((s.relative_deviation(2.0, 0.0) / sigma - 2f64.powf(1.75)).abs() < 1e-9);
        let n = 200_000;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for k in 0..n {
            let f = s.factor(k % 1000, f64::from(k / 1000) * 0.1, sigma);
            sum += f;
            sum2 += f * f;
        }
        let mean = sum / f64::from(n);
        let deviation = (sum2 / f64::from(n) - mean * mean).sqrt();
        assert!((mean - 1.0).abs() < 0.01, "{mean}");
        assert!((deviation - sigma).abs() < 0.02, "{deviation}");
        // Deterministic; constant within one exposure.
        assert_eq!(s.factor(3, 1.23, sigma), s.factor(3, 1.23, sigma));
        assert_eq!(s.factor(3, 1.21, sigma), s.factor(3, 1.29, sigma));
        let bad = Scintillation {
            aperture_m: 0.0,
            ..s
        };
        assert!(
            bad.validate()
                .unwrap_err()
                .to_string()
                .contains("aperture_m")
        );
    }
}
