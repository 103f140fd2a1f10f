//! The exact ray-cast horizon (the trade-off's reference).

use terrain::raycast::{ray_cast_hard_shadow, ray_cast_horizon_angle};
use terrain::{Heightfield, HorizonOptions, horizon_angle};

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

const HALF_PI: f64 = std::f64::consts::FRAC_PI_2;

#[test]
fn flat_plane_is_zero_inside_and_minus_half_pi_facing_out_of_the_map() {
    let hf = Heightfield::from_fn(9, 7, 10.0, |_, _| 5.0).unwrap();
    for opts in [HorizonOptions::flat(), HorizonOptions::default()] {
        for azimuth in [0.0, 0.4, 1.0, 2.0, 3.5, 5.0] {
            let a = ray_cast_horizon_angle(&hf, 4, 3, azimuth, &opts).unwrap();
            // With curvature the supremum is the slope limit at s -> 0: still 0.
            assert_eq!(a, 0.0, "azimuth {azimuth}");
        }
        let east_edge = ray_cast_horizon_angle(&hf, 8, 3, std::f64::consts::FRAC_PI_2, &opts);
        assert_eq!(east_edge.unwrap(), -HALF_PI);
    }
}

#[test]
fn along_rows_and_columns_equals_the_texel_horizon_on_a_flat_earth() {
    // Along a row the bilinear surface is the polyline through the texels, whose
    // elevation quotient is monotone on each piece: the sup is at a texel.
    let hf = random_terrain(31, 27, 3.0, 25.0, 11);
    let opts = HorizonOptions::flat();
    for (x, y) in [(0, 0), (15, 13), (30, 26), (7, 20)] {
        for azimuth in [
            0.0,
            std::f64::consts::FRAC_PI_2,
            std::f64::consts::PI,
            1.5 * std::f64::consts::PI,
        ] {
            let ray = ray_cast_horizon_angle(&hf, x, y, azimuth, &opts).unwrap();
            let texel = f64::from(horizon_angle(&hf, x, y, azimuth, &opts).unwrap());
            assert!(
                (ray - texel).abs() < 1e-6,
                "({x},{y}) az {azimuth}: {ray} vs {texel}"
            );
        }
    }
}

#[test]
fn oblique_ray_sees_a_meridian_wall_at_atan_h_over_slant_distance() {
    let (wall_x, height_m, spacing) = (40usize, 30.0, 2.0);
    let hf = Heightfield::from_fn(60, 60, spacing, |x, _| {
        if x >= wall_x { height_m as f32 } else { 0.0 }
    })
    .unwrap();
    for azimuth_deg in [60.0f64, 90.0, 120.0, 75.0] {
        let azimuth = azimuth_deg.to_radians();
        for d in [2usize, 5, 12] {
            let (x, y) = (wall_x - d, 30);
            let got = ray_cast_horizon_angle(&hf, x, y, azimuth, &HorizonOptions::flat()).unwrap();
            // The ramp between columns wall_x - 1 and wall_x tops out at the wall's
            // column, d·L / sin(azimuth) along the ray.
            let want = (height_m / (d as f64 * spacing / azimuth.sin())).atan();
            assert!(
                (got - want).abs() < 1e-9,
                "az {azimuth_deg} d {d}: {got} vs {want}"
            );
        }
    }
}

#[test]
fn equals_a_dense_sampling_of_the_bilinear_surface_with_curvature() {
    // Twisted cells (bilinear saddles) and a strong curvature make the supremum fall
    // inside cells as often as on grid lines; 200,000 samples per ray approximate it
    // from below to ~1e-8 rad.
    let hf = random_terrain(7, 6, 1.0, 3.0, 21);
    let opts = HorizonOptions {
        effective_radius: Some(4.0),
        ..HorizonOptions::flat()
    };
    let bilinear = |x: f64, y: f64| {
        let i = (x.floor() as usize).min(5);
        let j = (y.floor() as usize).min(4);
        let (fx, fy) = (x - i as f64, y - j as f64);
        let e = |a: usize, b: usize| hf.elevation(a, b).unwrap();
        let top = e(i, j) + (e(i + 1, j) - e(i, j)) * fx;
        let bottom = e(i, j + 1) + (e(i + 1, j + 1) - e(i, j + 1)) * fx;
        top + (bottom - top) * fy
    };
    let mut checked = 0;
    for (x, y) in [(0usize, 5usize), (1, 4), (3, 3), (6, 0), (2, 1)] {
        for k in 0..24 {
            let azimuth = 0.1 + k as f64 * std::f64::consts::TAU / 24.0;
            let got = ray_cast_horizon_angle(&hf, x, y, azimuth, &opts).unwrap();
            let (dx, dy) = (azimuth.sin(), -azimuth.cos());
            let exit = |p: f64, d: f64, hi: f64| {
                if d.abs() < 1e-12 {
                    f64::INFINITY
                } else if d > 0.0 {
                    (hi - p) / d
                } else {
                    -p / d
                }
            };
            let end = exit(x as f64, dx, 6.0).min(exit(y as f64, dy, 5.0));
            if end <= 0.0 {
                assert_eq!(got, -HALF_PI);
                continue;
            }
            let h_p = hf.elevation(x, y).unwrap();
            let mut dense = f64::NEG_INFINITY;
            // Uniform samples, and geometric ones toward the slope limit at s -> 0.
            let uniform = (1..=200_000).map(|i| end * f64::from(i) / 200_000.0);
            let tiny = (6..=7).map(|k| end * 10f64.powi(-k));
            // And every grid-line crossing, where the quotient has corners.
            let lines: Vec<f64> = (0..=6)
                .map(|g| (f64::from(g) - x as f64) / dx)
                .chain((0..=5).map(|g| (f64::from(g) - y as f64) / dy))
                .filter(|s| s.is_finite() && *s > 0.0 && *s <= end)
                .collect();
            for s in uniform.chain(tiny).chain(lines) {
                let h = bilinear(x as f64 + dx * s, y as f64 + dy * s);
                dense = dense.max((h - h_p - s * s / 8.0) / s);
            }
            let dense = dense.atan();
            assert!(
                got >= dense - 1e-8,
                "({x},{y}) az {azimuth}: {got} < {dense}"
            );
            assert!(
                got - dense < 1e-6,
                "({x},{y}) az {azimuth}: {got} vs {dense}"
            );
            checked += 1;
        }
    }
    assert!(checked > 60);
}

#[test]
fn hard_shadow_switches_at_the_horizon() {
    let hf = random_terrain(20, 20, 5.0, 40.0, 5);
    let opts = HorizonOptions::default();
    let h = ray_cast_horizon_angle(&hf, 3, 9, 1.2, &opts).unwrap();
    assert_eq!(
        ray_cast_hard_shadow(&hf, 3, 9, 1.2, h + 1e-9, &opts).unwrap(),
        1.0
    );
    assert_eq!(ray_cast_hard_shadow(&hf, 3, 9, 1.2, h, &opts).unwrap(), 0.0);
    assert!(ray_cast_hard_shadow(&hf, 3, 9, 1.2, f64::NAN, &opts).is_err());
}

#[test]
fn extremes_and_bad_input() {
    for &(w, h) in &[(1usize, 1usize), (1, 9), (9, 1), (5, 5)] {
        for spacing in [0.01, 1000.0] {
            let hf = random_terrain(w, h, spacing, 9000.0, 2);
            for azimuth in [0.0, 0.3, 1.6, 3.1, 4.8] {
                for y in 0..h {
                    for x in 0..w {
                        let a =
                            ray_cast_horizon_angle(&hf, x, y, azimuth, &HorizonOptions::default())
                                .unwrap();
                        assert!(a.is_finite() && (-HALF_PI..=HALF_PI).contains(&a), "{a}");
                    }
                }
            }
        }
    }
    let hf = random_terrain(3, 3, 1.0, 1.0, 1);
    assert!(ray_cast_horizon_angle(&hf, 0, 0, f64::NAN, &HorizonOptions::default()).is_err());
    assert!(ray_cast_horizon_angle(&hf, 3, 0, 0.0, &HorizonOptions::default()).is_err());
}
