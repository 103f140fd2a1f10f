//! Drawing the sky objects: the sun's limb-darkened disc and its aureole, the moon's
//! lit disc, and stars and planets as point sprites, each seen through the
//! atmosphere's transmittance. Twin of `shaders/celestial/draw.wgsl`: every function
//! here that WGSL also has shares its name, argument order and units; the generic ones
//! are written once over the float type (f32 = the twin, f64 = the reference).
//!
//! Units: radiance and irradiance are in the unit of
//! [`atmos::Atmosphere::sun_irradiance`] (per steradian for radiance), so the objects
//! add to the atmosphere's own in-scattered radiance in one frame buffer; photometric
//! quantities (star thresholds) are converted with a [`crate::light::LuminanceScale`].
//! Directions are unit vectors pointing away from the viewer, in any right-handed frame
//! shared with the camera (the `Sky` facade uses east/north/up).
//!
//! What is drawn, and why it looks the way it does:
//!
//! * **Sun**: a disc of the atmosphere's `sun_angular_radius` whose mean radiance is
//!   `sun_irradiance / Ω` (Ω the disc's solid angle), darkened toward the limb by the
//!   power law `I(μ)/I(1) = μ^α(λ)` of Hestroffer & Magnan (1998, A&A 333, 338:
//!   α = −0.023 + 0.292/λ with λ in µm) at each channel's wavelength, normalised so the disc
//!   still delivers `sun_irradiance` ([`sun_disc_limb_factor`]).
//! * **Aureole**: the single-scattered Mie light around the sun, which per-pixel atmos
//!   rungs already contain but a coarse dome cannot resolve: for a view within a few
//!   degrees of the sun the view path and the sun path coincide, so the radiance is
//!   `E · T · τ_M · p_CS(θ)` exactly in the limit θ → 0 (every scattering point sees the
//!   sun through the rest of the path and is seen through the path before it: the
//!   attenuation is always the whole path's) — [`sun_aureole_radiance`], with atmos'
//!   own Cornette–Shanks phase function and `mie_g`.
//! * **Moon**: a sphere lit from the direction of the sun *as seen from the moon*
//!   (built in 3-D, so phase and the bright limb's tilt follow for any observer and
//!   any camera roll) with the Lommel–Seeliger law `μ₀/(μ₀ + μ)` (a dark, porous
//!   regolith: no limb darkening at full moon, the terminator at μ₀ = 0)
//!   ([`moon_disc_lommel_seeliger`]), scaled so the disc delivers the moon's
//!   illuminance from its magnitude ([`crate::light::MoonLight`]).
//! * **Stars and planets**: point sources of illuminance `E·T` (magnitude, then the
//!   atmosphere's transmittance toward them), of which only what exceeds the human
//!   detection threshold against the sky's own luminance there is drawn
//!   ([`star_detection_threshold`], [`star_visible_illuminance`]): they fade in through
//!   twilight as the background darkens, by a published model of vision rather than a
//!   hand-set magnitude cut. Each is splatted as a normalised Gaussian over pixels, so
//!   the sprite's radiance integrates to the visible irradiance whatever the
//!   resolution ([`point_sprite_weight`], [`pixel_solid_angle`]).

use num_traits::Float;

use atmos::geometry::ray_sphere_intersect;
use atmos::ladder::LUMINANCE_WEIGHTS;
use atmos::phase::cornette_shanks_phase;

/// Hestroffer & Magnan (1998) solar limb-darkening exponent α at `wavelength_m`:
/// `I(μ)/I(1) = μ^α`, α = −0.023 + 0.292/λ with λ in micrometres (0.406, 0.508 and
/// 0.641 at atmos' 680, 550 and 440 nm channels).
pub fn solar_limb_darkening_exponent(wavelength_m: f64) -> f64 {
    -0.023 + 0.292 / (wavelength_m * 1e6)
}

/// The limb-darkening exponents of atmos' three channels
/// ([`atmos::reference::spectral::CHANNEL_WAVELENGTHS`]).
pub fn solar_limb_darkening_exponents() -> [f64; 3] {
    atmos::reference::spectral::CHANNEL_WAVELENGTHS.map(solar_limb_darkening_exponent)
}

fn constant<F: Float>(x: f64) -> F {
    F::from(x).expect("every float type represents the drawing constants")
}

/// Radiance of the sun's disc relative to its mean, at a view `sin_offset` = sin θ and
/// `cos_offset` = cos θ from the disc's centre (θ the angle between view and sun; pass
/// `|view × sun|` and `view · sun`, which keep their digits near the centre), for a
/// disc of angular radius ρ with `sin_radius` = sin ρ and limb-darkening `exponent` α:
/// `(α + 2)/2 · μ^α` with μ = √(1 − (sin θ / sin ρ)²) the cosine of the emergence angle
/// on the solar surface; 0 outside the disc. `(α + 2)/2` makes the disc's mean 1 (the
/// disc average of μ^α is 2/(α + 2)), so the disc delivers the irradiance it would
/// without darkening.
#[doc(hidden)]
pub fn sun_disc_limb_factor<F: Float>(
    sin_offset: F,
    cos_offset: F,
    sin_radius: F,
    exponent: F,
) -> F {
    if cos_offset <= F::zero() || sin_offset >= sin_radius {
        return F::zero();
    }
    let ratio = sin_offset / sin_radius;
    // 1 − ratio² as a product of exact factors: full relative accuracy at the limb.
    let mu = ((F::one() - ratio) * (F::one() + ratio)).sqrt();
    if mu <= F::zero() {
        return F::zero();
    }
    let two: F = constant(2.0);
    (exponent + two) / two * (exponent * mu.ln()).exp()
}

/// Single-scattered Mie radiance near the sun (one channel): `irradiance ·
/// transmittance · mie_optical_depth · p_CS(cos θ, g)`, with `irradiance` the sun's
/// above the atmosphere, `transmittance` the atmosphere's toward the sun,
/// `mie_optical_depth` the Mie *scattering* optical depth of the same path and
/// `cos_offset` = cos θ between view and sun. Exact as θ → 0 (see the module
/// documentation); its error grows with θ as the view path leaves the sun's path.
pub fn sun_aureole_radiance(
    cos_offset: f32,
    mie_g: f32,
    irradiance: f32,
    transmittance: f32,
    mie_optical_depth: f32,
) -> f32 {
    irradiance * transmittance * mie_optical_depth * cornette_shanks_phase(cos_offset, mie_g)
}

/// The f64 reference of [`sun_aureole_radiance`] (atmos' f64 phase function).
#[doc(hidden)]
pub fn sun_aureole_radiance_f64(
    cos_offset: f64,
    mie_g: f64,
    irradiance: f64,
    transmittance: f64,
    mie_optical_depth: f64,
) -> f64 {
    irradiance
        * transmittance
        * mie_optical_depth
        * atmos::reference::cornette_shanks_phase(cos_offset, mie_g)
}

fn dot<F: Float>(a: [F; 3], b: [F; 3]) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The Lommel–Seeliger reflectance factor `μ₀/(μ₀ + μ)` of the moon's sphere where the
/// view ray `view` meets it, for the moon's centre along `moon` with angular radius
/// ρ (`sin_radius` = sin ρ = R_moon / distance) lit from `to_sun`, the unit direction
/// from the moon toward the sun; 0 off the disc and on the night side. μ = √(1 − ρ̂²)
/// is the cosine of the emergence angle (ρ̂ the view's offset from the centre in disc
/// radii, the disc drawn orthographically: exact to O(ρ²) ≈ 2 × 10⁻⁵) and μ₀ the
/// cosine of the incidence, `n · to_sun` with the surface normal
/// n = ρ̂-offset − moon·μ. The disc average of this factor is
/// [`lommel_seeliger_disc_mean`].
#[doc(hidden)]
pub fn moon_disc_lommel_seeliger<F: Float>(
    view: [F; 3],
    moon: [F; 3],
    sin_radius: F,
    to_sun: [F; 3],
) -> F {
    let along = dot(view, moon);
    if along <= F::zero() {
        return F::zero();
    }
    let offset: [F; 3] = std::array::from_fn(|i| (view[i] - moon[i] * along) / sin_radius);
    let rho2 = dot(offset, offset);
    if rho2 >= F::one() {
        return F::zero();
    }
    let emergence = (F::one() - rho2).sqrt();
    let normal: [F; 3] = std::array::from_fn(|i| offset[i] - moon[i] * emergence);
    let incidence = dot(normal, to_sun);
    if incidence <= F::zero() {
        return F::zero();
    }
    incidence / (incidence + emergence)
}

/// The disc average of the Lommel–Seeliger factor at phase angle α:
/// `Φ(α)/2` with `Φ(α) = 1 − sin(α/2) tan(α/2) ln cot(α/4)` the law's integrated phase
/// function (1 at full moon, 0 at new moon). Near α = π the product is evaluated as
/// `sin(α/2) · 2 artanh(tan w) / tan 2w` with w = (π − α)/4, which has no 0 · ∞.
pub fn lommel_seeliger_disc_mean(phase_angle: crate::Angle) -> f64 {
    let alpha = phase_angle.radians().abs().min(std::f64::consts::PI);
    if alpha < 1e-9 {
        return 0.5;
    }
    let product = if alpha < std::f64::consts::FRAC_PI_2 {
        (alpha / 2.0).sin() * (alpha / 2.0).tan() * (1.0 / (alpha / 4.0).tan()).ln()
    } else {
        let w = (std::f64::consts::PI - alpha) / 4.0;
        if w < 1e-12 {
            (alpha / 2.0).sin()
        } else {
            (alpha / 2.0).sin() * 2.0 * w.tan().atanh() / (2.0 * w).tan()
        }
    };
    0.5 * (1.0 - product).max(0.0)
}

/// Unit conversions of Schaefer's threshold: nanolamberts per cd·m⁻² (π × 10⁵) and
/// lux per foot-candle.
const NANOLAMBERTS_PER_CD_M2: f64 = std::f64::consts::PI * 1e5;
const LUX_PER_FOOT_CANDLE: f64 = 10.763_910_416_709_722;

/// Illuminance (lux) at which a point source is just detected by the naked eye against
/// a background of `background_luminance` (cd·m⁻²): Hecht's fits as given by Schaefer
/// (1990, PASP 102, 212, eq. 2; 1993, Vistas Astron. 36, 311):
/// `I = c₁ (1 + √(c₂ B))²` with B in nanolamberts and I in foot-candles, for night
/// (rod) vision c₁ = 10^−9.8, c₂ = 10^−1.9 and for day (cone) vision c₁ = 10^−8.35,
/// c₂ = 10^−5.9. Schaefer switches branch at B = 1479 nL where the two differ by 8 %;
/// here the eye uses whichever is more sensitive (the smaller threshold), which is
/// continuous. At a dark sky (21.9 mag/arcsec²) it is magnitude 6.6; at the day sky
/// (5000 cd·m⁻²) magnitude −4.0 (Venus, at −4.6 when brightest, can be seen by day).
pub fn star_detection_threshold<F: Float>(background_luminance: F) -> F {
    let nanolamberts = background_luminance.max(F::zero()) * constant(NANOLAMBERTS_PER_CD_M2);
    let one = F::one();
    let rods = constant::<F>(10f64.powf(-9.8))
        * (one + (constant::<F>(10f64.powf(-1.9)) * nanolamberts).sqrt()).powi(2);
    let cones = constant::<F>(10f64.powf(-8.35))
        * (one + (constant::<F>(10f64.powf(-5.9)) * nanolamberts).sqrt()).powi(2);
    rods.min(cones) * constant(LUX_PER_FOOT_CANDLE)
}

/// The part of a point source's illuminance `illuminance` (lux, at the eye) above the
/// detection `threshold` (lux): what is drawn. 0 at and below the threshold, so a star
/// fades in continuously as its background darkens.
pub fn star_visible_illuminance<F: Float>(illuminance: F, threshold: F) -> F {
    (illuminance - threshold).max(F::zero())
}

/// What a point source delivers to the frame, per channel, in the atmosphere's
/// irradiance unit: its illuminance above the atmosphere `illuminance_lux` times
/// `scintillation` (1 = off), seen through `transmittance` (per channel) with its
/// unit-luminance linear sRGB `colour`, minus the detection threshold against
/// `background_luminance` (cd·m⁻²); divided by `lux_per_unit` (lux per unit of the
/// atmosphere's irradiance, [`crate::light::LuminanceScale`]). The vertex stage of the
/// GPU pass computes exactly this.
pub fn point_source_irradiance(
    illuminance_lux: f32,
    colour: [f32; 3],
    transmittance: [f32; 3],
    background_luminance: f32,
    scintillation: f32,
    lux_per_unit: f32,
) -> [f32; 3] {
    let weights = LUMINANCE_WEIGHTS.map(|w| w as f32);
    let seen_colour: [f32; 3] = std::array::from_fn(|i| colour[i] * transmittance[i]);
    let luminance_transmittance = dot(weights, seen_colour);
    if luminance_transmittance <= 0.0 {
        return [0.0; 3];
    }
    let seen = illuminance_lux * scintillation * luminance_transmittance;
    let visible = star_visible_illuminance(seen, star_detection_threshold(background_luminance));
    let scale = visible / (lux_per_unit * luminance_transmittance);
    seen_colour.map(|c| c * scale)
}

/// Weight per pixel of a point sprite at squared distance `offset_squared` (pixels²)
/// from its centre: a circular Gaussian of standard deviation `sigma` pixels,
/// `exp(−r²/2σ²)/(2πσ²)`, which sums to 1 over the pixel grid wherever the centre
/// falls for σ ≥ [`MIN_SPRITE_SIGMA_PX`] (the grid's aliasing error is
/// 4·e^{−2π²σ²} ≈ 2 × 10⁻⁴ there, 3 % at σ = 0.5), less the tail beyond the
/// [`SPRITE_CUTOFF_SIGMAS`] cut (e⁻⁸ = 3 × 10⁻⁴).
#[doc(hidden)]
pub fn point_sprite_weight<F: Float>(offset_squared: F, sigma: F) -> F {
    let two: F = constant(2.0);
    let two_pi: F = constant(std::f64::consts::TAU);
    let variance = sigma * sigma;
    (-offset_squared / (two * variance)).exp() / (two_pi * variance)
}

/// Radius (pixels, in units of σ) at which point sprites are cut.
pub const SPRITE_CUTOFF_SIGMAS: f32 = 4.0;

/// Smallest sprite width (σ, pixels) whose weights still sum to 1 on the pixel grid.
pub const MIN_SPRITE_SIGMA_PX: f32 = 0.75;

/// Solid angle (sr) of the pixel a view ray passes through, for a pinhole camera with
/// `tan_half_fov_y` and `height` pixels: `(2 tan(fov/2)/height)² · cos³θ`, with
/// `cos_forward` = cos θ the cosine between the view and the camera's forward axis
/// (square pixels, as [`atmos::frame::frame_view_direction`] lays them out).
pub fn pixel_solid_angle(tan_half_fov_y: f32, height: u32, cos_forward: f32) -> f32 {
    let side = 2.0 * tan_half_fov_y / height as f32;
    side * side * cos_forward * cos_forward * cos_forward
}

/// Where `direction` lands in the frame of `camera`: (x, y) in pixel coordinates
/// (pixel centres at i + 0.5, x right, y down, as [`atmos::frame::frame_view_direction`]
/// inverts) and the cosine to the forward axis; a non-positive cosine means behind
/// the camera (x, y are then meaningless).
pub fn project_direction(direction: [f32; 3], camera: &atmos::frame::FrameCamera) -> [f32; 3] {
    let x = dot(direction, camera.right);
    let y = dot(direction, camera.up);
    let z = dot(direction, camera.forward);
    let aspect = camera.width as f32 / camera.height as f32;
    let ndc_x = x / (z * camera.tan_half_fov_y * aspect);
    let ndc_y = y / (z * camera.tan_half_fov_y);
    [
        (ndc_x + 1.0) * 0.5 * camera.width as f32,
        (1.0 - ndc_y) * 0.5 * camera.height as f32,
        z,
    ]
}

/// What [`DiscObject::kind`] draws.
pub const DISC_NONE: u32 = 0;
/// [`DiscObject::kind`]: the sun (limb-darkened disc).
pub const DISC_SUN: u32 = 1;
/// [`DiscObject::kind`]: the moon (Lommel–Seeliger sphere).
pub const DISC_MOON: u32 = 2;

/// A disc in the sky (the sun or the moon) as the GPU pass and the CPU twin draw it;
/// layout identical to WGSL `DiscObject`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DiscObject {
    /// Unit direction of the disc's centre.
    pub direction: [f32; 3],
    /// sin of the angular radius.
    pub sin_radius: f32,
    /// Sun: mean disc radiance above the atmosphere; moon: the radiance where the
    /// Lommel–Seeliger factor is 1 (atmos units per sr).
    pub radiance: [f32; 3],
    /// [`DISC_NONE`], [`DISC_SUN`] or [`DISC_MOON`].
    pub kind: u32,
    /// Sun: limb-darkening exponents per channel; moon: the unit direction from the
    /// moon toward the sun.
    pub shading: [f32; 3],
    /// Zenith cosine of the centre (where the transmittance fit is centred).
    pub mu_centre: f32,
    /// ln(transmittance) at the centre, per channel.
    pub log_transmittance: [f32; 3],
    /// Keeps 16-byte rows.
    pub padding0: f32,
    /// d ln T / d μ at the centre, per channel.
    pub log_transmittance_slope: [f32; 3],
    /// Keeps 16-byte rows.
    pub padding1: f32,
    /// ½ d² ln T / d μ² at the centre, per channel.
    pub log_transmittance_curvature: [f32; 3],
    /// Keeps 16-byte rows.
    pub padding2: f32,
}

impl DiscObject {
    /// Nothing to draw.
    pub const NONE: DiscObject = DiscObject {
        direction: [0.0, 0.0, 1.0],
        sin_radius: 0.0,
        radiance: [0.0; 3],
        kind: DISC_NONE,
        shading: [0.0; 3],
        mu_centre: 1.0,
        log_transmittance: [0.0; 3],
        padding0: 0.0,
        log_transmittance_slope: [0.0; 3],
        padding1: 0.0,
        log_transmittance_curvature: [0.0; 3],
        padding2: 0.0,
    };
}

/// Radiance a view ray `view` (unit) receives from the disc `object`, for a viewer at
/// distance `r` from the planet centre with local zenith `zenith` (unit) above a
/// ground sphere of `planet_radius`: the disc's own radiance times the atmosphere's
/// transmittance along the view, `exp(ln T₀ + b·Δμ + c·Δμ²)` (Δμ the view's zenith
/// cosine minus the centre's: the transmittance follows the view across the disc, so a
/// setting sun is redder at its lower limb); 0 where the view ray hits the ground
/// (docs/architecture.md, "Rays at the ground").
pub fn disc_object_radiance(
    view: [f32; 3],
    object: &DiscObject,
    zenith: [f32; 3],
    r: f32,
    planet_radius: f32,
) -> [f32; 3] {
    if object.kind == DISC_NONE {
        return [0.0; 3];
    }
    let mu = dot(view, zenith);
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    if mu < 0.0 && ground[0] >= 0.0 {
        return [0.0; 3];
    }
    let d = object.direction;
    let cross = [
        view[1] * d[2] - view[2] * d[1],
        view[2] * d[0] - view[0] * d[2],
        view[0] * d[1] - view[1] * d[0],
    ];
    let sin_offset = dot(cross, cross).sqrt();
    let cos_offset = dot(view, d);
    let shape: [f32; 3] = if object.kind == DISC_SUN {
        std::array::from_fn(|i| {
            sun_disc_limb_factor(sin_offset, cos_offset, object.sin_radius, object.shading[i])
        })
    } else {
        [moon_disc_lommel_seeliger(view, d, object.sin_radius, object.shading); 3]
    };
    let dmu = mu - object.mu_centre;
    std::array::from_fn(|i| {
        let log_t = object.log_transmittance[i]
            + dmu
                * (object.log_transmittance_slope[i] + dmu * object.log_transmittance_curvature[i]);
        object.radiance[i] * shape[i] * log_t.min(0.0).exp()
    })
}

/// A star or planet as the GPU pass and the CPU twin draw it; layout identical to
/// WGSL `PointSource`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct PointSource {
    /// Unit direction.
    pub direction: [f32; 3],
    /// Illuminance above the atmosphere (lux).
    pub illuminance_lux: f32,
    /// Linear sRGB colour of unit luminance.
    pub colour: [f32; 3],
    /// Luminance of the sky behind it (cd·m⁻²), natural night-sky floor included.
    pub background_luminance: f32,
    /// The atmosphere's transmittance toward it, per channel.
    pub transmittance: [f32; 3],
    /// Scintillation factor (1 = off).
    pub scintillation: f32,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Angle;

    #[test]
    fn limb_darkening_exponents_and_normalisation() {
        let [red, green, blue] = solar_limb_darkening_exponents();
        assert!((red - 0.406).abs() < 1e-3 && (green - 0.508).abs() < 1e-3);
        assert!((blue - 0.641).abs() < 1e-3);
        // The disc average of the factor is 1 (midpoint rule over the disc).
        for alpha in [0.0, red, green, blue, 1.5] {
            let n = 600;
            let (mut sum, mut count) = (0.0, 0usize);
            for a in 0..n {
                for b in 0..n {
                    let x = -1.0 + (2 * a + 1) as f64 / n as f64;
                    let y = -1.0 + (2 * b + 1) as f64 / n as f64;
                    let rho = (x * x + y * y).sqrt();
                    if rho < 1.0 {
                        count += 1;
                        sum += sun_disc_limb_factor(rho * 0.01, 1.0, 0.01, alpha);
                    }
                }
            }
            let mean = sum / count as f64;
            assert!((mean - 1.0).abs() < 5e-3, "α {alpha}: mean {mean}");
        }
        // Limb darkened: centre brighter than halfway out, zero at and beyond the limb
        // and behind the viewer.
        let centre = sun_disc_limb_factor(0.0, 1.0, 0.0046, green);
        let half = sun_disc_limb_factor(0.0023, 1.0, 0.0046, green);
        assert!(centre > half && half > 0.0);
        assert!((centre - (green + 2.0) / 2.0).abs() < 1e-12);
        assert_eq!(sun_disc_limb_factor(0.0046, 1.0, 0.0046, green), 0.0);
        assert_eq!(sun_disc_limb_factor(0.0, -1.0, 0.0046, green), 0.0);
    }

    /// The Lommel–Seeliger disc mean against a midpoint-rule quadrature of the factor,
    /// at phases from full to a thin crescent; the lit area is the illuminated fraction.
    #[test]
    fn lommel_seeliger_mean_matches_quadrature() {
        let moon = [0.0, 0.0, 1.0];
        let sin_radius = 0.0045;
        for degrees in [0.0, 10.0, 45.0, 90.0, 120.0, 150.0, 175.0] {
            let alpha = f64::to_radians(degrees);
            // Sun from the moon: away from the observer by (π − α), toward +x.
            let to_sun = [alpha.sin(), 0.0, -alpha.cos()];
            let n = 500;
            let (mut sum, mut inside, mut lit) = (0.0, 0usize, 0usize);
            for a in 0..n {
                for b in 0..n {
                    let x = -1.0 + (2 * a + 1) as f64 / n as f64;
                    let y = -1.0 + (2 * b + 1) as f64 / n as f64;
                    if x * x + y * y >= 1.0 {
                        continue;
                    }
                    inside += 1;
                    let v = [x * sin_radius, y * sin_radius, 1.0];
                    let norm = dot(v, v).sqrt();
                    let view = v.map(|c| c / norm);
                    let f = moon_disc_lommel_seeliger(view, moon, sin_radius, to_sun);
                    sum += f;
                    lit += usize::from(f > 0.0);
                }
            }
            let mean = sum / inside as f64;
            let expected = lommel_seeliger_disc_mean(Angle::from_radians(alpha));
            assert!(
                (mean - expected).abs() < 2e-3,
                "α {degrees}°: quadrature {mean}, closed form {expected}"
            );
            let fraction = lit as f64 / inside as f64;
            assert!((fraction - 0.5 * (1.0 + alpha.cos())).abs() < 5e-3);
        }
        assert!((lommel_seeliger_disc_mean(Angle::from_degrees(180.0))).abs() < 1e-12);
        // Both branches meet at α = π/2.
        let below =
            lommel_seeliger_disc_mean(Angle::from_radians(std::f64::consts::FRAC_PI_2 - 1e-9));
        let above =
            lommel_seeliger_disc_mean(Angle::from_radians(std::f64::consts::FRAC_PI_2 + 1e-9));
        assert!((below - above).abs() < 1e-8);
    }

    #[test]
    fn detection_threshold_limits() {
        let magnitude = |lux: f64| -2.5 * (lux / crate::ZERO_MAGNITUDE_ILLUMINANCE_LX).log10();
        let dark = crate::photometry::luminance_from_surface_brightness(
            crate::photometry::NATURAL_NIGHT_SKY_V_MAG_PER_ARCSEC2,
        );
        let night_limit = magnitude(star_detection_threshold(dark));
        assert!((night_limit - 6.6).abs() < 0.1, "{night_limit}");
        // Absolute threshold (no background): 10^−9.8 fc → magnitude 8.0.
        assert!((magnitude(star_detection_threshold(0.0)) - 7.95).abs() < 0.05);
        // Daylight: 5000 cd/m² → −4.0 (Venus, −4.6 at best, is seen by day).
        let day = magnitude(star_detection_threshold(5000.0));
        assert!((-4.1..-3.9).contains(&day), "{day}");
        // Continuous and increasing across Schaefer's switch at 1479 nL.
        let switch = 1479.0 / NANOLAMBERTS_PER_CD_M2;
        let below = star_detection_threshold(switch * 0.999);
        let above = star_detection_threshold(switch * 1.001);
        assert!(above > below && (above / below - 1.0) < 0.01);
        let mut last = 0.0;
        for k in -60..60 {
            let t = star_detection_threshold(10f64.powf(f64::from(k) / 10.0));
            assert!(t > last);
            last = t;
        }
    }

    #[test]
    fn sprite_weights_sum_to_one() {
        for sigma in [f64::from(MIN_SPRITE_SIGMA_PX), 1.3, 3.0] {
            for centre in [(0.0, 0.0), (0.5, 0.5), (0.3, 0.8)] {
                let cut = (f64::from(SPRITE_CUTOFF_SIGMAS) * sigma).ceil() as i32 + 1;
                let mut sum = 0.0;
                for dx in -cut..=cut {
                    for dy in -cut..=cut {
                        let (x, y) = (f64::from(dx) - centre.0, f64::from(dy) - centre.1);
                        let r2 = x * x + y * y;
                        if r2.sqrt() <= f64::from(SPRITE_CUTOFF_SIGMAS) * sigma {
                            sum += point_sprite_weight(r2, sigma);
                        }
                    }
                }
                assert!((sum - 1.0).abs() < 1e-3, "σ {sigma} at {centre:?}: {sum}");
            }
        }
    }

    #[test]
    fn point_sources_fade_against_the_sky() {
        let colour = [1.0, 1.0, 1.0];
        let sirius = crate::illuminance_from_magnitude(-1.46f32);
        let lux_per_unit = 1.3e5;
        let night = point_source_irradiance(sirius, colour, [0.8; 3], 2e-4, 1.0, lux_per_unit);
        let day = point_source_irradiance(sirius, colour, [0.8; 3], 5000.0, 1.0, lux_per_unit);
        assert!(night[1] > 0.9 * 0.8 * sirius / lux_per_unit);
        assert_eq!(day, [0.0; 3]);
        // Opaque atmosphere: nothing, no NaN.
        assert_eq!(
            point_source_irradiance(sirius, colour, [0.0; 3], 2e-4, 1.0, lux_per_unit),
            [0.0; 3]
        );
    }

    #[test]
    fn projection_inverts_the_frame_camera() {
        let camera = atmos::frame::FrameCamera::look_at(
            glam::DVec3::new(0.0, 0.0, 6_360_100.0),
            glam::DVec3::new(0.3, 1.0, 0.2),
            glam::DVec3::Z,
            1.0,
            64,
            48,
            glam::DVec3::Z,
            None,
        )
        .unwrap();
        for pixel in [[0, 0], [63, 47], [10, 30], [32, 24]] {
            let view = atmos::frame::frame_view_direction(pixel, &camera);
            let [x, y, z] = project_direction(view, &camera);
            assert!((x - (pixel[0] as f32 + 0.5)).abs() < 1e-3, "{x}");
            assert!((y - (pixel[1] as f32 + 0.5)).abs() < 1e-3, "{y}");
            assert!(z > 0.0);
        }
    }
}
