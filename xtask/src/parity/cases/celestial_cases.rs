//! Parity cases of `celestial`: the equatorial → horizontal transform, Pogson's
//! magnitude → illuminance and the moon disc's incidence cosine; then, chained, the
//! drawing of the sky objects (`celestial_draw_cases`), the cloud layers' texture,
//! geometry and shadow (`celestial_cloud_cases`) and their light
//! (`celestial_cloud_light_cases`).

use super::*;
use crate::parity::compare::ulp_f32;

const PI64: f64 = std::f64::consts::PI;
const TAU64: f64 = std::f64::consts::TAU;

/// East/north/up components of the unit vector in f64 (inputs already f32-rounded).
fn enu(h: f64, d: f64, p: f64) -> [f64; 3] {
    [
        -d.cos() * h.sin(),
        d.sin() * p.cos() - d.cos() * h.cos() * p.sin(),
        d.sin() * p.sin() + d.cos() * h.cos() * p.cos(),
    ]
}

/// Absolute error of each f32 component: six sin/cos (lavapipe a few ULP of 1; 4
/// allowed each) and two products and a sum per component: ≤ 16u.
const COMPONENT_ERROR: f64 = 16.0 * U;

/// Forward bounds of (azimuth, elevation). Both are atan2 of components carrying
/// `COMPONENT_ERROR`: the angle moves by at most that over the length of the pair
/// (|(e, n)| for the azimuth, 1 for the elevation), plus atan2's own error (lavapipe
/// ≈ 300 ULP, 512 allowed). On the north meridian (|east| within the component
/// error) a sign flip of `east` wraps the azimuth by 2π, which is the same direction.
fn transform_bound(x: &[f64]) -> Vec<f64> {
    let [east, north, _] = enu(x[0], x[1], x[2]);
    let horizontal = east.hypot(north);
    let [azimuth, elevation] = celestial::equatorial_to_horizontal(x[0], x[1], x[2]);
    let mut azimuth_bound = 512.0 * ulp_f32(azimuth)
        + if horizontal > 0.0 {
            (2.0 * COMPONENT_ERROR / horizontal).min(PI64)
        } else {
            PI64
        };
    if horizontal <= 2.0 * COMPONENT_ERROR {
        // Within rounding of the zenith or nadir both components may change sign: the
        // azimuth is atan2 of rounding noise, any angle in [0, 2π] (the function's
        // contract). The NVIDIA H100 (Vulkan) differs here from lavapipe at the
        // celestial pole seen from the pole (components ~4e-8): error 4.5 rad.
        azimuth_bound = TAU64 + 512.0 * ulp_f32(TAU64);
    } else if east.abs() <= COMPONENT_ERROR && north >= 0.0 {
        // The wrapped value is a + TAU in f32: TAU's own rounding (1.7e-7) and the
        // sum's (½ ULP of 2π) come on top of the 2π.
        azimuth_bound += TAU64 + ulp_f32(TAU64);
    }
    vec![
        azimuth_bound,
        512.0 * ulp_f32(elevation) + 2.0 * COMPONENT_ERROR,
    ]
}

fn transform_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for h in linspace(-PI64, PI64, 49) {
        for d in linspace(-PI64 / 2.0, PI64 / 2.0, 25) {
            for p in linspace(-PI64 / 2.0, PI64 / 2.0, 25) {
                grid.push(vec![h, d, p]);
            }
        }
    }
    // Near the zenith (δ → φ, H → 0), at the poles and beyond one turn of hour angle.
    for k in 1..=6 {
        let e = 10f64.powi(-k);
        grid.extend([
            vec![e, 0.7 + e, 0.7],
            vec![-e, 0.7, 0.7 + e],
            vec![e, PI64 / 2.0 - e, PI64 / 2.0],
            vec![3.0, -PI64 / 2.0 + e, -PI64 / 2.0],
        ]);
    }
    grid.extend([
        vec![0.0, 0.7, 0.7],
        vec![7.5, 0.3, -0.4],
        vec![-12.0, -1.2, 1.1],
        vec![PI64, 0.0, 0.0],
    ]);
    grid
}

fn magnitude_grid() -> Vec<Vec<f64>> {
    let mut grid: Vec<Vec<f64>> = linspace(-27.0, 30.0, 11_401).map(|m| vec![m]).collect();
    grid.extend([vec![0.0], vec![-1.46], vec![-12.7], vec![-26.74], vec![6.5]]);
    grid
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "celestial::equatorial_to_horizontal",
            imports: &["celestial::coordinates"],
            arity: (3, 2),
            wgsl: "let r = equatorial_to_horizontal(x0, x1, x2); y0 = r.x; y1 = r.y;",
            grid: transform_grid,
            cpu: |x| celestial::equatorial_to_horizontal(x[0], x[1], x[2]).to_vec(),
            reference: |x| celestial::equatorial_to_horizontal(x[0], x[1], x[2]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(transform_bound),
                why: "components carry ≤ 16u (sin/cos, products, sums); each angle is an atan2 \
                      (512 ULP) moved by that error over the pair's length (|(e, n)| for azimuth, \
                      so it grows toward the zenith); a 2π wrap is allowed only on the north \
                      meridian, where east's sign is within rounding, and any azimuth where \
                      |(e, n)| is within rounding of 0 (zenith, nadir: atan2 of noise)",
            },
        },
        Case {
            name: "celestial::illuminance_from_magnitude",
            imports: &["celestial::coordinates"],
            arity: (1, 1),
            wgsl: "y0 = illuminance_from_magnitude(x0);",
            grid: magnitude_grid,
            cpu: |x| vec![celestial::illuminance_from_magnitude(x[0])],
            reference: |x| vec![celestial::illuminance_from_magnitude(x[0])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| {
                    // The exponent −0.921·m rounds (u·|arg|, amplified 1:1 by exp),
                    // the constants round (2u), exp itself: WGSL's 3 + 2|arg| ULP.
                    let arg = (0.4 * std::f64::consts::LN_10 * x[0]).abs();
                    let y = celestial::illuminance_from_magnitude(x[0]);
                    vec![y * U * (2.0 + 3.0 * arg)]
                }),
                why: "exp's argument −0.4 ln10·m rounds (relative u·|arg| in the result), two \
                      constants round (2u), exp within WGSL's 3 + 2|arg| ULP",
            },
        },
        Case {
            name: "celestial::moon_disc_incidence_cosine",
            imports: &["celestial::moon"],
            arity: (4, 1),
            wgsl: "y0 = moon_disc_incidence_cosine(x0, x1, x2, x3);",
            grid: moon_disc_grid,
            cpu: |x| {
                vec![celestial::moon_disc_incidence_cosine(
                    x[0], x[1], x[2], x[3],
                )]
            },
            reference: |x| {
                vec![celestial::moon_disc_incidence_cosine(
                    x[0], x[1], x[2], x[3],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(moon_disc_bound),
                why: "four sin/cos (4 ULP of 1 each), products and a sum of three unit-bounded \
                      terms (≤ 16u), and √(1 − ρ²) whose rounding of 1 − ρ² is amplified by \
                      1/(2√(1 − ρ²)) toward the limb",
            },
        },
    ]
    .into_iter()
    .chain(super::celestial_draw_cases::cases())
    .chain(super::celestial_cloud_cases::cases())
    .chain(super::celestial_cloud_light_cases::cases())
    .collect()
}

/// Disc points on a grid over the square around the disc (the outside must be 0)
/// plus points just inside and outside the limb, for phases 0…π and limbs 0…2π.
fn moon_disc_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for phase in linspace(0.0, PI64, 7) {
        for limb in linspace(0.0, TAU64, 9) {
            for east in linspace(-1.05, 1.05, 22) {
                for north in linspace(-1.05, 1.05, 22) {
                    grid.push(vec![east, north, phase, limb]);
                }
            }
            for k in 0..16 {
                let a = TAU64 * f64::from(k) / 16.0;
                for r in [1.0 - 1e-3, 1.0 - 1e-6, 1.0 + 1e-6] {
                    grid.push(vec![r * a.sin(), r * a.cos(), phase, limb]);
                }
            }
        }
    }
    grid
}

/// 16u for the unit-bounded products and sum (sin/cos included), plus the limb term:
/// 1 − ρ² carries ≤ 3u absolute, and √ amplifies it by 1/(2√(1 − ρ²)) (capped at the
/// √(3u) a rounding can produce from 0).
fn moon_disc_bound(x: &[f64]) -> Vec<f64> {
    let rho2 = x[0] * x[0] + x[1] * x[1];
    let depth = (1.0 - rho2).max(0.0);
    let limb = if depth > 3.0 * U {
        3.0 * U / (2.0 * depth.sqrt())
    } else {
        (6.0 * U).sqrt()
    };
    // The grid keeps every point ≥ 10⁻⁶ from the rim (≫ u), so no point is inside
    // the disc in one precision and outside in the other.
    vec![16.0 * U + limb]
}

// ---------------------------------------------------------------- celestial::draw
