//! Rule-by-rule, neighbourhood, randomness and naive-vs-packed tests.

use cloudsim::{
    Boundary, Config, Ellipsoid, Error, GridSize, Model, NaiveState, PackedState, Probabilities,
    Simulation, naive, packed,
};

const NO_RANDOMNESS: Probabilities = Probabilities {
    extinction: 0.0,
    humidity: 0.0,
    activation: 0.0,
};

fn model(size: GridSize, probabilities: Probabilities, boundary: Boundary) -> Model {
    let mut c = Config::new(size);
    c.probabilities = probabilities;
    c.boundary = boundary;
    Model::new(c).unwrap()
}

/// One step with the naive reference and the packed implementation (1 and 3
/// threads); asserts they agree and returns the result.
fn step_both(model: &Model, state: &NaiveState, step: u32) -> NaiveState {
    let expected = naive::step(model, state, step).unwrap();
    for threads in [1, 3] {
        let mut packed_state = PackedState::from_naive(state).unwrap();
        let mut scratch = PackedState::empty(model.size()).unwrap();
        packed::step(model, &mut packed_state, &mut scratch, step, threads).unwrap();
        assert_eq!(
            packed_state.to_naive(),
            expected,
            "packed ({threads} threads) differs from naive"
        );
    }
    expected
}

fn cells(state: &NaiveState, field: &[bool]) -> Vec<(u32, u32, u32)> {
    let size = state.size();
    let mut out = vec![];
    for z in 0..size.nz {
        for y in 0..size.ny {
            for x in 0..size.nx {
                if field[size.index(x, y, z).unwrap()] {
                    out.push((x, y, z));
                }
            }
        }
    }
    out
}

#[test]
fn rules_one_by_one() {
    let size = GridSize::new(12, 1, 1);
    let m = model(size, NO_RANDOMNESS, Boundary::Empty);
    let mut s = NaiveState::empty(size).unwrap();
    // x=0: humid, nothing active near -> stays humid, not active
    s.hum[0] = true;
    // x=5: humid and active -> hum' = 0, act' = 0, cld' = 1
    s.hum[5] = true;
    s.act[5] = true;
    // x=7: humid, neighbour x=5 (x-2) active -> act' = 1, hum' = 1, cld' unchanged 0
    s.hum[7] = true;
    // x=8: not humid, neighbour x=7? (7 not active) and x=6? no -> nothing
    // x=10: cloud only -> stays cloud
    s.cld[10] = true;
    let n = step_both(&m, &s, 0);
    assert_eq!(cells(&n, &n.hum), [(0, 0, 0), (7, 0, 0)]);
    assert_eq!(cells(&n, &n.act), [(7, 0, 0)]);
    assert_eq!(cells(&n, &n.cld), [(5, 0, 0), (10, 0, 0)]);

    // act without humidity: act' = 0, cld' = 1, hum' = 0, and it activates nothing dry
    let mut s = NaiveState::empty(size).unwrap();
    s.act[3] = true;
    let n = step_both(&m, &s, 0);
    assert!(n.act.iter().all(|&b| !b) && n.hum.iter().all(|&b| !b));
    assert_eq!(cells(&n, &n.cld), [(3, 0, 0)]);

    // hum' = hum ∧ ¬act: a humid active cell loses humidity, a humid inactive one keeps it
    // even when a neighbour is active (it becomes active instead)
    let mut s = NaiveState::empty(size).unwrap();
    s.hum[2] = true;
    s.act[2] = true;
    s.hum[3] = true;
    let n = step_both(&m, &s, 0);
    assert_eq!(cells(&n, &n.hum), [(3, 0, 0)]);
    assert_eq!(cells(&n, &n.act), [(3, 0, 0)]);
    assert_eq!(cells(&n, &n.cld), [(2, 0, 0)]);
    // and next step that cell turns into cloud, loses humidity, and nothing is left active
    let n2 = step_both(&m, &n, 1);
    assert!(n2.act.iter().all(|&b| !b) && n2.hum.iter().all(|&b| !b));
    assert_eq!(cells(&n2, &n2.cld), [(2, 0, 0), (3, 0, 0)]);
}

/// The cells one active cell at `p` can activate (humidity everywhere): those whose
/// neighbourhood (x±1, x±2, y±1, y±2, z+1, z−1, z−2) contains `p`.
fn expected_activation(size: GridSize, p: (i64, i64, i64), periodic: bool) -> Vec<(u32, u32, u32)> {
    let reflected = [
        (1, 0, 0),
        (-1, 0, 0),
        (2, 0, 0),
        (-2, 0, 0),
        (0, 1, 0),
        (0, -1, 0),
        (0, 2, 0),
        (0, -2, 0),
        (0, 0, -1), // p is the z+1 neighbour of the cell below
        (0, 0, 1),  // p is the z−1 neighbour of the cell above
        (0, 0, 2),  // p is the z−2 neighbour of the cell two above
    ];
    let (nx, ny, nz) = (i64::from(size.nx), i64::from(size.ny), i64::from(size.nz));
    let mut out: Vec<(u32, u32, u32)> = reflected
        .iter()
        .filter_map(|(dx, dy, dz)| {
            let (mut x, mut y, z) = (p.0 + dx, p.1 + dy, p.2 + dz);
            if periodic {
                x = x.rem_euclid(nx);
                y = y.rem_euclid(ny);
            }
            ((0..nx).contains(&x) && (0..ny).contains(&y) && (0..nz).contains(&z))
                .then_some((x as u32, y as u32, z as u32))
        })
        .collect();
    out.sort_by_key(|&(x, y, z)| (z, y, x));
    out.dedup();
    out
}

#[test]
fn one_active_cell_activates_exactly_the_eleven_neighbours() {
    for (size, boundary, positions) in [
        (
            GridSize::new(9, 9, 9),
            Boundary::Empty,
            vec![(4, 4, 4), (0, 0, 0), (8, 8, 8), (1, 7, 2)],
        ),
        (
            GridSize::new(70, 6, 6),
            Boundary::Empty,
            vec![
                (31, 3, 3),
                (32, 3, 3),
                (33, 2, 2),
                (63, 3, 3),
                (64, 3, 3),
                (69, 5, 5),
                (30, 3, 3),
            ],
        ),
        (
            GridSize::new(64, 5, 5),
            Boundary::Periodic,
            vec![(0, 0, 2), (63, 4, 2), (1, 1, 0), (32, 3, 4)],
        ),
        (
            GridSize::new(32, 3, 4),
            Boundary::Periodic,
            vec![(0, 0, 1), (31, 2, 3), (16, 1, 2)],
        ),
    ] {
        let m = model(size, NO_RANDOMNESS, boundary);
        for &(x, y, z) in &positions {
            let mut s = NaiveState::empty(size).unwrap();
            s.hum.iter_mut().for_each(|h| *h = true);
            s.act[size.index(x, y, z).unwrap()] = true;
            let n = step_both(&m, &s, 0);
            let got = cells(&n, &n.act);
            let want = expected_activation(
                size,
                (i64::from(x), i64::from(y), i64::from(z)),
                boundary == Boundary::Periodic,
            );
            assert_eq!(got, want, "{size:?} {boundary:?} active at {:?}", (x, y, z));
            if boundary == Boundary::Empty
                && (2..size.nx - 2).contains(&x)
                && (2..size.ny - 2).contains(&y)
                && (1..size.nz - 2).contains(&z)
            {
                assert_eq!(got.len(), 11);
            }
            // the active cell itself turned into cloud and lost its humidity
            assert_eq!(cells(&n, &n.cld), [(x, y, z)]);
            assert!(!n.hum[size.index(x, y, z).unwrap()]);
        }
    }
}

#[test]
fn updates_read_the_previous_state_only() {
    // A humid row with one active cell at x = 0: read from the previous state only,
    // exactly x = 1 and x = 2 activate. Updating in place (in x order) would let the
    // activation race down the whole row in one step.
    let size = GridSize::new(40, 1, 1);
    let m = model(size, NO_RANDOMNESS, Boundary::Empty);
    let mut s = NaiveState::empty(size).unwrap();
    s.hum.iter_mut().for_each(|h| *h = true);
    s.act[0] = true;
    let n = step_both(&m, &s, 0);
    assert_eq!(cells(&n, &n.act), [(1, 0, 0), (2, 0, 0)]);
    // The same in the other direction and along z (descending in-place order).
    let size = GridSize::new(1, 1, 12);
    let m = model(size, NO_RANDOMNESS, Boundary::Empty);
    let mut s = NaiveState::empty(size).unwrap();
    s.hum.iter_mut().for_each(|h| *h = true);
    s.act[11] = true;
    let n = step_both(&m, &s, 0);
    // cell z=10 has z+1 = 11 active; cells above 11 do not exist
    assert_eq!(cells(&n, &n.act), [(0, 0, 10)]);
    s.act[11] = false;
    s.act[3] = true;
    let n = step_both(&m, &s, 0);
    assert_eq!(cells(&n, &n.act), [(0, 0, 2), (0, 0, 4), (0, 0, 5)]);
}

/// `|count - n p| <= 6 sqrt(n p (1 - p)) + 1`.
fn assert_binomial(count: usize, n: usize, p: f64, what: &str) {
    let mean = n as f64 * p;
    let sd = (n as f64 * p * (1.0 - p)).sqrt();
    assert!(
        (count as f64 - mean).abs() <= 6.0 * sd + 1.0,
        "{what}: {count} events in {n} trials, expected {mean:.1} ± {sd:.1}"
    );
}

#[test]
fn the_three_draws_are_independent() {
    // Every cell is a cloud, dry and inactive, so every cell is a candidate for all
    // three events; with p = 1/2 each, a shared random number would make the pairs
    // coincide (P = 1/2) instead of P = 1/4.
    let size = GridSize::new(64, 64, 8);
    let n_cells = size.cells();
    let half = Probabilities {
        extinction: 0.5,
        humidity: 0.5,
        activation: 0.5,
    };
    let m = model(size, half, Boundary::Empty);
    let mut s = NaiveState::empty(size).unwrap();
    s.cld.iter_mut().for_each(|c| *c = true);
    let packed_start = PackedState::from_naive(&s).unwrap();
    let mut outcomes = vec![];
    for step in [0u32, 1] {
        let mut state = packed_start.clone();
        let mut scratch = PackedState::empty(size).unwrap();
        packed::step(&m, &mut state, &mut scratch, step, 2).unwrap();
        let n = state.to_naive();
        let ext: Vec<bool> = n.cld.iter().map(|&c| !c).collect();
        outcomes.push((ext, n.hum, n.act));
    }
    let count = |f: &dyn Fn(usize) -> bool| (0..n_cells).filter(|&i| f(i)).count();
    let (e, h, a) = &outcomes[0];
    assert_binomial(count(&|i| e[i]), n_cells, 0.5, "extinction");
    assert_binomial(count(&|i| h[i]), n_cells, 0.5, "humidity");
    assert_binomial(count(&|i| a[i]), n_cells, 0.5, "activation");
    assert_binomial(count(&|i| e[i] && h[i]), n_cells, 0.25, "ext & hum");
    assert_binomial(count(&|i| e[i] && a[i]), n_cells, 0.25, "ext & act");
    assert_binomial(count(&|i| h[i] && a[i]), n_cells, 0.25, "hum & act");
    assert_binomial(count(&|i| e[i] == h[i]), n_cells, 0.5, "ext == hum");
    assert_binomial(
        count(&|i| e[i] && h[i] && a[i]),
        n_cells,
        0.125,
        "all three",
    );
    // and draws of different steps are independent too
    let (e1, h1, _) = &outcomes[1];
    assert_binomial(count(&|i| e[i] && e1[i]), n_cells, 0.25, "ext step 0 & 1");
    assert_binomial(count(&|i| h[i] && h1[i]), n_cells, 0.25, "hum step 0 & 1");
}

#[test]
fn event_frequencies_match_the_probabilities() {
    let size = GridSize::new(64, 64, 16);
    let n_cells = size.cells();
    for p in [0.01f32, 0.1, 0.37, 0.9] {
        for stream in 0..3 {
            let mut probabilities = NO_RANDOMNESS;
            let mut s = NaiveState::empty(size).unwrap();
            match stream {
                0 => {
                    probabilities.extinction = p;
                    s.cld.iter_mut().for_each(|c| *c = true);
                }
                1 => probabilities.humidity = p,
                _ => probabilities.activation = p,
            }
            let m = model(size, probabilities, Boundary::Empty);
            let mut state = PackedState::from_naive(&s).unwrap();
            let mut scratch = PackedState::empty(size).unwrap();
            packed::step(&m, &mut state, &mut scratch, 7, 2).unwrap();
            let count = match stream {
                0 => n_cells - state.cloud_count() as usize,
                1 => state.hum.iter().map(|w| w.count_ones() as usize).sum(),
                _ => state.act.iter().map(|w| w.count_ones() as usize).sum(),
            };
            assert_binomial(
                count,
                n_cells,
                f64::from(p),
                &format!("stream {stream} p={p}"),
            );
        }
    }
}

#[test]
fn ellipsoid_masks_scale_the_frequencies() {
    // Sum of per-cell probabilities from the mask vs. observed events, per stream.
    let size = GridSize::new(64, 64, 16);
    let mut c = Config::new(size);
    c.probabilities = Probabilities {
        extinction: 0.6,
        humidity: 0.5,
        activation: 0.4,
    };
    c.ellipsoids = vec![
        Ellipsoid {
            center: [20.5, 30.5, 7.5],
            radii: [18.0, 20.0, 7.0],
        },
        Ellipsoid {
            center: [50.0, 20.0, 6.0],
            radii: [12.0, 12.0, 5.0],
        },
    ];
    let m = Model::new(c).unwrap();
    let mut s = NaiveState::empty(size).unwrap();
    s.cld.iter_mut().for_each(|c| *c = true);
    let n = step_both(&m, &s, 3);
    for stream in 0..3 {
        let mut mean = 0.0;
        let mut var = 0.0;
        let mut count = 0usize;
        for i in 0..size.cells() {
            // p = floor(t l / 256) / 2^16 (supply, activation) or floor(t (256 - l) /
            // 256) / 2^16 (extinction): one draw per cell against its own threshold
            let level = m.mask_levels()[i];
            let threshold = cloudsim::rng::lane_threshold(
                m.thresholds()[stream],
                u32::from(level),
                stream as u32,
            );
            let p = match stream {
                0 if level == 0 => 1.0, // removed outside the mask
                _ => f64::from(threshold) / 65536.0,
            };
            mean += p;
            var += p * (1.0 - p);
            let happened = match stream {
                0 => !n.cld[i],
                1 => n.hum[i],
                _ => n.act[i],
            };
            count += usize::from(happened);
            if level == 0 && stream > 0 {
                assert!(!happened, "no supply or activation outside the ellipsoids");
            }
        }
        assert!(
            (count as f64 - mean).abs() <= 6.0 * var.sqrt() + 1.0,
            "stream {stream}: {count} vs {mean:.1} ± {:.1}",
            var.sqrt()
        );
    }
    // mask level 0 removes clouds; the centre (level 255) never loses a cloud
    let centre = size.index(20, 30, 7).unwrap();
    assert_eq!(m.mask_levels()[centre], 256);
    assert!(n.cld[centre]);
    assert!(!n.cld[size.index(63, 63, 15).unwrap()]);
}

fn busy_config(size: GridSize, boundary: Boundary, seed: u32) -> Config {
    let mut c = Config::new(size);
    c.boundary = boundary;
    c.seed = seed;
    c.probabilities = Probabilities {
        extinction: 0.2,
        humidity: 0.3,
        activation: 0.05,
    };
    let (nx, ny, nz) = (size.nx as f32, size.ny as f32, size.nz as f32);
    c.ellipsoids = vec![
        Ellipsoid {
            center: [nx * 0.4, ny * 0.5, nz * 0.4],
            radii: [nx * 0.35, ny * 0.4, nz * 0.5],
        },
        Ellipsoid {
            center: [nx * 0.8, ny * 0.3, nz * 0.6],
            radii: [nx * 0.2 + 0.5, ny * 0.3 + 0.5, nz * 0.3 + 0.5],
        },
    ];
    c
}

#[test]
fn naive_equals_packed_on_random_states_seeds_and_thread_counts() {
    let cases = [
        (GridSize::new(37, 5, 4), Boundary::Empty, false, false),
        (GridSize::new(64, 7, 5), Boundary::Empty, true, false),
        (GridSize::new(5, 3, 6), Boundary::Empty, true, true),
        (GridSize::new(1, 1, 1), Boundary::Empty, false, false),
        (GridSize::new(2, 1, 3), Boundary::Periodic, false, true),
        (GridSize::new(96, 4, 3), Boundary::Periodic, true, true),
        (GridSize::new(32, 3, 3), Boundary::Periodic, true, false),
        (GridSize::new(100, 6, 5), Boundary::Empty, true, true),
    ];
    let mut checked = 0;
    for (case, &(size, boundary, ellipsoids, wind)) in cases.iter().enumerate() {
        if boundary == Boundary::Periodic && !size.nx.is_multiple_of(32) {
            let m = Model::new(busy_config(size, boundary, 1));
            assert!(matches!(m, Err(Error::PeriodicWidth { .. })));
            continue;
        }
        for seed in [0u32, 12_345, u32::MAX] {
            let mut c = busy_config(size, boundary, seed);
            if !ellipsoids {
                c.ellipsoids.clear();
            }
            if wind {
                c.wind = (0..size.nz)
                    .map(|z| [0.7 * z as f32 - 1.3, 2.25 - 0.9 * z as f32])
                    .collect();
            }
            let m = Model::new(c).unwrap();
            for (density, threads) in [(0.1f32, 1usize), (0.5, 2), (0.9, 5)] {
                let start =
                    PackedState::random(size, seed ^ case as u32, density, density * 0.5, density)
                        .unwrap();
                let mut reference = start.to_naive();
                let mut fast = start.clone();
                let mut scratch = PackedState::empty(size).unwrap();
                let first_step = seed.wrapping_mul(31);
                for k in 0..8u32 {
                    let step = first_step.wrapping_add(k);
                    reference = naive::step(&m, &reference, step).unwrap();
                    packed::step(&m, &mut fast, &mut scratch, step, threads).unwrap();
                    assert_eq!(
                        fast.to_naive(),
                        reference,
                        "{size:?} {boundary:?} seed {seed} density {density} threads {threads} step {k}"
                    );
                    fast.check().unwrap();
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 100);
}

#[test]
fn result_is_independent_of_thread_count() {
    let size = GridSize::new(160, 48, 12);
    let mut c = busy_config(size, Boundary::Empty, 99);
    c.wind = (0..12).map(|z| [0.3 * z as f32, -0.5]).collect();
    let m = Model::new(c).unwrap();
    let start = PackedState::random(size, 4, 0.4, 0.05, 0.2).unwrap();
    let mut results = vec![];
    for threads in [1usize, 2, 3, 7, 64] {
        let mut sim = Simulation::with_state(m.clone(), start.clone(), 0).unwrap();
        sim.set_threads(threads).unwrap();
        sim.advance(25).unwrap();
        results.push(sim.state().clone());
    }
    assert!(results[0].cloud_count() > 0);
    for r in &results[1..] {
        assert_eq!(r, &results[0]);
    }
}

#[test]
fn wind_moves_slices_with_their_velocity() {
    let size = GridSize::new(40, 8, 3);
    let mut c = Config::new(size);
    c.probabilities = NO_RANDOMNESS;
    c.wind = vec![[1.0, 0.0], [0.5, -1.0], [-2.0, 0.25]];
    let m = Model::new(c.clone()).unwrap();
    let mut s = NaiveState::empty(size).unwrap();
    s.cld[size.index(10, 4, 0).unwrap()] = true;
    s.cld[size.index(10, 4, 1).unwrap()] = true;
    s.cld[size.index(10, 4, 2).unwrap()] = true;
    for step in 0..4 {
        s = step_both(&m, &s, step);
    }
    // after 4 steps: z0 moved +4 in x; z1 +2 in x, -4 in y; z2 -8 in x, +1 in y
    assert_eq!(cells(&s, &s.cld), [(14, 4, 0), (12, 0, 1), (2, 5, 2)]);
    // one more step moves z1 out of the grid (y = -1) with empty boundaries
    s = step_both(&m, &s, 4);
    assert_eq!(cells(&s, &s.cld), [(15, 4, 0), (0, 5, 2)]);
    // periodic wrap
    c.size = GridSize::new(32, 8, 3);
    c.boundary = Boundary::Periodic;
    let m = Model::new(c).unwrap();
    let size = m.size();
    let mut s = NaiveState::empty(size).unwrap();
    s.cld[size.index(1, 0, 2).unwrap()] = true;
    s.cld[size.index(31, 0, 1).unwrap()] = true;
    s = step_both(&m, &s, 0);
    s = step_both(&m, &s, 1);
    // z2: x 1 -> 1-4 = -3 = 29, y 0 + floor(0.5) = 0; z1: x 31 + 1 = 0, y 0 - 2 = 6
    assert_eq!(cells(&s, &s.cld), [(0, 6, 1), (29, 0, 2)]);
}

#[test]
fn bad_calls_are_errors_not_panics() {
    let size = GridSize::new(8, 8, 8);
    let m = model(size, NO_RANDOMNESS, Boundary::Empty);
    let other = PackedState::empty(GridSize::new(8, 8, 4)).unwrap();
    let mut scratch = PackedState::empty(size).unwrap();
    let mut state = PackedState::empty(size).unwrap();
    assert!(matches!(
        packed::step(&m, &mut state, &mut scratch, 0, 0),
        Err(Error::ZeroThreads)
    ));
    let mut wrong = other.clone();
    assert!(matches!(
        packed::step(&m, &mut wrong, &mut scratch, 0, 1),
        Err(Error::SizeMismatch { .. })
    ));
    assert!(matches!(
        naive::step(&m, &other.to_naive(), 0),
        Err(Error::SizeMismatch { .. })
    ));
    assert!(matches!(
        Simulation::with_state(m.clone(), other, 0),
        Err(Error::SizeMismatch { .. })
    ));
    let mut sim = Simulation::new(m).unwrap();
    assert_eq!(sim.set_threads(0), Err(Error::ZeroThreads));
    let mut truncated = state.clone();
    truncated.hum.pop();
    assert!(matches!(
        packed::step(sim.model(), &mut truncated, &mut state, 0, 1),
        Err(Error::SizeMismatch { what: "hum", .. })
    ));
}

#[test]
fn clouds_grow_inside_the_ellipsoid_only() {
    let size = GridSize::new(64, 48, 24);
    let mut c = Config::new(size);
    c.seed = 2000;
    c.ellipsoids = vec![Ellipsoid {
        center: [32.0, 24.0, 12.0],
        radii: [20.0, 14.0, 8.0],
    }];
    c.probabilities = Probabilities {
        extinction: 0.1,
        humidity: 0.1,
        activation: 0.01,
    };
    let m = Model::new(c).unwrap();
    let mut sim = Simulation::new(m).unwrap();
    sim.advance(60).unwrap();
    assert_eq!(sim.step_index(), 60);
    let state = sim.state();
    let inside = state.cloud_count();
    assert!(inside > 500, "{inside} cloud cells");
    for z in 0..size.nz {
        for y in 0..size.ny {
            for x in 0..size.nx {
                if sim.model().mask_level(x, y, z).unwrap() == 0 {
                    assert!(!state.cloud(x, y, z).unwrap());
                }
            }
        }
    }
    let d = sim.density().unwrap();
    assert_eq!(d.len(), size.cells());
    assert!(d.iter().all(|v| (0.0..=1.0).contains(v)));
    assert!(d[size.index(32, 24, 12).unwrap()] > 0.0);
    assert_eq!(d[size.index(0, 0, 0).unwrap()], 0.0);
}
