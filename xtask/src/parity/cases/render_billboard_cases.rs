//! Parity case of `render::billboard_clouds`: a billboard particle's colour seen through
//! the air in front of it (`colour · T_air + L_air`, `shaders/render/billboard_air.wgsl`).

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "render::billboard_seen_through_air",
        imports: &["render::billboard_air"],
        arity: (9, 3),
        wgsl: "let c = billboard_seen_through_air(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), vec3<f32>(x6, x7, x8)); y0 = c.x; y1 = c.y; y2 = c.z;",
        grid: seen_through_air_grid,
        cpu: |x| {
            render::billboard_clouds::billboard_seen_through_air(
                [x[0], x[1], x[2]],
                [x[3], x[4], x[5]],
                [x[6], x[7], x[8]],
            )
            .to_vec()
        },
        reference: |x| (0..3).map(|k| x[k] * x[3 + k] + x[6 + k]).collect(),
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: Some(seen_through_air_bound),
            why: "a product and a sum, unfused (or fused: either fits): u·|c·T| + u·|c·T + L|, doubled",
        },
    }]
}

/// Colours (radiance per unit sun irradiance, 0 and 1e-6 … 10), transmittances (0, 1e-4
/// … 1) and air radiances (0, 1e-6 … 1), each channel its own value: 12 × 12 × 12 × 6
/// = 10,368 rows.
fn seen_through_air_grid() -> Vec<Vec<f64>> {
    let colours: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-6, 10.0, 11))
        .collect();
    let transmittances: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-4, 1.0, 11))
        .collect();
    let radiances: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-6, 1.0, 11))
        .collect();
    let mut grid = Vec::new();
    for &c in &colours {
        for &t in &transmittances {
            for &l in &radiances {
                for tilt in [0.5, 0.8, 1.0, 1.25, 2.0, 3.0] {
                    grid.push(vec![
                        c,
                        c * tilt,
                        c / tilt,
                        t,
                        (t * tilt).min(1.0),
                        t / tilt,
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

fn seen_through_air_bound(x: &[f64]) -> Vec<f64> {
    (0..3)
        .map(|k| {
            let product = (x[k] * x[3 + k]).abs();
            2.0 * U * (product + (x[k] * x[3 + k] + x[6 + k]).abs())
        })
        .collect()
}
