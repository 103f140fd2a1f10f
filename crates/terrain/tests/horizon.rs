//! Horizon-angle tests: analytic cases, extremes, sweep == brute force, threading.

use std::f32::consts::FRAC_PI_2;
use std::num::NonZeroUsize;

use terrain::generate::{Fractal, GeneratorParams, Noise, generate};
use terrain::horizon::{EAST, EFFECTIVE_EARTH_RADIUS, NO_HORIZON, WEST};
use terrain::{
    Algorithm, Heightfield, HorizonOptions, bake_azimuths, bake_east_west, bake_horizon,
    horizon_angle,
};

const ALGORITHMS: [Algorithm; 2] = [Algorithm::BruteForce, Algorithm::HullSweep];

fn flat(width: usize, height: usize, spacing: f64) -> Heightfield {
    Heightfield::from_fn(width, height, spacing, |_, _| 0.0).unwrap()
}

/// Small deterministic pseudo-random terrain (xorshift), heights in [0, amplitude).
fn random_terrain(
    width: usize,
    height: usize,
    spacing: f64,
    amplitude: f32,
    seed: u64,
) -> Heightfield {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    Heightfield::from_fn(width, height, spacing, |_, _| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 24) as f32 * amplitude
    })
    .unwrap()
}

fn max_abs_diff(a: &[f32], b: &[f32]) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f32::max)
}

fn assert_valid(angles: &[f32]) {
    for &a in angles {
        assert!(a.is_finite(), "non-finite angle {a}");
        assert!(
            (-FRAC_PI_2..=FRAC_PI_2).contains(&a),
            "angle {a} out of [-pi/2, pi/2]"
        );
    }
}

#[test]
fn flat_plane_without_curvature_is_zero_and_edges_see_nothing() {
    let hf = flat(17, 9, 3.0);
    for algorithm in ALGORITHMS {
        let maps = bake_east_west(&hf, &HorizonOptions::flat(), algorithm).unwrap();
        for y in 0..9 {
            for x in 0..17 {
                let east = if x == 16 { NO_HORIZON } else { 0.0 };
                let west = if x == 0 { NO_HORIZON } else { 0.0 };
                assert_eq!(
                    maps.east.angle(x, y).unwrap(),
                    east,
                    "{algorithm:?} ({x},{y})"
                );
                assert_eq!(
                    maps.west.angle(x, y).unwrap(),
                    west,
                    "{algorithm:?} ({x},{y})"
                );
            }
        }
    }
}

#[test]
fn flat_plane_with_curvature_is_exactly_the_dip_of_the_nearest_sample() {
    let spacing = 250.0;
    let hf = flat(40, 3, spacing);
    let dip = (-(spacing / (2.0 * EFFECTIVE_EARTH_RADIUS))).atan() as f32;
    assert!(dip < -1e-5, "the test needs a visible dip: {dip}");
    for algorithm in ALGORITHMS {
        for max_distance in [None, Some(1000.0)] {
            let options = HorizonOptions {
                max_distance,
                ..HorizonOptions::default()
            };
            let maps = bake_east_west(&hf, &options, algorithm).unwrap();
            for x in 0..39 {
                let ulp = f32::EPSILON * dip.abs();
                assert!(
                    (maps.east.angle(x, 1).unwrap() - dip).abs() <= ulp,
                    "{algorithm:?} x={x}"
                );
                assert!(
                    (maps.west.angle(x + 1, 1).unwrap() - dip).abs() <= ulp,
                    "{algorithm:?} x={x}"
                );
            }
        }
    }
}

#[test]
fn vertical_wall_is_atan_height_over_distance() {
    let (spacing, wall_x, wall_h) = (2.5, 30usize, 40.0f32);
    let hf = Heightfield::from_fn(
        50,
        4,
        spacing,
        |x, _| if x == wall_x { wall_h } else { 0.0 },
    )
    .unwrap();
    for algorithm in ALGORITHMS {
        let maps = bake_east_west(&hf, &HorizonOptions::flat(), algorithm).unwrap();
        for x in 0..wall_x {
            let d = (wall_x - x) as f64 * spacing;
            let expected = (f64::from(wall_h) / d).atan() as f32;
            assert!(
                (maps.east.angle(x, 2).unwrap() - expected).abs() < 1e-6,
                "{algorithm:?} x={x}"
            );
        }
        // Behind the wall (east of it) the ground is flat again.
        assert_eq!(maps.east.angle(wall_x + 1, 2).unwrap(), 0.0);
        // Looking west from beyond the wall sees it too.
        let expected = (f64::from(wall_h) / (5.0 * spacing)).atan() as f32;
        assert!((maps.west.angle(wall_x + 5, 0).unwrap() - expected).abs() < 1e-6);
        // From the top of the wall everything east is below; the least steep sample is
        // the farthest one (the map edge, 19 steps away).
        let from_top = (-(f64::from(wall_h)) / (19.0 * spacing)).atan() as f32;
        assert!((maps.east.angle(wall_x, 1).unwrap() - from_top).abs() < 1e-6);
        // A maximum distance shorter than the wall's distance hides it.
        let options = HorizonOptions {
            max_distance: Some(10.0 * spacing),
            ..HorizonOptions::flat()
        };
        let limited = bake_east_west(&hf, &options, algorithm).unwrap();
        assert_eq!(limited.east.angle(wall_x - 11, 0).unwrap(), 0.0);
        let at_limit = (f64::from(wall_h) / (10.0 * spacing)).atan() as f32;
        assert!((limited.east.angle(wall_x - 10, 0).unwrap() - at_limit).abs() < 1e-6);
    }
}

#[test]
fn single_spike_is_seen_along_rows_columns_and_diagonals() {
    let (n, c, spike, spacing) = (41usize, 20usize, 100.0f32, 10.0);
    let hf = Heightfield::from_fn(
        n,
        n,
        spacing,
        |x, y| if (x, y) == (c, c) { spike } else { 0.0 },
    )
    .unwrap();
    let options = HorizonOptions::flat();
    let maps = bake_azimuths(&hf, 8, &options, Algorithm::HullSweep).unwrap();
    let expect = |d: f64| (f64::from(spike) / d).atan() as f32;
    for k in 1..=10usize {
        let d = k as f64 * spacing;
        let diag = d * std::f64::consts::SQRT_2;
        // Layer 0 north, 2 east, 4 south, 6 west; 1 north-east.
        assert!(
            (maps.layers()[2].angle(c - k, c).unwrap() - expect(d)).abs() < 1e-6,
            "east k={k}"
        );
        assert!(
            (maps.layers()[6].angle(c + k, c).unwrap() - expect(d)).abs() < 1e-6,
            "west k={k}"
        );
        assert!(
            (maps.layers()[0].angle(c, c + k).unwrap() - expect(d)).abs() < 1e-6,
            "north k={k}"
        );
        assert!(
            (maps.layers()[4].angle(c, c - k).unwrap() - expect(d)).abs() < 1e-6,
            "south k={k}"
        );
        assert!(
            (maps.layers()[1].angle(c - k, c + k).unwrap() - expect(diag)).abs() < 1e-6,
            "north-east k={k}"
        );
        assert!(
            (maps.layers()[5].angle(c + k, c - k).unwrap() - expect(diag)).abs() < 1e-6,
            "south-west k={k}"
        );
        // Off the spike's line: flat ground only.
        assert_eq!(maps.layers()[2].angle(c - k, c + 1).unwrap(), 0.0);
    }
}

#[test]
fn mirror_symmetry_east_west_and_north_south() {
    let hf = random_terrain(37, 23, 5.0, 50.0, 7);
    let (w, h) = (hf.width(), hf.height());
    let flipped_x =
        Heightfield::from_fn(w, h, 5.0, |x, y| hf.samples()[y * w + (w - 1 - x)]).unwrap();
    let flipped_y =
        Heightfield::from_fn(w, h, 5.0, |x, y| hf.samples()[(h - 1 - y) * w + x]).unwrap();
    for algorithm in ALGORITHMS {
        for options in [
            HorizonOptions::flat(),
            HorizonOptions {
                max_distance: Some(40.0),
                ..HorizonOptions::default()
            },
        ] {
            let a = bake_east_west(&hf, &options, algorithm).unwrap();
            let b = bake_east_west(&flipped_x, &options, algorithm).unwrap();
            let north = bake_horizon(&hf, 0.0, &options, algorithm).unwrap();
            let south =
                bake_horizon(&flipped_y, std::f64::consts::PI, &options, algorithm).unwrap();
            for y in 0..h {
                for x in 0..w {
                    assert_eq!(
                        a.east.angle(x, y).unwrap(),
                        b.west.angle(w - 1 - x, y).unwrap()
                    );
                    assert_eq!(
                        a.west.angle(x, y).unwrap(),
                        b.east.angle(w - 1 - x, y).unwrap()
                    );
                    assert_eq!(
                        north.angle(x, y).unwrap(),
                        south.angle(x, h - 1 - y).unwrap()
                    );
                }
            }
        }
    }
}

#[test]
fn slope_sees_its_own_gradient() {
    let a = 0.5f32;
    let hf = Heightfield::from_fn(30, 5, 1.0, |x, _| a * x as f32).unwrap();
    for algorithm in ALGORITHMS {
        let maps = bake_east_west(&hf, &HorizonOptions::flat(), algorithm).unwrap();
        for x in 0..29 {
            assert!((maps.east.angle(x, 2).unwrap() - a.atan()).abs() < 1e-6);
            assert!((maps.west.angle(x + 1, 2).unwrap() + a.atan()).abs() < 1e-6);
        }
    }
}

#[test]
fn curvature_can_move_the_horizon_point_and_both_algorithms_follow() {
    // Spacing 1 km: a 100 m hill 10 km away and a 2000 m ridge 190 km away.
    let hf = Heightfield::from_fn(200, 1, 1000.0, |x, _| match x {
        10 => 100.0,
        190 => 2000.0,
        _ => 0.0,
    })
    .unwrap();
    let far = (2000.0f64 / 190_000.0).atan() as f32;
    let near_curved = {
        let d = 10_000.0f64;
        ((100.0 - d * d / (2.0 * EFFECTIVE_EARTH_RADIUS)) / d).atan() as f32
    };
    for algorithm in ALGORITHMS {
        let flat = bake_horizon(&hf, EAST, &HorizonOptions::flat(), algorithm).unwrap();
        assert!(
            (flat.angle(0, 0).unwrap() - far).abs() < 1e-6,
            "{algorithm:?}"
        );
        let curved = bake_horizon(&hf, EAST, &HorizonOptions::default(), algorithm).unwrap();
        assert!(
            (curved.angle(0, 0).unwrap() - near_curved).abs() < 1e-6,
            "{algorithm:?}"
        );
    }
}

fn option_grid(spacing: f64) -> Vec<HorizonOptions> {
    let mut out = Vec::new();
    for effective_radius in [None, Some(EFFECTIVE_EARTH_RADIUS), Some(2.0e5)] {
        for steps in [
            None,
            Some(0.5),
            Some(1.0),
            Some(2.0),
            Some(3.5),
            Some(7.0),
            Some(16.0),
            Some(1e9),
        ] {
            out.push(HorizonOptions {
                effective_radius,
                max_distance: steps.map(|s| s * spacing),
                threads: None,
            });
        }
    }
    out
}

#[test]
fn sweep_equals_brute_force_on_random_terrains() {
    let cases = [
        (48usize, 31usize, 1.0f64, 20.0f32, 1u64),
        (31, 48, 1000.0, 3000.0, 2),
        (64, 64, 30.0, 9000.0, 3),
        (1, 40, 5.0, 100.0, 4),
        (40, 1, 5.0, 100.0, 5),
        (23, 2, 0.01, 5.0, 6),
    ];
    let azimuths = [
        EAST,
        WEST,
        0.0,
        std::f64::consts::PI,
        0.3,
        1.0,
        2.2,
        3.9,
        5.5,
        std::f64::consts::FRAC_PI_4,
    ];
    let mut max_diff = 0.0f32;
    let mut max_distance_mattered = false;
    let mut curvature_mattered = false;
    for &(w, h, spacing, amplitude, seed) in &cases {
        let hf = random_terrain(w, h, spacing, amplitude, seed);
        let unlimited_flat =
            bake_horizon(&hf, 1.0, &HorizonOptions::flat(), Algorithm::BruteForce).unwrap();
        for options in option_grid(spacing) {
            for &azimuth in &azimuths {
                let brute = bake_horizon(&hf, azimuth, &options, Algorithm::BruteForce).unwrap();
                let sweep = bake_horizon(&hf, azimuth, &options, Algorithm::HullSweep).unwrap();
                assert_valid(brute.angles());
                let diff = max_abs_diff(brute.angles(), sweep.angles());
                assert!(
                    diff <= 1e-6,
                    "{w}x{h} spacing {spacing} azimuth {azimuth} {options:?}: max diff {diff}"
                );
                max_diff = max_diff.max(diff);
                if azimuth == 1.0 && w > 1 && h > 1 {
                    let d = max_abs_diff(brute.angles(), unlimited_flat.angles());
                    if options.effective_radius.is_none()
                        && options.max_distance == Some(7.0 * spacing)
                    {
                        max_distance_mattered |= d > 1e-3;
                    }
                    if options.max_distance.is_none() && options.effective_radius.is_some() {
                        curvature_mattered |= d > 1e-3;
                    }
                }
            }
        }
    }
    // The grid must exercise the options (otherwise the comparison proves little).
    assert!(max_distance_mattered && curvature_mattered);
    eprintln!("sweep vs brute force: max |diff| = {max_diff:e} rad");
}

#[test]
fn sweep_equals_brute_force_on_generated_terrain_with_many_azimuths() {
    for (noise, fractal) in [
        (Noise::Gradient, Fractal::Fbm),
        (Noise::Value, Fractal::Ridged),
    ] {
        let params = GeneratorParams {
            noise,
            fractal,
            amplitude: 2500.0,
            ..GeneratorParams::new(57, 45, 90.0, 11)
        };
        let hf = generate(&params).unwrap();
        for options in [
            HorizonOptions::default(),
            HorizonOptions {
                max_distance: Some(1200.0),
                ..HorizonOptions::default()
            },
        ] {
            let brute = bake_azimuths(&hf, 16, &options, Algorithm::BruteForce).unwrap();
            let sweep = bake_azimuths(&hf, 16, &options, Algorithm::HullSweep).unwrap();
            for (b, s) in brute.layers().iter().zip(sweep.layers()) {
                assert!(
                    max_abs_diff(b.angles(), s.angles()) <= 1e-6,
                    "azimuth {}",
                    b.azimuth()
                );
            }
        }
    }
}

/// Windows of a maximum distance where the near field hides the far samples (their
/// searches and hull builds are skipped) and where it does not: terraces rising every
/// few texels, with noise, for windows of 1 to 40 far samples, every block layout
/// (the skips and the lazily built hulls must give the brute force's angles).
#[test]
fn windowed_sweep_equals_brute_force_where_searches_are_skipped_and_not() {
    let spacing = 30.0;
    let noise = random_terrain(61, 47, spacing, 40.0, 7);
    let hf = Heightfield::from_fn(61, 47, spacing, |x, y| {
        300.0 * ((3 * x + 2 * y) % 11) as f32 + noise.samples()[y * 61 + x]
    })
    .unwrap();
    for steps in [
        0.5, 1.0, 4.5, 5.5, 6.5, 7.5, 9.5, 13.5, 17.5, 25.0, 40.0, 60.0,
    ] {
        for effective_radius in [None, Some(EFFECTIVE_EARTH_RADIUS)] {
            let options = HorizonOptions {
                effective_radius,
                max_distance: Some(steps * spacing),
                ..HorizonOptions::default()
            };
            let brute = bake_azimuths(&hf, 16, &options, Algorithm::BruteForce).unwrap();
            let sweep = bake_azimuths(&hf, 16, &options, Algorithm::HullSweep).unwrap();
            for (b, s) in brute.layers().iter().zip(sweep.layers()) {
                let d = max_abs_diff(b.angles(), s.angles());
                assert!(d <= 1e-6, "{steps} steps, azimuth {}: {d}", b.azimuth());
            }
        }
    }
}

#[test]
fn single_texel_query_matches_the_bake() {
    let hf = random_terrain(29, 33, 12.0, 200.0, 9);
    let options = HorizonOptions {
        max_distance: Some(150.0),
        ..HorizonOptions::default()
    };
    for azimuth in [EAST, WEST, 0.7, 4.0] {
        let map = bake_horizon(&hf, azimuth, &options, Algorithm::HullSweep).unwrap();
        for (x, y) in [(0, 0), (28, 32), (5, 17), (14, 3), (28, 0)] {
            let single = horizon_angle(&hf, x, y, azimuth, &options).unwrap();
            assert!(
                (single - map.angle(x, y).unwrap()).abs() <= 1e-6,
                "({x},{y}) azimuth {azimuth}"
            );
        }
    }
    assert!(horizon_angle(&hf, 29, 0, EAST, &options).is_err());
    assert!(horizon_angle(&hf, 0, 0, f64::NAN, &options).is_err());
}

#[test]
fn result_does_not_depend_on_thread_count() {
    let hf = random_terrain(70, 50, 20.0, 300.0, 21);
    for algorithm in ALGORITHMS {
        for azimuth in [EAST, 0.9] {
            let run = |threads: usize| {
                let options = HorizonOptions {
                    threads: NonZeroUsize::new(threads),
                    max_distance: Some(400.0),
                    ..HorizonOptions::default()
                };
                bake_horizon(&hf, azimuth, &options, algorithm).unwrap()
            };
            let one = run(1);
            assert_eq!(one, run(2));
            assert_eq!(one, run(3));
            assert_eq!(one, run(64));
        }
    }
}

#[test]
fn extremes_give_finite_angles_in_range() {
    for (w, h) in [(1usize, 1usize), (1, 17), (17, 1), (2, 2)] {
        for spacing in [0.01, 1.0, 1000.0] {
            let hf = random_terrain(w, h, spacing, 9000.0, (w * 31 + h) as u64);
            for options in [
                HorizonOptions::flat(),
                HorizonOptions::default(),
                HorizonOptions {
                    max_distance: Some(spacing * 3.0),
                    ..HorizonOptions::default()
                },
            ] {
                for algorithm in ALGORITHMS {
                    let maps = bake_azimuths(&hf, 8, &options, algorithm).unwrap();
                    for layer in maps.layers() {
                        assert_valid(layer.angles());
                    }
                }
            }
        }
    }
    // A 1x1 map has no samples in any direction.
    let one = flat(1, 1, 1.0);
    let maps = bake_azimuths(&one, 4, &HorizonOptions::default(), Algorithm::HullSweep).unwrap();
    assert!(maps.layers().iter().all(|l| l.angles() == [NO_HORIZON]));
    // 9,000 m spike at 1 cm spacing: just below pi/2, never above.
    let spike = Heightfield::from_fn(5, 1, 0.01, |x, _| if x == 2 { 9000.0 } else { 0.0 }).unwrap();
    for algorithm in ALGORITHMS {
        let maps = bake_east_west(&spike, &HorizonOptions::default(), algorithm).unwrap();
        assert_valid(maps.east.angles());
        assert!(maps.east.angle(1, 0).unwrap() > FRAC_PI_2 - 1e-4);
        assert!(maps.east.angle(2, 0).unwrap() < -FRAC_PI_2 + 1e-4);
    }
}

#[test]
fn azimuth_interpolation_hits_layers_and_blends_between() {
    let hf = random_terrain(20, 20, 5.0, 40.0, 3);
    let maps = bake_azimuths(&hf, 8, &HorizonOptions::flat(), Algorithm::HullSweep).unwrap();
    let step = std::f32::consts::TAU / 8.0;
    for (x, y) in [(3, 4), (10, 10), (19, 0)] {
        for k in 0..8 {
            let exact = maps.layers()[k].angle(x, y).unwrap();
            assert!((maps.horizon_angle(x, y, k as f32 * step).unwrap() - exact).abs() < 1e-6);
            let next = maps.layers()[(k + 1) % 8].angle(x, y).unwrap();
            let mid = maps.horizon_angle(x, y, (k as f32 + 0.5) * step).unwrap();
            assert!((mid - 0.5 * (exact + next)).abs() < 1e-5, "k={k}");
        }
        // Wrapping: -step/2 blends layer 7 and layer 0.
        let wrapped = maps.horizon_angle(x, y, -0.5 * step).unwrap();
        let expect =
            0.5 * (maps.layers()[7].angle(x, y).unwrap() + maps.layers()[0].angle(x, y).unwrap());
        assert!((wrapped - expect).abs() < 1e-5);
    }
}

#[test]
fn invalid_options_are_typed_errors() {
    let hf = flat(4, 4, 1.0);
    let bad = [
        HorizonOptions {
            effective_radius: Some(0.0),
            ..HorizonOptions::default()
        },
        HorizonOptions {
            effective_radius: Some(f64::NAN),
            ..HorizonOptions::default()
        },
        HorizonOptions {
            max_distance: Some(-1.0),
            ..HorizonOptions::default()
        },
        HorizonOptions {
            max_distance: Some(f64::NAN),
            ..HorizonOptions::default()
        },
    ];
    for options in bad {
        let err = bake_horizon(&hf, EAST, &options, Algorithm::HullSweep).unwrap_err();
        assert!(
            matches!(err, terrain::TerrainError::InvalidParameter { .. }),
            "{err}"
        );
    }
    for count in [0, 3, 65] {
        let err = bake_azimuths(&hf, count, &HorizonOptions::default(), Algorithm::HullSweep)
            .unwrap_err();
        assert!(
            err.to_string().contains(&format!("`count` = {count}")),
            "{err}"
        );
    }
    let err = bake_horizon(
        &hf,
        f64::INFINITY,
        &HorizonOptions::default(),
        Algorithm::BruteForce,
    )
    .unwrap_err();
    assert!(err.to_string().contains("azimuth"), "{err}");
    let _ = WEST;
}
