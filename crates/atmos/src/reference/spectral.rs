//! The spectral Reference: rung 4 evaluated at 18 wavelengths (390 … 730 nm, 20 nm
//! apart) and converted to linear sRGB through the CIE 1931 2° observer, so the RGB
//! rendering of every other rung (three coefficient sets read as sRGB channels) can
//! itself be measured.
//!
//! How an RGB [`Atmosphere`] becomes a spectrum (the channels are its coefficients at
//! [`CHANNEL_WAVELENGTHS`], ≈ 680, 550, 440 nm):
//! * Rayleigh and Mie scattering, Mie extinction: a power law in λ between neighbouring
//!   channel wavelengths, the end segments' laws extrapolated
//!   ([`spectral_coefficient`]): exact for Rayleigh's λ⁻⁴ and an Ångström-law aerosol,
//!   so Earth's coefficients come out as Bruneton's `1.24062e-6 / λ⁴` (λ in µm).
//! * Ozone: the measured absorption cross-section of O₃ (its Chappuis band, peaking
//!   near 600 nm; [`ozone_cross_section`]) scaled to the green channel. Earth's three
//!   channels are that shape at 680 / 550 / 440 nm to 0.2 %.
//! * Ground albedo: linear in λ between channel wavelengths, constant beyond.
//! * The sun: a 5,778 K black body ([`planck_spectral_radiance`]) above the atmosphere.
//!
//! Output unit: as every rung, radiance per unit sun irradiance per channel (times the
//! atmosphere's `sun_irradiance`). A spectrum is turned into a colour with the sun's
//! own spectrum as the white: channel c of a result is sRGB_c(S·L) / sRGB_c(S), where S
//! is the sun's spectral irradiance and L the per-unit-irradiance spectral radiance. A
//! wavelength-independent atmosphere therefore gives exactly the RGB Reference's
//! answer (tested), and the difference on Earth's atmosphere is the error of rendering
//! it in three channels.
//!
//! Cost: six RGB References (three wavelengths each), so six times rung 4's
//! precomputation and query.

use super::multiple_scattering::{ReferenceSettings, ReferenceSky};
use crate::{AtmosError, Atmosphere, SkyModel, SkyQuery, SkySample};

/// The wavelengths the three channels of an [`Atmosphere`] stand for (m): red, green,
/// blue.
pub const CHANNEL_WAVELENGTHS: [f64; 3] = [680e-9, 550e-9, 440e-9];

/// How many wavelengths the spectral Reference evaluates.
pub const SPECTRAL_SAMPLES: usize = 18;

/// The spectral Reference's wavelengths (m): 390 … 730 nm, 20 nm apart. Beyond them
/// the CIE 1931 functions are below 0.4 % of their peaks.
pub fn spectral_wavelengths() -> [f64; SPECTRAL_SAMPLES] {
    std::array::from_fn(|k| (390.0 + 20.0 * k as f64) * 1e-9)
}

/// Temperature of the black body that stands for the sun's spectrum (K).
pub const SUN_TEMPERATURE: f64 = 5_778.0;

/// CIE 1931 2° colour-matching functions (x̄, ȳ, z̄) at `wavelength` (m): the
/// multi-lobe Gaussian fit of Wyman, Sloan & Shirley 2013 ("Simple analytic
/// approximations to the CIE XYZ color matching functions", JCGT 2(2)), within a few
/// per cent of the tabulated functions over the visible range.
pub fn cie_1931_color_matching(wavelength: f64) -> [f64; 3] {
    let nm = wavelength * 1e9;
    // A Gaussian with different widths left and right of its peak.
    let lobe = |peak: f64, left: f64, right: f64| {
        let t = (nm - peak) / if nm < peak { left } else { right };
        (-0.5 * t * t).exp()
    };
    [
        1.056 * lobe(599.8, 37.9, 31.0) + 0.362 * lobe(442.0, 16.0, 26.7)
            - 0.065 * lobe(501.1, 20.4, 26.2),
        0.821 * lobe(568.8, 46.9, 40.5) + 0.286 * lobe(530.9, 16.3, 31.1),
        1.217 * lobe(437.0, 11.8, 36.0) + 0.681 * lobe(459.0, 26.0, 13.8),
    ]
}

/// CIE XYZ to linear sRGB (D65 white; IEC 61966-2-1).
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    const M: [[f64; 3]; 3] = [
        [3.240_454_2, -1.537_138_5, -0.498_531_4],
        [-0.969_266_0, 1.876_010_8, 0.041_556_0],
        [0.055_643_4, -0.204_025_9, 1.057_225_2],
    ];
    std::array::from_fn(|i| M[i][0] * xyz[0] + M[i][1] * xyz[1] + M[i][2] * xyz[2])
}

/// Planck's law: spectral radiance of a black body (W sr⁻¹ m⁻³) at `wavelength` (m)
/// and `temperature` (K).
pub fn planck_spectral_radiance(wavelength: f64, temperature: f64) -> f64 {
    const PLANCK: f64 = 6.626_070_15e-34; // J s
    const LIGHT_SPEED: f64 = 299_792_458.0; // m/s
    const BOLTZMANN: f64 = 1.380_649e-23; // J/K
    let exponent = PLANCK * LIGHT_SPEED / (wavelength * BOLTZMANN * temperature);
    2.0 * PLANCK * LIGHT_SPEED * LIGHT_SPEED / wavelength.powi(5) / exponent.exp_m1()
}

/// Absorption cross-section of ozone (m² per molecule) at `wavelength` (m), linear
/// between 10 nm samples from 360 to 730 nm, clamped beyond. The values are those of
/// Bruneton's 2017 reference implementation (from Serdyuchenko et al. 2013 at 293 K,
/// as tabulated there).
pub fn ozone_cross_section(wavelength: f64) -> f64 {
    const CROSS_SECTION: [f64; 38] = [
        1.18e-27, 2.182e-28, 2.818e-28, 6.636e-28, 1.527e-27, 2.763e-27, 5.52e-27, 8.451e-27,
        1.582e-26, 2.316e-26, 3.669e-26, 4.924e-26, 7.752e-26, 9.016e-26, 1.48e-25, 1.602e-25,
        2.139e-25, 2.755e-25, 3.091e-25, 3.5e-25, 4.266e-25, 4.672e-25, 4.398e-25, 4.701e-25,
        5.019e-25, 4.305e-25, 3.74e-25, 3.215e-25, 2.662e-25, 2.238e-25, 1.852e-25, 1.473e-25,
        1.209e-25, 9.423e-26, 7.455e-26, 6.566e-26, 5.105e-26, 4.15e-26,
    ];
    let position = ((wavelength * 1e9 - 360.0) / 10.0).clamp(0.0, 37.0);
    let below = (position.floor() as usize).min(36);
    let t = position - below as f64;
    CROSS_SECTION[below] + (CROSS_SECTION[below + 1] - CROSS_SECTION[below]) * t
}

/// A scattering or extinction coefficient at `wavelength` (m) from its values at
/// [`CHANNEL_WAVELENGTHS`]: a power law between neighbouring channel wavelengths and
/// the nearer segment's law beyond them (log-log linear). Where a channel is 0 the law
/// is undefined and the spectrum is linear in λ instead (constant beyond the ends).
pub fn spectral_coefficient(channels: [f64; 3], wavelength: f64) -> f64 {
    // Ordered by wavelength: blue (440), green (550), red (680).
    let points = [
        (CHANNEL_WAVELENGTHS[2], channels[2]),
        (CHANNEL_WAVELENGTHS[1], channels[1]),
        (CHANNEL_WAVELENGTHS[0], channels[0]),
    ];
    let segment = if wavelength < points[1].0 { 0 } else { 1 };
    let (l0, v0) = points[segment];
    let (l1, v1) = points[segment + 1];
    if v0 > 0.0 && v1 > 0.0 {
        let exponent = (v1 / v0).ln() / (l1 / l0).ln();
        v0 * (wavelength / l0).powf(exponent)
    } else {
        let t = ((wavelength - l0) / (l1 - l0)).clamp(0.0, 1.0);
        v0 + (v1 - v0) * t
    }
}

/// Ground albedo at `wavelength` (m): linear between the channel wavelengths,
/// constant beyond them.
pub fn spectral_albedo(channels: [f64; 3], wavelength: f64) -> f64 {
    let [red, green, blue] = channels;
    let [l_red, l_green, l_blue] = CHANNEL_WAVELENGTHS;
    if wavelength <= l_blue {
        blue
    } else if wavelength <= l_green {
        blue + (green - blue) * (wavelength - l_blue) / (l_green - l_blue)
    } else if wavelength <= l_red {
        green + (red - green) * (wavelength - l_green) / (l_red - l_green)
    } else {
        red
    }
}

/// The atmosphere at three wavelengths, one per channel (sun irradiance 1 in each:
/// results per unit spectral irradiance).
pub fn monochromatic_atmosphere(atmosphere: &Atmosphere, wavelengths: [f64; 3]) -> Atmosphere {
    let ozone_per_cross_section =
        atmosphere.ozone_absorption[1] / ozone_cross_section(CHANNEL_WAVELENGTHS[1]);
    let at = |channels: [f64; 3]| wavelengths.map(|l| spectral_coefficient(channels, l));
    Atmosphere {
        rayleigh_scattering: at(atmosphere.rayleigh_scattering),
        mie_scattering: at(atmosphere.mie_scattering),
        mie_extinction: at(atmosphere.mie_extinction),
        ozone_absorption: wavelengths.map(|l| ozone_per_cross_section * ozone_cross_section(l)),
        ground_albedo: wavelengths.map(|l| spectral_albedo(atmosphere.ground_albedo, l)),
        sun_irradiance: [1.0; 3],
        ..*atmosphere
    }
}

/// Rung 4 at [`SPECTRAL_SAMPLES`] wavelengths (or a list of the user's), as linear
/// sRGB white-balanced to the sun.
#[derive(Debug)]
pub struct SpectralReferenceSky {
    /// Three wavelengths each, in wavelength order.
    skies: Vec<ReferenceSky>,
    /// Per wavelength: the sun's spectral irradiance × the CIE functions × Δλ.
    xyz_weights: Vec<[f64; 3]>,
    /// The sun's own linear sRGB through the same weights (the white).
    sun_srgb: [f64; 3],
    /// The atmosphere's sun irradiance per channel (the output unit).
    sun_irradiance: [f64; 3],
    settings: ReferenceSettings,
}

impl SpectralReferenceSky {
    /// Validates `atmosphere` and precomputes one Reference per three of
    /// [`spectral_wavelengths`].
    pub fn new(atmosphere: &Atmosphere, settings: ReferenceSettings) -> Result<Self, AtmosError> {
        Self::with_wavelengths(atmosphere, settings, &spectral_wavelengths())
    }

    /// The same at `wavelengths` (m): evenly spaced, increasing, a multiple of three
    /// (one RGB Reference per three), within 360 … 830 nm. The error names the field.
    pub fn with_wavelengths(
        atmosphere: &Atmosphere,
        settings: ReferenceSettings,
        wavelengths: &[f64],
    ) -> Result<Self, AtmosError> {
        atmosphere.validate()?;
        let invalid = |value: f64, reason: &'static str| AtmosError::InvalidSetting {
            setting: "spectral reference",
            field: "wavelengths".to_owned(),
            value,
            reason,
        };
        if wavelengths.len() < 3 || !wavelengths.len().is_multiple_of(3) {
            return Err(invalid(
                wavelengths.len() as f64,
                "must be a non-zero multiple of 3 wavelengths",
            ));
        }
        let step = wavelengths[1] - wavelengths[0];
        for (i, &l) in wavelengths.iter().enumerate() {
            if !(360e-9..=830e-9).contains(&l) {
                return Err(invalid(l, "must lie in 360 … 830 nm (given in metres)"));
            }
            let expected = wavelengths[0] + step * i as f64;
            if step <= 0.0 || (l - expected).abs() > 1e-3 * step {
                return Err(invalid(l, "must be evenly spaced and increasing"));
            }
        }
        let skies = wavelengths
            .chunks(3)
            .map(|l| {
                ReferenceSky::new(
                    &monochromatic_atmosphere(atmosphere, [l[0], l[1], l[2]]),
                    settings,
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        let xyz_weights: Vec<[f64; 3]> = wavelengths
            .iter()
            .map(|&l| {
                let sun = planck_spectral_radiance(l, SUN_TEMPERATURE);
                cie_1931_color_matching(l).map(|cmf| sun * cmf * step)
            })
            .collect();
        let sun_xyz = std::array::from_fn(|i| xyz_weights.iter().map(|w| w[i]).sum());
        Ok(Self {
            skies,
            xyz_weights,
            sun_srgb: xyz_to_linear_srgb(sun_xyz),
            sun_irradiance: atmosphere.sun_irradiance,
            settings,
        })
    }

    /// How many wavelengths it evaluates.
    pub fn wavelength_count(&self) -> usize {
        self.xyz_weights.len()
    }

    /// Precomputation time of its References (s).
    pub fn precompute_seconds(&self) -> f64 {
        self.skies
            .iter()
            .map(ReferenceSky::precompute_seconds)
            .sum()
    }

    /// Radiance and transmittance at every wavelength, per unit spectral irradiance,
    /// in wavelength order: (radiance, transmittance) per wavelength.
    pub fn evaluate_spectrum(&self, query: &SkyQuery) -> Vec<(f64, f64)> {
        self.skies
            .iter()
            .flat_map(|sky| {
                let sample = sky.evaluate(query);
                (0..3).map(move |c| (sample.radiance[c], sample.transmittance[c]))
            })
            .collect()
    }

    /// A spectrum (per unit spectral irradiance) as linear sRGB per unit sun
    /// irradiance, white-balanced to the sun.
    pub fn spectrum_to_srgb(&self, spectrum: &[f64]) -> [f64; 3] {
        let xyz: [f64; 3] = std::array::from_fn(|i| {
            spectrum
                .iter()
                .zip(&self.xyz_weights)
                .map(|(value, weight)| value * weight[i])
                .sum()
        });
        let srgb = xyz_to_linear_srgb(xyz);
        std::array::from_fn(|c| srgb[c] / self.sun_srgb[c] * self.sun_irradiance[c])
    }
}

impl SkyModel for SpectralReferenceSky {
    fn label(&self) -> String {
        format!(
            "reference, spectral ({} wavelengths, {} orders)",
            self.wavelength_count(),
            self.settings.scattering_orders
        )
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
        let spectrum = self.evaluate_spectrum(query);
        let radiance: Vec<f64> = spectrum.iter().map(|s| s.0).collect();
        let transmittance: Vec<f64> = spectrum.iter().map(|s| s.1).collect();
        let radiance = self.spectrum_to_srgb(&radiance);
        // The transmittance of a sun-coloured beam, as the same white-balanced colour
        // (per unit irradiance, so divide the unit back out).
        let transmitted = self.spectrum_to_srgb(&transmittance);
        SkySample {
            radiance,
            transmittance: std::array::from_fn(|c| {
                (transmitted[c] / self.sun_irradiance[c]).clamp(0.0, 1.0)
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nm(l: f64) -> f64 {
        l * 1e-9
    }

    /// x̄, ȳ, z̄ summed at 1 nm over 360–830 nm (an equal-energy spectrum's XYZ).
    fn color_matching_sums() -> [f64; 3] {
        (360..=830).fold([0.0; 3], |sum, l| {
            let cmf = cie_1931_color_matching(nm(f64::from(l)));
            std::array::from_fn(|i| sum[i] + cmf[i])
        })
    }

    #[test]
    fn color_matching_fit_integrates_like_the_cie_tables() {
        // CIE 1931 2°, 1 nm sums over 360–830 nm: x̄ 106.866, ȳ 106.857, z̄ 106.892.
        let sum = color_matching_sums();
        for (i, want) in [106.866, 106.857, 106.892].into_iter().enumerate() {
            assert!((sum[i] / want - 1.0).abs() < 0.01, "{i}: {}", sum[i]);
        }
        // ȳ peaks at 1 near 555 nm
        let y555 = cie_1931_color_matching(nm(555.0))[1];
        assert!((y555 - 1.0).abs() < 0.01, "{y555}");
    }

    #[test]
    fn equal_energy_is_white_and_d65_maps_to_srgb_white() {
        let xyz = color_matching_sums();
        let total: f64 = xyz.iter().sum();
        // illuminant E: chromaticity (1/3, 1/3)
        assert!((xyz[0] / total - 1.0 / 3.0).abs() < 0.005, "{xyz:?}");
        assert!((xyz[1] / total - 1.0 / 3.0).abs() < 0.005, "{xyz:?}");
        let white = xyz_to_linear_srgb([0.950_47, 1.0, 1.088_83]);
        for c in white {
            assert!((c - 1.0).abs() < 1e-3, "{white:?}");
        }
    }

    #[test]
    fn planck_peaks_where_wien_says() {
        let peak = (300..=1200)
            .map(|l| nm(f64::from(l)))
            .max_by(|a, b| {
                planck_spectral_radiance(*a, SUN_TEMPERATURE)
                    .total_cmp(&planck_spectral_radiance(*b, SUN_TEMPERATURE))
            })
            .unwrap();
        let wien = 2.897_771_955e-3 / SUN_TEMPERATURE;
        assert!((peak - wien).abs() < 1.5e-9, "{peak} vs {wien}");
        // Stefan–Boltzmann: π ∫ B dλ = σT⁴ (1 nm steps, 50 nm – 50 µm)
        let integral: f64 = (50..50_000)
            .map(|l| planck_spectral_radiance(nm(f64::from(l) + 0.5), SUN_TEMPERATURE) * 1e-9)
            .sum();
        let sigma_t4 = 5.670_374_419e-8 * SUN_TEMPERATURE.powi(4);
        assert!(
            (std::f64::consts::PI * integral / sigma_t4 - 1.0).abs() < 1e-3,
            "{integral}"
        );
    }

    #[test]
    fn earth_spectra_match_its_channels_and_physical_laws() {
        let earth = Atmosphere::earth();
        let mono = monochromatic_atmosphere(&earth, CHANNEL_WAVELENGTHS);
        for c in 0..3 {
            let rel = |a: f64, b: f64| (a / b - 1.0).abs();
            assert!(rel(mono.rayleigh_scattering[c], earth.rayleigh_scattering[c]) < 1e-12);
            assert!(rel(mono.mie_extinction[c], earth.mie_extinction[c]) < 1e-12);
            assert!(
                rel(mono.ozone_absorption[c], earth.ozone_absorption[c]) < 2e-3,
                "ozone channel {c}: {} vs {}",
                mono.ozone_absorption[c],
                earth.ozone_absorption[c]
            );
        }
        // Rayleigh's λ⁻⁴ (Bruneton: 1.24062e-6 / λ⁴, λ in µm) beyond the channels
        for l in [390.0, 500.0, 730.0] {
            let want = 1.24062e-6 / (l / 1000.0f64).powi(4);
            let got = spectral_coefficient(earth.rayleigh_scattering, nm(l));
            assert!((got / want - 1.0).abs() < 2e-3, "{l} nm: {got} vs {want}");
        }
        // Ozone's Chappuis band peaks near 600 nm
        assert!(ozone_cross_section(nm(600.0)) > ozone_cross_section(nm(550.0)));
        assert!(ozone_cross_section(nm(600.0)) > ozone_cross_section(nm(680.0)));
        // zero channels fall back to linear, never NaN
        let v = spectral_coefficient([0.0, 1e-6, 2e-6], nm(600.0));
        assert!(v.is_finite() && (0.0..=1e-6).contains(&v), "{v}");
        assert_eq!(spectral_albedo([0.3, 0.2, 0.1], nm(390.0)), 0.1);
        assert_eq!(spectral_albedo([0.3, 0.2, 0.1], nm(730.0)), 0.3);
    }

    #[test]
    fn a_grey_atmosphere_gives_the_rgb_reference_answer() {
        // Wavelength-independent coefficients: every wavelength sees the same sky, so
        // the white-balanced colour must be the RGB Reference's, channel by channel.
        let grey = Atmosphere {
            rayleigh_scattering: [13.558e-6; 3],
            mie_scattering: [3.996e-6; 3],
            mie_extinction: [4.4e-6; 3],
            ozone_absorption: [0.0; 3],
            ground_albedo: [0.3; 3],
            sun_irradiance: [2.0, 1.5, 1.0],
            ..Atmosphere::earth()
        };
        let settings = ReferenceSettings::low();
        let spectral = SpectralReferenceSky::new(&grey, settings).unwrap();
        let rgb = ReferenceSky::new(&grey, settings).unwrap();
        let sun = glam::DVec3::new(0.6, 0.0, 0.8);
        for (altitude, view) in [
            (10.0, glam::DVec3::new(0.3, 0.2, 0.93)),
            (2_000.0, glam::DVec3::new(-0.9, 0.1, 0.05)),
        ] {
            let position = glam::DVec3::new(0.0, 0.0, grey.planet_radius + altitude);
            let q = SkyQuery::new(grey.planet_radius, position, view.normalize(), sun).unwrap();
            let got = spectral.evaluate(&q);
            let want = rgb.evaluate(&q);
            for c in 0..3 {
                let r = got.radiance[c] / want.radiance[c] - 1.0;
                let t = got.transmittance[c] - want.transmittance[c];
                assert!(r.abs() < 1e-9 && t.abs() < 1e-9, "channel {c}: {r} {t}");
            }
        }
    }

    #[test]
    fn wavelength_lists_are_validated_naming_the_field() {
        let earth = Atmosphere::earth();
        let settings = ReferenceSettings::low();
        for bad in [
            vec![500e-9, 520e-9],
            vec![500e-9, 520e-9, 560e-9],
            vec![500e-9, 500e-9, 500e-9],
            vec![300e-9, 320e-9, 340e-9],
            vec![500.0, 520.0, 540.0],
        ] {
            match SpectralReferenceSky::with_wavelengths(&earth, settings, &bad) {
                Err(AtmosError::InvalidSetting { field, .. }) => assert_eq!(field, "wavelengths"),
                other => panic!("{bad:?}: {other:?}"),
            }
        }
    }

    /// Convergence in the wavelength count and the RGB Reference's signed luminance
    /// error against the spectrum (low Reference settings, 72 sky queries from 1 km,
    /// suns 10°, 30°, 60°). CI runs it (about 8 s in the dev profile, which optimises
    /// atmos); figures: `cargo test -p atmos --lib -- --nocapture
    /// spectral_sampling_convergence`.
    #[test]
    fn spectral_sampling_convergence() {
        let earth = Atmosphere::earth();
        let settings = ReferenceSettings::low();
        let mut queries = Vec::new();
        for sun_deg in [10.0f64, 30.0, 60.0] {
            let sun = glam::DVec3::new(sun_deg.to_radians().cos(), 0.0, sun_deg.to_radians().sin());
            for i in 0..24 {
                let z = 0.02 + 0.98 * (f64::from(i) + 0.5) / 24.0;
                let phi = 2.4 * f64::from(i);
                let radius = (1.0 - z * z).sqrt();
                let view = glam::DVec3::new(radius * phi.cos(), radius * phi.sin(), z);
                let position = glam::DVec3::new(0.0, 0.0, earth.planet_radius + 1_000.0);
                queries.push(SkyQuery::new(earth.planet_radius, position, view, sun).unwrap());
            }
        }
        let every_20_nm = SpectralReferenceSky::new(&earth, settings).unwrap();
        let every_10_nm: Vec<f64> = (0..36).map(|k| nm(385.0 + 10.0 * f64::from(k))).collect();
        let every_10_nm =
            SpectralReferenceSky::with_wavelengths(&earth, settings, &every_10_nm).unwrap();
        let rgb = ReferenceSky::new(&earth, settings).unwrap();
        let (mut sampling, mut rgb_signed) = (0.0, 0.0);
        for q in &queries {
            let coarse = crate::ladder::luminance(every_20_nm.evaluate(q).radiance);
            let fine = crate::ladder::luminance(every_10_nm.evaluate(q).radiance);
            sampling += (coarse / fine - 1.0).abs();
            rgb_signed += crate::ladder::luminance(rgb.evaluate(q).radiance) / fine - 1.0;
        }
        let n = queries.len() as f64;
        eprintln!(
            "20 nm vs 10 nm: mean |ΔY| {:.4} %; RGB Reference vs 10 nm: signed mean ΔY {:+.2} %",
            100.0 * sampling / n,
            100.0 * rgb_signed / n
        );
        assert!(
            sampling / n < 1e-3,
            "18 wavelengths not converged: {}",
            sampling / n
        );
    }
}
