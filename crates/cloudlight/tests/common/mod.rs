//! Test clouds the march tests share.

use cloudlight::CloudVolume;

/// A lumpy blob on a 32³ grid of 25 m cells, 1 km up: an ellipsoid of density up to
/// 1.5 with a deterministic ±30 % wobble from cell to cell.
pub fn lumpy_blob() -> CloudVolume {
    let n = 32u32;
    let mut density = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let p = [x, y, z].map(|c| (f64::from(c) + 0.5) / f64::from(n) * 2.0 - 1.0);
                let r2 = p[0] * p[0] + p[1] * p[1] + 1.4 * p[2] * p[2];
                let wobble = 0.3 * ((x * 7 + y * 3 + z * 5) % 5) as f64 / 4.0;
                density.push((1.5 * (1.0 + wobble) * (1.0 - r2).max(0.0)) as f32);
            }
        }
    }
    CloudVolume::new([n, n, n], [-400.0, -400.0, 1000.0], 25.0, 0.02, density).unwrap()
}
