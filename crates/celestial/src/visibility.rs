//! Visibility and fog: the meteorological visibility V (m) as a physical aerosol for
//! atmos (Koschmieder: the distance at which a black object's contrast against the
//! horizon sky falls to 2 %, so the extinction is −ln 0.02 / V = 3.912 / V), and
//! SGSky's classic `exp²` fog as the cheap option.
//!
//! The exponential fog factor `exp(−β d)` is what the atmosphere itself does to a
//! ground object's light (its transmittance); SGSky's ports (Speed Dreams, delta3d,
//! ossimPlanet) use `exp(−(ρ d)²)` with ρ = √(−ln c)/V, which keeps near objects
//! clearer and closes in faster beyond V. Both reach the same contrast at V here: the
//! Koschmieder threshold 2 % (SGSky's ports use 1 %, `√(−ln 0.01)`; stated so a user
//! porting their fog can match it).

use atmos::Atmosphere;

use crate::error::{CelestialError, Result, check_range};

/// Koschmieder's contrast threshold: 2 % (WMO's meteorological optical range uses 5 %;
/// the 2 % threshold is the one the issue and most graphics literature take).
pub const KOSCHMIEDER_CONTRAST: f64 = 0.02;

/// Shortest accepted visibility (m): 1 m (inside dense fog; shorter is not a
/// visibility any instrument reports).
pub const MIN_VISIBILITY_M: f64 = 1.0;
/// Longest accepted visibility (m): 1,000 km (beyond the Rayleigh limit of ~290 km
/// in green light, so an input this large says "clear air").
pub const MAX_VISIBILITY_M: f64 = 1.0e6;

/// Checks a visibility a user gives (m), naming `field`.
pub fn check_visibility(field: &'static str, visibility_m: f64) -> Result<f64> {
    check_range(field, visibility_m, MIN_VISIBILITY_M, MAX_VISIBILITY_M, "m")
}

/// Shortest visibility accepted where it is derived rather than given (m): inside
/// several overlapping cloud layers the effective visibility can fall below the 1 m a
/// user may set.
pub const MIN_DERIVED_VISIBILITY_M: f64 = 1e-3;

/// Extinction coefficient (1/m) for a visibility (m, in [1 mm, 1000 km]):
/// `−ln(0.02)/V = 3.912/V`.
pub fn extinction_from_visibility(visibility_m: f64) -> Result<f64> {
    let v = check_range(
        "visibility_m",
        visibility_m,
        MIN_DERIVED_VISIBILITY_M,
        MAX_VISIBILITY_M,
        "m",
    )?;
    Ok(-KOSCHMIEDER_CONTRAST.ln() / v)
}

/// The visibility (m) of an extinction coefficient (1/m): `3.912/β`.
pub fn visibility_from_extinction(extinction_per_m: f64) -> f64 {
    -KOSCHMIEDER_CONTRAST.ln() / extinction_per_m
}

/// Fraction of an object's contrast left at `distance_m` for a visibility (the
/// physical fog): `exp(−3.912 d / V)`.
pub fn koschmieder_fog_factor(distance_m: f64, visibility_m: f64) -> f64 {
    (KOSCHMIEDER_CONTRAST.ln() * distance_m / visibility_m).exp()
}

/// SGSky's cheap fog: `exp(−(ρ d)²)` with ρ = √(−ln 0.02)/V, equal to the physical
/// fog's 2 % at d = V.
pub fn exp2_fog_factor(distance_m: f64, visibility_m: f64) -> f64 {
    let density = (-KOSCHMIEDER_CONTRAST.ln()).sqrt() / visibility_m;
    let x = density * distance_m;
    (-x * x).exp()
}

/// An atmosphere whose aerosol gives the visibility V at the viewer's altitude.
#[derive(Debug, Clone, PartialEq)]
pub struct VisibilityAerosol {
    /// The atmosphere with its Mie coefficients scaled.
    pub atmosphere: Atmosphere,
    /// Total extinction at the viewer in the green channel (1/m).
    pub extinction_per_m: f64,
    /// The visibility this atmosphere has at the viewer (m): the asked one, or the
    /// Rayleigh limit when the asked one exceeds it.
    pub effective_visibility_m: f64,
    /// Whether the air alone (Rayleigh, ozone) already limits the visibility below the
    /// one asked for: the aerosol is then zero, and `effective_visibility_m` says what
    /// the air allows. Not silent: the caller sees it.
    pub rayleigh_limited: bool,
}

/// The green channel (550 nm), where Koschmieder's visibility is defined (the eye's
/// photopic peak).
const GREEN: usize = 1;

/// `atmosphere` with its aerosol (Mie scattering and extinction, keeping their
/// spectral shape and single-scattering albedo) scaled so that the total extinction in
/// green at `altitude_m` is 3.912/V. The aerosol keeps its scale height, so the
/// density at the ground follows from the one at the viewer. When Rayleigh scattering
/// and ozone alone exceed 3.912/V the aerosol is set to zero and the result says so
/// ([`VisibilityAerosol::rayleigh_limited`]). An atmosphere without aerosol gets
/// a grey one (equal channels, single-scattering albedo 0.9: continental aerosol,
/// Hess, Koepke & Schult 1998, OPAC).
pub fn aerosol_for_visibility(
    atmosphere: &Atmosphere,
    visibility_m: f64,
    altitude_m: f64,
) -> Result<VisibilityAerosol> {
    atmosphere
        .validate()
        .map_err(|source| CelestialError::Atmos {
            field: "atmosphere",
            source,
        })?;
    let target = extinction_from_visibility(visibility_m)?;
    let top = atmosphere.top_radius - atmosphere.planet_radius;
    let altitude = check_range("altitude_m", altitude_m, -500.0, top, "m")?;
    let rayleigh_density = (-altitude / atmosphere.rayleigh_scale_height).exp();
    let ozone_density = (1.0
        - (altitude - atmosphere.ozone_center_altitude).abs() / atmosphere.ozone_half_width)
        .max(0.0);
    let air = atmosphere.rayleigh_scattering[GREEN] * rayleigh_density
        + atmosphere.ozone_absorption[GREEN] * ozone_density;
    let mie_density = (-altitude / atmosphere.mie_scale_height).exp();
    let (shape_extinction, shape_scattering) = if atmosphere.mie_extinction[GREEN] > 0.0 {
        (
            atmosphere
                .mie_extinction
                .map(|b| b / atmosphere.mie_extinction[GREEN]),
            atmosphere
                .mie_scattering
                .map(|b| b / atmosphere.mie_extinction[GREEN]),
        )
    } else {
        ([1.0; 3], [0.9; 3])
    };
    if air >= target {
        return Ok(VisibilityAerosol {
            atmosphere: Atmosphere {
                mie_extinction: [0.0; 3],
                mie_scattering: [0.0; 3],
                ..atmosphere.clone()
            },
            extinction_per_m: air,
            effective_visibility_m: visibility_from_extinction(air),
            rayleigh_limited: true,
        });
    }
    let ground_green = (target - air) / mie_density;
    Ok(VisibilityAerosol {
        atmosphere: Atmosphere {
            mie_extinction: shape_extinction.map(|s| s * ground_green),
            mie_scattering: shape_scattering.map(|s| s * ground_green),
            ..atmosphere.clone()
        },
        extinction_per_m: target,
        effective_visibility_m: visibility_m,
        rayleigh_limited: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn koschmieder_and_exp2_meet_at_the_visibility() {
        for v in [1.0, 25.0, 5_000.0, 1e6] {
            assert!((koschmieder_fog_factor(v, v) - 0.02).abs() < 1e-12);
            assert!((exp2_fog_factor(v, v) - 0.02).abs() < 1e-12);
            // exp² is clearer nearby and thicker beyond V.
            assert!(exp2_fog_factor(0.3 * v, v) > koschmieder_fog_factor(0.3 * v, v));
            assert!(exp2_fog_factor(1.5 * v, v) < koschmieder_fog_factor(1.5 * v, v));
        }
        assert!((extinction_from_visibility(1000.0).unwrap() - 3.912e-3).abs() < 1e-6);
        for bad in [0.0, 1e-4, -1.0, f64::NAN, 2e6] {
            let e = extinction_from_visibility(bad).unwrap_err().to_string();
            assert!(e.contains("visibility_m"), "{e}");
        }
    }

    #[test]
    fn aerosol_gives_the_visibility_at_the_viewer() {
        let earth = Atmosphere::earth();
        for (v, altitude) in [
            (1.0, 0.0),
            (10_000.0, 0.0),
            (20_000.0, 3_000.0),
            (50.0, 9_000.0),
        ] {
            let a = aerosol_for_visibility(&earth, v, altitude).unwrap();
            assert!(!a.rayleigh_limited);
            a.atmosphere.validate().unwrap();
            let p = a.atmosphere.to_uniforms().unwrap();
            let beta = atmos::atmosphere::extinction_at_altitude(&p, altitude as f32)[GREEN];
            let visibility = visibility_from_extinction(f64::from(beta));
            assert!(
                (visibility / v - 1.0).abs() < 1e-4,
                "{v} at {altitude}: {visibility}"
            );
            // Spectral shape and albedo kept.
            assert!(
                (a.atmosphere.mie_scattering[0] / a.atmosphere.mie_extinction[0]
                    - earth.mie_scattering[0] / earth.mie_extinction[0])
                    .abs()
                    < 1e-12
            );
        }
        // 1000 km: clearer than clean air allows; the aerosol is zero and the result
        // says what the air allows (~290 km in green at sea level).
        let clear = aerosol_for_visibility(&earth, 1e6, 0.0).unwrap();
        assert!(clear.rayleigh_limited);
        assert_eq!(clear.atmosphere.mie_extinction, [0.0; 3]);
        assert!(
            (280e3..300e3).contains(&clear.effective_visibility_m),
            "{}",
            clear.effective_visibility_m
        );
        let e = aerosol_for_visibility(&earth, 1000.0, f64::INFINITY)
            .unwrap_err()
            .to_string();
        assert!(e.contains("altitude_m"), "{e}");
    }
}
