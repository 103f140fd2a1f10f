//! `cloudlight::march::temporal` (`shaders/cloudlight/march_temporal.wgsl`): which
//! pixels a frame of the amortised march marches, and where a pixel's cloud was in the
//! last frame's image.

use super::*;

/// The grid of reprojections: a camera, the last frame's camera moved up to 50 m and
/// turned up to ~1.5°, a pixel in the inner 60 % of the image (whose cloud stays in the
/// last image, away from its edges) and a distance.
fn reprojection_grid() -> Vec<Vec<f64>> {
    use glam::DVec3;
    let mut grid = Vec::new();
    let sizes = [[64.0, 48.0], [1280.0, 720.0], [320.0, 180.0]];
    for k in 0..170u32 {
        let t = f64::from(k);
        let forward =
            DVec3::new((0.7 * t).cos(), (0.7 * t).sin(), 0.2 * (0.3 * t).sin()).normalize();
        let basis = |f: DVec3| {
            let right = f.cross(DVec3::Z).normalize();
            (f, right, right.cross(f))
        };
        let (f, r, u) = basis(forward);
        let turned =
            (forward + 0.025 * (0.9 * t).sin() * r + 0.015 * (1.3 * t).cos() * u).normalize();
        let (bf, br, bu) = basis(turned);
        let origin = DVec3::new(
            800.0 * (0.4 * t).sin(),
            -600.0 * (0.5 * t).cos(),
            900.0 + 40.0 * t,
        );
        let moved = origin + DVec3::new(50.0 * (1.7 * t).sin(), 30.0 * (2.1 * t).cos(), 10.0);
        let size = sizes[k as usize % 3];
        let tan_x = [0.3, 0.6, 1.0][k as usize % 3];
        let tan_y = tan_x * size[1] / size[0];
        for i in 0..5 {
            for j in 0..4 {
                let px = (size[0] * (0.2 + 0.6 * f64::from(i) / 4.0)).floor();
                let py = (size[1] * (0.2 + 0.6 * f64::from(j) / 3.0)).floor();
                for along in [200.0, 1500.0, 5000.0] {
                    let mut row = vec![size[0], size[1], px, py, along];
                    for v in [origin, f, r, u] {
                        row.extend(v.to_array());
                    }
                    row.extend([tan_x, tan_y]);
                    for v in [moved, bf, br, bu] {
                        row.extend(v.to_array());
                    }
                    row.extend([tan_x, tan_y]);
                    grid.push(row);
                }
            }
        }
    }
    grid
}

/// The reprojection in f64 with glam, written apart from the generic twin.
fn reprojection_f64(x: &[f64]) -> Vec<f64> {
    use glam::DVec3;
    let v = |k: usize| DVec3::new(x[k], x[k + 1], x[k + 2]);
    let (size, pixel, along) = ([x[0], x[1]], [x[2], x[3]], x[4]);
    let (origin, forward, right, up, tan) = (v(5), v(8), v(11), v(14), [x[17], x[18]]);
    let (b_origin, b_forward, b_right, b_up, b_tan) = (v(19), v(22), v(25), v(28), [x[31], x[32]]);
    let sx = (2.0 * (pixel[0] + 0.5) / size[0] - 1.0) * tan[0];
    let sy = (1.0 - 2.0 * (pixel[1] + 0.5) / size[1]) * tan[1];
    let point = origin + (forward + sx * right + sy * up).normalize() * along;
    let local = point - b_origin;
    let depth = local.dot(b_forward);
    let x_image = (local.dot(b_right) / (depth * b_tan[0]) + 1.0) * 0.5 * size[0];
    let y_image = (1.0 - local.dot(b_up) / (depth * b_tan[1])) * 0.5 * size[1];
    let inside =
        depth > 0.0 && (0.0..size[0]).contains(&x_image) && (0.0..size[1]).contains(&y_image);
    if inside {
        vec![x_image, y_image]
    } else {
        vec![-1.0, -1.0]
    }
}

pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::interleave_marches",
            imports: &["cloudlight::march_temporal"],
            arity: (3, 1),
            wgsl: "y0 = select(0.0, 1.0, interleave_marches(vec2<u32>(u32(x0), u32(x1)), \
                   u32(x2)));",
            grid: || {
                let mut grid = Vec::new();
                for y in 0..12 {
                    for x in 0..12 {
                        for phase in 0..70 {
                            grid.push(vec![f64::from(x), f64::from(y), f64::from(phase)]);
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                let marched = cloudlight::march::temporal::interleave_marches(
                    [x[0] as u32, x[1] as u32],
                    x[2] as u32,
                );
                vec![if marched { 1.0 } else { 0.0 }]
            },
            // A 2×2 block's pixels in the order (0,0), (1,0), (0,1), (1,1), by phase mod 4.
            reference: |x| {
                let order = [(0, 0), (1, 0), (0, 1), (1, 1)];
                let phase = (x[2] as usize) % 4;
                let block = ((x[0] as u32) % 2, (x[1] as u32) % 2);
                vec![if order[phase] == block { 1.0 } else { 0.0 }]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "integer arithmetic: exact",
            },
        },
        Case {
            name: "cloudlight::reprojected_position",
            imports: &["cloudlight::march_temporal"],
            arity: (33, 2),
            wgsl: "let now = MarchCamera(vec3<f32>(x5, x6, x7), vec3<f32>(x8, x9, x10), \
                   vec3<f32>(x11, x12, x13), vec3<f32>(x14, x15, x16), vec2<f32>(x17, x18)); \
                   let before = MarchCamera(vec3<f32>(x19, x20, x21), vec3<f32>(x22, x23, x24), \
                   vec3<f32>(x25, x26, x27), vec3<f32>(x28, x29, x30), vec2<f32>(x31, x32)); \
                   let p = reprojected_position(now, before, vec2<u32>(u32(x0), u32(x1)), \
                   vec2<u32>(u32(x2), u32(x3)), x4, 1.0e6); y0 = p.x; y1 = p.y;",
            grid: reprojection_grid,
            cpu: |x| {
                use cloudlight::march::temporal::{MarchCamera, reprojected_position};
                let v = |k: usize| [x[k], x[k + 1], x[k + 2]];
                let camera = |k: usize| MarchCamera {
                    origin: v(k),
                    forward: v(k + 3),
                    right: v(k + 6),
                    up: v(k + 9),
                    tan_half: [x[k + 12], x[k + 13]],
                };
                reprojected_position(
                    &camera(5),
                    &camera(19),
                    [x[0] as u32, x[1] as u32],
                    [x[2] as u32, x[3] as u32],
                    x[4],
                    1.0e6,
                )
                .map_or(vec![-1.0, -1.0], |p| p.to_vec())
            },
            reference: reprojection_f64,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.02,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "pixels: the point's coordinates (under 6 km here) carry ~4u of absolute \
                      rounding each (under 1.5 mm), 1.5e-5 rad over depths of 100 m or more, \
                      at most 0.016 px at 640 px per unit tangent (the widest here: 1280 px over \
                      tan 1.0); the screen mapping adds a few u of the position (4e-4 px)",
            },
        },
    ]
}
