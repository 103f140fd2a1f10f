use super::hull::first_true;
use super::lines::Lines;
use super::sampler::{LineScratch, NEAR_STEPS, Sampler};
use crate::Heightfield;

/// The near field looked up by [`Sampler::build`] equals
/// [`Sampler::near_best`] bit for bit for every view of every line, including the
/// views whose ray reaches the line's last texel or leaves the map, and maximum
/// distances shorter than the near field; and [`Sampler::build_batch`] gives
/// every line of a batch exactly what [`Sampler::build`] gives it alone.
#[test]
fn build_near_field_is_near_best() {
    let (w, h) = (23, 17);
    let hf = Heightfield::from_fn(w, h, 30.0, |x, y| {
        let (x, y) = (x as f32, y as f32);
        // Rough terrain with exact zeros and negative heights.
        ((x * 1.7 + y * 0.9).sin() * 300.0 + (x * y * 0.37).cos() * 120.0).round() - 60.0
    })
    .unwrap();
    // 32 even azimuths, and slopes t = ±1/2, ±1/4 where some step k·t is (about) an
    // integer: the near field's per-texel path instead of the row-wise one.
    let mut azimuths: Vec<f64> = (0..32)
        .map(|k| k as f64 * std::f64::consts::TAU / 32.0)
        .collect();
    for t in [0.5f64, 0.25] {
        azimuths.extend([
            super::EAST + t.atan(),
            super::EAST - t.atan(),
            super::WEST + t.atan(),
            std::f64::consts::PI - t.atan(),
        ]);
    }
    for (k, &azimuth) in azimuths.iter().enumerate() {
        let lines = Lines::new(w, h, hf.spacing(), azimuth);
        if lines.exact {
            continue;
        }
        let grid = lines.dominant_major(&hf);
        for max_steps in [1, 2, NEAR_STEPS, 7, usize::MAX] {
            for inv_two_r in [0.0, 0.5 / 6.371e6] {
                let sampler = Sampler::new(&lines, &grid, inv_two_r, max_steps);
                // A batch of lines is built as each line on its own.
                let ids: Vec<i64> = lines.ids().collect();
                let mut batch: Vec<LineScratch> = (0..5).map(|_| LineScratch::default()).collect();
                let mut sc = LineScratch::default();
                for group in ids.chunks(5) {
                    sampler.build_batch(group, &mut batch[..group.len()]);
                    for (&c, b) in group.iter().zip(&batch) {
                        sampler.build(c, &mut sc);
                        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                        assert_eq!(bits(&b.h), bits(&sc.h), "line {c}");
                        assert_eq!(bits(&b.g), bits(&sc.g), "line {c}");
                        let key = |v: &super::sampler::View| {
                            (v.i, v.texel, [v.h, v.m, v.e, v.g, v.near].map(f64::to_bits))
                        };
                        let (kb, ks): (Vec<_>, Vec<_>) = (
                            b.views.iter().map(key).collect(),
                            sc.views.iter().map(key).collect(),
                        );
                        assert_eq!(kb, ks, "line {c}");
                    }
                }
                for c in lines.ids() {
                    sampler.build(c, &mut sc);
                    let last = sc.views.last().map_or(0, |v| v.i);
                    for v in &sc.views {
                        let expected = sampler.near_best(v, last);
                        assert_eq!(
                            v.near.to_bits(),
                            expected.to_bits(),
                            "azimuth {k}, K {max_steps}, line {c}, view {}",
                            v.i
                        );
                    }
                }
            }
        }
    }
}

/// The row-by-row bake of a maximum distance ([`super::window::bake_rows`]) gives
/// [`super::Algorithm::BruteForce`]'s angles bit for bit: every window length from
/// none to past the map, odd azimuths (the per-texel rows where `u·t` is about an
/// integer, slopes 1/2, 1/3, 1/4) and the axes and diagonals, curvature on and
/// off, maps narrower and wider than the window, 1 and 3 threads.
#[test]
fn rows_are_brute_force_bit_for_bit() {
    use super::{Algorithm, HorizonOptions, bake_horizon, window};
    let rough = |x: usize, y: usize| {
        let (x, y) = (x as f32, y as f32);
        ((x * 1.7 + y * 0.9).sin() * 300.0 + (x * y * 0.37).cos() * 120.0).round() - 60.0
    };
    let mut azimuths: Vec<f64> = (0..32)
        .map(|k| k as f64 * std::f64::consts::TAU / 32.0)
        .collect();
    azimuths.extend([0.3, 1.0, 2.2, 3.9, 5.5, 0.05]);
    for t in [0.5f64, 1.0 / 3.0, 0.25] {
        azimuths.extend([
            super::EAST + t.atan(),
            super::EAST - t.atan(),
            super::WEST + t.atan(),
            std::f64::consts::PI - t.atan(),
            t.atan(),
        ]);
    }
    // Flat stretches of +0 and −0 and plateaus: tangents that tie at ±0 and at
    // equal values (the maximum must keep the same one).
    let zeros = |x: usize, y: usize| match (x * 7 + y * 3) % 5 {
        0 => -0.0,
        1 | 2 => 0.0,
        3 => 30.0,
        _ => 60.0,
    };
    // 150 columns: blocks of texels whose samples cross 2, 4, …, 128 (weights per
    // binade) and whose windows leave the map.
    type Height<'a> = &'a dyn Fn(usize, usize) -> f32;
    let maps: [(usize, usize, Height); 5] = [
        (150, 61, &rough),
        (23, 17, &rough),
        (9, 40, &rough),
        (40, 3, &rough),
        (19, 21, &zeros),
    ];
    for (w, h, height) in maps {
        let hf = Heightfield::from_fn(w, h, 30.0, height).unwrap();
        for &azimuth in &azimuths {
            let lines = Lines::new(w, h, hf.spacing(), azimuth);
            let grid = lines.dominant_major(&hf);
            for max_steps in [0, 1, 3, NEAR_STEPS, 5, 6, 7, 9, 13, 22, 39, 60] {
                for effective_radius in [None, Some(6.371e6)] {
                    let options = HorizonOptions {
                        effective_radius,
                        max_distance: Some(max_steps as f64 * lines.step),
                        threads: std::num::NonZeroUsize::new(1),
                    };
                    assert_eq!(lines.max_steps(options.max_distance), max_steps);
                    let brute =
                        bake_horizon(&hf, azimuth, &options, Algorithm::BruteForce).unwrap();
                    for threads in [1, 3] {
                        let rows = window::bake_rows(
                            &lines,
                            &grid,
                            options.inv_two_r(),
                            max_steps,
                            threads,
                        );
                        let bits = |a: &[f32]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                        assert_eq!(
                            bits(&rows),
                            bits(brute.angles()),
                            "{w}x{h}, azimuth {azimuth}, K {max_steps}, {effective_radius:?}, {threads} threads"
                        );
                    }
                }
            }
        }
    }
}

/// A maximum distance baked through the unlimited sweep
/// ([`super::window::Method::ByUnlimited`]: the window only for the texels whose
/// horizon point over the whole line lies beyond it) and by the windowed sweep
/// gives [`super::Algorithm::BruteForce`]'s angles bit for bit: window lengths from
/// none to past the map, even and odd azimuths (the axes and diagonals' texel
/// lines and the others' line samples), curvature on and off, a generated
/// mountain map (horizon points near and far), rough maps, and flat stretches of
/// `+0` and `−0` (tied zero tangents), 1 and 3 threads.
#[test]
fn limited_sweeps_are_brute_force_bit_for_bit() {
    use super::bake::bake_with;
    use super::window::Method;
    use super::{Algorithm, HorizonOptions};
    let rough = |x: usize, y: usize| {
        let (x, y) = (x as f32, y as f32);
        ((x * 1.7 + y * 0.9).sin() * 300.0 + (x * y * 0.37).cos() * 120.0).round() - 60.0
    };
    let zeros = |x: usize, y: usize| match (x * 7 + y * 3) % 5 {
        0 => -0.0,
        1 | 2 => 0.0,
        3 => 30.0,
        _ => 60.0,
    };
    let mountains = crate::generate::generate(&crate::generate::GeneratorParams {
        amplitude: 2000.0,
        wavelength: 1500.0,
        octaves: 6,
        ..crate::generate::GeneratorParams::new(90, 70, 30.0, 2010)
    })
    .unwrap();
    let mut maps = vec![
        mountains,
        Heightfield::from_fn(61, 23, 30.0, rough).unwrap(),
        Heightfield::from_fn(9, 40, 30.0, rough).unwrap(),
        Heightfield::from_fn(19, 21, 30.0, zeros).unwrap(),
    ];
    maps.push(Heightfield::from_fn(40, 3, 30.0, rough).unwrap());
    let mut azimuths: Vec<f64> = (0..16)
        .map(|k| k as f64 * std::f64::consts::TAU / 16.0)
        .collect();
    azimuths.extend([0.3, 1.0, 2.2, 3.9, 5.5, 0.05]);
    let bits = |a: &[f32]| a.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    for hf in &maps {
        for &azimuth in &azimuths {
            let step = Lines::new(hf.width(), hf.height(), hf.spacing(), azimuth).step;
            for max_steps in [0, 1, 3, NEAR_STEPS, 5, 6, 9, 17, 30, 55, 89, 200] {
                for effective_radius in [None, Some(6.371e6)] {
                    let options = HorizonOptions {
                        effective_radius,
                        max_distance: Some(max_steps as f64 * step),
                        threads: std::num::NonZeroUsize::new(1),
                    };
                    let brute =
                        bake_with(hf, azimuth, &options, Algorithm::BruteForce, None).unwrap();
                    for method in [Method::Windowed, Method::ByUnlimited] {
                        for threads in [1, 3] {
                            let options = HorizonOptions {
                                threads: std::num::NonZeroUsize::new(threads),
                                ..options
                            };
                            let sweep = bake_with(
                                hf,
                                azimuth,
                                &options,
                                Algorithm::HullSweep,
                                Some(method),
                            )
                            .unwrap();
                            assert_eq!(
                                bits(sweep.angles()),
                                bits(brute.angles()),
                                "{}x{}, azimuth {azimuth}, K {max_steps}, \
                                 {effective_radius:?}, {method:?}, {threads} threads",
                                hf.width(),
                                hf.height()
                            );
                        }
                    }
                }
            }
        }
    }
}

/// The galloping search finds the first true position from every guess, as a
/// bisection of the whole range does (the tangent searches rely on it).
#[test]
fn first_true_from_any_guess_is_the_bisection_answer() {
    for len in 1..40 {
        for answer in 0..=len {
            let expected = answer.min(len - 1);
            for guess in 0..len + 3 {
                let got = first_true(len, guess, |i| {
                    assert!(i + 1 < len, "pred called past len − 2: {i} (len {len})");
                    i >= answer
                });
                assert_eq!(got, expected, "len {len}, answer {answer}, guess {guess}");
            }
        }
    }
}
