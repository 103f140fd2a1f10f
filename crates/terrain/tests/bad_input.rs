//! Bad input to terrain's accessors and encoders is a typed error naming the field,
//! never a panic, a silent clamp or a silent wrong texel.

use terrain::shadow::azimuth_layers;
use terrain::{
    Algorithm, HorizonEncoding, HorizonOptions, NormalMap, TerrainError, bake_azimuths,
    bake_east_west, encode_horizon_angle, encode_horizon_unorm8, encode_horizon_unorm16,
};

fn hill() -> terrain::Heightfield {
    terrain::Heightfield::from_fn(5, 4, 10.0, |x, y| (x * y) as f32).unwrap()
}

#[test]
fn out_of_range_texels_name_the_coordinate() {
    let hf = hill();
    let maps = bake_east_west(&hf, &HorizonOptions::flat(), Algorithm::HullSweep).unwrap();
    // x = 5 on a 5-wide map must not read texel (0, y + 1).
    for (result, field) in [
        (maps.east.angle(5, 0).map(|_| ()), "x"),
        (maps.east.angle(0, 4).map(|_| ()), "y"),
        (hf.elevation(5, 0).map(|_| ()), "x"),
        (hf.elevation(0, 9).map(|_| ()), "y"),
        (
            NormalMap::from_heightfield(&hf).normal(7, 0).map(|_| ()),
            "x",
        ),
    ] {
        let error = result.unwrap_err();
        assert!(
            matches!(error, TerrainError::OutOfRange { field: f, .. } if f == field),
            "{error}"
        );
        assert!(error.to_string().contains(&format!("`{field}`")), "{error}");
    }
    let stack = bake_azimuths(&hf, 4, &HorizonOptions::flat(), Algorithm::HullSweep).unwrap();
    assert!(stack.horizon_angle(5, 0, 0.3).is_err());
    assert!(stack.horizon_angle(0, 0, f32::NAN).is_err());
    assert!(stack.horizon_angle(4, 3, 0.3).is_ok());
}

#[test]
fn azimuth_layers_rejects_zero_layers_and_non_finite_azimuths() {
    let error = azimuth_layers(1.0, 0).unwrap_err();
    assert!(error.to_string().contains("`count`"), "{error}");
    for azimuth in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let error = azimuth_layers(azimuth, 8).unwrap_err();
        assert!(error.to_string().contains("`sun_azimuth`"), "{error}");
    }
    let l = azimuth_layers(1e30, 8).unwrap();
    assert!(l.lower < 8 && l.upper < 8);
}

#[test]
fn png16_rejects_elevations_it_cannot_hold_instead_of_clamping() {
    let hf = hill(); // elevations 0..=12 m
    let error = hf.to_png16(0.1, 5.0).unwrap_err();
    assert!(
        matches!(
            error,
            TerrainError::ElevationNotRepresentable { x: 0, y: 0, .. }
        ),
        "{error}"
    );
    assert!(error.to_string().contains("`scale, offset`"), "{error}");
    // 12 m at 1 mm per count is 12,000 counts: representable.
    assert!(hf.to_png16(0.001, 0.0).is_ok());
    // 12 m at 0.1 mm per count is 120,000 counts: not.
    let error = hf.to_png16(0.0001, 0.0).unwrap_err();
    assert!(
        matches!(error, TerrainError::ElevationNotRepresentable { .. }),
        "{error}"
    );
}

#[test]
fn horizon_encodings_reject_nan_and_angles_beyond_the_poles() {
    for angle in [f32::NAN, 1.6, -1.6, f32::INFINITY] {
        for result in [
            encode_horizon_angle(angle).map(|_| ()),
            encode_horizon_unorm8(angle).map(|_| ()),
            encode_horizon_unorm16(angle).map(|_| ()),
        ] {
            let error = result.unwrap_err();
            assert!(error.to_string().contains("`angle`"), "{error}");
        }
        for encoding in HorizonEncoding::ALL {
            assert!(encoding.round_trip(angle).is_err(), "{encoding:?} {angle}");
        }
    }
    // f32's π/2 (4.4e-8 above π/2) is the end of the range, not an error.
    assert_eq!(
        encode_horizon_unorm16(std::f32::consts::FRAC_PI_2).unwrap(),
        65535
    );
}

/// A finite but huge `max_distance` means "no limit", like +inf (counting steps up to
/// `max_distance / spacing` would be about 10^299 iterations for 1e300 m).
#[test]
fn a_huge_finite_max_distance_is_no_limit_not_a_hang() {
    let hf = hill();
    let options = |max_distance| HorizonOptions {
        max_distance: Some(max_distance),
        ..HorizonOptions::flat()
    };
    for algorithm in [Algorithm::HullSweep, Algorithm::BruteForce] {
        let huge = bake_east_west(&hf, &options(1e300), algorithm).unwrap();
        let unlimited = bake_east_west(&hf, &options(f64::INFINITY), algorithm).unwrap();
        assert_eq!(huge, unlimited);
        let max = bake_east_west(&hf, &options(f64::MAX), algorithm).unwrap();
        assert_eq!(max, unlimited);
    }
}

#[test]
fn a_generator_finer_than_the_lattice_hash_can_index_is_rejected() {
    use terrain::generate::{GeneratorParams, generate};
    // 16 octaves of lacunarity 1e6 from a 1 m wavelength: the finest octave would sample
    // lattice cell 10^91 (which must not overflow the corner index and panic).
    let params = GeneratorParams {
        octaves: 16,
        wavelength: 1.0,
        lacunarity: 1e6,
        ..GeneratorParams::new(4, 4, 10.0, 7)
    };
    let error = generate(&params).unwrap_err();
    assert!(
        matches!(
            error,
            TerrainError::InvalidParameter {
                field: "wavelength",
                ..
            }
        ),
        "{error}"
    );
    // The defaults stay well inside the limit.
    assert!(generate(&GeneratorParams::new(64, 64, 30.0, 7)).is_ok());
}
