//! Parity case of `render::cloud_order`: two marched clouds seen at one pixel composited
//! in depth order (`S_near + T_near · S_far`, `T_near · T_far`,
//! `shaders/render/cloud_order.wgsl`), the scene's shell and volume cloud by depth.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "render::clouds_in_depth_order",
        imports: &["render::cloud_order"],
        arity: (10, 4),
        wgsl: "let c = clouds_in_depth_order(vec4<f32>(x0, x1, x2, x3), x4, vec4<f32>(x5, x6, x7, x8), x9); y0 = c.x; y1 = c.y; y2 = c.z; y3 = c.w;",
        grid: clouds_in_depth_order_grid,
        cpu: |x| {
            let cloud = |i: usize| render::cloud_order::SeenCloud {
                radiance: [x[i], x[i + 1], x[i + 2]],
                transmittance: x[i + 3],
                depth: x[i + 4],
            };
            let c = render::cloud_order::in_depth_order(cloud(0), cloud(5));
            vec![c.radiance[0], c.radiance[1], c.radiance[2], c.transmittance]
        },
        reference: |x| {
            let (near, far) = if x[9] < x[4] { (5, 0) } else { (0, 5) };
            let mut y: Vec<f64> = (0..3)
                .map(|k| x[near + k] + x[near + 3] * x[far + k])
                .collect();
            y.push(x[near + 3] * x[far + 3]);
            y
        },
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: Some(clouds_in_depth_order_bound),
            why: "a product and a sum per channel, unfused or fused (either fits): u·(|T_near·S_far| + |sum|), doubled; the transmittance one product: u·|T|, doubled",
        },
    }]
}

/// Two clouds at three depth orders (the first nearer, the second nearer, a tie): cloud
/// radiances (0, 1e-9 … 10) and transmittances (0, 1e-4 … 1) for each, each channel its
/// own value: 8 × 8 × 8 × 8 × 3 = 12,288 rows (with both "no cloud" (0, 0, 0, 1) inputs
/// among them).
fn clouds_in_depth_order_grid() -> Vec<Vec<f64>> {
    let radiances: Vec<f64> = std::iter::once(0.0)
        .chain(logspace(1e-9, 10.0, 7))
        .collect();
    let transmittances: Vec<f64> = std::iter::once(0.0).chain(logspace(1e-4, 1.0, 7)).collect();
    let mut grid = Vec::new();
    for &a in &radiances {
        for &t_a in &transmittances {
            for &b in &radiances {
                for &t_b in &transmittances {
                    for (d_a, d_b) in [(850.0, 2400.0), (5200.0, 1100.0), (1500.0, 1500.0)] {
                        grid.push(vec![
                            a,
                            a * 0.8,
                            a * 1.25,
                            t_a,
                            d_a,
                            b,
                            b * 1.5,
                            b / 1.5,
                            t_b,
                            d_b,
                        ]);
                    }
                }
            }
        }
    }
    grid
}

fn clouds_in_depth_order_bound(x: &[f64]) -> Vec<f64> {
    let (near, far) = if x[9] < x[4] { (5, 0) } else { (0, 5) };
    let mut bound: Vec<f64> = (0..3)
        .map(|k| {
            let product = (x[near + 3] * x[far + k]).abs();
            let sum = (x[near + k] + x[near + 3] * x[far + k]).abs();
            2.0 * U * (product + sum)
        })
        .collect();
    bound.push(2.0 * U * (x[near + 3] * x[far + 3]).abs());
    bound
}
