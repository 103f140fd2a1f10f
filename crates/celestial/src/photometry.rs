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

#[cfg(test)]
mod tests {
    use super::*;

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
