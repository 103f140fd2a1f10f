//! Star colour from the B−V colour index: B−V → effective temperature (Ballesteros
//! 2012, EPL 97, 34008: T = 4600 K · (1/(0.92 (B−V) + 1.7) + 1/(0.92 (B−V) + 0.62)),
//! a black-body fit), → the black body's CIE 1931 XYZ, → linear sRGB (IEC 61966-2-1
//! matrix, D65 white) scaled to unit luminance Y. Brightness comes from the
//! magnitude ([`crate::photometry`]); this is chromaticity only.
//!
//! The colour-matching functions are the multi-lobe Gaussian fit of Wyman, Sloan &
//! Shirley (JCGT 2(2), 2013), integrated against Planck's law from 360 to 830 nm in
//! 1 nm steps. The tests check the chromaticity of CIE illuminant A (a 2856 K
//! black body) and of the Planckian locus at 6500 K.

/// Effective temperature (K) of a star of colour index `b_minus_v` (Ballesteros 2012).
pub fn temperature_from_b_minus_v(b_minus_v: f64) -> f64 {
    4600.0 * (1.0 / (0.92 * b_minus_v + 1.7) + 1.0 / (0.92 * b_minus_v + 0.62))
}

/// Piecewise Gaussian lobe of the Wyman–Sloan–Shirley fit.
fn lobe(wavelength_nm: f64, mean: f64, sigma_below: f64, sigma_above: f64) -> f64 {
    let sigma = if wavelength_nm < mean {
        sigma_below
    } else {
        sigma_above
    };
    let t = (wavelength_nm - mean) / sigma;
    (-0.5 * t * t).exp()
}

/// CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `wavelength_nm` (fit).
pub fn colour_matching(wavelength_nm: f64) -> [f64; 3] {
    let l = wavelength_nm;
    [
        1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7)
            - 0.065 * lobe(l, 501.1, 20.4, 26.2),
        0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1),
        1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8),
    ]
}

/// CIE XYZ of a black body at `temperature_k`, scaled so that Y = 1.
pub fn black_body_xyz(temperature_k: f64) -> [f64; 3] {
    // Planck's law up to constant factors: λ⁻⁵ / (exp(c₂/(λT)) − 1), c₂ = hc/k.
    const SECOND_RADIATION_CONSTANT_M_K: f64 = 1.438_776_877e-2;
    let mut xyz = [0.0; 3];
    for nm in 360..=830 {
        let wavelength_m = f64::from(nm) * 1e-9;
        let radiance = wavelength_m.powi(-5)
            / (SECOND_RADIATION_CONSTANT_M_K / (wavelength_m * temperature_k)).exp_m1();
        let cmf = colour_matching(f64::from(nm));
        for k in 0..3 {
            xyz[k] += radiance * cmf[k];
        }
    }
    let y = xyz[1];
    xyz.map(|c| c / y)
}

/// Linear sRGB (D65) from CIE XYZ (IEC 61966-2-1).
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    let [x, y, z] = xyz;
    [
        3.2406 * x - 1.5372 * y - 0.4986 * z,
        -0.9689 * x + 1.8758 * y + 0.0415 * z,
        0.0557 * x - 0.2040 * y + 1.0570 * z,
    ]
}

/// Linear sRGB colour (unit luminance) of a star of colour index `b_minus_v`. Hot
/// stars fall slightly outside the sRGB gamut (negative red is clamped to 0 by the
/// caller's display path, not here).
pub fn star_colour_from_b_minus_v(b_minus_v: f64) -> [f64; 3] {
    xyz_to_linear_srgb(black_body_xyz(temperature_from_b_minus_v(b_minus_v)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chromaticity(xyz: [f64; 3]) -> (f64, f64) {
        let sum = xyz[0] + xyz[1] + xyz[2];
        (xyz[0] / sum, xyz[1] / sum)
    }

    /// Ballesteros' formula gives the sun's 5772 K to within ~10 K for B−V = 0.65.
    #[test]
    fn ballesteros_sun() {
        let t = temperature_from_b_minus_v(0.65);
        println!("B-V 0.65: {t:.0} K");
        assert!((t - 5778.0).abs() < 10.0, "{t}");
    }

    /// CIE illuminant A is a 2856 K black body: (x, y) = (0.44757, 0.40745); the
    /// Planckian locus at 6500 K is near (0.3135, 0.3236). The fitted CMFs are good
    /// to ~0.002 in chromaticity.
    #[test]
    fn black_body_chromaticities() {
        let (x, y) = chromaticity(black_body_xyz(2856.0));
        println!(
            "illuminant A: dx {:+.4}, dy {:+.4}",
            x - 0.44757,
            y - 0.40745
        );
        assert!(
            (x - 0.44757).abs() < 0.003 && (y - 0.40745).abs() < 0.003,
            "A: {x} {y}"
        );
        let (x, y) = chromaticity(black_body_xyz(6500.0));
        println!("6500 K: dx {:+.4}, dy {:+.4}", x - 0.3135, y - 0.3236);
        assert!(
            (x - 0.3135).abs() < 0.003 && (y - 0.3236).abs() < 0.003,
            "6500 K: {x} {y}"
        );
        // A 6500 K black body is nearly sRGB white; a cool star is red, a hot one blue.
        let white = xyz_to_linear_srgb(black_body_xyz(6500.0));
        assert!(white.iter().all(|c| (c - 1.0).abs() < 0.1), "{white:?}");
        let red = star_colour_from_b_minus_v(1.6);
        let blue = star_colour_from_b_minus_v(-0.2);
        assert!(red[0] > red[2] && blue[2] > blue[0], "{red:?} {blue:?}");
    }
}
