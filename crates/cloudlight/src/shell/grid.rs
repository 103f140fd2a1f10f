//! A weather grid's bilinear, repeating lookup.

use atmos::real::Real;

/// The four cells a weather grid's bilinear lookup reads ([`weather_grid_taps`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeatherGridTaps<F> {
    /// Flat indices (x fastest) of cells `(i, j)`, `(i + 1, j)`, `(i, j + 1)`,
    /// `(i + 1, j + 1)` wrapped into the grid, `i = ⌊x/cell − ½⌋`, `j = ⌊y/cell − ½⌋`.
    pub index: [u32; 4],
    /// `(x/cell − ½ − ⌊x/cell − ½⌋, y/cell − ½ − ⌊y/cell − ½⌋)`, each in [0, 1].
    pub fraction: [F; 2],
}

/// The cells and fractions of a bilinear lookup of a repeating grid of `size` cells of
/// `cell` metres at horizontal position `xy` (metres; cell `(i, j)`'s centre at
/// `((i + ½)·cell, (j + ½)·cell)`, the grid repeating every `size·cell` metres). The
/// caller reads each index's value (on the GPU from its storage binding) and blends
/// them with [`weather_grid_bilinear`]; [`bilinear_wrapped`] is the two over a slice.
/// The cell coordinate `⌊xy/cell − ½⌋` is taken to `i32` saturating (as WGSL's `i32()`
/// does), then wrapped into the grid: exact for `|xy/cell| < 2³¹`. WGSL twin
/// `weather_grid_taps` (same arguments, same order).
pub fn weather_grid_taps<F: Real>(size: [u32; 2], cell: F, xy: [F; 2]) -> WeatherGridTaps<F> {
    let half = F::of(0.5);
    let gx = xy[0] / cell - half;
    let gy = xy[1] / cell - half;
    let (fx, fy) = (gx.floor(), gy.floor());
    // f → i32 saturating (NaN → 0), then into [0, n).
    let wrap = |f: F, n: u32| -> u32 {
        let i = f.to_f64().unwrap_or(0.0) as i32;
        i64::from(i).rem_euclid(i64::from(n)) as u32
    };
    let one = F::one();
    let (x0, x1) = (wrap(fx, size[0]), wrap(fx + one, size[0]));
    let (y0, y1) = (wrap(fy, size[1]), wrap(fy + one, size[1]));
    let nx = size[0];
    WeatherGridTaps {
        index: [x0 + nx * y0, x1 + nx * y0, x0 + nx * y1, x1 + nx * y1],
        fraction: [gx - fx, gy - fy],
    }
}

/// One layer's bilinear blend of its four cells (in [`WeatherGridTaps::index`]'s order)
/// at `fraction`: `a + ty·(b − a)` with `a = v₀₀ + tx·(v₁₀ − v₀₀)`, `b = v₀₁ + tx·(v₁₁ − v₀₁)`.
fn grid_lerp<F: Real>(v: [F; 4], t: [F; 2]) -> F {
    let a = v[0] + t[0] * (v[1] - v[0]);
    let b = v[2] + t[0] * (v[3] - v[2]);
    a + t[1] * (b - a)
}

/// The weather grid's `[coverage, cloud_type]` at a lookup's `fraction` from its four
/// cells' `values` (each `[coverage, cloud_type]`, in [`WeatherGridTaps::index`]'s
/// order): per layer `a + ty·(b − a)`, `a = v₀₀ + tx·(v₁₀ − v₀₀)`,
/// `b = v₀₁ + tx·(v₁₁ − v₀₁)`. WGSL twin `weather_grid_bilinear` (`vec2` per cell).
pub fn weather_grid_bilinear<F: Real>(values: [[F; 2]; 4], fraction: [F; 2]) -> [F; 2] {
    [0, 1].map(|k| grid_lerp(values.map(|v| v[k]), fraction))
}

/// Bilinear sample of one layer (`size[0]·size[1]` values, x fastest) of a repeating grid
/// of `cell` metres at `xy` (metres): [`weather_grid_taps`], then the blend of
/// [`weather_grid_bilinear`] on this layer. What [`CloudShell::weather_at`](super::CloudShell::weather_at) computes per
/// layer of a [`WeatherGrid`](super::WeatherGrid); on the GPU each pass reads its own binding between the two
/// (WGSL passes no storage array to a function).
pub fn bilinear_wrapped<F: Real>(layer: &[f32], size: [u32; 2], cell: F, xy: [F; 2]) -> F {
    let taps = weather_grid_taps(size, cell, xy);
    let at = |k: u32| F::of(f64::from(layer[k as usize]));
    grid_lerp(taps.index.map(at), taps.fraction)
}
