//! Continuous density: Dobashi's weighted space–time smoothing of `cld`, times the
//! per-slice density scale.

use crate::{Boundary, Error, Model};

/// Smoothed density, one `f32` per cell (linear index `x + nx * (y + ny * z)`).
///
/// `cld_history[0]` is the newest packed `cld` field, `cld_history[1]` the one a step
/// before, and so on; at most `radius_steps + 1` are used. With `R = radius_cells`,
/// `T = radius_steps` the density of cell `c` in slice `z` is
///
/// ```text
/// scale[z] * Σ_tau Σ_d (T+1-tau) (R+1-|dx|)(R+1-|dy|)(R+1-|dz|) cld_tau(c + d)
///          / (Σ_tau (T+1-tau) * (R+1)^6)
/// ```
///
/// over the available history (`tau < len`), with cells beyond the grid empty (x and y
/// wrap when periodic). All sums are exact integers, so the result is deterministic;
/// it lies in `[0, scale[z]]` and is exactly `scale[z]` deep inside a solid cloud.
pub fn density(model: &Model, cld_history: &[&[u32]]) -> Result<Vec<f32>, Error> {
    Ok(density_f64(model, cld_history)?
        .into_iter()
        .map(|d| d as f32)
        .collect())
}

/// [`density()`] before its final rounding to `f32`: the exact integer sums divided and
/// scaled in f64 (the parity reference of the WGSL `density_main`).
pub fn density_f64(model: &Model, cld_history: &[&[u32]]) -> Result<Vec<f64>, Error> {
    let size = model.size();
    let words = size.words();
    if cld_history.is_empty() {
        return Err(Error::SizeMismatch {
            what: "cld_history",
            got: 0,
            expected: 1,
        });
    }
    for field in cld_history {
        if field.len() != words {
            return Err(Error::SizeMismatch {
                what: "cld_history[..]",
                got: field.len(),
                expected: words,
            });
        }
    }
    let smoothing = model.smoothing();
    let r = smoothing.radius_cells as i64;
    let t = smoothing.radius_steps as usize;
    let used = cld_history.len().min(t + 1);
    let (nx, ny, nz) = (size.nx as usize, size.ny as usize, size.nz as usize);
    let wpr = size.words_per_row();
    let periodic = model.boundary() == Boundary::Periodic;

    // Time: weighted count per cell.
    let mut acc = vec![0u32; size.cells()];
    let mut time_weight = 0u32;
    for (tau, field) in cld_history[..used].iter().enumerate() {
        let w = (t + 1 - tau) as u32;
        time_weight += w;
        for row in 0..ny * nz {
            for x in 0..nx {
                if field[row * wpr + x / 32] >> (x % 32) & 1 == 1 {
                    acc[row * nx + x] += w;
                }
            }
        }
    }
    // Space: separable tent filters along x, y, z.
    let tent = |acc: &[u32], stride: usize, len: usize, wrap: bool| -> Vec<u32> {
        let mut out = vec![0u32; acc.len()];
        for (i, o) in out.iter_mut().enumerate() {
            let coord = (i / stride % len) as i64;
            let mut sum = 0u32;
            for d in -r..=r {
                let c = coord + d;
                let c = if wrap {
                    c.rem_euclid(len as i64)
                } else if (0..len as i64).contains(&c) {
                    c
                } else {
                    continue;
                };
                let j = (i as i64 + (c - coord) * stride as i64) as usize;
                sum += (r + 1 - d.abs()) as u32 * acc[j];
            }
            *o = sum;
        }
        out
    };
    if r > 0 {
        acc = tent(&acc, 1, nx, periodic);
        acc = tent(&acc, nx, ny, periodic);
        acc = tent(&acc, nx * ny, nz, false);
    }
    let space_weight = ((r + 1) * (r + 1)) as u64;
    let norm = u64::from(time_weight) * space_weight.pow(3);
    let scale = model.slice_density();
    Ok(acc
        .iter()
        .enumerate()
        .map(|(i, &sum)| {
            let z = i / (nx * ny);
            sum as f64 / norm as f64 * f64::from(scale[z])
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Config, GridSize, NaiveState, PackedState, Smoothing};

    fn model(r: u32, t: u32, boundary: Boundary) -> Model {
        let mut c = Config::new(GridSize::new(32, 9, 9));
        c.smoothing = Smoothing {
            radius_cells: r,
            radius_steps: t,
        };
        c.boundary = boundary;
        c.slice_density = (0..9).map(|z| 1.0 + z as f32).collect();
        Model::new(c).unwrap()
    }

    #[test]
    fn single_cell_spreads_as_a_tent_and_conserves_mass() {
        let m = model(2, 0, Boundary::Empty);
        let size = m.size();
        let mut n = NaiveState::empty(size).unwrap();
        n.cld[size.index(10, 4, 4).unwrap()] = true;
        let p = PackedState::from_naive(&n).unwrap();
        let d = density(&m, &[&p.cld]).unwrap();
        let at = |x, y, z| d[size.index(x, y, z).unwrap()];
        // centre weight 3*3*3 / 9^3, scale 5 (z = 4)
        approx::assert_relative_eq!(at(10, 4, 4), 27.0 / 729.0 * 5.0, max_relative = 1e-6);
        approx::assert_relative_eq!(at(11, 4, 4), 18.0 / 729.0 * 5.0, max_relative = 1e-6);
        approx::assert_relative_eq!(at(10, 4, 2), 9.0 / 729.0 * 3.0, max_relative = 1e-6);
        assert_eq!(at(13, 4, 4), 0.0);
        assert_eq!(at(10, 4, 1), 0.0);
        // unscaled mass is 1
        let mass: f64 = d
            .iter()
            .enumerate()
            .map(|(i, &v)| f64::from(v) / (1.0 + (i / (32 * 9)) as f64))
            .sum();
        approx::assert_relative_eq!(mass, 1.0, max_relative = 1e-5);
    }

    #[test]
    fn solid_cloud_is_the_slice_scale_and_history_is_weighted() {
        let m = model(1, 2, Boundary::Periodic);
        let size = m.size();
        let full = PackedState::random(size, 1, 0.0, 0.0, 1.0).unwrap();
        let empty = PackedState::empty(size).unwrap();
        let d = density(&m, &[&full.cld]).unwrap();
        // periodic in x and y; z = 4 is more than R from the top and bottom
        assert_eq!(d[size.index(0, 0, 4).unwrap()], 5.0);
        assert!(d[size.index(0, 0, 0).unwrap()] < 1.0);
        // newest weight 3, then 2, then 1: (3) / (3+2+1) with full only newest
        let d = density(&m, &[&full.cld, &empty.cld, &empty.cld, &full.cld]).unwrap();
        approx::assert_relative_eq!(
            d[size.index(5, 5, 4).unwrap()],
            0.5 * 5.0,
            max_relative = 1e-6
        );
        let d = density(&m, &[&empty.cld, &full.cld]).unwrap();
        approx::assert_relative_eq!(
            d[size.index(5, 5, 4).unwrap()],
            0.4 * 5.0,
            max_relative = 1e-6
        );
        assert!(density(&m, &[]).is_err());
        assert!(density(&m, &[&full.cld[1..]]).is_err());
    }
}
