//! Parity case of `render::in_cloud_fog`: the transmittance of the in-cloud fog around
//! a camera inside or near a cloud layer (`shaders/render/in_cloud_fog.wgsl`), the
//! smaller of the camera's extinction × distance and the column out of the layers.

use super::*;

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "render::in_cloud_fog_transmittance",
        imports: &["render::in_cloud_fog"],
        arity: (7, 1),
        wgsl: "y0 = in_cloud_fog_transmittance(x0, x1, x2, x3, x4, x5, x6);",
        grid: in_cloud_fog_grid,
        cpu: |x| {
            vec![render::in_cloud_fog::in_cloud_fog_transmittance(
                x[0], x[1], x[2], x[3], x[4], x[5], x[6],
            )]
        },
        reference: |x| vec![(-optical_depth(x)).exp()],
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 1.2e-38,
            rel: 0.0,
            ulp: 0.0,
            bound: Some(in_cloud_fog_bound),
            why: "views within a part in 10⁶ of a band's edge may take either branch, so the grid's distances stay off them; τ from one product or one division (u·|τ| each side, doubled) through exp: T·2u|τ| plus exp's 3 + 2|τ| ULP (WGSL spec), doubled; abs: exp below the smallest normal f32 flushes to 0 on lavapipe",
        },
    }]
}

/// The optical depth the case's reference takes: the column / max(|μ|, 10⁻³) (above
/// for μ > 0, below otherwise) for a view reaching past the bands, else the smaller of
/// that and extinction × min(d, 3e38).
fn optical_depth(x: &[f64]) -> f64 {
    let (column, band) = if x[0] > 0.0 {
        (x[3], x[5])
    } else {
        (x[4], x[6])
    };
    let distance = x[1].min(3.0e38);
    let slant = column / x[0].abs().max(1e-3);
    if distance * x[0].abs() >= band {
        return slant;
    }
    (x[2] * distance).min(slant)
}

/// View cosines from straight down to straight up through the horizon (±10⁻⁴ and 0
/// among them), scene distances from 0 m to the sky's 3e38, extinctions from clear to
/// SGSky's 25 m in-cloud visibility (3.912/25 m⁻¹), columns from 0 to 50, bands of
/// 150 m above and 430 m below (views ending on both sides of them): 23 × 7 × 5 × 5 × 5
/// = 20,125 rows.
fn in_cloud_fog_grid() -> Vec<Vec<f64>> {
    let mut cosines: Vec<f64> = (0..=20).map(|i| -1.0 + 0.1 * f64::from(i)).collect();
    cosines.extend([1e-4, -1e-4]);
    let distances = [0.0, 1.0, 10.0, 100.0, 1000.0, 1.0e4, 3.0e38];
    let extinctions = [0.0, 1e-4, 1e-3, 1e-2, 3.912_023 / 25.0];
    let columns = [0.0, 0.1, 1.0, 10.0, 50.0];
    let mut grid = Vec::new();
    for &mu in &cosines {
        for &d in &distances {
            for &k in &extinctions {
                for &up in &columns {
                    for &down in &columns {
                        grid.push(vec![mu, d, k, up, down, 150.0, 430.0]);
                    }
                }
            }
        }
    }
    grid
}

fn in_cloud_fog_bound(x: &[f64]) -> Vec<f64> {
    let tau = optical_depth(x);
    let t = (-tau).exp();
    vec![2.0 * t * (2.0 * U * tau + (3.0 + 2.0 * tau) * 2.0 * U)]
}
