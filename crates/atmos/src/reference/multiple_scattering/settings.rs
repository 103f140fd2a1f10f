//! The Reference's resolutions and sample counts.

use std::f64::consts::PI;

use crate::AtmosError;

/// Resolutions and sample counts of the Reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReferenceSettings {
    /// Total scattering orders, single scattering included (≥ 4).
    pub scattering_orders: u32,
    /// Query: samples along the view segment (single scattering and the
    /// multiple-scattering source alike).
    pub view_samples: u32,
    /// Query: samples along each light path of single scattering.
    pub light_samples: u32,
    /// Source table: radius (ρ/H) samples.
    pub radius_size: usize,
    /// Source table: view zenith angle samples over [0, π].
    pub view_zenith_size: usize,
    /// Source table: sun zenith angle samples over [0, [`MAX_SUN_ZENITH`]].
    pub sun_zenith_size: usize,
    /// Source table: view azimuth (relative to the sun) samples over [0, π].
    pub azimuth_size: usize,
    /// Sphere of incoming directions: zenith cells over [0, π].
    pub sphere_zenith_size: usize,
    /// Sphere of incoming directions: azimuth cells over [0, π] (mirrored to 2π).
    pub sphere_azimuth_size: usize,
    /// Samples per incoming-direction ray march during precomputation.
    pub march_samples: u32,
    /// Worker threads for the precomputation (0: all available).
    pub threads: usize,
}

/// Sun zenith angles beyond this (120°) see no light scattered from the sunlit side:
/// at the top of the atmosphere the planet's shadow starts at 100.2°, so a point at
/// 120° is > 2,000 km into the night. The source table stops here (and is 0 beyond).
pub const MAX_SUN_ZENITH: f64 = 2.0 * PI / 3.0;

impl Default for ReferenceSettings {
    /// See [`ReferenceSettings::DEFAULT_JUSTIFICATION`].
    fn default() -> Self {
        Self {
            scattering_orders: 7,
            view_samples: 256,
            light_samples: 64,
            radius_size: 16,
            view_zenith_size: 32,
            sun_zenith_size: 24,
            azimuth_size: 12,
            sphere_zenith_size: 24,
            sphere_azimuth_size: 24,
            march_samples: 32,
            threads: 0,
        }
    }
}

impl ReferenceSettings {
    /// Why the defaults: measured by `crates/atmos/tests/reference.rs`
    /// (`reference_convergence`, release only; `--nocapture` prints the figures).
    pub const DEFAULT_JUSTIFICATION: &'static str = "7 orders: the 7th contributes at most \
        0.035 % of the luminance at sun elevations ≥ 5° (orders ≥ 2 are 25 % on average); \
        256 view / 64 light samples per query (doubling both: 0.002 % mean change); a \
        16×32×24×12 source table (doubling every axis: 0.28 %) from 24×24 half-sphere \
        incoming directions marched with 32 samples (doubling all three: 0.46 %; these two \
        from runs predating the current path tracer); against the path tracer \
        (1,320 views, 4,096 samples each) day mean 0.31 %, max 1.34 %, twilight mean \
        2.0 %; about 40 s of precomputation on 2 busy cores";

    /// Small tables for tests in debug builds (a second, not a minute).
    pub fn low() -> Self {
        Self {
            scattering_orders: 4,
            view_samples: 64,
            light_samples: 16,
            radius_size: 8,
            view_zenith_size: 16,
            sun_zenith_size: 12,
            azimuth_size: 6,
            sphere_zenith_size: 12,
            sphere_azimuth_size: 8,
            march_samples: 24,
            threads: 0,
        }
    }

    /// Checks every count (the error names the field).
    pub fn validate(&self) -> Result<(), AtmosError> {
        let checks: [(&str, usize, usize, usize); 11] = [
            ("scattering_orders", self.scattering_orders as usize, 4, 64),
            ("view_samples", self.view_samples as usize, 1, 1 << 16),
            ("light_samples", self.light_samples as usize, 1, 1 << 16),
            ("radius_size", self.radius_size, 2, 1024),
            ("view_zenith_size", self.view_zenith_size, 2, 4096),
            ("sun_zenith_size", self.sun_zenith_size, 2, 4096),
            ("azimuth_size", self.azimuth_size, 2, 4096),
            ("sphere_zenith_size", self.sphere_zenith_size, 2, 4096),
            ("sphere_azimuth_size", self.sphere_azimuth_size, 1, 4096),
            ("march_samples", self.march_samples as usize, 1, 1 << 16),
            ("threads", self.threads, 0, 1024),
        ];
        for (field, value, min, max) in checks {
            if value < min || value > max {
                return Err(AtmosError::InvalidSetting {
                    setting: "reference settings",
                    field: field.to_owned(),
                    value: value as f64,
                    reason: "outside the accepted range (see ReferenceSettings::validate)",
                });
            }
        }
        Ok(())
    }
}
