//! Parity cases of `atmos`: phase functions, densities, geometry, optical depth, transmittance, closed form.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::rayleigh_phase",
            imports: &["atmos::phase"],
            arity: (1, 1),
            wgsl: "y0 = rayleigh_phase(x0);",
            grid: || cosines(20_001).into_iter().map(|mu| vec![mu]).collect(),
            cpu: |x| vec![atmos::phase::rayleigh_phase(x[0])],
            reference: |x| vec![f64ref::rayleigh_phase(x[0])],
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            cpu: |x| vec![atmos::twins::exponential_density(x[0], x[1])],
            reference: |x| vec![f64ref::exponential_density(x[0], x[1])],
            audit: Audit::INDEPENDENT,
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
            cpu: |x| vec![atmos::twins::tent_density(x[0], x[1], x[2])],
            reference: |x| vec![f64ref::tent_density(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
    ]
}
