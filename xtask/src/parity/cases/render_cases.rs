//! Parity cases of `render`: tone mapping, sRGB encoding, dither and quantisation.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "render::volume_shadow_texel",
            imports: &["render::volume_shadow"],
            arity: (10, 2),
            wgsl: "let t = volume_shadow_texel(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), x6, vec2<f32>(x7, x8), x9); y0 = t.x; y1 = t.y;",
            grid: volume_shadow_grid,
            cpu: |x| {
                render::volume_clouds::volume_shadow_texel(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    x[6],
                    [x[7], x[8]],
                    x[9],
                )
                .to_vec()
            },
            reference: |x| {
                let t = (x[6] - x[2]) / x[5];
                vec![
                    (x[0] + t * x[3] - x[7]) / x[9] - 0.5,
                    (x[1] + t * x[4] - x[8]) / x[9] - 0.5,
                ]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(volume_shadow_bound),
                why: "the subtraction, division and product roundings scaled by the magnitudes they meet (|x|, |t·s|, |origin|: metres over the cell)",
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
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(tonemap_bound),
                why: "one product (u·x in the argument) then atmos::one_minus_exp_neg's budget",
            },
        },
        Case {
            name: "render::tonemap_neutral",
            imports: &["render::tonemap"],
            arity: (4, 3),
            wgsl: "let d = tonemap_neutral(vec3<f32>(x0, x1, x2), x3); y0 = d.x; y1 = d.y; y2 = d.z;",
            grid: || {
                // Greys, mild and strong colours (a sunset sun's R/B is ~15) across
                // the toe, the compression start (0.76), the shoulder and past the
                // f16 target's largest value, at several exposures.
                let mut grid = Vec::new();
                for exposure in [0.5, 1.0, 30.0] {
                    for radiance in std::iter::once(0.0).chain(logspace(1e-6, 1e7, 1120)) {
                        for ratios in [[1.0, 1.0, 1.0], [1.0, 0.5, 2.0], [1.0, 0.36, 1.0 / 15.0]] {
                            grid.push(vec![
                                radiance * ratios[0],
                                radiance * ratios[1],
                                radiance * ratios[2],
                                exposure,
                            ]);
                        }
                    }
                }
                grid
            },
            cpu: |x| render::tonemap::tonemap_neutral([x[0], x[1], x[2]], x[3]).to_vec(),
            reference: tonemap_neutral_f64,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 12.0,
                bound: None,
                why: "one product (exposure), then on the shoulder peak − 0.52 (the product's \
                      rounding grows up to 0.76/0.24 ≈ 3.2× relative), a division, 1 − q \
                      (q ≤ 0.24), the scale's division and the mix's three roundings: \
                      about 10 u, no cancellation (the mix adds non-negative terms)",
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
            audit: Audit::INDEPENDENT,
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
                vec![super::integer_references::dither_offset(
                    [x[0] as u32, x[1] as u32],
                    x[2] as u32,
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer hash and one exact int → f32 conversion and power-of-two scale: \
                      bit-exact against a second formulation (the hashes in u64 reduced \
                      by hand, the triangular sum in f64)",
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
                let offset =
                    super::integer_references::dither_offset([x[3] as u32, x[4] as u32], 7);
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
            audit: Audit::INDEPENDENT.loose(
                "integer codes: the smallest non-zero tolerance is one code, and agreement \
                 is usually exact (observed 0), so any tolerance is infinitely loose by the \
                 ratio; a wrong transfer curve or dither moves many codes by more than one",
            ),
            tolerance: Tolerance {
                abs: 1.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "a value within linear_to_srgb's bound of a code boundary may round either way: one code value",
            },
        },
    ]
}

/// The present pass's camera and display constants, as WGSL literals and in Rust.
macro_rules! present_wgsl {
    () => {
        "let camera = FrameCamera(vec3<f32>(0.0, 0.0, 6360002.0), 64u, vec3<f32>(0.0, -1.0, 0.0), \
         64u, vec3<f32>(0.0, 0.0, 1.0), 0.75, vec3<f32>(1.0, 0.0, 0.0), 1e30, \
         vec3<f32>(0.8, 0.0, 0.6), 0u); \
         let present = PresentParameters(vec3<f32>(14565.0, 14000.0, 13000.0), 0.9999891, \
         6360000.0, 20.0, 0u, 0u);"
    };
}

fn present_camera() -> atmos::frame::FrameCamera {
    atmos::frame::FrameCamera {
        position: [0.0, 0.0, 6_360_002.0],
        width: 64,
        right: [0.0, -1.0, 0.0],
        height: 64,
        up: [0.0, 0.0, 1.0],
        tan_half_fov_y: 0.75,
        forward: [1.0, 0.0, 0.0],
        max_distance: 1e30,
        sun: [0.8, 0.0, 0.6],
        padding: 0,
    }
}

fn present_parameters() -> render::present::PresentParameters {
    render::present::PresentParameters {
        sun_disc_radiance: [14_565.0, 14_000.0, 13_000.0],
        cos_sun_radius: 0.999_989_1,
        planet_radius: 6_360_000.0,
        exposure: 20.0,
        dither_seed: 0,
        display_transform: 0,
    }
}

/// View directions around the sun disc and across the horizon (elevation, azimuth
/// offsets from the sun), leaving out those within f32 rounding of the disc's edge or
/// of the horizon's tangent, where either answer is right.
fn present_grid() -> Vec<Vec<f64>> {
    let sun = glam::DVec3::new(0.8, 0.0, 0.6);
    let cos_radius = f64::from(0.999_989_1f32);
    let mut grid = Vec::new();
    let mut add = |v: glam::DVec3| {
        let v = v.normalize();
        let v32 = v.as_vec3().as_dvec3();
        let near_edge = (v32.dot(sun) - cos_radius).abs() < 1e-6;
        // Horizon from 2 m up: mu of the tangent ≈ −7.9e-4.
        let near_horizon = (v32.z + 7.93e-4).abs() < 2e-5;
        if !near_edge && !near_horizon {
            grid.push(vec![v32.x, v32.y, v32.z]);
        }
    };
    for i in 0..101 {
        for j in 0..101 {
            // ±0.02 rad around the sun (the disc's radius is 0.0047 rad).
            let (de, da) = (-0.02 + 0.0004 * f64::from(i), -0.02 + 0.0004 * f64::from(j));
            let elevation = 0.6f64.asin() + de;
            add(glam::DVec3::new(
                elevation.cos() * da.cos(),
                elevation.cos() * da.sin(),
                elevation.sin(),
            ));
        }
    }
    for i in 0..400 {
        // Across the horizon, away from the sun.
        let elevation = -0.01 + 0.00005 * f64::from(i);
        add(glam::DVec3::new(-elevation.cos(), 0.3, elevation.sin()));
    }
    grid
}

/// The present pass's parity case (appended to this crate's cases by `cases()`).
pub fn present_case() -> Case {
    Case {
        name: "render::present_radiance",
        imports: &["render::present"],
        arity: (3, 3),
        wgsl: concat!(
            present_wgsl!(),
            " let l = present_radiance(vec3<f32>(x0, x1, x2), vec3<f32>(0.1, 0.2, 0.3), \
             vec3<f32>(0.5, 0.6, 0.7), camera, present); y0 = l.x; y1 = l.y; y2 = l.z;"
        ),
        grid: present_grid,
        cpu: |x| {
            render::present::present_radiance(
                [x[0], x[1], x[2]],
                [0.1, 0.2, 0.3],
                [0.5, 0.6, 0.7],
                &present_camera(),
                &present_parameters(),
            )
            .to_vec()
        },
        reference: |x| {
            let v = glam::DVec3::new(x[0], x[1], x[2]);
            let p = present_parameters();
            let radiance = [0.1f32, 0.2, 0.3].map(f64::from);
            let transmittance = [0.5f32, 0.6, 0.7].map(f64::from);
            let position = glam::DVec3::new(0.0, 0.0, 6_360_002.0);
            let r = position.length();
            let ground = f64ref::ray_sphere_intersect(r, v.dot(position) / r, 6_360_000.0);
            let sees_disc = ground[0] < 0.0
                && v.dot(glam::DVec3::new(0.8, 0.0, 0.6)) >= f64::from(p.cos_sun_radius);
            (0..3)
                .map(|i| {
                    if sees_disc {
                        radiance[i] + transmittance[i] * f64::from(p.sun_disc_radiance[i])
                    } else {
                        radiance[i]
                    }
                })
                .collect()
        },
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 2.0,
            bound: None,
            why: "one product and one sum, correctly rounded on both sides; the disc and \
                  horizon tests are exact away from their edges (grid points within f32 \
                  rounding of an edge are left out)",
        },
    }
}

/// Terrain points over 60 km (east, north) at 0–4 km, suns 2°–90° at 8 azimuths, the
/// shadow plane at 1.5 and 3 km, origins and cells of real maps: 10,368 inputs.
fn volume_shadow_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for &elevation in &[2.0f64, 5.0, 15.0, 35.0, 60.0, 89.0] {
        for k in 0..8 {
            let azimuth = f64::from(k) * 45.0 + 10.0;
            let (e, a) = (elevation.to_radians(), azimuth.to_radians());
            let s = [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()];
            for &(plane, origin, cell) in &[
                (1500.0, [-12_000.0, -9_000.0], 50.0),
                (3000.0, [-40_000.0, 5_000.0], 187.5),
            ] {
                for i in 0..6 {
                    for j in 0..6 {
                        for &z in &[0.0, 900.0, 2450.0] {
                            let x = -30_000.0 + 12_000.0 * f64::from(i) + 37.0;
                            let y = -30_000.0 + 12_000.0 * f64::from(j) - 11.0;
                            grid.push(vec![
                                x, y, z, s[0], s[1], s[2], plane, origin[0], origin[1], cell,
                            ]);
                        }
                    }
                }
            }
        }
    }
    grid
}

/// `volume_shadow_texel`'s forward bound (on the f32 inputs): `t = (plane − z)/s_z`
/// (two roundings), `x + t·s_x` (two), `− origin` (one), `/ cell`
/// (one), `− ½` (one): each rounding contributes u × the magnitude it meets, over the
/// cell; doubled.
fn volume_shadow_bound(x: &[f64]) -> Vec<f64> {
    let t = ((x[6] - x[2]) / x[5]).abs();
    let t_bound = t * 4.0 * U + (x[6].abs() + x[2].abs()) / x[5].abs() * 2.0 * U;
    (0..2)
        .map(|k| {
            let s = x[3 + k].abs();
            let position = x[k].abs() + t * s + x[7 + k].abs();
            let coordinate = (x[k] + t * x[3 + k] - x[7 + k]).abs() / x[9];
            2.0 * ((position * 4.0 * U + t_bound * s) / x[9] + coordinate * 3.0 * U + 0.5 * U)
        })
        .collect()
}

/// `render::tonemap::tonemap_neutral` in f64 on the same f32 constants.
fn tonemap_neutral_f64(x: &[f64]) -> Vec<f64> {
    let constant = |c: f32| f64::from(c);
    let largest = constant(render::tonemap::HDR_LARGEST);
    let start = constant(render::tonemap::NEUTRAL_COMPRESSION_START);
    let desaturation = constant(render::tonemap::NEUTRAL_DESATURATION);
    let limit = constant(render::tonemap::NEUTRAL_WHITE_MIX_LIMIT);
    let unfitted: Vec<f64> = (0..3).map(|i| (x[i] * x[3]).max(0.0)).collect();
    let brightest = unfitted[0].max(unfitted[1]).max(unfitted[2]);
    let fit = if brightest > largest {
        largest / brightest
    } else {
        1.0
    };
    let exposed: Vec<f64> = unfitted.iter().map(|c| c * fit).collect();
    let peak = exposed[0].max(exposed[1]).max(exposed[2]);
    if peak < start {
        return exposed;
    }
    let new_peak = 1.0 - constant(0.0576) / (peak - constant(0.52));
    let white_mix = limit * (1.0 - 1.0 / (desaturation * (peak - new_peak) + 1.0));
    exposed
        .iter()
        .map(|c| c * (new_peak / peak) * (1.0 - white_mix) + new_peak * white_mix)
        .collect()
}
