//! Horizon maps off the grid axes: against the exact bilinear ray cast, every azimuth is
//! as accurate as the diagonals. Digital lines that sample texels up to one texel beside
//! the ray at their distance along the line make the mean error at odd multiples of
//! 22.5° several times the diagonals' and biased towards more shadow.

use terrain::generate::{GeneratorParams, generate};
use terrain::raycast::ray_cast_horizon_angle;
use terrain::{Algorithm, Heightfield, HorizonOptions, bake_horizon};

/// A steep generated DEM: 2 km relief at 10 m spacing (the trade-off's steep map,
/// smaller), where a 20° sun casts many shadows.
fn steep(side: usize) -> Heightfield {
    generate(&GeneratorParams {
        amplitude: 2_000.0,
        wavelength: 2_560.0,
        octaves: 7,
        ..GeneratorParams::new(side, side, 10.0, 2010)
    })
    .unwrap()
}

/// Mean |error|, mean signed error (positive: more shadow) and the wrong hard-shadow
/// fraction at a 20° sun, over every texel where both the map and the ray cast
/// see terrain.
fn accuracy(hf: &Heightfield, azimuth: f64, options: &HorizonOptions) -> (f64, f64, f64) {
    let map = bake_horizon(hf, azimuth, options, Algorithm::HullSweep).unwrap();
    let sun = 20f64.to_radians();
    let nothing = -std::f64::consts::FRAC_PI_2 + 1e-6;
    let (mut sum, mut signed, mut wrong, mut n) = (0.0, 0.0, 0usize, 0usize);
    for y in (0..hf.height()).step_by(1) {
        for x in (0..hf.width()).step_by(1) {
            let stored = f64::from(map.angle(x, y).unwrap());
            let truth = ray_cast_horizon_angle(hf, x, y, azimuth, options).unwrap();
            if stored <= nothing || truth <= nothing {
                continue;
            }
            sum += (stored - truth).abs();
            signed += stored - truth;
            wrong += usize::from((sun > stored) != (sun > truth));
            n += 1;
        }
    }
    let n = n as f64;
    (sum / n, signed / n, wrong as f64 / n)
}

#[test]
fn every_azimuth_is_as_accurate_as_the_diagonals() {
    let hf = steep(96);
    for options in [
        HorizonOptions::default(),
        HorizonOptions {
            max_distance: Some(300.0),
            ..HorizonOptions::default()
        },
    ] {
        let results: Vec<(f64, (f64, f64, f64))> = (0..16)
            .map(|k| {
                let azimuth = k as f64 * std::f64::consts::TAU / 16.0;
                (azimuth, accuracy(&hf, azimuth, &options))
            })
            .collect();
        for (azimuth, r) in &results {
            println!(
                "{:6.1}° mean {:.5} bias {:+.5} wrong {:.4}",
                azimuth.to_degrees(),
                r.0,
                r.1,
                r.2
            );
        }
        // The axes sample the grid lines exactly: no error beyond the curvature term's
        // in-cell extremum.
        for (azimuth, (mean, _, _)) in results.iter().step_by(4) {
            assert!(*mean < 1e-6, "axis {azimuth}: mean error {mean}");
        }
        let diagonal = |f: fn(&(f64, f64, f64)) -> f64| {
            results
                .iter()
                .skip(2)
                .step_by(4)
                .map(|(_, r)| f(r))
                .fold(0.0, f64::max)
        };
        let (mean_d, bias_d, wrong_d) = (
            diagonal(|r| r.0),
            diagonal(|r| r.1.abs()),
            diagonal(|r| r.2),
        );
        for (azimuth, (mean, bias, wrong)) in &results {
            let deg = azimuth.to_degrees();
            assert!(
                *mean <= mean_d,
                "{deg}°: mean error {mean} rad > diagonals' {mean_d} ({options:?})"
            );
            assert!(
                bias.abs() <= bias_d,
                "{deg}°: bias {bias} rad, diagonals' {bias_d} ({options:?})"
            );
            assert!(
                *wrong <= wrong_d,
                "{deg}°: wrong shadows {wrong}, diagonals' {wrong_d} ({options:?})"
            );
        }
    }
}
