//! Parity cases of `terrain`: shadow queries and the terrain shading term.

use super::*;
use crate::parity::compare::ulp_f32;

const TAU64: f64 = std::f64::consts::TAU;

/// Directions toward the sun over the whole sphere (elevation −89.9°…90°, every
/// azimuth) plus the axes and near-axis extremes; components are not normalised on
/// purpose (the functions must not assume unit length for angles).
fn sun_directions() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for e in linspace(-89.9, 90.0, 101) {
        for a in linspace(0.0, 359.0, 101) {
            let (e, a) = (e.to_radians(), a.to_radians());
            grid.push(vec![e.cos() * a.sin(), e.cos() * a.cos(), e.sin()]);
        }
    }
    for d in [1e-7, 1e-5, 1e-3] {
        for v in [
            [1.0, 0.0, d],
            [1.0, 0.0, -d],
            [0.0, 1.0, d],
            [d, 1.0, 0.2],
            [-d, 1.0, 0.2],
            [d, -1.0, 0.0],
            [d, d, 1.0],
            [3.0, 4.0, d],
        ] {
            grid.push(v.to_vec());
        }
    }
    grid.extend([
        vec![0.0, 0.0, 1.0],
        vec![0.0, 0.0, -1.0],
        vec![1.0, 0.0, 0.0],
        vec![0.0, 1.0, 0.0],
        vec![-1.0, 0.0, 0.0],
        vec![0.0, -1.0, 0.0],
        vec![300.0, -400.0, 120.0],
    ]);
    grid
}

/// `atan2(z, |xy|)` in f64 (the reference elevation).
fn elevation_f64(x: f64, y: f64, z: f64) -> f64 {
    z.atan2(x.hypot(y))
}

/// Error bound of the f32 elevation: atan2 (lavapipe ≈ 300 ULP, 512 allowed) plus the
/// squares, sum and sqrt of |xy| (≤ 4u relative), which move the angle by at most
/// 4u·|z·r|/(z² + r²).
fn elevation_bound(x: f64, y: f64, z: f64) -> f64 {
    let r = x.hypot(y);
    let e = elevation_f64(x, y, z);
    let sensitivity = if r == 0.0 && z == 0.0 {
        0.0
    } else {
        (z * r).abs() / (z * z + r * r)
    };
    512.0 * ulp_f32(e) + 4.0 * U * e.abs() + 4.0 * U * sensitivity
}

/// `azimuth_layers` in f64: `f = azimuth/2π·N` wrapped into `[0, N)`.
fn azimuth_layers_f64(azimuth: f64, count: f64) -> (f64, f64, f64) {
    let f0 = azimuth / TAU64 * count;
    let f = f0 - (f0 / count).floor() * count;
    let k = f.floor();
    let lower = k.rem_euclid(count);
    (lower, (lower + 1.0).rem_euclid(count), f - k)
}

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
            cpu: |x| vec![terrain::twins::sun_disc_visible_fraction(x[0])],
            reference: |x| vec![terrain::twins::sun_disc_visible_fraction_f64(x[0])],
            audit: Audit::INDEPENDENT,
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
            reference: |x| vec![terrain::twins::soft_shadow_f64(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
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
            audit: Audit::INDEPENDENT,
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
            name: "terrain::decode_horizon_angle",
            imports: &["terrain::shadow"],
            arity: (1, 1),
            wgsl: "y0 = decode_horizon_angle(x0);",
            grid: || {
                // Every 8-bit code, every 6th 16-bit code and the ends: what a unorm
                // texture returns.
                let mut v: Vec<f64> = (0..=255).map(|q| f64::from(q) / 255.0).collect();
                v.extend((0..=65_535).step_by(6).map(|q| f64::from(q) / 65_535.0));
                v.extend([0.0, 1.0, 0.5, 1e-7, 1.0 - 1e-7]);
                v.into_iter().map(|a| vec![a]).collect()
            },
            cpu: |x| vec![terrain::twins::decode_horizon_angle(x[0])],
            reference: |x| vec![x[0] * std::f64::consts::PI - std::f64::consts::FRAC_PI_2],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // PI rounded to f32 (≤ u relative), the product, the half and the
                // difference: absolute ≤ 4u·(α·π + π/2) whatever the cancellation near
                // α = ½ (fused or not).
                bound: Some(|x| {
                    vec![4.0 * U * (x[0] * std::f64::consts::PI + std::f64::consts::FRAC_PI_2)]
                }),
                why: "α·π − π/2 with π in f32: three roundings of terms ≤ π, 4u·(απ + π/2) \
                      absolute (≤ 7.5e-7 rad, 1/64 of a 16-bit step); relative error is \
                      meaningless at the cancellation α = ½",
            },
        },
        Case {
            name: "terrain::hard_shadow",
            imports: &["terrain::shadow"],
            arity: (2, 1),
            wgsl: "y0 = hard_shadow(x0, x1);",
            grid: || {
                let mut grid = Vec::new();
                for horizon in linspace(
                    -std::f64::consts::FRAC_PI_2,
                    std::f64::consts::FRAC_PI_2,
                    101,
                ) {
                    let h = f64::from(horizon as f32);
                    for offset in linspace(-0.05, 0.05, 101) {
                        grid.push(vec![h + offset, h]);
                    }
                    // Equal, and the next f32 either side. WGSL lets an implementation
                    // flush subnormal inputs of any operation to zero (the NVIDIA H100
                    // does: 1e-45 > 0 gave 0), so at h = 0 the neighbour is the smallest
                    // normal value, not the subnormal one ULP away.
                    let next = f32::from_bits((h as f32).to_bits() + 1);
                    let up = if next.is_subnormal() {
                        f64::from(f32::MIN_POSITIVE.copysign(next))
                    } else {
                        f64::from(next)
                    };
                    grid.extend([vec![h, h], vec![up, h], vec![h, up]]);
                }
                grid
            },
            cpu: |x| vec![terrain::twins::hard_shadow(x[0], x[1])],
            reference: |x| vec![if x[0] > x[1] { 1.0 } else { 0.0 }],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "a comparison of two f32 values is exact on every side: 0 or 1, \
                      bit-exact (ties and next-f32 neighbours included; subnormal inputs, \
                      which WGSL may flush to zero, are left out)",
            },
        },
        Case {
            name: "terrain::sun_elevation",
            imports: &["terrain::shadow"],
            arity: (3, 1),
            wgsl: "y0 = sun_elevation(vec3<f32>(x0, x1, x2));",
            grid: sun_directions,
            cpu: |x| {
                vec![terrain::shadow::sun_elevation(glam::Vec3::new(
                    x[0], x[1], x[2],
                ))]
            },
            reference: |x| vec![elevation_f64(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![elevation_bound(x[0], x[1], x[2])]),
                why: "atan2 (lavapipe ≈ 300 ULP, 512 allowed) plus |xy| = sqrt(x² + y²) \
                      (≤ 4u relative), scaled by the angle's sensitivity |z·r|/(z² + r²)",
            },
        },
        Case {
            name: "terrain::sun_azimuth",
            imports: &["terrain::shadow"],
            arity: (3, 1),
            wgsl: "y0 = sun_azimuth(vec3<f32>(x0, x1, x2));",
            grid: || {
                // The straight-up and straight-down axes have no azimuth (atan2(0, 0)):
                // left out.
                sun_directions()
                    .into_iter()
                    .filter(|d| d[0] != 0.0 || d[1] != 0.0)
                    .collect()
            },
            cpu: |x| {
                vec![terrain::shadow::sun_azimuth(glam::Vec3::new(
                    x[0], x[1], x[2],
                ))]
            },
            reference: |x| {
                let a = x[0].atan2(x[1]);
                vec![if a < 0.0 { a + TAU64 } else { a }]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    let a = x[0].atan2(x[1]);
                    // atan2 (512 ULP of its result) and, west of the meridian, the f32
                    // TAU (u relative) and the addition (½ ULP of the sum).
                    let wrap = if a < 0.0 { 2.0 * ulp_f32(TAU64) } else { 0.0 };
                    vec![512.0 * ulp_f32(a) + 4.0 * U * a.abs() + wrap]
                }),
                why: "atan2 (lavapipe ≈ 300 ULP, 512 allowed); west of the meridian the f32 \
                      TAU and the addition add ≤ 2 ULP(2π)",
            },
        },
        Case {
            name: "terrain::azimuth_layers",
            imports: &["terrain::shadow"],
            arity: (2, 3),
            wgsl: "let l = azimuth_layers(x0, u32(x1)); y0 = f32(l.lower); y1 = f32(l.upper); y2 = l.weight;",
            grid: || {
                let mut grid = Vec::new();
                for count in [
                    1.0, 2.0, 3.0, 4.0, 6.0, 8.0, 12.0, 16.0, 24.0, 32.0, 48.0, 64.0,
                ] {
                    for azimuth in linspace(-TAU64, 2.0 * TAU64, 1201) {
                        let azimuth = f64::from(azimuth as f32);
                        let (_, _, weight) = azimuth_layers_f64(azimuth, count);
                        // Within rounding of a layer boundary the layer index is
                        // undecidable in f32 (both answers are right): left out.
                        let margin = 64.0 * U * ((azimuth / TAU64 * count).abs() + count);
                        if weight < margin || weight > 1.0 - margin {
                            continue;
                        }
                        grid.push(vec![azimuth, count]);
                    }
                }
                grid
            },
            cpu: |x| {
                let l = terrain::shadow::azimuth_layers(x[0], x[1] as u32)
                    .expect("the grid's counts are >= 1 and its azimuths finite");
                vec![l.lower as f32, l.upper as f32, l.weight]
            },
            reference: |x| {
                let (lower, upper, weight) = azimuth_layers_f64(x[0], x[1]);
                vec![lower, upper, weight]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| {
                    // f0 = azimuth / TAU · N: the f32 TAU (u), the division (WGSL 2.5 ULP)
                    // and the product, ≤ 5u·|f0|; the wrap f0 − floor(f0/N)·N rounds to
                    // half an ULP of f < N; floor and f − k are exact away from layer
                    // boundaries (excluded): 8u·(|f0| + N) with margin.
                    let f0 = (x[0] / TAU64 * x[1]).abs();
                    vec![0.0, 0.0, 8.0 * U * (f0 + x[1])]
                }),
                why: "layer indices exact (inputs within 64u·|f| of a layer boundary are left \
                      out: the index is undecidable there); weight: f32 TAU, 2.5-ULP division, \
                      the product and the wrap into [0, N): 8u·(|azimuth/2π·N| + N)",
            },
        },
        Case {
            name: "terrain::self_shadow_east_west",
            imports: &["terrain::shadow"],
            arity: (6, 1),
            wgsl: "y0 = self_shadow_east_west(x0, x1, vec3<f32>(x2, x3, x4), x5);",
            grid: || {
                let mut grid = Vec::new();
                for (east, west) in [
                    (0.1, -0.2),
                    (-0.05, 0.3),
                    (0.02, 0.02),
                    (0.5, -std::f64::consts::FRAC_PI_2),
                ] {
                    for azimuth_deg in [
                        -179.0f64, -120.0, -60.0, -1.0, 0.0, 1.0, 45.0, 90.0, 135.0, 179.0, 180.0,
                    ] {
                        let azimuth = azimuth_deg.to_radians();
                        let horizon: f64 = if azimuth.sin() >= 0.0 { east } else { west };
                        for radius in [0.004654f64, 0.02, 0.0] {
                            for k in linspace(-3.0, 3.0, 101) {
                                let elevation = horizon + k * radius.max(0.004654);
                                let row: Vec<f64> = [
                                    east,
                                    west,
                                    elevation.cos() * azimuth.sin(),
                                    elevation.cos() * azimuth.cos(),
                                    elevation.sin(),
                                    radius,
                                ]
                                .iter()
                                .map(|&v| f64::from(v as f32))
                                .collect();
                                // A hard shadow whose sun is within the f32 elevation's
                                // error of the horizon is undecidable (both answers are
                                // right): left out.
                                let e = elevation_f64(row[2], row[3], row[4]);
                                let h = if row[2] >= 0.0 { row[0] } else { row[1] };
                                if radius == 0.0
                                    && (e - h).abs() <= elevation_bound(row[2], row[3], row[4])
                                {
                                    continue;
                                }
                                grid.push(row);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                vec![terrain::shadow::self_shadow_east_west(
                    x[0],
                    x[1],
                    glam::Vec3::new(x[2], x[3], x[4]),
                    x[5],
                )]
            },
            reference: |x| {
                let horizon = if x[2] >= 0.0 { x[0] } else { x[1] };
                vec![terrain::twins::soft_shadow_f64(
                    elevation_f64(x[2], x[3], x[4]),
                    horizon,
                    x[5],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| {
                    let elevation = elevation_f64(x[2], x[3], x[4]);
                    let horizon = if x[2] >= 0.0 { x[0] } else { x[1] };
                    if x[5] > 0.0 {
                        // The elevation's error and the argument's two roundings, through
                        // the fraction's slope (≤ 2/π per unit argument).
                        let arg = (elevation - horizon) / x[5];
                        let arg_error =
                            elevation_bound(x[2], x[3], x[4]) / x[5] + 3.0 * U * arg.abs();
                        vec![disc_fraction_bound(arg) + 2.0 / std::f64::consts::PI * arg_error]
                    } else {
                        // Hard shadows are exact (undecidable inputs are not in the grid).
                        vec![0.0]
                    }
                }),
                why: "side chosen by the sign of x (exact); sun_elevation's bound (atan2 512 \
                      ULP, sqrt) divided by the radius, plus sun_disc_visible_fraction's bound; \
                      hard shadows (radius 0) exact (suns within the elevation's error of the \
                      horizon are left out: undecidable)",
            },
        },
    ]
}
