//! The registry of parity cases: each pairs one WGSL function with its Rust f32 twin
//! and (where one exists) an f64 reference, over a dense input grid plus extremes.

pub use super::audit::Audit;
use super::compare::{Tolerance, UNIT_ROUNDOFF as U};
use atmos::reference as f64ref;

mod atmos_cases;
mod atmos_closed_form_sky_cases;
mod atmos_dome_cases;
mod atmos_lut_cases;
pub(crate) use atmos_lut_cases::transmittance_r_mu_error;
mod atmos_moments_cases;
mod atmos_single_scattering_cases;
mod atmos_view_cases;
mod celestial_cases;
mod celestial_cloud_cases;
mod celestial_cloud_light_cases;
mod celestial_dome_cases;
mod celestial_draw_cases;
mod cloudlight_billboard_cases;
mod cloudlight_cases;
mod cloudlight_march_cases;
mod cloudlight_shadow_cases;
mod cloudlight_shell_cases;
mod cloudlight_temporal_cases;
mod cloudlight_weather_grid_cases;
mod cloudsim_cases;
mod common_cases;
mod integer_references;
mod render_billboard_cases;
mod render_cases;
mod render_cloud_order_cases;
mod render_fog_cases;
mod render_terrain_materials_cases;
mod render_volume_cases;
mod terrain_cases;

/// One WGSL function (or pass) against its twins.
pub struct Case {
    /// `crate::function`.
    pub name: &'static str,
    /// WGSL modules the kernel imports.
    pub imports: &'static [&'static str],
    /// Number of f32 inputs per element (`x0`, `x1`, …) and outputs (`y0`, …).
    pub arity: (usize, usize),
    /// WGSL statements computing `y*` from `x*`.
    pub wgsl: &'static str,
    /// The inputs (each row has `arity.0` values; they are rounded to f32 before use).
    pub grid: fn() -> Vec<Vec<f64>>,
    /// The Rust f32 twin.
    pub cpu: fn(&[f32]) -> Vec<f32>,
    /// The f64 reference, evaluated on the f32-rounded inputs.
    pub reference: fn(&[f64]) -> Vec<f64>,
    /// Whether the reference is independent of the CPU side, and why the tolerance
    /// may be loose (`Audit::INDEPENDENT` for most cases).
    pub audit: Audit,
    /// Tolerance with its justification.
    pub tolerance: Tolerance,
}

const R_GROUND: f64 = 6_360_000.0;
const R_TOP: f64 = 6_460_000.0;
/// The Earth coefficients used by the closed-form cases (1/m).
const BETA_RAYLEIGH: [f64; 3] = [5.802e-6, 13.558e-6, 33.1e-6];
const BETA_MIE: [f64; 3] = [3.996e-6, 3.996e-6, 3.996e-6];

fn linspace(a: f64, b: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| a + (b - a) * i as f64 / (n - 1) as f64)
}

fn logspace(a: f64, b: f64, n: usize) -> impl Iterator<Item = f64> {
    linspace(a.ln(), b.ln(), n).map(f64::exp)
}

fn to_f32(v: [f64; 3]) -> [f32; 3] {
    v.map(|x| x as f32)
}

/// Cosines dense over [−1, 1] plus the ends approached geometrically.
fn cosines(n: usize) -> Vec<f64> {
    let mut v: Vec<f64> = linspace(-1.0, 1.0, n).collect();
    for k in 1..=8 {
        let d = 10f64.powi(-k);
        v.extend([1.0 - d, -1.0 + d]);
    }
    v.extend([0.0, 1.0, -1.0]);
    v
}

/// Anisotropies over (−1, 1), denser towards ±1, with ±0.9999 as the extremes.
fn anisotropies() -> Vec<f64> {
    let mut v: Vec<f64> = linspace(-0.99, 0.99, 81).collect();
    v.extend([-0.9999, -0.999, -0.995, 0.995, 0.999, 0.9999, 0.0]);
    v
}

// ---------------------------------------------------------------- phase functions

fn phase_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for g in anisotropies() {
        for mu in cosines(201) {
            grid.push(vec![mu, g]);
        }
    }
    grid
}

// ---------------------------------------------------------------- ray geometry

fn altitudes() -> [f64; 14] {
    [
        -10.0, 0.0, 1.0, 10.0, 100.0, 1e3, 1e4, 5e4, 99_999.0, 100_000.0, 100_001.0, 2e5, 1e6, 1e7,
    ]
}

/// Bound on the absolute error of the discriminant b² − c in f32 (b = r·mu,
/// c = (r − R)(r + R)): each product is correctly rounded in WGSL and Rust, so
/// |δD| ≤ 4u(b² + |c|) with margin.
fn discriminant_and_error(r: f64, mu: f64, radius: f64) -> (f64, f64) {
    let b = r * mu;
    let c = (r - radius) * (r + radius);
    (b * b - c, 4.0 * U * (b * b + c.abs()))
}

fn ray_sphere_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in altitudes() {
        for radius in [R_GROUND, R_TOP] {
            let r = f64::from((R_GROUND + altitude) as f32);
            let mut mus = cosines(401);
            if r > radius {
                // Rays grazing this sphere: around the tangent cosine.
                let tangent = -(1.0 - (radius / r).powi(2)).sqrt();
                for k in 0..20 {
                    let d = 1e-7 * 1.6f64.powi(k);
                    mus.extend([tangent - d, tangent + d]);
                }
            }
            for mu in mus {
                let mu32 = f64::from(mu as f32);
                let (d, error) = discriminant_and_error(r, mu32, radius);
                // Hit or miss is undecidable in f32 within rounding of D = 0: such
                // near-tangent rays are excluded (both answers are right).
                if d.abs() < error {
                    continue;
                }
                grid.push(vec![r, mu, radius]);
            }
        }
    }
    grid
}

/// |δt| ≤ 2·δ√D + 12u|t|, with δ√D = min(δD/(2√D), √δD): the roots inherit the
/// discriminant's absolute error (q has no cancellation, |c/q| ≤ |q|), plus
/// sqrt (WGSL: 1/inverseSqrt, ≤ 4.5 ULP), division (2.5 ULP) and a few roundings.
fn ray_sphere_bound(x: &[f64]) -> Vec<f64> {
    let (d, error) = discriminant_and_error(x[0], x[1], x[2]);
    let t = f64ref::ray_sphere_intersect(x[0], x[1], x[2]);
    let sqrt_error = if d > 0.0 {
        (error / (2.0 * d.sqrt())).min(error.sqrt())
    } else {
        0.0
    };
    t.iter()
        .map(|t| 2.0 * sqrt_error + 12.0 * U * t.abs())
        .collect()
}

fn altitude_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in [-10.0, 0.0, 1.0, 100.0, 1e3, 1e4, 1e5, 1e6, 1e7] {
        let r = R_GROUND + altitude;
        for mu in linspace(-1.0, 1.0, 41) {
            for t in std::iter::once(0.0).chain(logspace(1e-2, 1e7, 30)) {
                grid.push(vec![r, mu, t, R_GROUND]);
            }
        }
    }
    grid
}

/// Forward bound of `altitude_along_ray`: the numerator
/// (r − R)(r + R) + t(2rμ + t) has |δ| ≤ 4u(|(r−R)(r+R)| + |t|(2|rμ| + |t|)) (inner
/// sum 2rμ + t may cancel), divided by r_t + R; plus 8u|h| for the sqrt and division.
fn altitude_error(r: f64, mu: f64, t: f64, planet_radius: f64) -> f64 {
    let e1 = ((r - planet_radius) * (r + planet_radius)).abs();
    let r_t = (r * r + t * (2.0 * r * mu + t)).max(0.0).sqrt();
    let h = f64ref::altitude_along_ray(r, mu, t, planet_radius);
    4.0 * U * (e1 + t.abs() * (2.0 * (r * mu).abs() + t.abs())) / (r_t + planet_radius)
        + 8.0 * U * h.abs()
}

const OPTICAL_SAMPLES: f64 = 16.0;

fn optical_length_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let altitudes: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1.0, 99_000.0, 19))
        .collect();
    for scale_height in [1200.0, 8000.0] {
        for &altitude in &altitudes {
            let r = R_GROUND + altitude;
            for mu in linspace(-1.0, 1.0, 251) {
                let ground = f64ref::ray_sphere_intersect(r, mu, R_GROUND);
                let top = f64ref::ray_sphere_intersect(r, mu, R_TOP);
                // Rays that meet the ground stop there (at 0 for a camera on the ground).
                let length = if ground[0] >= 0.0 { ground[0] } else { top[1] };
                grid.push(vec![r, mu, length, R_GROUND, scale_height, OPTICAL_SAMPLES]);
            }
        }
    }
    grid
}

/// Σᵢ dt·e^{−xᵢ}·(2u(3 + 2xᵢ) + 5u·xᵢ + δhᵢ/H) + (n + 4)u·result: WGSL's exp bound
/// (3 + 2|x| ULP), the division h/H (2.5 ULP), each sample's altitude error (incl.
/// 4u·t from t = (i + ½)·dt), and the summation of n positive terms.
fn optical_length_bound(x: &[f64]) -> Vec<f64> {
    let (r, mu, length, planet, scale_height) = (x[0], x[1], x[2], x[3], x[4]);
    let n = x[5] as u32;
    let dt = length / f64::from(n);
    let mut bound = 0.0;
    let mut total = 0.0;
    for i in 0..n {
        let t = (f64::from(i) + 0.5) * dt;
        let h = f64ref::altitude_along_ray(r, mu, t, planet);
        let xi = h / scale_height;
        let term = (-xi).exp() * dt;
        let dh = altitude_error(r, mu, t, planet) + 4.0 * U * t;
        bound += term * (2.0 * U * (3.0 + 2.0 * xi.abs()) + 5.0 * U * xi.abs() + dh / scale_height);
        total += term;
    }
    vec![bound + (f64::from(n) + 4.0) * U * total]
}

// ---------------------------------------------------------------- exponentials

fn optical_depths() -> Vec<f64> {
    let mut v: Vec<f64> = logspace(1e-8, 1e4, 9000).collect();
    v.extend(linspace(0.0, 100.0, 1001));
    v.extend([0.0, 87.0, 88.0, 95.0, 103.0, 1e4]);
    v
}

/// WGSL: exp has 3 + 2|x| ULP; write it as a relative bound 2u(3 + 2|x|).
fn exp_relative_error(x: f64) -> f64 {
    2.0 * U * (3.0 + 2.0 * x.abs())
}

fn one_minus_exp_bound(x: f64) -> f64 {
    if x.abs() < 0.5 {
        0.0
    } else {
        // 1 − e^{−x}: the exp error, absolute, plus the subtraction's rounding.
        exp_relative_error(x) * (-x).exp() + U * (1.0 - (-x).exp()).abs()
    }
}

fn closed_form_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for g in [0.0, 0.76, 0.9, -0.5] {
        for mu in linspace(-1.0, 1.0, 41) {
            for s in std::iter::once(0.0).chain(logspace(1.0, 1e7, 64)) {
                grid.push(vec![mu, g, s]);
            }
        }
    }
    grid
}

fn closed_form_optical_depths(s: f64) -> [f64; 3] {
    std::array::from_fn(|i| (BETA_RAYLEIGH[i] + BETA_MIE[i]) * s)
}

// ---------------------------------------------------------------- display encoding

fn tonemap_bound(x: &[f64]) -> Vec<f64> {
    // x·exposure rounds once (u relative → an absolute u·x in the argument, scaled by
    // the derivative e^{−x}), then 1 − e^{−x}'s own bound.
    (0..3)
        .map(|i| {
            let arg = x[i] * x[3];
            U * arg * (-arg).exp() + one_minus_exp_bound(arg)
        })
        .collect()
}

/// WGSL pow(x, y) is exp2(y·log2 x): log2 is within 2⁻²¹ absolute on [0.5, 2] and
/// 3 ULP elsewhere, exp2 within 3 + 2|a| ULP; then ×1.055 and −0.055, whose
/// cancellation near the linear segment makes the bound absolute.
fn srgb_bound(x: f64) -> f64 {
    if x <= 0.003_130_8 {
        return 0.0;
    }
    let log2 = x.log2();
    let log2_error = if (0.5..=2.0).contains(&x) {
        2f64.powi(-21)
    } else {
        6.0 * U * log2.abs()
    };
    let a = log2 / 2.4;
    let power = x.powf(1.0 / 2.4);
    let pow_relative =
        2.0 * U * (3.0 + 2.0 * a.abs()) + std::f64::consts::LN_2 * (log2_error / 2.4 + U * a.abs());
    1.055 * power * (pow_relative + 2.0 * U) + U * (1.055 * power + 0.055)
}

// ---------------------------------------------------------------- atmosphere profiles

/// The f64 view of the f32 Earth uniforms: the reference sees the parameters the f32
/// sides see.
fn earth_f32_as_f64() -> atmos::Atmosphere {
    uniforms_as_f64(&atmos::Atmosphere::earth())
}

/// An atmosphere's f32 uniforms read back as f64 (what both f32 sides see).
fn uniforms_as_f64(atmosphere: &atmos::Atmosphere) -> atmos::Atmosphere {
    let u = atmosphere
        .to_uniforms()
        .expect("the parity atmospheres are valid");
    let f = |v: [f32; 3]| v.map(f64::from);
    atmos::Atmosphere {
        planet_radius: f64::from(u.planet_radius),
        top_radius: f64::from(u.top_radius),
        rayleigh_scattering: f(u.rayleigh_scattering),
        rayleigh_scale_height: f64::from(u.rayleigh_scale_height),
        mie_scattering: f(u.mie_scattering),
        mie_extinction: f(u.mie_extinction),
        mie_scale_height: f64::from(u.mie_scale_height),
        mie_g: f64::from(u.mie_g),
        ozone_absorption: f(u.ozone_absorption),
        ozone_center_altitude: f64::from(u.ozone_center_altitude),
        ozone_half_width: f64::from(u.ozone_half_width),
        ground_albedo: f(u.ground_albedo),
        sun_irradiance: f(u.sun_irradiance),
        sun_angular_radius: f64::from(u.sun_angular_radius),
    }
}

/// exp(−h/H): the division (2.5 ULP → 5u·x absolute in the exponent) and WGSL exp.
fn exponential_density_error(altitude: f64, scale_height: f64) -> f64 {
    let x = altitude / scale_height;
    (-x).exp() * (exp_relative_error(x) + 5.0 * U * x.abs())
}

/// 1 − |h − c|/w: the subtraction (u|h − c|), division (2.5 ULP) and the final
/// 1 − q, whose cancellation near the tent's feet makes the bound absolute: ≤ 5u.
const TENT_ERROR: f64 = 5.0 * U;

fn profile_altitudes() -> Vec<f64> {
    let mut v: Vec<f64> = linspace(-10.0, 100_000.0, 10_001).collect();
    v.extend(logspace(1e-3, 1e7, 200));
    v.extend([0.0, 10_000.0, 25_000.0, 40_000.0]);
    v
}

// ---------------------------------------------------------------- terrain shadows

/// θ = atan2(√((1−a)(1+a)), a) is the only transcendental; lavapipe's atan2 was
/// measured at ≈ 300 ULP (512 allowed). The area's derivative in θ is at most 2/π,
/// and the series branch (u = 2θ < 0.5) has relative error 3·δθ/θ on a value ≤ u³/12.
fn disc_fraction_bound(x: f64) -> f64 {
    let a = x.abs().min(1.0);
    let theta = ((1.0 - a) * (1.0 + a)).sqrt().atan2(a);
    let theta_error = 512.0 * super::compare::ulp_f32(theta) + 4.0 * U * theta;
    2.0 / std::f64::consts::PI * theta_error + 4.0 * U
}

/// All function cases, in report order (one file per crate).
pub fn all() -> Vec<Case> {
    [
        atmos_cases::cases(),
        atmos_single_scattering_cases::cases(),
        atmos_closed_form_sky_cases::cases(),
        atmos_dome_cases::cases(),
        atmos_lut_cases::cases(),
        atmos_moments_cases::cases(),
        atmos_view_cases::cases(),
        render_cases::cases(),
        vec![render_cases::present_case()],
        render_billboard_cases::cases(),
        render_volume_cases::cases(),
        render_cloud_order_cases::cases(),
        render_fog_cases::cases(),
        render_terrain_materials_cases::cases(),
        terrain_cases::cases(),
        cloudlight_cases::cases(),
        cloudlight_cases::cone_cases(),
        cloudlight_march_cases::cases(),
        cloudlight_temporal_cases::cases(),
        cloudlight_shell_cases::cases(),
        cloudlight_weather_grid_cases::cases(),
        cloudlight_billboard_cases::cases(),
        cloudlight_shadow_cases::cases(),
        cloudsim_cases::cases(),
        celestial_cases::cases(),
        celestial_dome_cases::cases(),
        common_cases::cases(),
    ]
    .into_iter()
    .flatten()
    .collect()
}
