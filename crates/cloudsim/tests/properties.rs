//! Property tests: every public constructor and loader of `cloudsim` takes arbitrary
//! input (NaN, ±inf, 0, huge, negative, wrong lengths) without panicking, and every
//! rejection's message names the field at fault.
//!
//! Grids stay tiny (valid sizes up to 12³) so `cargo test` stays fast in debug builds.

use cloudsim::{
    Boundary, Config, Ellipsoid, Error, GridSize, MAX_DIMENSION, Model, NaiveState, PackedState,
    Probabilities, Simulation, Smoothing,
};
use proptest::prelude::*;

fn wild_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(-1.0),
        Just(1.0),
        Just(1e-6),
        Just(f32::MAX),
        0.0..1.0f32,
        -40.0..40.0f32,
        any::<f32>(),
    ]
}

/// Small dimensions, sometimes 0 or beyond the limit (never a large valid one).
fn wild_dimension() -> impl Strategy<Value = u32> {
    prop_oneof![
        6 => 0u32..13,
        1 => Just(32),
        1 => Just(MAX_DIMENSION + 1),
        1 => Just(u32::MAX),
    ]
}

fn wild_size() -> impl Strategy<Value = GridSize> {
    (wild_dimension(), wild_dimension(), wild_dimension())
        .prop_map(|(nx, ny, nz)| GridSize::new(nx, ny, nz))
}

/// The rejection names one of `fields` (every message quotes the field in backticks).
fn names_one_of(error: &Error, fields: &[&str]) -> Result<(), TestCaseError> {
    let message = error.to_string();
    prop_assert!(
        fields.iter().any(|f| message.contains(f)),
        "{message:?} names none of {fields:?}"
    );
    Ok(())
}

const SIZE_FIELDS: &[&str] = &["size.nx", "size.ny", "size.nz", "grid "];

fn wild_config() -> impl Strategy<Value = Config> {
    (
        wild_size(),
        any::<bool>(),
        (wild_f32(), wild_f32(), wild_f32()),
        prop::collection::vec(
            (
                [wild_f32(), wild_f32(), wild_f32()],
                [wild_f32(), wild_f32(), wild_f32()],
            ),
            0..3,
        ),
        prop::collection::vec([wild_f32(), wild_f32()], 0..4),
        prop::collection::vec(wild_f32(), 0..4),
        (0u32..12, 0u32..20),
    )
        .prop_map(
            |(
                size,
                periodic,
                (extinction, humidity, activation),
                ellipsoids,
                wind,
                slice_density,
                (radius_cells, radius_steps),
            )| Config {
                size,
                boundary: if periodic {
                    Boundary::Periodic
                } else {
                    Boundary::Empty
                },
                seed: 3,
                probabilities: Probabilities {
                    extinction,
                    humidity,
                    activation,
                },
                ellipsoids: ellipsoids
                    .into_iter()
                    .map(|(center, radii)| Ellipsoid { center, radii })
                    .collect(),
                wind,
                slice_density,
                smoothing: Smoothing {
                    radius_cells,
                    radius_steps,
                },
            },
        )
}

const CONFIG_FIELDS: &[&str] = &[
    "size.nx",
    "size.ny",
    "size.nz",
    "grid ",
    "probabilities.",
    "ellipsoids[",
    "`wind",
    "`slice_density",
    "smoothing.",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn grid_size_validate_and_index(
        size in (
            prop_oneof![wild_dimension(), Just(MAX_DIMENSION)],
            prop_oneof![wild_dimension(), Just(MAX_DIMENSION)],
            prop_oneof![wild_dimension(), Just(MAX_DIMENSION)],
        ).prop_map(|(nx, ny, nz)| GridSize::new(nx, ny, nz)),
        x in prop_oneof![0u32..14, any::<u32>()],
        y in prop_oneof![0u32..14, any::<u32>()],
        z in prop_oneof![0u32..14, any::<u32>()],
    ) {
        if let Err(e) = size.validate() {
            names_one_of(&e, SIZE_FIELDS)?;
        } else {
            match size.index(x, y, z) {
                Ok(i) => prop_assert!(i < size.cells()),
                Err(e) => names_one_of(&e, &["`x`", "`y`", "`z`"])?,
            }
        }
    }

    #[test]
    fn model_new(config in wild_config()) {
        if let Err(e) = Model::new(config) {
            names_one_of(&e, CONFIG_FIELDS)?;
        }
    }

    #[test]
    fn states(
        size in wild_size(),
        hum in wild_f32(),
        act in wild_f32(),
        cld in wild_f32(),
        extra in 0usize..3,
    ) {
        if let Err(e) = PackedState::empty(size) {
            names_one_of(&e, SIZE_FIELDS)?;
        }
        if let Err(e) = PackedState::random(size, 9, hum, act, cld) {
            names_one_of(&e, &["size.nx", "size.ny", "size.nz", "grid ", "hum", "act", "cld"])?;
        }
        match NaiveState::empty(size) {
            Ok(mut naive) => {
                // Lengths that disagree with the grid.
                naive.act.extend(std::iter::repeat_n(true, extra));
                if let Err(e) = PackedState::from_naive(&naive) {
                    prop_assert!(extra > 0);
                    names_one_of(&e, &["`act`"])?;
                }
            }
            Err(e) => names_one_of(&e, SIZE_FIELDS)?,
        }
    }

    #[test]
    fn simulation(
        (nx, ny, nz) in (1u32..12, 1u32..12, 1u32..6),
        seed in any::<u32>(),
        wind in (-16.0..16.0f32, -16.0..16.0f32),
        steps in 0u32..3,
        threads in 0usize..3,
    ) {
        let size = GridSize::new(nx, ny, nz);
        let model = Model::new(Config {
            seed,
            wind: vec![[wind.0, wind.1]; nz as usize],
            ..Config::new(size)
        })
        .unwrap();
        let mut sim = Simulation::new(model).unwrap();
        if let Err(e) = sim.set_threads(threads) {
            prop_assert_eq!(threads, 0);
            names_one_of(&e, &["`threads`"])?;
        }
        sim.advance(steps).unwrap();
        let density = sim.density().unwrap();
        prop_assert!(density.iter().all(|d| d.is_finite() && *d >= 0.0));
    }
}
