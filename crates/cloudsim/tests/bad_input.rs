//! Cell coordinates outside the grid are a typed error naming the coordinate, not a
//! silent read of the next row.

use cloudsim::{Config, Error, GridSize, Model, PackedState};

#[test]
fn out_of_range_cells_name_the_coordinate() {
    let size = GridSize::new(40, 3, 2);
    let model = Model::new(Config::new(size)).unwrap();
    let state = PackedState::empty(size).unwrap();
    for (x, y, z, field) in [(40, 0, 0, "x"), (0, 3, 0, "y"), (0, 0, 2, "z")] {
        for error in [
            size.index(x, y, z).unwrap_err(),
            model.mask_level(x, y, z).unwrap_err(),
            state.cloud(x, y, z).unwrap_err(),
        ] {
            assert!(
                matches!(error, Error::CellOutOfRange { field: f, .. } if f == field),
                "{error}"
            );
            assert!(error.to_string().contains(&format!("`{field}`")), "{error}");
        }
    }
    // x = 40 must not alias cell (0, 1, 0); the last cell is still reachable.
    assert_eq!(size.index(39, 2, 1).unwrap(), size.cells() - 1);
    assert_eq!(size.index(0, 1, 0).unwrap(), 40);
    assert!(!state.cloud(39, 2, 1).unwrap());
}

#[test]
fn random_states_reject_probabilities_the_draws_cannot_resolve() {
    let size = GridSize::new(32, 2, 2);
    for (hum, act, cld, field) in [
        (1e-6, 0.0, 0.0, "`hum`"),
        (0.0, f32::NAN, 0.0, "`act`"),
        (0.0, 0.0, 1.5, "`cld`"),
    ] {
        let error = PackedState::random(size, 1, hum, act, cld).unwrap_err();
        assert!(error.to_string().contains(field), "{error}");
    }
    assert!(PackedState::random(size, 1, 0.5, 0.0, 1.0).is_ok());
}
