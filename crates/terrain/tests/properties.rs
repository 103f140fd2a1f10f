//! Property tests: every public constructor, loader and bake of `terrain` takes
//! arbitrary input (NaN, ±inf, 0, huge, negative, wrong lengths, random bytes)
//! without panicking, and every rejection's message names the field at fault.
//!
//! Case counts are modest and maps tiny so `cargo test` stays fast in debug builds.

use proptest::prelude::*;
use terrain::generate::{Fractal, GeneratorParams, Noise, generate};
use terrain::shadow::azimuth_layers;
use terrain::tilted::{Side, bake_east_west_tilted, tilted_horizon_angle};
use terrain::{
    Algorithm, Heightfield, HorizonEncoding, HorizonOptions, MAX_SIDE, NormalMap, TerrainError,
    bake_azimuths, bake_east_west, encode_horizon_angle, horizon_angle,
};

/// Floats that break naive code: NaN, infinities, zeros, signs, extremes, and any value.
fn wild_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(-1.0),
        Just(f64::MAX),
        Just(f64::MIN_POSITIVE),
        Just(1e300),
        -1e6..1e6f64,
        any::<f64>(),
    ]
}

fn wild_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(0.0),
        Just(f32::MAX),
        -1e4..1e4f32,
        any::<f32>(),
    ]
}

/// Sides: mostly small, sometimes 0 or beyond the limit (never a large valid size,
/// which would allocate).
fn wild_side() -> impl Strategy<Value = usize> {
    prop_oneof![
        4 => 0usize..9,
        1 => Just(MAX_SIDE + 1),
        1 => Just(usize::MAX),
    ]
}

/// The rejection names one of `fields` (quoted in backticks, or a texel such as
/// `height at (x = 1, y = 2)`).
fn names_one_of(error: &TerrainError, fields: &[&str]) -> Result<(), TestCaseError> {
    let message = error.to_string();
    prop_assert!(
        fields
            .iter()
            .any(|f| message.contains(&format!("`{f}")) || message.contains(f))
            || matches!(
                error,
                TerrainError::Png { .. } | TerrainError::PixelFormat { .. }
            ),
        "{message:?} names none of {fields:?}"
    );
    Ok(())
}

fn small_field() -> Heightfield {
    Heightfield::from_fn(6, 5, 10.0, |x, y| ((x * 7 + y * 3) % 5) as f32).unwrap()
}

fn wild_options() -> impl Strategy<Value = HorizonOptions> {
    (prop::option::of(wild_f64()), prop::option::of(wild_f64())).prop_map(
        |(effective_radius, max_distance)| HorizonOptions {
            effective_radius,
            max_distance,
            threads: None,
        },
    )
}

const OPTION_FIELDS: &[&str] = &["effective_radius", "max_distance"];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn heightfield_new(
        width in wild_side(),
        height in wild_side(),
        spacing in wild_f64(),
        vertical_scale in wild_f64(),
        samples in prop::collection::vec(wild_f32(), 0..70),
    ) {
        if let Err(e) = Heightfield::new(width, height, spacing, vertical_scale, samples) {
            names_one_of(&e, &["width", "height", "width * height", "spacing",
                "vertical_scale", "samples", "height at"])?;
        }
    }

    #[test]
    fn heightfield_from_fn_and_scale(
        width in wild_side(),
        height in wild_side(),
        spacing in wild_f64(),
        value in wild_f32(),
        scale in wild_f64(),
    ) {
        match Heightfield::from_fn(width, height, spacing, |_, _| value) {
            Ok(hf) => {
                if let Err(e) = hf.with_vertical_scale(scale) {
                    names_one_of(&e, &["vertical_scale", "height at"])?;
                }
            }
            Err(e) => names_one_of(
                &e,
                &["width", "height", "width * height", "spacing", "height at"],
            )?,
        }
    }

    #[test]
    fn heightfield_loaders(
        bytes in prop::collection::vec(any::<u8>(), 0..80),
        width in wild_side(),
        height in wild_side(),
        spacing in wild_f64(),
        scale in wild_f64(),
        offset in wild_f64(),
    ) {
        for result in [
            Heightfield::from_png16(&bytes, spacing, scale, offset),
            Heightfield::from_png8(&bytes, spacing, scale, offset),
        ] {
            if let Err(e) = result {
                names_one_of(&e, &["spacing", "scale", "offset"])?;
            }
        }
        if let Err(e) = Heightfield::from_raw_f32_le(&bytes, width, height, spacing) {
            names_one_of(&e, &["width", "height", "width * height", "spacing",
                "raw f32 bytes", "height at"])?;
        }
    }

    #[test]
    fn png16_writer_round_trips_or_names_the_range(scale in wild_f64(), offset in wild_f64()) {
        let hf = small_field();
        match hf.to_png16(scale, offset) {
            Ok(png) => match Heightfield::from_png16(&png, 10.0, scale, offset) {
                Ok(back) => {
                    // Half a count, plus the f32 rounding of the stored samples.
                    let magnitude = offset.abs() + 65535.0 * scale;
                    for (a, b) in hf.elevations().iter().zip(back.elevations()) {
                        prop_assert!((a - b).abs() <= 0.5 * scale * (1.0 + 1e-6) + 1e-6 * magnitude);
                    }
                }
                Err(e) => names_one_of(&e, &["height at"])?,
            },
            Err(e) => names_one_of(&e, &["scale", "offset"])?,
        }
    }

    #[test]
    fn generator(
        width in wild_side(),
        height in wild_side(),
        spacing in wild_f64(),
        octaves in prop_oneof![0u32..10, Just(u32::MAX)],
        wavelength in wild_f64(),
        amplitude in wild_f64(),
        lacunarity in wild_f64(),
        gain in wild_f64(),
        ridged in any::<bool>(),
    ) {
        let params = GeneratorParams {
            octaves,
            wavelength,
            amplitude,
            lacunarity,
            gain,
            noise: if ridged { Noise::Value } else { Noise::Gradient },
            fractal: if ridged { Fractal::Ridged } else { Fractal::Fbm },
            ..GeneratorParams::new(width, height, spacing, 7)
        };
        if let Err(e) = generate(&params) {
            names_one_of(&e, &["width", "height", "width * height", "spacing", "octaves",
                "wavelength", "amplitude", "lacunarity", "gain", "height at"])?;
        }
    }

    #[test]
    fn bakes_and_single_texel_queries(
        options in wild_options(),
        count in prop_oneof![0usize..10, Just(64), Just(65), Just(usize::MAX)],
        x in prop_oneof![0usize..8, Just(usize::MAX)],
        y in prop_oneof![0usize..8, Just(usize::MAX)],
        azimuth in wild_f64(),
        latitude in wild_f64(),
    ) {
        let hf = small_field();
        if let Err(e) = bake_east_west(&hf, &options, Algorithm::HullSweep) {
            names_one_of(&e, OPTION_FIELDS)?;
        }
        if let Err(e) = bake_azimuths(&hf, count, &options, Algorithm::BruteForce) {
            names_one_of(&e, &["count", "effective_radius", "max_distance"])?;
        }
        if let Err(e) = horizon_angle(&hf, x, y, azimuth, &options) {
            names_one_of(&e, &["x", "y", "azimuth", "effective_radius", "max_distance"])?;
        }
        if let Err(e) = terrain::raycast::ray_cast_horizon_angle(&hf, x, y, azimuth, &options) {
            names_one_of(&e, &["x", "y", "azimuth", "effective_radius", "max_distance"])?;
        }
        if let Err(e) = bake_east_west_tilted(&hf, latitude, &options) {
            names_one_of(&e, &["latitude", "effective_radius", "max_distance"])?;
        }
        if let Err(e) = tilted_horizon_angle(&hf, x, y, Side::West, latitude, &options) {
            names_one_of(&e, &["x", "y", "latitude", "effective_radius", "max_distance"])?;
        }
    }

    #[test]
    fn accessors_and_encodings(
        x in prop_oneof![0usize..8, Just(usize::MAX)],
        y in prop_oneof![0usize..8, Just(usize::MAX)],
        angle in wild_f32(),
        azimuth in wild_f32(),
        count in prop_oneof![0u32..4, any::<u32>()],
    ) {
        let hf = small_field();
        let maps = bake_east_west(&hf, &HorizonOptions::flat(), Algorithm::HullSweep).unwrap();
        let checks = [
            maps.east.angle(x, y).map(|_| ()),
            hf.elevation(x, y).map(|_| ()),
            NormalMap::from_heightfield(&hf).normal(x, y).map(|_| ()),
        ];
        for result in checks {
            match result {
                Ok(()) => prop_assert!(x < 6 && y < 5),
                Err(e) => names_one_of(&e, &["x", "y"])?,
            }
        }
        match encode_horizon_angle(angle) {
            Ok(v) => prop_assert!((0.0..=1.0).contains(&v)),
            Err(e) => names_one_of(&e, &["angle"])?,
        }
        for encoding in HorizonEncoding::ALL {
            if let Err(e) = encoding.round_trip(angle) {
                names_one_of(&e, &["angle"])?;
            }
        }
        match azimuth_layers(azimuth, count) {
            Ok(l) => prop_assert!(l.lower < count && l.upper < count),
            Err(e) => names_one_of(&e, &["count", "sun_azimuth"])?,
        }
    }
}
