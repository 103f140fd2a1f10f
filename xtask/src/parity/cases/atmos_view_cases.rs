//! Parity cases of a camera given by view and projection matrices (`atmos::view`): the
//! ray through a target position and the distance a depth value stands for. The view
//! below is a pinhole 1280×720 target looking along +y (right +x, up +z) with a
//! reversed infinite projection (near plane 0.5 m), written with values exact in f32
//! so that the WGSL literals and the Rust struct hold the same numbers.

use super::*;
use atmos::view::{FrameView, frame_view_direction_at, frame_view_distance};

/// `direction_from_position`'s columns, the inverse projection's, the viewport.
const C0: [f64; 3] = [1.0 / 512.0, 0.0, 0.0];
const C1: [f64; 3] = [0.0, 0.0, -1.0 / 512.0];
const C2: [f64; 3] = [-1.25, 1.0, 0.703_125];
/// tan(fov/2)·aspect, tan(fov/2), 1/near.
const TAN_X: f64 = 1.25;
const TAN_Y: f64 = 0.703_125;
const INVERSE_NEAR: f64 = 2.0;

macro_rules! view_wgsl {
    () => {
        "let view = FrameView(mat3x3<f32>(vec3<f32>(0.001953125, 0.0, 0.0), \
         vec3<f32>(0.0, 0.0, -0.001953125), vec3<f32>(-1.25, 1.0, 0.703125)), \
         mat4x4<f32>(vec4<f32>(1.25, 0.0, 0.0, 0.0), vec4<f32>(0.0, 0.703125, 0.0, 0.0), \
         vec4<f32>(0.0, 0.0, 0.0, 2.0), vec4<f32>(0.0, 0.0, -1.0, 0.0)), \
         vec4<f32>(0.0, 0.0, 1280.0, 720.0)); "
    };
}

fn view() -> FrameView {
    let column = |c: [f64; 3]| [c[0] as f32, c[1] as f32, c[2] as f32, 0.0];
    FrameView {
        direction_from_position: [column(C0), column(C1), column(C2)],
        view_from_clip: [
            [TAN_X as f32, 0.0, 0.0, 0.0],
            [0.0, TAN_Y as f32, 0.0, 0.0],
            [0.0, 0.0, 0.0, INVERSE_NEAR as f32],
            [0.0, 0.0, -1.0, 0.0],
        ],
        viewport: [0.0, 0.0, 1280.0, 720.0],
    }
}

/// Target positions over the whole target (pixel centres and fractions: jittered
/// samples) and its edges.
fn positions() -> Vec<[f64; 2]> {
    let mut grid = Vec::new();
    for y in linspace(0.0, 720.0, 97) {
        for x in linspace(0.0, 1280.0, 129) {
            grid.push([x, y]);
        }
    }
    grid.extend([[640.0, 360.0], [0.5, 0.5], [1279.5, 719.5]]);
    grid
}

pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::frame_view_direction_at",
            imports: &["atmos::frame"],
            arity: (2, 3),
            wgsl: concat!(
                view_wgsl!(),
                "let d = frame_view_direction_at(vec2<f32>(x0, x1), view); y0 = d.x; y1 = d.y; y2 = d.z;"
            ),
            grid: || positions().into_iter().map(|p| p.to_vec()).collect(),
            cpu: |x| frame_view_direction_at([x[0], x[1]], &view()).to_vec(),
            reference: |x| {
                let d: [f64; 3] = std::array::from_fn(|i| C0[i] * x[0] + C1[i] * x[1] + C2[i]);
                let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                d.map(|c| c / length).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 4.0 * U,
                rel: 0.0,
                ulp: 8.0,
                bound: None,
                why: "each component c0·x + c1·y + c2: two roundings of terms up to 1.25 \
                      that cancel at the centre (≤ 4u of 1.25 absolutely, over a length \
                      ≥ 1); then normalize: a sum of squares, WGSL's sqrt (4.5 ULP) or \
                      inverseSqrt and a division (2.5 ULP): 8 ULP relative",
            },
        },
        Case {
            name: "atmos::frame_view_distance",
            imports: &["atmos::frame"],
            arity: (3, 1),
            wgsl: concat!(
                view_wgsl!(),
                "y0 = frame_view_distance(vec2<f32>(x0, x1), x2, view);"
            ),
            grid: || {
                let depths: Vec<f64> = logspace(1e-6, 1.0, 24).collect();
                positions()
                    .into_iter()
                    .step_by(5)
                    .flat_map(|[x, y]| depths.iter().map(move |&d| vec![x, y, d]))
                    .collect()
            },
            cpu: |x| vec![frame_view_distance([x[0], x[1]], x[2], &view())],
            reference: |x| {
                let ndc_x = 2.0 * x[0] / 1280.0 - 1.0;
                let ndc_y = 1.0 - 2.0 * x[1] / 720.0;
                let (px, py) = (TAN_X * ndc_x, TAN_Y * ndc_y);
                vec![(px * px + py * py + 1.0).sqrt() / (INVERSE_NEAR * x[2])]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 16.0,
                bound: None,
                why: "the NDC (a subtraction, a division of 2.5 ULP, an affine map that \
                      cancels at the centre, where its terms enter the length only through \
                      squares next to 1), the inverse projection's products (exact for the \
                      zero entries), three divisions by w (2.5 ULP each) and length's \
                      sqrt (4.5 ULP): 16 ULP relative",
            },
        },
    ]
}
