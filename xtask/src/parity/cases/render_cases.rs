//! Parity cases of `render`: tone mapping, sRGB encoding, dither and quantisation.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
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
    ]
}
