//! Visual magnitude → illuminance (Pogson's law).
//!
//! E = E₀ · 10^(−0.4 m), with E₀ the illuminance (lux, outside the atmosphere) of a
//! point source of visual magnitude 0. E₀ is derived from the zero point of the
//! CIE V(λ) magnitude scale in AB magnitudes given by S. Bará, "Magnitudes per
//! square arcsecond and luminance", Lighting Journal (Lighting Research &
//! Technology group, lightingjournal.org/index.php/path/article/view/77):
//! a surface of 0 mag/arcsec² has luminance L₀ = 10.96 × 10⁴ cd·m⁻², so one square
//! arcsecond of it — a point source of magnitude 0 — gives
//! E₀ = L₀ · (1″)² = 10.96 × 10⁴ · (π / 648 000)² ≈ 2.58 × 10⁻⁶ lx.
//! (The value 2.54 × 10⁻⁶ lx often quoted from Allen's *Astrophysical Quantities*
//! is 1.4 % lower; catalogue V magnitudes approximate V(λ) magnitudes.)
//!
//! [`illuminance_from_magnitude`] is written once over the float type; its f32
//! instance is the twin of the WGSL function of the same name.

use num_traits::Float;

/// Luminance of a surface of 0 mag/arcsec² in the CIE V(λ) band (cd·m⁻², Bará).
pub const ZERO_POINT_LUMINANCE_CD_M2: f64 = 10.96e4;

/// Solid angle of one square arcsecond (sr).
pub const SQUARE_ARCSECOND_SR: f64 =
    (std::f64::consts::PI / 648_000.0) * (std::f64::consts::PI / 648_000.0);

/// Illuminance of a magnitude-0 point source outside the atmosphere (lux).
pub const ZERO_MAGNITUDE_ILLUMINANCE_LX: f64 = ZERO_POINT_LUMINANCE_CD_M2 * SQUARE_ARCSECOND_SR;

/// Illuminance (lux, perpendicular to the line of sight, outside the atmosphere) of
/// a point source of visual magnitude `magnitude`: E₀ · 10^(−0.4 m).
pub fn illuminance_from_magnitude<F: Float>(magnitude: F) -> F {
    // 10^(−0.4 m) = exp(−0.4 ln 10 · m): one exp, as the WGSL twin computes it.
    let rate = F::from(-0.4 * std::f64::consts::LN_10).expect("constant fits the float type");
    let zero = F::from(ZERO_MAGNITUDE_ILLUMINANCE_LX).expect("E0 fits the float type");
    zero * (rate * magnitude).exp()
}

/// The sun's apparent visual magnitude at 1 AU, V = −26.76 (Willmer 2018, "The
/// Absolute Magnitude of the Sun in Several Filters", ApJS 236, 47, table 3). With the
/// zero point above it gives 1.30 × 10⁵ lx, inside the 1.27–1.34 × 10⁵ lx range of
/// published luminous solar constants (Darula, Kittler & Gueymard 2005).
pub const SUN_V_MAGNITUDE_AT_1_AU: f64 = -26.76;

/// Illuminance (lux) of the sun outside the atmosphere at `distance_m` from it:
/// Pogson's law for [`SUN_V_MAGNITUDE_AT_1_AU`] and the inverse square of the
/// distance in astronomical units.
pub fn sun_illuminance_lx(distance_m: f64) -> f64 {
    let au = distance_m / crate::sun::ASTRONOMICAL_UNIT_M;
    illuminance_from_magnitude(SUN_V_MAGNITUDE_AT_1_AU) / (au * au)
}

/// Luminance (cd·m⁻²) of a surface of `magnitude_per_square_arcsecond` (Bará's V(λ)
/// zero point [`ZERO_POINT_LUMINANCE_CD_M2`]).
pub fn luminance_from_surface_brightness(magnitude_per_square_arcsecond: f64) -> f64 {
    ZERO_POINT_LUMINANCE_CD_M2 * 10f64.powf(-0.4 * magnitude_per_square_arcsecond)
}

/// Surface brightness of the moonless, sunless night sky at the zenith of a dark site
/// (V mag/arcsec²): airglow, zodiacal light and unresolved starlight, 21.9 at La Palma
/// near solar minimum (Benn & Ellison 1998, "Brightness of the night sky over La
/// Palma", New Astron. Rev. 42, 503). It is the floor of the background a star is
/// seen against ([`crate::draw::star_detection_threshold`]); at it the naked-eye
/// limiting magnitude comes out at 6.6.
pub const NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2: f64 = 21.9;

/// The moon's visual magnitude at phase angle `phase_angle` (Sun–Moon–observer), at
/// distance `distance_m` from the observer and `sun_distance_m` from the sun:
/// m = −12.73 + 0.026|α| + 4 × 10⁻⁹ α⁴ (α in degrees; Allen's phase law as used by
/// Krisciunas & Schaefer 1991, PASP 103, 1033, eq. 9, valid at the mean distances)
/// plus 5 log₁₀ of the distances relative to the mean Earth–Moon distance
/// (384 400 km) and 1 AU. The law is fitted for |α| up to ~150°; near new moon it
/// extrapolates (the moon is then within a few degrees of the sun and not drawn
/// against the day sky anyway). Opposition brightening within ~7° of full is not
/// modelled (K&S: up to 35 %).
pub fn moon_magnitude(phase_angle: crate::Angle, distance_m: f64, sun_distance_m: f64) -> f64 {
    const MEAN_DISTANCE_M: f64 = 384_400e3;
    let alpha = phase_angle.degrees().abs();
    let au = sun_distance_m / crate::sun::ASTRONOMICAL_UNIT_M;
    -12.73
        + 0.026 * alpha
        + 4e-9 * alpha.powi(4)
        + 5.0 * (distance_m / MEAN_DISTANCE_M * au).log10()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sun_moon_and_night_sky_photometry() {
        let sun = sun_illuminance_lx(crate::sun::ASTRONOMICAL_UNIT_M);
        assert!((1.27e5..1.34e5).contains(&sun), "{sun}");
        // Perihelion (0.9833 AU) is 3.4 % brighter than 1 AU.
        let perihelion = sun_illuminance_lx(0.9833 * crate::sun::ASTRONOMICAL_UNIT_M);
        assert!((perihelion / sun - 1.0 / (0.9833 * 0.9833)).abs() < 1e-12);
        // Full moon at mean distances: −12.73 (≈ 0.32 lx); first quarter: −12.73 + 2.34
        // + 0.26244 = −10.12756, 2.6 magnitudes (11×) fainter.
        let au = crate::sun::ASTRONOMICAL_UNIT_M;
        let full = moon_magnitude(crate::Angle::ZERO, 384_400e3, au);
        assert!((full + 12.73).abs() < 1e-12);
        let quarter = moon_magnitude(crate::Angle::from_degrees(90.0), 384_400e3, au);
        assert!((quarter + 10.12756).abs() < 1e-9, "{quarter}");
        // Perigee (356 500 km) is 0.16 mag brighter than the mean distance.
        let perigee = moon_magnitude(crate::Angle::ZERO, 356_500e3, au);
        assert!((perigee - full - 5.0 * (356_500.0f64 / 384_400.0).log10()).abs() < 1e-12);
        // 21.9 mag/arcsec² ≈ 1.9 × 10⁻⁴ cd/m² (a dark site).
        let night = luminance_from_surface_brightness(NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2);
        assert!((night - 1.91e-4).abs() < 0.01e-4, "{night}");
    }

    #[test]
    fn zero_point_and_pogson_ratio() {
        assert!((ZERO_MAGNITUDE_ILLUMINANCE_LX - 2.576e-6).abs() < 1e-9);
        let e0 = illuminance_from_magnitude(0.0_f64);
        assert!((e0 - ZERO_MAGNITUDE_ILLUMINANCE_LX).abs() < 1e-21);
        // Five magnitudes are exactly a factor 100 (Pogson's definition).
        let ratio = illuminance_from_magnitude(1.0_f64) / illuminance_from_magnitude(6.0_f64);
        assert!((ratio - 100.0).abs() < 1e-11);
        // Sirius (V = −1.46) gives ~9.9 µlx; the full moon (V ≈ −12.7) ~0.3 lx.
        assert!((illuminance_from_magnitude(-1.46_f64) - 9.92e-6).abs() < 0.05e-6);
        let moon = illuminance_from_magnitude(-12.7_f64);
        assert!((0.25..0.35).contains(&moon), "{moon}");
    }
}
