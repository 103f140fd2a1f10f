//! Parity cases of `celestial::clouds`' texture, geometry and shadow: value noise, fBm,
//! the coverage density, the two-stream reflectance, the distance to a layer and the
//! shadow on the ground. The f64 references and the layers the cases use are shared
//! with `celestial_cloud_light_cases`.

use super::*;
use crate::parity::compare::ulp_f32;

// ---------------------------------------------------------------- celestial::clouds

use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};

/// f64 value noise: the same lattice hashes (integers, bit-equal), f64 blending.
pub(super) fn noise64(x: f64, y: f64, seed: u32) -> f64 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i32, fy as i32);
    let (tx, ty) = (x - fx, y - fy);
    let corner = |dx: i32, dy: i32| {
        f64::from(unit_float_from_bits(hash_combine(
            hash_combine(seed, ix.wrapping_add(dx) as u32),
            iy.wrapping_add(dy) as u32,
        )))
    };
    let sx = tx * tx * (3.0 - 2.0 * tx);
    let sy = ty * ty * (3.0 - 2.0 * ty);
    let bottom = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    let top = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

pub(super) fn fbm64(x: f64, y: f64, octaves: u32, seed: u32) -> f64 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0, 1.0, 0.0, 1.0);
    for octave in 0..octaves {
        sum += amplitude * noise64(x * frequency, y * frequency, hash_combine(seed, octave));
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total
}

/// Blending error of the value noise: the smoothstep weights (≈ 6u) and two lerps of
/// corner differences ≤ 1 (≈ 6u): 12u absolute.
pub(super) const NOISE_ERROR: f64 = 12.0 * U;

/// Largest slope of the value noise per lattice unit: the smoothstep's 1.5 times a
/// corner difference ≤ 1, in each axis.
pub(super) const NOISE_SLOPE: f64 = 1.5;

/// The fBm's absolute error when its coordinates carry `dx` (lattice units of the
/// first octave): each octave's blending error and slope·frequency·dx, weighted by
/// its amplitude over the total; the coordinate scalings by powers of two are exact.
pub(super) fn fbm_error(octaves: u32, dx: f64) -> f64 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0, 1.0, 0.0, 1.0);
    for _ in 0..octaves {
        sum += amplitude * (NOISE_ERROR + 2.0 * NOISE_SLOPE * frequency * dx);
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total + 4.0 * U * f64::from(octaves)
}

pub(super) fn noise_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for seed in [0.0, 7.0, 123_456.0] {
        for x in linspace(-40.0, 40.0, 61) {
            for y in linspace(-3.1, 57.3, 61) {
                grid.push(vec![x, y, seed]);
            }
        }
    }
    grid
}

pub(super) fn fbm_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for octaves in [1.0, 3.0, 5.0] {
        for seed in [0.0, 99.0] {
            for x in linspace(-20.0, 60.0, 41) {
                for y in linspace(-5.5, 30.25, 41) {
                    grid.push(vec![x, y, octaves, seed]);
                }
            }
        }
    }
    grid
}

/// The case's layers: one per kind (texture constants, τ, g) at 2 km, 300 m thick,
/// seed 5, coverage 0.5.
pub(super) fn case_layers() -> Vec<celestial::clouds::CloudLayerUniforms> {
    static LAYERS: std::sync::OnceLock<Vec<celestial::clouds::CloudLayerUniforms>> =
        std::sync::OnceLock::new();
    LAYERS.get_or_init(make_case_layers).clone()
}

pub(super) fn make_case_layers() -> Vec<celestial::clouds::CloudLayerUniforms> {
    let frame = celestial::clouds::CloudLayerFrame {
        planet_radius_m: R_GROUND,
        offset_m: [300.0, -200.0],
        fog_extinction_per_m: 3.912 / 30_000.0,
        exp2_fog: false,
        sun_direction: [0.0, 0.6, 0.8],
        sunlight: [1.0, 0.95, 0.9],
        skylight: [0.3, 0.4, 0.6],
        fog_colour: [0.2, 0.25, 0.3],
    };
    celestial::clouds::CloudKind::ALL
        .iter()
        .map(|&kind| {
            let layer = celestial::clouds::CloudLayer {
                seed: 5,
                coverage: 0.5,
                ..celestial::clouds::CloudLayer::new(2000.0, 300.0, 100.0, 40_000.0, kind)
                    .expect("valid layer")
            };
            layer.uniforms(&frame)
        })
        .collect()
}

/// A layer uniform from a case row: x[k0..] = base, top, curved, feature, stretch,
/// octaves, seed, threshold, softness, τ, g, exp2, core depth (the rest fixed as
/// `case_layers`).
/// [`layer_from`] of a case's f32 inputs (the CPU twin's side).
pub(super) fn layer_from_f32(x: &[f32], k0: usize) -> celestial::clouds::CloudLayerUniforms {
    layer_from(&x.iter().map(|&v| f64::from(v)).collect::<Vec<_>>(), k0)
}

pub(super) fn layer_from(x: &[f64], k0: usize) -> celestial::clouds::CloudLayerUniforms {
    static FIRST: std::sync::OnceLock<celestial::clouds::CloudLayerUniforms> =
        std::sync::OnceLock::new();
    let mut layer = *FIRST.get_or_init(|| case_layers()[0]);
    layer.base_radius = x[k0] as f32;
    layer.top_radius = x[k0 + 1] as f32;
    layer.curved = x[k0 + 2] as u32;
    layer.feature_size = x[k0 + 3] as f32;
    layer.stretch = x[k0 + 4] as f32;
    layer.octaves = x[k0 + 5] as u32;
    layer.seed = x[k0 + 6] as u32;
    layer.threshold = x[k0 + 7] as f32;
    layer.softness = x[k0 + 8] as f32;
    layer.optical_thickness = x[k0 + 9] as f32;
    layer.asymmetry = x[k0 + 10] as f32;
    layer.exp2_fog = x[k0 + 11] as u32;
    layer.core_depth = x[k0 + 12] as f32;
    layer
}

pub(super) fn layer_row(
    layer: &celestial::clouds::CloudLayerUniforms,
    curved: u32,
    exp2: u32,
) -> Vec<f64> {
    vec![
        f64::from(layer.base_radius),
        f64::from(layer.top_radius),
        f64::from(curved),
        f64::from(layer.feature_size),
        f64::from(layer.stretch),
        f64::from(layer.octaves),
        f64::from(layer.seed),
        f64::from(layer.threshold),
        f64::from(layer.softness),
        f64::from(layer.optical_thickness),
        f64::from(layer.asymmetry),
        f64::from(exp2),
        f64::from(layer.core_depth),
    ]
}

/// The WGSL constructor of the case's layer from `x{k0}…` (the fixed fields as
/// `case_layers`): offset (300, −200), half span 20 km, fog 3.912/30 km, the light.
macro_rules! layer_wgsl {
    ($k:literal, $k1:literal, $k2:literal, $k3:literal, $k4:literal, $k5:literal, $k6:literal, $k7:literal, $k8:literal, $k9:literal, $k10:literal, $k11:literal, $k12:literal) => {
        concat!(
            "let layer = CloudLayerUniforms(",
            $k,
            ", ",
            $k1,
            ", 6360000.0, u32(",
            $k2,
            "), ",
            $k3,
            ", ",
            $k4,
            ", u32(",
            $k5,
            "), u32(",
            $k6,
            "), ",
            $k7,
            ", ",
            $k8,
            ", ",
            $k9,
            ", ",
            $k10,
            ", vec2<f32>(300.0, -200.0), 20000.0, 0.0001304, ",
            "vec3<f32>(0.0, 0.6, 0.8), u32(",
            $k11,
            "), vec3<f32>(1.0, 0.95, 0.9), ",
            $k12,
            ", ",
            "vec3<f32>(0.3, 0.4, 0.6), 0.0, vec3<f32>(0.2, 0.25, 0.3), 0.0); "
        )
    };
}
pub(super) use layer_wgsl;

pub(super) fn density64(u: f64, v: f64, l: &celestial::clouds::CloudLayerUniforms) -> f64 {
    let x = u / (f64::from(l.feature_size) * f64::from(l.stretch));
    let y = v / f64::from(l.feature_size);
    let n = fbm64(x, y, l.octaves, l.seed);
    let t = ((n - f64::from(l.threshold)) / f64::from(l.softness) + 0.5).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Density error when (u, v) carry `duv` metres: the coordinates' own quotient
/// rounding (WGSL division 2.5 ULP, twice: 6u relative) plus `duv`, through the fBm's
/// slope, then the threshold map's slope 1.5/softness.
pub(super) fn density_error(
    u: f64,
    v: f64,
    duv: f64,
    l: &celestial::clouds::CloudLayerUniforms,
) -> f64 {
    let scale = f64::from(l.feature_size);
    let dx = (6.0 * U * u.abs().max(v.abs()) + duv) / scale;
    1.5 / f64::from(l.softness) * (fbm_error(l.octaves, dx) + 4.0 * U) + 4.0 * U
}

pub(super) fn density_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for (k, layer) in case_layers().iter().enumerate() {
        for u in linspace(-25_000.0, 25_000.0, 45) {
            for v in linspace(-25_000.0, 25_000.0, 45) {
                let mut row = vec![u + 37.0 * k as f64, v];
                row.extend(layer_row(layer, 1, 0));
                grid.push(row);
            }
        }
    }
    grid
}

pub(super) fn reflectance64(tau: f64, g: f64, mu: f64) -> f64 {
    if mu <= 0.0 {
        return 0.0;
    }
    let scaled = (1.0 - g) * tau;
    let direct = 1.0 - (-tau / mu).exp();
    ((scaled + (2.0 / 3.0 - mu) * direct) / (4.0 / 3.0 + scaled)).clamp(0.0, 1.0)
}

pub(super) fn distance64(r: f64, mu: f64, layer_radius: f64, curved: u32) -> f64 {
    if curved != 0 {
        let hit = f64ref::ray_sphere_intersect(r, mu, layer_radius);
        if r < layer_radius {
            return hit[1];
        }
        if hit[0] >= 0.0 && mu < 0.0 {
            return hit[0];
        }
        return -1.0;
    }
    let height = layer_radius - r;
    if (height > 0.0 && mu > 0.0) || (height < 0.0 && mu < 0.0) {
        return height / mu;
    }
    -1.0
}

pub(super) fn layer_distance_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in [0.0, 500.0, 2_000.0, 2_150.0, 9_000.0] {
        let r = R_GROUND + altitude;
        for layer_altitude in [1_000.0, 2_100.0, 6_000.0] {
            let radius = R_GROUND + layer_altitude;
            for curved in [0.0, 1.0] {
                for mu in cosines(341) {
                    let mu32 = f64::from(mu as f32);
                    let (r32, radius32) = (f64::from(r as f32), f64::from(radius as f32));
                    if curved == 1.0 {
                        let (d, error) = discriminant_and_error(r32, mu32, radius32);
                        if d.abs() < error {
                            continue;
                        }
                    }
                    grid.push(vec![r, mu, radius, curved]);
                }
            }
        }
    }
    grid
}

/// Flat: height/μ (the height difference is exact, the quotient 2.5 ULP in WGSL);
/// curved: the ray–sphere bound.
pub(super) fn layer_distance_bound(x: &[f64]) -> Vec<f64> {
    let d = distance64(x[0], x[1], x[2], x[3] as u32);
    if x[3] == 0.0 {
        return vec![3.0 * U * d.abs()];
    }
    let bounds = ray_sphere_bound(&[x[0], x[1], x[2]]);
    vec![bounds[0].max(bounds[1])]
}

/// f64 `cloud_shadow` (the case layer's sun (0, 0.6, 0.8), half span 20 km, offset
/// (300, −200)), with the crossing point it samples.
pub(super) fn shadow64(
    p: [f64; 3],
    r: f64,
    l: &celestial::clouds::CloudLayerUniforms,
) -> (f64, [f64; 2]) {
    let sun = l.sun_direction.map(f64::from);
    let point_radius = r + p[2];
    if sun[2] <= 0.0 || point_radius >= f64::from(l.top_radius) {
        return (1.0, [0.0; 2]);
    }
    let distance = (f64::from(l.base_radius) - point_radius).max(0.0) / sun[2];
    let x = p[0] + sun[0] * distance;
    let y = p[1] + sun[1] * distance;
    if x.hypot(y) >= f64::from(l.half_span) {
        return (1.0, [x, y]);
    }
    let density = density64(x + f64::from(l.offset[0]), y + f64::from(l.offset[1]), l);
    (
        (-f64::from(l.optical_thickness) * density / sun[2]).exp(),
        [x, y],
    )
}

pub(super) fn cloud_shadow_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let r = 6_360_000.0 + 1000.0;
    for (k, layer) in case_layers().iter().enumerate() {
        for x in linspace(-9_000.0, 9_000.0, 31) {
            for y in linspace(-9_000.0, 9_000.0, 31) {
                // Points from 800 m below the viewer to above the layer's top.
                for z in [-800.0, -250.0, 0.0, 400.0, 900.0, 2_500.0] {
                    let mut row = vec![x + 41.0 * k as f64, y, z, r];
                    row.extend(layer_row(layer, 1, 0));
                    grid.push(row);
                }
            }
        }
    }
    grid
}

/// The cases, in report order.
pub(super) fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "celestial::cloud_shadow",
            imports: &["celestial::clouds"],
            arity: (17, 1),
            wgsl: concat!(
                layer_wgsl!(
                    "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13", "x14", "x15",
                    "x16"
                ),
                "y0 = cloud_shadow(vec3<f32>(x0, x1, x2), x3, layer);"
            ),
            grid: cloud_shadow_grid,
            cpu: |x| {
                let l = layer_from_f32(x, 4);
                vec![celestial::clouds::cloud_shadow(
                    [x[0], x[1], x[2]],
                    x[3],
                    &l,
                )]
            },
            reference: |x| vec![shadow64([x[0], x[1], x[2]], x[3], &layer_from(x, 4)).0],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| {
                    let l = layer_from(x, 4);
                    let (shadow, [cx, cy]) = shadow64([x[0], x[1], x[2]], x[3], &l);
                    if shadow == 1.0 {
                        return vec![0.0];
                    }
                    let mu = f64::from(l.sun_direction[2]);
                    let base = f64::from(l.base_radius);
                    let point_radius = x[3] + x[2];
                    let distance = (base - point_radius) / mu;
                    // The crossing point moves by the f32 rounding of the point's radius
                    // r + z (half an ULP: 0.25 m at 6.4e6 m; the difference with the base
                    // is then exact, Sterbenz) over μ☉, plus the quotient's, products'
                    // and sums' roundings; the density moves by that times its local
                    // slope (a central difference over ±duv, doubled for curvature), plus
                    // its own rounding (the cloud_density case's bound at exact inputs).
                    let radius_rounding = 0.5 * ulp_f32(point_radius);
                    let duv = (radius_rounding + 4.0 * U * distance) / mu
                        + 3.0 * U * (cx.abs() + cy.abs() + 500.0);
                    let (u0, v0) = (cx + 300.0, cy - 200.0);
                    let slope_change = [(duv, 0.0), (0.0, duv)]
                        .iter()
                        .map(|&(du, dv)| {
                            (density64(u0 + du, v0 + dv, &l) - density64(u0 - du, v0 - dv, &l))
                                .abs()
                                * 0.5
                        })
                        .fold(0.0, f64::max);
                    let density_shift = 2.0 * 2.0 * slope_change + density_error(u0, v0, 0.0, &l);
                    let tau_over_mu = f64::from(l.optical_thickness) / mu;
                    let density = density64(u0, v0, &l);
                    let arg = tau_over_mu * density;
                    vec![
                        shadow
                            * (tau_over_mu * density_shift
                                + 3.0 * U * arg
                                + exp_relative_error(arg)),
                    ]
                }),
                why: "the sun's crossing of the base moves with the f32 rounding of the \
                      point's radius (0.25 m at 6.4e6 m) over μ☉ and the sums', through the \
                      density's local slope there (a central difference, ×2 for curvature, \
                      both axes) plus the cloud_density case's own rounding bound, times τ/μ☉ \
                      in the exponent; the exponent's two roundings and WGSL exp's 3 + 2|x| ULP",
            },
        },
        Case {
            name: "celestial::cloud_value_noise",
            imports: &["celestial::clouds"],
            arity: (3, 1),
            wgsl: "y0 = cloud_value_noise(x0, x1, u32(x2));",
            grid: noise_grid,
            cpu: |x| vec![celestial::twins::cloud_value_noise(x[0], x[1], x[2] as u32)],
            reference: |x| vec![noise64(x[0], x[1], x[2] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: NOISE_ERROR,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "the lattice hashes are integers (bit-equal); the smoothstep weights (6u) \
                      and two lerps of corner differences ≤ 1 (6u) round: 12u absolute",
            },
        },
        Case {
            name: "celestial::cloud_fbm",
            imports: &["celestial::clouds"],
            arity: (4, 1),
            wgsl: "y0 = cloud_fbm(x0, x1, u32(x2), u32(x3));",
            grid: fbm_grid,
            cpu: |x| {
                vec![celestial::twins::cloud_fbm(
                    x[0],
                    x[1],
                    x[2] as u32,
                    x[3] as u32,
                )]
            },
            reference: |x| vec![fbm64(x[0], x[1], x[2] as u32, x[3] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![fbm_error(x[2] as u32, 0.0)]),
                why: "each octave's 12u blending error weighted by its amplitude (the \
                      frequency scalings are powers of two, exact), 4u per octave for the \
                      weighted sum and the normalisation",
            },
        },
        Case {
            name: "celestial::cloud_density",
            imports: &["celestial::clouds"],
            arity: (15, 1),
            wgsl: concat!(
                layer_wgsl!(
                    "x2", "x3", "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13",
                    "x14"
                ),
                "y0 = cloud_density(x0, x1, layer);"
            ),
            grid: density_grid,
            cpu: |x| {
                let l = layer_from_f32(x, 2);
                vec![celestial::twins::cloud_density(x[0], x[1], &l)]
            },
            reference: |x| vec![density64(x[0], x[1], &layer_from(x, 2))],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| vec![density_error(x[0], x[1], 0.0, &layer_from(x, 2))]),
                why: "u/(size·stretch) and v/size round (WGSL division 2.5 ULP: 6u of the \
                      coordinate), moving the fBm by its slope (1.5 per lattice unit per octave, \
                      ×frequency×amplitude) plus its blending error; the threshold map scales by \
                      1.5/softness",
            },
        },
        Case {
            name: "celestial::cloud_reflectance",
            imports: &["celestial::clouds"],
            arity: (3, 1),
            wgsl: "y0 = cloud_reflectance(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for tau in logspace(1e-3, 200.0, 60) {
                    for g in [0.0, 0.75, 0.85, 0.95] {
                        for mu in linspace(-0.2, 1.0, 49) {
                            grid.push(vec![tau, g, mu]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![celestial::twins::cloud_reflectance(x[0], x[1], x[2])],
            reference: |x| vec![reflectance64(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| {
                    if x[2] <= 0.0 {
                        return vec![0.0];
                    }
                    let arg = x[0] / x[2];
                    let direct = 1.0 - (-arg).exp();
                    let scaled = (1.0 - x[1]) * x[0];
                    let denominator = 4.0 / 3.0 + scaled;
                    // exp (3 + 2|arg| ULP of e^{−arg}, times |2/3 − μ|), the sums' rounding
                    // relative to their terms, the quotient.
                    let numerator_error =
                        exp_relative_error(arg) * (-arg).exp() * (2.0 / 3.0 - x[2]).abs()
                            + 6.0 * U * (scaled.abs() + (2.0 / 3.0 - x[2]).abs() * direct);
                    vec![numerator_error / denominator + 4.0 * U * reflectance64(x[0], x[1], x[2])]
                }),
                why: "exp(−τ/μ) (3 + 2|τ/μ| ULP) times |2/3 − μ|, the numerator's sum (6u of \
                      its terms), over the denominator, and the quotient's 4u",
            },
        },
        Case {
            name: "celestial::cloud_layer_distance",
            imports: &["celestial::clouds"],
            arity: (4, 1),
            wgsl: "y0 = cloud_layer_distance(x0, x1, x2, u32(x3));",
            grid: layer_distance_grid,
            cpu: |x| {
                vec![celestial::twins::cloud_layer_distance(
                    x[0],
                    x[1],
                    x[2],
                    x[3] as u32,
                )]
            },
            reference: |x| vec![distance64(x[0], x[1], x[2], x[3] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(layer_distance_bound),
                why: "flat: the height difference is exact (Sterbenz), the quotient 2.5 ULP; \
                      curved: atmos' ray–sphere forward bound (rays within rounding of \
                      tangency are left out, as in atmos' case)",
            },
        },
    ]
}
