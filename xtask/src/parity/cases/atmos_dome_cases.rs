//! Parity cases of `atmos::dome`: where a per-vertex sky dome's rows sit. The f32 twin
//! and the f64 reference are one generic function instantiated twice.

use super::*;
use atmos::twins::{dome_horizon_mu, dome_row_coordinate, dome_row_mu};

/// Viewer altitudes (m): the ground, a millimetre, a metre … geostationary orbit,
/// both sides of the atmosphere's top.
fn altitudes(n: usize) -> Vec<f64> {
    let mut v: Vec<f64> = logspace(1e-3, 3.6e7, n).collect();
    v.extend([0.0, 99_999.0, 100_000.0, 100_001.0]);
    v
}

/// Forward error of `√x` when `x` carries an absolute error `delta` (the sqrt is
/// ill-conditioned at 0: an error of 1e-7 in `x` moves `√x` by 3e-4).
fn sqrt_spread(x: f64, delta: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    (x + delta).sqrt() - (x - delta).max(0.0).sqrt()
}

/// Absolute error of the f32 quantities a row's `mu` is built from: a few roundings of
/// values ≤ 2 (2.4e-7 each) and the horizon's `√((r − R)(r + R))/r` (≈ 8 ULP of ≤ 1).
const MU_ERROR: f64 = 2e-6;

fn coordinate_bound(x: &[f64]) -> Vec<f64> {
    let (mu, rings, r, planet, top) = (x[0], x[1], x[2], x[3], x[4]);
    let horizon = dome_horizon_mu(r, planet);
    let bands = (rings - (rings / 2.0).floor()).max(rings / 2.0);
    // The ratio under the square root, as the reference forms it, and its denominator:
    // numerator and denominator are differences of mu values each carrying ≲ MU_ERROR,
    // so the ratio carries ≲ 2·MU_ERROR/|denominator| (large when the limb band is
    // thin, seen from far above the atmosphere).
    let (ratio, denominator) = if mu < horizon {
        let seam = horizon - atmos::dome::DOME_SEAM_OFFSET;
        ((seam - mu) / (1.0 + seam), 1.0 + seam)
    } else {
        let seam = horizon + atmos::dome::DOME_SEAM_OFFSET;
        let limb = dome_horizon_mu(r, top);
        if r > top && mu > limb {
            ((mu - limb) / (1.0 - limb), 1.0 - limb)
        } else {
            let far = if r > top { limb } else { 1.0 };
            ((mu - seam) / (far - seam), far - seam)
        }
    };
    let ratio_error = 2.0 * MU_ERROR / denominator.abs() + 4.0 * U;
    // A view within the horizon's f32 error of the horizon may be put on either side of
    // the seam: the coordinate then jumps by exactly 1 (the seam's zero-width band).
    let seam_jump = if (mu - horizon).abs() <= 8.0 * U {
        1.0
    } else {
        0.0
    };
    vec![bands * sqrt_spread(ratio, ratio_error) + 8.0 * U * rings + seam_jump]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "atmos::dome_horizon_mu",
            imports: &["atmos::dome"],
            arity: (2, 1),
            wgsl: "y0 = dome_horizon_mu(x0, x1);",
            grid: || {
                let mut grid = Vec::new();
                for altitude in altitudes(4_000) {
                    for radius in [R_GROUND, R_TOP] {
                        grid.push(vec![R_GROUND + altitude, radius]);
                    }
                }
                for altitude in linspace(-10.0, 10.0, 2_001) {
                    grid.push(vec![R_GROUND + altitude, R_GROUND]);
                }
                grid
            },
            cpu: |x| vec![dome_horizon_mu(x[0], x[1])],
            reference: |x| vec![dome_horizon_mu(x[0], x[1])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 8.0 * U,
                rel: 0.0,
                ulp: 8.0,
                bound: None,
                why: "(r − R) exact (Sterbenz) or 1 rounding, × and ÷ 2.5 ULP each in WGSL, \
                      sqrt = 1/inverseSqrt ≤ 4.5 ULP (halved by the root): ≤ 8 ULP; the \
                      absolute part covers the reference's own rounding to f32 near 0",
            },
        },
        Case {
            name: "atmos::dome_row_mu",
            imports: &["atmos::dome"],
            arity: (5, 1),
            wgsl: "y0 = dome_row_mu(u32(x0), u32(x1), x2, x3, x4);",
            grid: || {
                let mut grid = Vec::new();
                for altitude in altitudes(60) {
                    for rings in [4u32, 5, 8, 12, 16, 24, 32, 48, 64] {
                        for row in 0..rings + 2 {
                            grid.push(vec![
                                f64::from(row),
                                f64::from(rings),
                                R_GROUND + altitude,
                                R_GROUND,
                                R_TOP,
                            ]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![dome_row_mu(x[0] as u32, x[1] as u32, x[2], x[3], x[4])],
            reference: |x| vec![dome_row_mu(x[0] as u32, x[1] as u32, x[2], x[3], x[4])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 5e-7,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "a row's mu is the horizon's mu ± 1e-4 moved by (1 ± mu)·t²: about four \
                      roundings of values ≤ 1 (≤ 6e-8 each) plus the horizon's ≤ 2 ULP seen \
                      here (≤ 8 allowed): absolute, since rows pass through 0",
            },
        },
        Case {
            name: "atmos::dome_row_coordinate",
            imports: &["atmos::dome"],
            arity: (5, 1),
            wgsl: "y0 = dome_row_coordinate(x0, u32(x1), x2, x3, x4);",
            grid: || {
                let mut grid = Vec::new();
                for altitude in altitudes(30) {
                    let r = R_GROUND + altitude;
                    let mut mus = cosines(101);
                    for sphere in [R_GROUND, R_TOP] {
                        let tangent = dome_horizon_mu(r, sphere);
                        for d in [0.0, 1e-6, 1e-5, 1e-4, 2e-4, 1e-3, 1e-2] {
                            mus.extend([tangent - d, tangent + d]);
                        }
                    }
                    for rings in [4u32, 16, 64] {
                        for &mu in &mus {
                            if mu.abs() <= 1.0 {
                                grid.push(vec![mu, f64::from(rings), r, R_GROUND, R_TOP]);
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![dome_row_coordinate(x[0], x[1] as u32, x[2], x[3], x[4])],
            reference: |x| vec![dome_row_coordinate(x[0], x[1] as u32, x[2], x[3], x[4])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 16.0,
                bound: Some(coordinate_bound),
                why: "bands × √ratio: the ratio's numerator and denominator are differences \
                      of mu values carrying ≲ 2e-6 each (the rows' budget), so the ratio \
                      carries ≲ 4e-6/|denominator| — large for the thin limb band seen from \
                      far above — which √ magnifies near 0 (bound: bands × spread of √ over \
                      ratio ± that error); a view within 8 ULP of the horizon may fall on \
                      either side of the seam (a jump of exactly 1)",
            },
        },
    ]
}
