//! Parity case of `render::volume_clouds`: the volume cloud seen through the air in front
//! of it (`L_c · T_air + L_air · (1 − T_c)`, `shaders/render/volume_composite.wgsl`), the
//! term the composite adds per light (the sun's, and the moon's at night).

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "render::cloud_through_air",
        imports: &["render::volume_composite"],
        arity: (10, 3),
        wgsl: "let c = cloud_through_air(vec4<f32>(x0, x1, x2, x3), vec3<f32>(x4, x5, x6), vec3<f32>(x7, x8, x9)); y0 = c.x; y1 = c.y; y2 = c.z;",
        grid: cloud_through_air_grid,
        cpu: |x| {
            let cloud = cloudlight::march::MarchResult {
                radiance: [x[0], x[1], x[2]],
                transmittance: x[3],
                depth: 0.0,
            };
            render::marched_cloud::cloud_through_air(&cloud, [x[4], x[5], x[6]], [x[7], x[8], x[9]])
                .to_vec()
        },
        reference: |x| {
            (0..3)
                .map(|k| x[k] * x[4 + k] + x[7 + k] * (1.0 - x[3]))
                .collect()
        },
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: Some(cloud_through_air_bound),
            why: "two products, 1 − T_c and a sum, unfused (or fused: either fits): u·(|L_c·T| + |L_air|·|1 − T_c|·2 + |sum|), doubled",
        },
    }]
}

/// Cloud radiances (0, 1e-9 … 10: a moonlit cloud is ~1e-7 of the sun's unit), cloud
/// transmittances (0, 1e-4 … 1), air transmittances (0, 1e-3 … 1) and air radiances
/// (0, 1e-9 … 1), each channel its own value: 12 × 12 × 12 × 6 = 10,368 rows.
fn cloud_through_air_grid() -> Vec<Vec<f64>> {
    let radiances: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-9, 10.0, 11))
        .collect();
    let cloud_transmittances: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-4, 1.0, 11))
        .collect();
    let air: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-9, 1.0, 11))
        .collect();
    let mut grid = Vec::new();
    for &c in &radiances {
        for &t_c in &cloud_transmittances {
            for &l in &air {
                for tilt in [0.5f64, 0.8, 1.0, 1.25, 2.0, 3.0] {
                    let t_air = (0.9 / tilt).min(1.0);
                    grid.push(vec![
                        c,
                        c * tilt,
                        c / tilt,
                        t_c,
                        t_air,
                        t_air * 0.5,
                        t_air * 0.1,
                        l,
                        l / tilt,
                        l * tilt,
                    ]);
                }
            }
        }
    }
    grid
}

fn cloud_through_air_bound(x: &[f64]) -> Vec<f64> {
    let opacity = (1.0 - x[3]).abs();
    (0..3)
        .map(|k| {
            let product = (x[k] * x[4 + k]).abs();
            let air = x[7 + k].abs() * opacity;
            let sum = (x[k] * x[4 + k] + x[7 + k] * (1.0 - x[3])).abs();
            2.0 * U * (product + 2.0 * air + sum)
        })
        .collect()
}
