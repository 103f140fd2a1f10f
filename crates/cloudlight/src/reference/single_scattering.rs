//! Single scattering, converged: the radiance reaching a camera along a view ray after one
//! scattering of the directional sun,
//!
//! `L = ϖ · p(cos θ) · E · ∫ σ_t ρ(x(t)) · exp(−τ_view(0, t)) · exp(−τ_sun(x(t))) dt`,
//!
//! with `ϖ` the single-scattering albedo, `p` the phase function at
//! `cos θ = dot(view, to_sun)` (constant along the ray: the sun is directional), `E` the
//! sun's irradiance, `τ_view(0, t)` the optical depth from the camera to `x(t)` and
//! `τ_sun(x)` the optical depth from `x` toward the sun out of the field. Both optical
//! depths come from [`ReferenceField::reference_optical_depth`] at every quadrature point
//! (exact for a [`CloudVolume`](crate::CloudVolume)); the integral over `t` is adaptive
//! Simpson on each piece between the field's breakpoints (cut into panels no longer than
//! its [`max_panel_length`](ReferenceField::max_panel_length)), refined until Richardson's error
//! estimate is below `relative_tolerance` of a first estimate. The reached error is
//! returned. No ground, black background.

use super::{
    Integral, Phase, ReferenceError, ReferenceField, Sun, adaptive_simpson, initial_panels, unit,
};

/// Settings of [`single_scattering`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleScatteringSettings {
    /// Single-scattering albedo ϖ = σ_s/σ_t, [0, 1] (clouds: 0.99–1).
    pub albedo: f64,
    /// Target error of the view integral relative to its value (> 0).
    pub relative_tolerance: f64,
    /// Absolute optical-depth tolerance for fields without an exact optical depth (> 0).
    pub optical_depth_tolerance: f64,
    /// Most integrand evaluations of the view quadrature (≥ 3); a result that ran out says
    /// so (`integral.converged == false`) with its reached error.
    pub max_evaluations: usize,
}

impl Default for SingleScatteringSettings {
    /// Albedo 1, relative tolerance 1e-6, optical depth to 1e-9, 10⁶ evaluations.
    fn default() -> Self {
        Self {
            albedo: 1.0,
            relative_tolerance: 1e-6,
            optical_depth_tolerance: 1e-9,
            max_evaluations: 1_000_000,
        }
    }
}

impl SingleScatteringSettings {
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
        if !(self.relative_tolerance > 0.0 && self.relative_tolerance.is_finite()) {
            return bad(
                "relative_tolerance",
                self.relative_tolerance,
                "must be finite and > 0",
            );
        }
        if !(self.optical_depth_tolerance > 0.0 && self.optical_depth_tolerance.is_finite()) {
            return bad(
                "optical_depth_tolerance",
                self.optical_depth_tolerance,
                "must be finite and > 0",
            );
        }
        if self.max_evaluations < 3 {
            return bad(
                "max_evaluations",
                self.max_evaluations as f64,
                "must be ≥ 3",
            );
        }
        Ok(())
    }
}

/// Single-scattered radiance along one view ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleScattering {
    /// Radiance toward the camera, RGB (the sun's irradiance unit per steradian).
    pub radiance: [f64; 3],
    /// The view integral `∫ σ_t ρ T_view T_sun dt` (dimensionless) with its reached error
    /// and evaluation count.
    pub integral: Integral,
    /// Transmittance from the camera through the whole field along the ray.
    pub transmittance: f64,
}

/// Single-scattered radiance along `origin + t·direction` (`t ≥ 0`, metres; `direction`
/// any non-zero vector) through `field`, lit by `sun`, scattered by `phase`.
pub fn single_scattering<F: ReferenceField + ?Sized>(
    field: &F,
    origin: [f64; 3],
    direction: [f64; 3],
    sun: &Sun,
    phase: &Phase,
    settings: &SingleScatteringSettings,
) -> Result<SingleScattering, ReferenceError> {
    settings.validate()?;
    phase.validate()?;
    for (field_name, value) in ["origin.x", "origin.y", "origin.z"].into_iter().zip(origin) {
        if !value.is_finite() {
            return Err(ReferenceError::BadRay {
                field: field_name,
                value,
                requirement: "must be finite (metres)",
            });
        }
    }
    let d = unit(
        direction,
        ["direction.x", "direction.y", "direction.z"],
        "direction",
    )?;
    let to_sun = sun.to_sun();
    let tol_tau = settings.optical_depth_tolerance;
    let sigma = field.extinction_per_density();

    // Pieces: every span, split at the field's breakpoints.
    let spans = field.ray_spans(origin, d);
    let mut pieces = Vec::new();
    for &(a, b) in spans.as_slice() {
        let mut cuts = field.breakpoints(origin, d, a, b);
        cuts.push(a);
        cuts.push(b);
        cuts.sort_by(f64::total_cmp);
        for w in cuts.windows(2).filter(|w| w[1] > w[0]) {
            let n = initial_panels(w[1] - w[0], field.max_panel_length());
            let h = (w[1] - w[0]) / n as f64;
            pieces.extend((0..n).map(|k| {
                let end = if k + 1 == n {
                    w[1]
                } else {
                    w[0] + (k + 1) as f64 * h
                };
                (w[0] + k as f64 * h, end)
            }));
        }
    }

    // The view optical depth at each piece's start, accumulated piece by piece, so that an
    // integrand evaluation integrates only from its piece's start.
    let mut tau_start = Vec::with_capacity(pieces.len());
    let mut tau = 0.0;
    let mut previous = 0.0;
    for &(a, _) in &pieces {
        let from = [0, 1, 2].map(|i| origin[i] + previous * d[i]);
        tau += field
            .reference_optical_depth(from, d, a - previous, tol_tau)?
            .value;
        tau_start.push(tau);
        previous = a;
    }

    // The integrand on piece `k`; an optical-depth error (none for valid input) is kept
    // and returned.
    let mut failure = None;
    let mut integrand = |k: usize, t: f64| -> f64 {
        let x = [0, 1, 2].map(|i| origin[i] + t * d[i]);
        let rho = field.density(x);
        if rho == 0.0 {
            return 0.0;
        }
        let a = pieces[k].0;
        let from = [0, 1, 2].map(|i| origin[i] + a * d[i]);
        let view = field.reference_optical_depth(from, d, t - a, tol_tau);
        let light = field.reference_optical_depth(x, to_sun, f64::INFINITY, tol_tau);
        match (view, light) {
            (Ok(v), Ok(l)) => sigma * rho * (-(tau_start[k] + v.value + l.value)).exp(),
            (Err(e), _) | (_, Err(e)) => {
                failure = Some(e);
                0.0
            }
        }
    };

    // A first estimate (one Simpson panel per piece) sets the absolute tolerance.
    let mut first = 0.0;
    for (k, &(a, b)) in pieces.iter().enumerate() {
        first +=
            (b - a) / 6.0 * (integrand(k, a) + 4.0 * integrand(k, 0.5 * (a + b)) + integrand(k, b));
    }
    let total_length: f64 = pieces.iter().map(|&(a, b)| b - a).sum();
    let tolerance = settings.relative_tolerance * first.abs().max(1e-12);
    let mut integral = Integral::exact(0.0);
    let mut budget = settings.max_evaluations.saturating_sub(3 * pieces.len());
    for (k, &(a, b)) in pieces.iter().enumerate() {
        integral.add(adaptive_simpson(
            &mut |t| integrand(k, t),
            a,
            b,
            tolerance * (b - a) / total_length,
            1,
            &mut budget,
        ));
    }
    if let Some(e) = failure {
        return Err(e);
    }
    let transmittance = (-field
        .reference_optical_depth(origin, d, f64::INFINITY, tol_tau)?
        .value)
        .exp();
    let cos_theta = (0..3).map(|i| d[i] * to_sun[i]).sum::<f64>();
    let scale = settings.albedo * phase.value(cos_theta) * integral.value;
    Ok(SingleScattering {
        radiance: sun.irradiance().map(|e| e * scale),
        integral,
        transmittance,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CloudVolume;

    #[test]
    fn homogeneous_cube_seen_from_above_matches_the_slab_formula_at_its_centre() {
        // A 400 m cube, σ_t 0.005 /m (τ = 2 top to bottom), sun at 90° (straight above),
        // camera straight above looking down: no side leaks on the axis for a vertical sun.
        let v = CloudVolume::new([4, 4, 4], [0.0; 3], 100.0, 0.005, vec![1.0; 64]).unwrap();
        let sun = Sun::new([0.0, 0.0, 1.0], [1.0, 2.0, 3.0]).unwrap();
        let phase = Phase::HenyeyGreenstein { g: 0.6 };
        let s = single_scattering(
            &v,
            [200.0, 200.0, 1000.0],
            [0.0, 0.0, -1.0],
            &sun,
            &phase,
            &SingleScatteringSettings::default(),
        )
        .unwrap();
        // μ_v = μ_0 = 1: L = ϖ p(−1) E · ½ (1 − e^{−2τ}).
        let expected = phase.value(-1.0) * 0.5 * (1.0 - (-4.0f64).exp());
        for (c, e) in [1.0, 2.0, 3.0].into_iter().enumerate() {
            let rel = s.radiance[c] / (e * expected) - 1.0;
            assert!(rel.abs() < 1e-6, "{c}: {rel:e} ({:?})", s.integral);
        }
        assert!(s.integral.converged);
        assert!((s.transmittance - (-2.0f64).exp()).abs() < 1e-14);
    }

    #[test]
    fn bad_settings_are_named() {
        let v = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, 0.1, vec![1.0]).unwrap();
        let sun = Sun::new([0.0, 0.0, 1.0], [1.0; 3]).unwrap();
        let phase = Phase::HenyeyGreenstein { g: 0.5 };
        let settings = SingleScatteringSettings {
            albedo: 1.5,
            ..Default::default()
        };
        let err =
            single_scattering(&v, [0.0; 3], [1.0, 0.0, 0.0], &sun, &phase, &settings).unwrap_err();
        assert!(err.to_string().starts_with("albedo = 1.5"), "{err}");
        let err = single_scattering(
            &v,
            [0.0; 3],
            [1.0, 0.0, 0.0],
            &sun,
            &Phase::HenyeyGreenstein { g: 1.0 },
            &SingleScatteringSettings::default(),
        )
        .unwrap_err();
        assert!(err.to_string().starts_with("g = 1"), "{err}");
        assert!(Sun::new([0.0; 3], [1.0; 3]).is_err());
        assert!(Sun::new([0.0, 0.0, 1.0], [1.0, -1.0, 1.0]).is_err());
    }
}
