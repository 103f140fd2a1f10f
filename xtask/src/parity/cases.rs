//! The registry of parity cases: each pairs one WGSL function with its Rust f32 twin
//! and (where one exists) an f64 reference, over a dense input grid plus extremes.

use super::compare::{Tolerance, UNIT_ROUNDOFF as U};
use atmos::reference as f64ref;

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
    let u = atmos::Atmosphere::earth()
        .to_uniforms()
        .expect("Earth is valid");
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

/// The case list, in report order.
pub fn all() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::rayleigh_phase",
            imports: &["atmos::phase"],
            arity: (1, 1),
            wgsl: "y0 = rayleigh_phase(x0);",
            grid: || cosines(20_001).into_iter().map(|mu| vec![mu]).collect(),
            cpu: |x| vec![atmos::phase::rayleigh_phase(x[0])],
            reference: |x| vec![f64ref::rayleigh_phase(x[0])],
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: None,
                why: "3 correctly rounded + and × (WGSL and Rust), the constant folded once; \
                      ≤ 2 ULP plus the reference's rounding to f32",
            },
        },
        Case {
            name: "atmos::henyey_greenstein_phase",
            imports: &["atmos::phase"],
            arity: (2, 1),
            wgsl: "y0 = henyey_greenstein_phase(x0, x1);",
            grid: phase_grid,
            cpu: |x| vec![atmos::phase::henyey_greenstein_phase(x[0], x[1])],
            reference: |x| vec![f64ref::henyey_greenstein_phase(x[0], x[1])],
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 16.0,
                bound: None,
                why: "stable base (≤ 2 ULP, sums of non-negative terms) enters as base^{3/2} (×1.5); \
                      WGSL sqrt = 1/inverseSqrt ≤ 4.5 ULP, ÷ 2.5 ULP, 4 × and (1−g)(1+g) ≤ 2.5: \
                      ≈ 13 ULP",
            },
        },
        Case {
            name: "atmos::cornette_shanks_phase",
            imports: &["atmos::phase"],
            arity: (2, 1),
            wgsl: "y0 = cornette_shanks_phase(x0, x1);",
            grid: phase_grid,
            cpu: |x| vec![atmos::phase::cornette_shanks_phase(x[0], x[1])],
            reference: |x| vec![f64ref::cornette_shanks_phase(x[0], x[1])],
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 20.0,
                bound: None,
                why: "the Henyey–Greenstein budget (13 ULP) plus (1 + cos²θ) and (2 + g²) \
                      factors (≤ 3 ULP) and one more product",
            },
        },
        Case {
            name: "atmos::exponential_density",
            imports: &["atmos::atmosphere"],
            arity: (2, 1),
            wgsl: "y0 = exponential_density(x0, x1);",
            grid: || {
                let mut grid = Vec::new();
                for scale_height in [1200.0, 8000.0] {
                    for h in profile_altitudes() {
                        grid.push(vec![h, scale_height]);
                    }
                }
                grid
            },
            cpu: |x| vec![atmos::atmosphere::exponential_density(x[0], x[1])],
            reference: |x| vec![f64ref::exponential_density(x[0], x[1])],
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 1.0,
                bound: Some(|x| vec![exponential_density_error(x[0], x[1])]),
                why: "h/H (2.5 ULP, absolute 5u·x in the exponent) then WGSL exp (3 + 2|x| ULP); \
                      flushed subnormals allowed",
            },
        },
        Case {
            name: "atmos::tent_density",
            imports: &["atmos::atmosphere"],
            arity: (3, 1),
            wgsl: "y0 = tent_density(x0, x1, x2);",
            grid: || {
                profile_altitudes()
                    .into_iter()
                    .map(|h| vec![h, 25_000.0, 15_000.0])
                    .collect()
            },
            cpu: |x| vec![atmos::atmosphere::tent_density(x[0], x[1], x[2])],
            reference: |x| vec![f64ref::tent_density(x[0], x[1], x[2])],
            tolerance: Tolerance {
                abs: TENT_ERROR,
                rel: 0.0,
                ulp: 1.0,
                bound: None,
                why: "|h − c| (0.5 ULP), ÷ w (2.5 ULP), then 1 − q cancels near the feet: \
                      absolute 5u",
            },
        },
        Case {
            name: "atmos::extinction_at_altitude",
            imports: &["atmos::atmosphere"],
            arity: (1, 3),
            // Earth's parameters as the f32 uniforms hold them (the f32 nearest each literal).
            wgsl: "let earth = AtmosphereParameters(vec3<f32>(5.802e-6, 13.558e-6, 33.1e-6), 8000.0, \
                   vec3<f32>(3.996e-6), 1200.0, vec3<f32>(4.40e-6), 0.8, \
                   vec3<f32>(0.650e-6, 1.881e-6, 0.085e-6), 25000.0, vec3<f32>(0.1), 15000.0, \
                   vec3<f32>(1.0), 0.004675, 6360000.0, 6460000.0, vec2<f32>(0.0)); \
                   let e = extinction_at_altitude(earth, x0); y0 = e.x; y1 = e.y; y2 = e.z;",
            grid: || profile_altitudes().into_iter().map(|h| vec![h]).collect(),
            cpu: |x| {
                let earth = atmos::Atmosphere::earth().to_uniforms().unwrap();
                atmos::atmosphere::extinction_at_altitude(&earth, x[0]).to_vec()
            },
            reference: |x| f64ref::extinction_at_altitude(&earth_f32_as_f64(), x[0]).to_vec(),
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 3.0,
                bound: Some(|x| {
                    let a = earth_f32_as_f64();
                    let rayleigh = exponential_density_error(x[0], a.rayleigh_scale_height);
                    let mie = exponential_density_error(x[0], a.mie_scale_height);
                    (0..3)
                        .map(|i| {
                            a.rayleigh_scattering[i] * rayleigh
                                + a.mie_extinction[i] * mie
                                + a.ozone_absorption[i] * TENT_ERROR
                        })
                        .collect()
                }),
                why: "each profile's bound times its coefficient, plus 3 ULP for the products \
                      and sums of positive terms",
            },
        },
        Case {
            name: "atmos::ray_sphere_intersect",
            imports: &["atmos::geometry"],
            arity: (3, 2),
            wgsl: "let hit = ray_sphere_intersect(x0, x1, x2); y0 = hit.x; y1 = hit.y;",
            grid: ray_sphere_grid,
            cpu: |x| atmos::geometry::ray_sphere_intersect(x[0], x[1], x[2]).to_vec(),
            reference: |x| f64ref::ray_sphere_intersect(x[0], x[1], x[2]).to_vec(),
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(ray_sphere_bound),
                why: "forward bound: 2·δ√D + 12u|t| with δD = 4u(b² + |c|) (near-tangent rays \
                      are ill-conditioned in f32 whatever the formula; rays within rounding of \
                      tangency are excluded as undecidable)",
            },
        },
        Case {
            name: "atmos::altitude_along_ray",
            imports: &["atmos::geometry"],
            arity: (4, 1),
            wgsl: "y0 = altitude_along_ray(x0, x1, x2, x3);",
            grid: altitude_grid,
            cpu: |x| vec![atmos::geometry::altitude_along_ray(x[0], x[1], x[2], x[3])],
            reference: |x| vec![f64ref::altitude_along_ray(x[0], x[1], x[2], x[3])],
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| vec![altitude_error(x[0], x[1], x[2], x[3])]),
                why: "forward bound: 4u(|(r−R)(r+R)| + |t|(2|rμ| + |t|))/(r_t + R) + 8u|h| \
                      (the only cancellation left is the geometric one in 2rμ + t)",
            },
        },
        Case {
            name: "atmos::optical_length_exponential",
            imports: &["atmos::optical_depth"],
            arity: (6, 1),
            wgsl: "y0 = optical_length_exponential(x0, x1, x2, x3, x4, u32(x5));",
            grid: optical_length_grid,
            cpu: |x| {
                vec![atmos::optical_depth::optical_length_exponential(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                )]
            },
            reference: |x| {
                vec![f64ref::optical_length_exponential(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                )]
            },
            tolerance: Tolerance {
                abs: 1e-30,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(optical_length_bound),
                why: "forward bound summed over the 16 samples: WGSL exp (3 + 2|x| ULP), h/H \
                      (2.5 ULP), each altitude's bound, n-term summation; abs 1e-30 m for \
                      samples flushed to 0 above ~100 km with H = 1.2 km",
            },
        },
        Case {
            name: "atmos::transmittance_from_optical_depth",
            imports: &["atmos::transmittance"],
            arity: (3, 3),
            wgsl: "let t = transmittance_from_optical_depth(vec3<f32>(x0, x1, x2)); \
                   y0 = t.x; y1 = t.y; y2 = t.z;",
            grid: || {
                optical_depths()
                    .into_iter()
                    .map(|tau| vec![tau, tau * 0.37, tau * 3.1])
                    .collect()
            },
            cpu: |x| {
                atmos::transmittance::transmittance_from_optical_depth([x[0], x[1], x[2]]).to_vec()
            },
            reference: |x| f64ref::transmittance_from_optical_depth([x[0], x[1], x[2]]).to_vec(),
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 1.0,
                bound: Some(|x| {
                    x.iter()
                        .map(|&tau| exp_relative_error(tau) * (-tau).exp())
                        .collect()
                }),
                why: "WGSL exp: 3 + 2|x| ULP (lavapipe: 61 ULP at worst over this grid); results \
                      below f32::MIN_POSITIVE may flush to 0 (exp(−95) does on lavapipe)",
            },
        },
        Case {
            name: "atmos::one_minus_exp_neg",
            imports: &["atmos::transmittance"],
            arity: (1, 1),
            wgsl: "y0 = one_minus_exp_neg(x0);",
            grid: || {
                let mut v: Vec<f64> = logspace(1e-8, 1e4, 8000).collect();
                v.extend(linspace(-0.5, 2.0, 2001));
                v.extend([0.0, 1e-8, 0.5, 0.499_999_97, -0.499_999_97]);
                v.into_iter().map(|x| vec![x]).collect()
            },
            cpu: |x| vec![atmos::transmittance::one_minus_exp_neg(x[0])],
            reference: |x| vec![f64ref::one_minus_exp_neg(x[0])],
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| vec![one_minus_exp_bound(x[0])]),
                why: "|x| < 0.5: 8-term Horner series, each factor in [0.7, 1.3] (≤ 4 ULP); \
                      beyond: WGSL exp's 3 + 2|x| ULP scaled by e^{−x}, plus one subtraction",
            },
        },
        Case {
            name: "atmos::closed_form_inscatter",
            imports: &["atmos::closed_form"],
            arity: (3, 3),
            wgsl: "let l = closed_form_inscatter(vec3<f32>(5.802e-6, 13.558e-6, 33.1e-6), \
                   vec3<f32>(3.996e-6), x0, x1, x2); y0 = l.x; y1 = l.y; y2 = l.z;",
            grid: closed_form_grid,
            cpu: |x| {
                atmos::closed_form::closed_form_inscatter(
                    to_f32(BETA_RAYLEIGH),
                    to_f32(BETA_MIE),
                    x[0],
                    x[1],
                    x[2],
                )
                .to_vec()
            },
            reference: |x| {
                f64ref::closed_form_inscatter(
                    to_f32(BETA_RAYLEIGH).map(f64::from),
                    to_f32(BETA_MIE).map(f64::from),
                    x[0],
                    x[1],
                    x[2],
                )
                .to_vec()
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 32.0,
                bound: Some(|x| {
                    let reference = f64ref::closed_form_inscatter(
                        to_f32(BETA_RAYLEIGH).map(f64::from),
                        to_f32(BETA_MIE).map(f64::from),
                        x[0],
                        x[1],
                        x[2],
                    );
                    let tau = closed_form_optical_depths(x[2]);
                    (0..3)
                        .map(|i| {
                            let fraction = f64ref::one_minus_exp_neg(tau[i]);
                            if fraction > 0.0 {
                                reference[i] * one_minus_exp_bound(tau[i]) / fraction
                            } else {
                                0.0
                            }
                        })
                        .collect()
                }),
                why: "phases (HG 13 + Rayleigh 2 ULP, weighted sum 1), 1 − e^{−τ} (4 ULP, or exp's \
                      bound relative to the result), τ = βs (1.5), division (2.5): ≤ 32 ULP \
                      plus the exp term",
            },
        },
        Case {
            name: "atmos::closed_form_extinction",
            imports: &["atmos::closed_form"],
            arity: (3, 3),
            wgsl: "let t = closed_form_extinction(vec3<f32>(5.802e-6, 13.558e-6, 33.1e-6), \
                   vec3<f32>(3.996e-6), x2); y0 = t.x; y1 = t.y; y2 = t.z;",
            grid: closed_form_grid,
            cpu: |x| {
                atmos::closed_form::closed_form_extinction(
                    to_f32(BETA_RAYLEIGH),
                    to_f32(BETA_MIE),
                    x[2],
                )
                .to_vec()
            },
            reference: |x| {
                f64ref::closed_form_extinction(
                    to_f32(BETA_RAYLEIGH).map(f64::from),
                    to_f32(BETA_MIE).map(f64::from),
                    x[2],
                )
                .to_vec()
            },
            tolerance: Tolerance {
                abs: f32::MIN_POSITIVE as f64,
                rel: 0.0,
                ulp: 1.0,
                bound: Some(|x| {
                    closed_form_optical_depths(x[2])
                        .iter()
                        .map(|&tau| (-tau).exp() * (exp_relative_error(tau) + 3.0 * U * tau))
                        .collect()
                }),
                why: "τ = (βR + βM)·s carries 1.5u relative (an absolute 1.5u·τ in the exponent), \
                      then WGSL exp's 3 + 2|τ| ULP; flushed subnormals allowed",
            },
        },
        Case {
            name: "render::tonemap_exposure",
            imports: &["render::tonemap"],
            arity: (4, 3),
            wgsl: "let d = tonemap_exposure(vec3<f32>(x0, x1, x2), x3); y0 = d.x; y1 = d.y; y2 = d.z;",
            grid: || {
                let mut grid = Vec::new();
                for exposure in [0.5, 1.0, 20.0, 100.0] {
                    for radiance in std::iter::once(0.0).chain(logspace(1e-8, 1e3, 2600)) {
                        grid.push(vec![radiance, radiance * 0.5, radiance * 2.0, exposure]);
                    }
                }
                grid
            },
            cpu: |x| render::tonemap::tonemap_exposure([x[0], x[1], x[2]], x[3]).to_vec(),
            reference: |x| {
                (0..3)
                    .map(|i| f64ref::one_minus_exp_neg(x[i] * x[3]))
                    .collect()
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(tonemap_bound),
                why: "one product (u·x in the argument) then atmos::one_minus_exp_neg's budget",
            },
        },
        Case {
            name: "render::linear_to_srgb",
            imports: &["render::tonemap"],
            arity: (1, 1),
            wgsl: "y0 = linear_to_srgb(x0);",
            grid: || {
                let mut v: Vec<f64> = linspace(0.0, 1.0, 20_001).collect();
                v.extend([0.003_130_8, 0.003_130_9, 1e-7, 1.0]);
                v.into_iter().map(|x| vec![x]).collect()
            },
            cpu: |x| vec![render::tonemap::linear_to_srgb(x[0])],
            reference: |x| {
                // The cut-off compares in f32 on both f32 sides; do the same here.
                vec![if x[0] as f32 <= 0.003_130_8f32 {
                    12.92f32 as f64 * x[0]
                } else {
                    1.055 * x[0].powf(1.0 / 2.4) - 0.055
                }]
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| vec![srgb_bound(x[0])]),
                why: "pow = exp2(y·log2 x): WGSL log2 2⁻²¹ abs on [0.5, 2] else 3 ULP, exp2 3 + 2|a| ULP; −0.055 cancels up to ×12 near the linear segment",
            },
        },
        Case {
            name: "render::dither_offset",
            imports: &["render::tonemap"],
            arity: (3, 1),
            wgsl: "y0 = dither_offset(vec2<u32>(u32(x0), u32(x1)), u32(x2));",
            grid: || {
                let mut grid = Vec::new();
                for seed in [0.0, 1.0, 12_345.0] {
                    for y in 0..60 {
                        for x in 0..60 {
                            grid.push(vec![f64::from(x * 37), f64::from(y * 53), seed]);
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                vec![render::tonemap::dither_offset(
                    [x[0] as u32, x[1] as u32],
                    x[2] as u32,
                )]
            },
            reference: |x| {
                vec![f64::from(render::tonemap::dither_offset(
                    [x[0] as u32, x[1] as u32],
                    x[2] as u32,
                ))]
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer hash and one exact int → f32 conversion and power-of-two scale: \
                      bit-exact (the CPU twin is the reference)",
            },
        },
        Case {
            name: "render::quantize_srgb8",
            imports: &["render::tonemap"],
            arity: (5, 3),
            wgsl: "let q = quantize_srgb8(vec3<f32>(x0, x1, x2), vec2<u32>(u32(x3), u32(x4)), 7u); \
                   y0 = q.x; y1 = q.y; y2 = q.z;",
            grid: || {
                linspace(0.0, 1.0, 10_201)
                    .enumerate()
                    .map(|(i, v)| vec![v, v * v, v.sqrt(), (i % 101) as f64, (i / 101) as f64])
                    .collect()
            },
            cpu: |x| {
                render::tonemap::quantize_srgb8([x[0], x[1], x[2]], [x[3] as u32, x[4] as u32], 7)
                    .to_vec()
            },
            reference: |x| {
                let offset = f64::from(render::tonemap::dither_offset(
                    [x[3] as u32, x[4] as u32],
                    7,
                ));
                (0..3)
                    .map(|i| {
                        let encoded = if x[i] as f32 <= 0.003_130_8f32 {
                            12.92f32 as f64 * x[i]
                        } else {
                            1.055 * x[i].powf(1.0 / 2.4) - 0.055
                        };
                        (encoded * 255.0 + offset + 0.5).floor().clamp(0.0, 255.0)
                    })
                    .collect()
            },
            tolerance: Tolerance {
                abs: 1.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "a value within linear_to_srgb's bound of a code boundary may round either way: one code value",
            },
        },
        Case {
            name: "terrain::sun_disc_visible_fraction",
            imports: &["terrain::shadow"],
            arity: (1, 1),
            wgsl: "y0 = sun_disc_visible_fraction(x0);",
            grid: || {
                let mut v: Vec<f64> = linspace(-1.5, 1.5, 20_001).collect();
                for k in 1..=7 {
                    let d = 10f64.powi(-k);
                    v.extend([1.0 - d, -1.0 + d, d, -d]);
                }
                v.into_iter().map(|x| vec![x]).collect()
            },
            cpu: |x| vec![terrain::shadow::sun_disc_visible_fraction(x[0])],
            reference: |x| {
                vec![terrain::shadow::reference::sun_disc_visible_fraction_f64(
                    x[0],
                )]
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| vec![disc_fraction_bound(x[0])]),
                why: "reference is the independent asin form; the f32 form's only transcendental \
                      is atan2 (lavapipe ≈ 300 ULP, 512 allowed), scaled by dA/dθ ≤ 2/π",
            },
        },
        Case {
            name: "terrain::soft_shadow",
            imports: &["terrain::shadow"],
            arity: (3, 1),
            wgsl: "y0 = soft_shadow(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for horizon in [-0.3, 0.0, 0.05, 0.4] {
                    for radius in [0.004654, 0.02] {
                        for offset in linspace(-0.03, 0.03, 1301) {
                            grid.push(vec![horizon + offset, horizon, radius]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![terrain::shadow::soft_shadow(x[0], x[1], x[2])],
            reference: |x| {
                vec![terrain::shadow::reference::soft_shadow_f64(
                    x[0], x[1], x[2],
                )]
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| {
                    // (e − h)/r rounds twice: the argument moves by 2u|x|, the
                    // fraction by at most (2/π)·that per unit x.
                    let arg = (x[0] - x[1]) / x[2];
                    vec![
                        disc_fraction_bound(arg) + 2.0 / std::f64::consts::PI * 3.0 * U * arg.abs(),
                    ]
                }),
                why: "sun_disc_visible_fraction's bound at x = (e − h)/r, plus that argument's \
                      two roundings times the fraction's slope (≤ 2/π)",
            },
        },
        Case {
            name: "terrain::terrain_shading",
            imports: &["terrain::shading"],
            arity: (5, 3),
            wgsl: "let n = normalize(vec3<f32>(x0, x1, 1.0)); let l = normalize(vec3<f32>(x2, 0.3, x3)); \
                   let c = terrain_shading(n, l, vec3<f32>(0.2, 0.3, 0.1), x4, 0.8); y0 = c.x; y1 = c.y; y2 = c.z;",
            grid: || {
                let mut grid = Vec::new();
                for (i, slope) in linspace(-2.0, 2.0, 41).enumerate() {
                    for sun in linspace(-1.0, 1.0, 61) {
                        for shadow in [0.0, 0.37, 1.0] {
                            grid.push(vec![
                                slope,
                                0.5 - slope * 0.1,
                                sun,
                                0.2 + 0.01 * i as f64,
                                shadow,
                            ]);
                        }
                    }
                }
                // Straight-up normals swept through the terminator.
                grid.extend(
                    (0..2601).map(|i| vec![0.0, 0.0, 0.0, -1.3 + 0.001 * f64::from(i), 1.0]),
                );
                grid
            },
            cpu: |x| {
                let n = glam::Vec3::new(x[0], x[1], 1.0).normalize();
                let l = glam::Vec3::new(x[2], 0.3, x[3]).normalize();
                terrain::shadow::terrain_shading(n, l, glam::Vec3::new(0.2, 0.3, 0.1), x[4], 0.8)
                    .to_array()
                    .to_vec()
            },
            reference: |x| {
                let norm = |v: [f64; 3]| {
                    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                    v.map(|c| c / l)
                };
                let n = norm([x[0], x[1], 1.0]);
                let l = norm([x[2], 0.3, x[3]]);
                let n_dot_l = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0);
                let albedo = [0.2f32, 0.3, 0.1].map(f64::from);
                albedo
                    .iter()
                    .map(|a| a * n_dot_l * x[4] * f64::from(0.8f32))
                    .collect()
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                // normalize (WGSL: inverseSqrt-based, ≤ 8u relative per vector) and a dot
                // product that cancels near the terminator: absolute 24u on N·L.
                bound: Some(|_| vec![24.0 * U * 0.3; 3]),
                why: "two normalize calls (≤ 8u each) and a 3-term dot that cancels at the \
                      terminator: 24u absolute on N·L, times albedo ≤ 0.3",
            },
        },
        Case {
            name: "cloudlight::slice_attenuation",
            imports: &["cloudlight::slice_attenuation"],
            arity: (3, 1),
            wgsl: "y0 = slice_attenuation(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for light in [1.0, 0.37, 1e-3] {
                    for ratio in linspace(0.0, 1.0, 41) {
                        for density in linspace(0.0, 1.0, 101) {
                            grid.push(vec![light, density, ratio]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![cloudlight::slice::slice_attenuation(x[0], x[1], x[2])],
            reference: |x| vec![x[0] * (1.0 - (1.0 - x[2]) * x[1])],
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                // 1 − (1 − r)·d cancels as (1 − r)·d → 1: each of its three roundings is
                // at most u relative to 1, so the bound is absolute, times the light.
                bound: Some(|x| vec![3.0 * U * x[0].abs()]),
                why: "four correctly rounded ops; 1 − (1 − r)d cancels for dense, opaque slices: \
                      3u absolute, times the incoming light",
            },
        },
        Case {
            name: "cloudlight::bayer_jitter_4x4",
            imports: &["cloudlight::jitter"],
            arity: (2, 1),
            wgsl: "y0 = bayer_jitter_4x4(vec2<u32>(u32(x0), u32(x1)));",
            grid: || {
                let mut grid = Vec::new();
                for y in 0..101 {
                    for x in 0..101 {
                        grid.push(vec![f64::from(x * 13), f64::from(y * 7)]);
                    }
                }
                grid
            },
            cpu: |x| {
                vec![cloudlight::jitter::bayer_jitter_4x4([
                    x[0] as u32,
                    x[1] as u32,
                ])]
            },
            reference: |x| {
                const BAYER: [[u32; 4]; 4] =
                    [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];
                let (px, py) = (x[0] as usize % 4, x[1] as usize % 4);
                vec![f64::from(BAYER[py][px]) / 16.0]
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer bit interleave and an exact power-of-two scale: bit-exact \
                      (reference: the classic matrix by table)",
            },
        },
        Case {
            name: "common::hash_u32",
            imports: &["common::hash"],
            arity: (2, 2),
            wgsl: "let h = hash_u32(u32(x0) | (u32(x1) << 16u)); y0 = f32(h >> 8u); y1 = f32(h & 0xffu);",
            grid: || {
                let mut v = Vec::new();
                for hi in (0..65_536u32).step_by(4099) {
                    for lo in (0..65_536u32).step_by(97) {
                        v.push(vec![f64::from(lo), f64::from(hi)]);
                    }
                }
                v.push(vec![65_535.0, 65_535.0]);
                v
            },
            cpu: |x| {
                let h = skyscape_wgsl::common::hash_u32(x[0] as u32 | ((x[1] as u32) << 16));
                vec![(h >> 8) as f32, (h & 0xff) as f32]
            },
            reference: |x| {
                let h = skyscape_wgsl::common::hash_u32(x[0] as u32 | ((x[1] as u32) << 16));
                vec![f64::from(h >> 8), f64::from(h & 0xff)]
            },
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer arithmetic wraps identically in WGSL and Rust: bit-exact",
            },
        },
    ]
}
