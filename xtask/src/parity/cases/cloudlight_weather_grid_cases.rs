//! Parity case of `cloudlight`'s user weather grid (`shaders/cloudlight/shell.wgsl`'s
//! `weather_grid_taps` then `weather_grid_bilinear`; Rust twins
//! `cloudlight::shell::weather_grid_taps` / `weather_grid_bilinear`, which
//! `CloudShell::weather_at` and `bilinear_wrapped` compose). The grid's cells are an
//! exact function of the flat index (multiples of 1/128), so the WGSL reads them from the
//! taps' indices as a pass reads its storage binding, and a wrong index shows as a wrong
//! value. Reference: an independent f64 lookup written here (cell coordinates, `rem_euclid`
//! wrap, the four weights `(1 − tx)(1 − ty)`, …), not the generic function.

use super::*;
use cloudlight::shell;

/// A deterministic value in [0, 1) for row `i` and channel `salt`.
fn unit(i: u32, salt: u32) -> f64 {
    f64::from(skyscape_wgsl::common::hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt) >> 8)
        / 16_777_216.0
}

/// Grid sizes (cells along x, y): 1×1 up to 37×23.
const SIZES: [[u32; 2]; 9] = [
    [1, 1],
    [1, 7],
    [2, 3],
    [5, 1],
    [8, 8],
    [13, 17],
    [4, 29],
    [31, 2],
    [37, 23],
];
/// Cell edges, metres.
const CELLS: [f64; 5] = [1.0, 250.0, 500.0, 1234.5, 3000.0];

/// The test grid's (coverage, cloud type) of flat cell `k`: multiples of 1/128, exact in
/// f32 (the WGSL snippet computes the same from the index).
fn cell_value(k: u64) -> [f64; 2] {
    [
        ((k * 37 + 11) % 128) as f64 / 128.0,
        ((k * 53 + 7) % 128) as f64 / 128.0,
    ]
}

/// One coordinate for row `i` (salt picks the axis) of a grid of `n` cells of `cell` m:
/// inside the extent, on a cell centre, on a cell edge (both from −2 to +3 extents),
/// negative (to −10 extents) or far (±10⁴ extents).
fn coordinate(i: u32, salt: u32, n: u32, cell: f64) -> f64 {
    let extent = f64::from(n) * cell;
    let k = (5.0 * f64::from(n) * unit(i, salt + 1)).floor() - 2.0 * f64::from(n);
    match (i / 7 + salt) % 5 {
        0 => extent * unit(i, salt + 2),
        1 => (k + 0.5) * cell,
        2 => k * cell,
        3 => -10.0 * extent * unit(i, salt + 2),
        _ => 1e4 * extent * (2.0 * unit(i, salt + 2) - 1.0),
    }
}

fn grid() -> Vec<Vec<f64>> {
    (0..10_080u32)
        .map(|i| {
            let [nx, ny] = SIZES[i as usize % SIZES.len()];
            let cell = CELLS[(i as usize / SIZES.len()) % CELLS.len()];
            vec![
                coordinate(i, 10, nx, cell),
                coordinate(i, 20, ny, cell),
                f64::from(nx),
                f64::from(ny),
                cell,
            ]
        })
        .collect()
}

/// The f32 twin: the taps, the cells read by index, the blend.
fn cpu(x: &[f32]) -> Vec<f32> {
    let size = [x[2] as u32, x[3] as u32];
    let taps = shell::weather_grid_taps(size, x[4], [x[0], x[1]]);
    let values = taps
        .index
        .map(|k| cell_value(u64::from(k)).map(|v| v as f32));
    shell::weather_grid_bilinear(values, taps.fraction).to_vec()
}

/// Independent f64 lookup: cell coordinates `g = x/cell − ½`, `i = ⌊g⌋` wrapped by
/// `rem_euclid`, the four product weights.
fn reference(x: &[f64]) -> Vec<f64> {
    let (nx, ny, cell) = (x[2], x[3], x[4]);
    let gx = x[0] / cell - 0.5;
    let gy = x[1] / cell - 0.5;
    let (ix, iy) = (gx.floor(), gy.floor());
    let (tx, ty) = (gx - ix, gy - iy);
    let flat = |i: f64, j: f64| (i.rem_euclid(nx) + nx * j.rem_euclid(ny)) as u64;
    let v = [
        cell_value(flat(ix, iy)),
        cell_value(flat(ix + 1.0, iy)),
        cell_value(flat(ix, iy + 1.0)),
        cell_value(flat(ix + 1.0, iy + 1.0)),
    ];
    let w = [
        (1.0 - tx) * (1.0 - ty),
        tx * (1.0 - ty),
        (1.0 - tx) * ty,
        tx * ty,
    ];
    (0..2)
        .map(|c| (0..4).map(|k| w[k] * v[k][c]).sum())
        .collect()
}

/// The f32 cell coordinate `x/cell − ½` is off by ≤ 3u·|x/cell| (the division: WGSL
/// allows 2.5 ULP) + u·|g| (the subtraction); `g − ⌊g⌋` is exact. The lookup is
/// continuous (a floor that differs only moves to the neighbouring cell at weight 0
/// or 1) with slope ≤ 127/128 < 1 per cell along each axis, so each axis adds
/// ≤ 4u·(|x/cell| + 1); the blend's 3 + 3 + 3 roundings of values ≤ 1 add ≤ 9u.
fn bound(x: &[f64]) -> Vec<f64> {
    let axis = |c: f64| 4.0 * U * ((c / x[4]).abs() + 1.0);
    let e = axis(x[0]) + axis(x[1]) + 9.0 * U;
    vec![e, e]
}

/// The case.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "cloudlight::weather_grid_taps + weather_grid_bilinear",
        imports: &["cloudlight::shell"],
        arity: (5, 2),
        wgsl: "let t = weather_grid_taps(vec2<u32>(u32(x2), u32(x3)), x4, vec2<f32>(x0, x1)); \
               var v: array<vec2<f32>, 4>; \
               for (var k = 0; k < 4; k++) { let c = t.index[k]; \
               v[k] = vec2<f32>(f32((c * 37u + 11u) % 128u), f32((c * 53u + 7u) % 128u)) \
               * 0.0078125; } \
               let w = weather_grid_bilinear(v, t.fraction); y0 = w.x; y1 = w.y;",
        grid,
        cpu,
        reference,
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: Some(bound),
            why: "the cell coordinate x/cell − ½ (division ≤ 3u, WGSL's 2.5 ULP, plus the \
                  subtraction's u of |g|) moves a continuous lookup of slope < 1 per cell: \
                  4u(|x/cell| + 1) per axis, plus 9u for the blend's roundings (reference: \
                  an independent f64 lookup with rem_euclid wrap and product weights)",
        },
    }]
}
