//! Parity cases of `cloudlight::billboard` (Dobashi et al. 2000's billboards): the soft splat, the
//! opacity it gives a pixel, and a billboard's place and size on the image. The screen
//! function's reference is the generic function's f64 instantiation (one formula, two
//! precisions: the error is rounding); the splat's and the opacity's are independent
//! forms.

use super::*;
use cloudlight::billboard::{
    Camera, FieldOfView, Opacity, ScreenFrame, SizeRule, billboard_screen, splat_opacity,
};
use glam::DVec3;

/// The cameras of the screen case: several orientations and image sizes.
fn cameras() -> Vec<Camera> {
    let setups = [
        (DVec3::new(0.0, -1.0, 0.0), DVec3::Z, 40.0, 128, 128),
        (DVec3::new(0.6, 0.7, 0.3), DVec3::Z, 60.0, 1280, 720),
        (DVec3::new(-0.2, 0.1, 0.97), DVec3::X, 20.0, 512, 384),
        (DVec3::new(1.0, 0.0, -0.4), DVec3::Z, 90.0, 64, 200),
        (
            DVec3::new(-0.5, -0.5, 0.1),
            DVec3::new(0.1, 0.0, 1.0),
            5.0,
            4096,
            2160,
        ),
    ];
    setups
        .into_iter()
        .map(|(look, up, fov, w, h)| {
            Camera::new(
                DVec3::new(10.0, -20.0, 1500.0),
                look,
                up,
                FieldOfView::from_degrees(fov),
                w,
                h,
            )
            .expect("the parity cameras are valid")
        })
        .collect()
}

fn hash01(i: u32, salt: u32) -> f64 {
    f64::from(skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt) & 0xffff)
        / 65_535.0
}

fn screen_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for camera in cameras() {
        for (mode, scale) in [(0.0, 9500.0), (1.0, 125.0), (2.0, 310.0)] {
            let size = match mode as u32 {
                0 => SizeRule::Seed { k: scale },
                1 => SizeRule::World {
                    metres_per_density: scale,
                },
                _ => SizeRule::Fixed { diameter: scale },
            };
            let f = ScreenFrame::<f64>::new(&camera, size, Opacity::default());
            for i in 0..1000u32 {
                // Directions within the view (±0.6 of the depth sideways), distances 10 m to
                // 50 km, densities 0.3 to 3.
                let depth = 10.0 * 5000f64.powf(hash01(i, 1));
                let sx = (hash01(i, 2) - 0.5) * 1.2 * depth;
                let sy = (hash01(i, 3) - 0.5) * 1.2 * depth;
                let rel: Vec<f64> = (0..3)
                    .map(|a| f.forward[a] * depth + f.right[a] * sx + f.up[a] * sy)
                    .collect();
                let density = 0.3 + 2.7 * hash01(i, 4);
                let mut row = vec![rel[0], rel[1], rel[2], density];
                row.extend(f.right);
                row.push(f.focal);
                row.extend(f.up);
                row.push(f.half_width);
                row.extend(f.forward);
                row.push(f.half_height);
                row.extend([mode, scale]);
                grid.push(row);
            }
        }
    }
    grid
}

fn frame_of<F: atmos::real::Real>(x: &[F]) -> ScreenFrame<F> {
    ScreenFrame {
        right: [x[4], x[5], x[6]],
        focal: x[7],
        up: [x[8], x[9], x[10]],
        half_width: x[11],
        forward: [x[12], x[13], x[14]],
        half_height: x[15],
        size_mode: x[16].to_u32().unwrap_or(0),
        size_scale: x[17],
        opacity_mode: 0,
    }
}

/// Forward bound of `billboard_screen`: each 3-term dot product of the relative position
/// with a unit vector is within 3u·|rel|; x/z adds WGSL's division (2.5 ULP → 5u) and
/// inherits the dot products' errors over |z|; the centre adds a product and a sum (2u of
/// each term). Seed size: |rel|'s dot (3u), WGSL sqrt (≤ 4.5 ULP → 9u over 2), a division
/// (5u) and two products: 16u relative. World size: two products, a division and z's
/// relative error; fixed size: a product, a division and z's relative error. Doubled
/// for margin.
fn screen_bound(x: &[f64]) -> Vec<f64> {
    let rel = [x[0], x[1], x[2]];
    let n = (rel[0] * rel[0] + rel[1] * rel[1] + rel[2] * rel[2]).sqrt();
    let f = frame_of(x);
    let d = |b: [f64; 3]| rel[0] * b[0] + rel[1] * b[1] + rel[2] * b[2];
    let (px, py, z) = (d(f.right), d(f.up), d(f.forward));
    let dot_error = 3.0 * U * n * 1.01;
    let ratio_error =
        |p: f64| (dot_error + (p / z).abs() * dot_error) / z.abs() + 5.0 * U * (p / z).abs();
    let cx = f.half_width + f.focal * (px / z);
    let cy = f.half_height - f.focal * (py / z);
    let centre_error = |p: f64, c: f64| {
        f.focal * ratio_error(p) + 2.0 * U * (f.focal * (p / z)).abs() + 2.0 * U * c.abs()
    };
    let radius = billboard_screen(&f, rel, x[3])[2];
    let relative = if f.size_mode == 0 {
        16.0 * U
    } else {
        8.0 * U + dot_error / z.abs()
    };
    vec![
        2.0 * centre_error(px, cx),
        2.0 * centre_error(py, cy),
        2.0 * relative * radius,
    ]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "cloudlight::splat_alpha",
            imports: &["cloudlight::billboard"],
            arity: (1, 1),
            wgsl: "y0 = splat_alpha(x0);",
            grid: || {
                let mut grid: Vec<Vec<f64>> = linspace(0.0, 1.5, 10_001).map(|r| vec![r]).collect();
                for k in 1..=7 {
                    let d = 10f64.powi(-k);
                    grid.extend([vec![1.0 - d], vec![1.0 + d], vec![d]]);
                }
                grid.extend([vec![0.0], vec![1.0], vec![2.0], vec![1e6]]);
                grid
            },
            cpu: |x| vec![cloudlight::billboard::splat_alpha(x[0])],
            // Independent form: (1 − r)²(1 + r)².
            reference: |x| {
                let r = x[0];
                vec![if r < 1.0 {
                    ((1.0 - r) * (1.0 + r)).powi(2)
                } else {
                    0.0
                }]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                // q = 1 − r·r: the product's rounding (u·r²) and the difference's (u·q); then
                // q·q doubles q's relative error and rounds once more.
                bound: Some(|x| {
                    let r = x[0];
                    if r >= 1.0 {
                        return vec![0.0];
                    }
                    let q = 1.0 - r * r;
                    vec![2.0 * q * (U * r * r + U * q) + U * q * q]
                }),
                why: "q = 1 − r² then q²: r² and the difference round once each (u·r² + u·q \
                      absolute in q, which cancels near the rim), doubled relative by the \
                      square, plus its rounding; 0 at r ≥ 1 on both sides (reference: \
                      (1 − r)²(1 + r)² in f64)",
            },
        },
        Case {
            name: "cloudlight::splat_opacity",
            imports: &["cloudlight::billboard"],
            arity: (3, 1),
            wgsl: "y0 = splat_opacity(x0, x1, u32(x2));",
            grid: || {
                // Weights 10⁻⁶ to 40 (an optical depth at the centre, or an opacity ≤ 1 for
                // mode 0), kernels 0 to 1, both modes.
                let mut grid = Vec::new();
                for weight in logspace(1e-6, 40.0, 101) {
                    for kernel in linspace(0.0, 1.0, 51) {
                        for mode in [0.0, 1.0] {
                            grid.push(vec![weight, kernel, mode]);
                        }
                    }
                }
                grid.extend([
                    vec![0.0, 0.5, 1.0],
                    vec![0.0, 0.5, 0.0],
                    vec![1e4, 1.0, 1.0],
                ]);
                grid
            },
            cpu: |x| vec![splat_opacity(x[0], x[1], x[2] as u32)],
            // Independent forms: −expm1(−w·k) and the product.
            reference: |x| {
                let optical_depth = x[0] * x[1];
                vec![if x[2] == 1.0 {
                    -(-optical_depth).exp_m1()
                } else {
                    optical_depth
                }]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 1.0,
                // Mode 1: x = w·k rounds (u·x relative, e^{−x}·u·x absolute in 1 − e^{−x});
                // e = exp(−x) carries (4 + 2x) ULP of itself (WGSL exp), which the
                // cancelling subtraction keeps as an absolute error. Mode 0: one product.
                bound: Some(|x| {
                    let optical_depth = x[0] * x[1];
                    if x[2] == 1.0 {
                        let e = (-optical_depth).exp();
                        vec![
                            (4.0 + 2.0 * optical_depth) * super::super::compare::ulp_f32(e)
                                + e * U * optical_depth,
                        ]
                    } else {
                        vec![U * optical_depth]
                    }
                }),
                why: "1 − exp(−w·k): the product's rounding (u·x, times e^{−x}) and WGSL exp's \
                      3 + 2x ULP of exp(−x) (+1 for libm) kept as an absolute error by the \
                      cancelling subtraction, + 1 ULP of the result; mode 0 the product's \
                      rounding (reference: −expm1(−w·k) in f64, or w·k)",
            },
        },
        Case {
            name: "cloudlight::billboard_screen",
            imports: &["cloudlight::billboard"],
            arity: (18, 3),
            wgsl: "let f = BillboardFrame(vec3<f32>(x4, x5, x6), x7, vec3<f32>(x8, x9, x10), x11, \
                   vec3<f32>(x12, x13, x14), x15, u32(x16), x17, 0u, 0u); \
                   let s = billboard_screen(f, vec3<f32>(x0, x1, x2), x3); \
                   y0 = s.x; y1 = s.y; y2 = s.z;",
            grid: screen_grid,
            cpu: |x| billboard_screen(&frame_of(x), [x[0], x[1], x[2]], x[3]).to_vec(),
            reference: |x| billboard_screen(&frame_of(x), [x[0], x[1], x[2]], x[3]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(screen_bound),
                why: "dot products with the unit camera basis (3u·|rel| each), x/z and the \
                      centre's product and sum, the seed size's sqrt and division (16u) or the \
                      world size's products, division and z: a forward bound, doubled \
                      (reference: the generic function at f64 on the f32-rounded inputs)",
            },
        },
    ]
}
