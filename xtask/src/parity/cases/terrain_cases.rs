//! Parity cases of `terrain`: shadow queries and the seed-000 shading term.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
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
    ]
}
