//! Variant (c): east/west horizons in the tilted plane of the sun's daily path.

use std::f32::consts::FRAC_PI_2;
use std::num::NonZeroUsize;

use terrain::tilted::{Side, bake_east_west_tilted, tilted_horizon_angle};
use terrain::{Algorithm, Heightfield, HorizonOptions, bake_east_west};

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

fn options() -> Vec<HorizonOptions> {
    vec![
        HorizonOptions::flat(),
        HorizonOptions::default(),
        HorizonOptions {
            max_distance: Some(7.5),
            ..HorizonOptions::default()
        },
        HorizonOptions {
            effective_radius: Some(2000.0),
            max_distance: Some(3.0),
            ..HorizonOptions::default()
        },
    ]
}

#[test]
fn latitude_zero_is_variant_a_bit_for_bit() {
    let shapes = [(1, 1), (1, 9), (9, 1), (17, 13), (40, 33)];
    for (seed, &(w, h)) in shapes.iter().enumerate() {
        let hf = random_terrain(w, h, 1.0, 20.0, seed as u64 + 1);
        for opts in options() {
            let plain = bake_east_west(&hf, &opts, Algorithm::BruteForce).unwrap();
            let sweep = bake_east_west(&hf, &opts, Algorithm::HullSweep).unwrap();
            for latitude in [0.0, -0.0] {
                let tilted = bake_east_west_tilted(&hf, latitude, &opts).unwrap();
                assert_eq!(
                    tilted.east.angles(),
                    plain.east.angles(),
                    "{w}x{h} {opts:?}"
                );
                assert_eq!(
                    tilted.west.angles(),
                    plain.west.angles(),
                    "{w}x{h} {opts:?}"
                );
                assert_eq!(
                    tilted.east.angles(),
                    sweep.east.angles(),
                    "{w}x{h} {opts:?}"
                );
            }
        }
    }
}

#[test]
fn wall_along_the_meridian_is_atan_h_over_d_cos_latitude() {
    // A north-south wall of height H at column 30; the plane tilted by phi meets its top
    // at b = H / cos(phi) above P, a = d metres east: tan(theta) = H / (d cos phi).
    let (wall_x, height_m, spacing) = (30usize, 40.0f64, 2.0);
    let hf = Heightfield::from_fn(48, 200, spacing, |x, _| {
        if x == wall_x { height_m as f32 } else { 0.0 }
    })
    .unwrap();
    for latitude_deg in [10.0f64, 30.0, 45.0, 60.0, -30.0, -60.0] {
        let latitude = latitude_deg.to_radians();
        // Enough rows toward the equator for the plane to reach the wall top.
        let y = if latitude > 0.0 { 20 } else { 179 };
        for d in [1usize, 3, 10, 25] {
            let x = wall_x - d;
            let got =
                tilted_horizon_angle(&hf, x, y, Side::East, latitude, &HorizonOptions::flat())
                    .unwrap();
            let want = (height_m / (d as f64 * spacing * latitude.cos())).atan();
            assert!(
                (f64::from(got) - want).abs() < 1e-6,
                "lat {latitude_deg} d {d}: {got} vs {want}"
            );
            // Looking west the ground is flat: the plane meets it along the axis.
            let west =
                tilted_horizon_angle(&hf, x, y, Side::West, latitude, &HorizonOptions::flat())
                    .unwrap();
            assert_eq!(west, 0.0, "lat {latitude_deg} d {d}");
        }
    }
}

#[test]
fn ground_sloping_toward_the_equator_less_than_the_plane_has_a_zero_horizon() {
    // h depends on the row only and rises south with slope 0.3 < cot(40 deg): the plane
    // contains the east-west axis of P and the ground stays below it elsewhere.
    let hf = Heightfield::from_fn(20, 30, 5.0, |_, y| 0.3 * 5.0 * y as f32).unwrap();
    let maps = bake_east_west_tilted(&hf, 40f64.to_radians(), &HorizonOptions::flat()).unwrap();
    for y in 0..30 {
        for x in 0..20 {
            let east = maps.east.angle(x, y).unwrap();
            let west = maps.west.angle(x, y).unwrap();
            assert_eq!(east, if x == 19 { -FRAC_PI_2 } else { 0.0 }, "({x},{y})");
            assert_eq!(west, if x == 0 { -FRAC_PI_2 } else { 0.0 }, "({x},{y})");
        }
    }
    // The same slope at 80 degrees (cot = 0.18 < 0.3) rises above the plane: positive.
    let steep = bake_east_west_tilted(&hf, 80f64.to_radians(), &HorizonOptions::flat()).unwrap();
    assert!(steep.east.angle(5, 5).unwrap() > 0.0);
}

#[test]
fn single_texel_query_and_thread_count_match_the_bake() {
    let hf = random_terrain(23, 19, 3.0, 30.0, 7);
    let opts = HorizonOptions::default();
    let latitude = 0.7;
    let one = bake_east_west_tilted(
        &hf,
        latitude,
        &HorizonOptions {
            threads: NonZeroUsize::new(1),
            ..opts
        },
    )
    .unwrap();
    let three = bake_east_west_tilted(
        &hf,
        latitude,
        &HorizonOptions {
            threads: NonZeroUsize::new(3),
            ..opts
        },
    )
    .unwrap();
    assert_eq!(one, three);
    for (x, y) in [(0, 0), (22, 18), (5, 11), (17, 3)] {
        let e = tilted_horizon_angle(&hf, x, y, Side::East, latitude, &opts).unwrap();
        let w = tilted_horizon_angle(&hf, x, y, Side::West, latitude, &opts).unwrap();
        assert_eq!(e, one.east.angle(x, y).unwrap());
        assert_eq!(w, one.west.angle(x, y).unwrap());
    }
}

#[test]
fn extremes_give_finite_angles_in_range() {
    for &(w, h) in &[(1usize, 1usize), (1, 7), (7, 1), (12, 9)] {
        for spacing in [0.01, 1.0, 1000.0] {
            for amplitude in [0.0f32, 9000.0] {
                let hf = random_terrain(w, h, spacing, amplitude, 3);
                for latitude in [-1.5, -0.6, 0.3, 1.2, 1.5] {
                    let maps =
                        bake_east_west_tilted(&hf, latitude, &HorizonOptions::default()).unwrap();
                    for &a in maps.east.angles().iter().chain(maps.west.angles()) {
                        assert!(
                            a.is_finite() && (-FRAC_PI_2..=FRAC_PI_2).contains(&a),
                            "{a}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn invalid_latitudes_are_typed_errors() {
    let hf = random_terrain(4, 4, 1.0, 1.0, 1);
    for latitude in [f64::NAN, f64::INFINITY, std::f64::consts::FRAC_PI_2, -2.0] {
        let err = bake_east_west_tilted(&hf, latitude, &HorizonOptions::default()).unwrap_err();
        assert!(err.to_string().contains("latitude"), "{err}");
    }
    assert!(tilted_horizon_angle(&hf, 4, 0, Side::East, 0.1, &HorizonOptions::default()).is_err());
}
