//! Heightfield loaders, the generator and their error cases.

use image::ImageEncoder as _;
use terrain::generate::{Fractal, GeneratorParams, Noise, generate};
use terrain::{Heightfield, MAX_SIDE, TerrainError};

fn png(data: &[u8], width: u32, height: u32, color: image::ExtendedColorType) -> Vec<u8> {
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(data, width, height, color)
        .unwrap();
    out
}

fn png16(values: &[u16], width: u32, height: u32) -> Vec<u8> {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
    png(&bytes, width, height, image::ExtendedColorType::L16)
}

#[test]
fn png16_loads_with_scale_and_offset() {
    let values = [0u16, 1, 65535, 30000, 12345, 7];
    let hf = Heightfield::from_png16(&png16(&values, 3, 2), 30.0, 0.1, -100.0).unwrap();
    assert_eq!((hf.width(), hf.height(), hf.spacing()), (3, 2, 30.0));
    for (i, &v) in values.iter().enumerate() {
        let expected = -100.0 + 0.1 * f64::from(v);
        assert!(
            (hf.elevation(i % 3, i / 3).unwrap() - expected).abs() < 1e-3,
            "texel {i}"
        );
    }
    // Round trip through the 16-bit writer.
    let again =
        Heightfield::from_png16(&hf.to_png16(0.1, -100.0).unwrap(), 30.0, 0.1, -100.0).unwrap();
    for (a, b) in hf.samples().iter().zip(again.samples()) {
        assert!((a - b).abs() < 1e-3);
    }
}

#[test]
fn png8_loads_with_scale_and_offset() {
    let data = [0u8, 128, 255, 3];
    let hf = Heightfield::from_png8(
        &png(&data, 2, 2, image::ExtendedColorType::L8),
        1.0,
        10.0,
        5.0,
    )
    .unwrap();
    assert_eq!(hf.samples(), &[5.0, 1285.0, 2555.0, 35.0]);
}

#[test]
fn wrong_bit_depth_and_layout_are_rejected() {
    let eight = png(&[1, 2, 3, 4], 2, 2, image::ExtendedColorType::L8);
    let err = Heightfield::from_png16(&eight, 1.0, 1.0, 0.0).unwrap_err();
    assert!(matches!(err, TerrainError::PixelFormat { .. }), "{err}");
    assert!(
        err.to_string().contains("L8") && err.to_string().contains("16-bit"),
        "{err}"
    );
    let sixteen = png16(&[1, 2], 2, 1);
    let err = Heightfield::from_png8(&sixteen, 1.0, 1.0, 0.0).unwrap_err();
    assert!(err.to_string().contains("L16"), "{err}");
    let rgb = png(&[0; 12], 2, 2, image::ExtendedColorType::Rgb8);
    let err = Heightfield::from_png8(&rgb, 1.0, 1.0, 0.0).unwrap_err();
    assert!(err.to_string().contains("Rgb8"), "{err}");
}

#[test]
fn corrupt_and_truncated_png_are_errors() {
    let good = png16(&[1, 2, 3, 4], 2, 2);
    let err = Heightfield::from_png16(&good[..good.len() - 20], 1.0, 1.0, 0.0).unwrap_err();
    assert!(matches!(err, TerrainError::Png { .. }), "{err}");
    let err = Heightfield::from_png16(b"not a png at all", 1.0, 1.0, 0.0).unwrap_err();
    assert!(matches!(err, TerrainError::Png { .. }), "{err}");
    let err = Heightfield::from_png16(&[], 1.0, 1.0, 0.0).unwrap_err();
    assert!(matches!(err, TerrainError::Png { .. }), "{err}");
}

#[test]
fn oversized_png_is_rejected_before_decoding() {
    let wide = png(
        &vec![0u8; MAX_SIDE + 1],
        (MAX_SIDE + 1) as u32,
        1,
        image::ExtendedColorType::L8,
    );
    let err = Heightfield::from_png8(&wide, 1.0, 1.0, 0.0).unwrap_err();
    assert!(
        matches!(err, TerrainError::TooLarge { field: "width", value, .. } if value == (MAX_SIDE + 1) as u64),
        "{err}"
    );
}

#[test]
fn raw_f32_loads_and_checks_size() {
    let values = [1.0f32, -2.5, 8848.86, 0.0, 3.0, 4.0];
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    let hf = Heightfield::from_raw_f32_le(&bytes, 3, 2, 5.0).unwrap();
    assert_eq!(hf.samples(), &values);
    assert_eq!(hf.elevation(2, 0).unwrap(), f64::from(8848.86f32));
    let err = Heightfield::from_raw_f32_le(&bytes[..23], 3, 2, 5.0).unwrap_err();
    assert!(
        matches!(
            err,
            TerrainError::SizeMismatch {
                expected: 24,
                found: 23,
                ..
            }
        ),
        "{err}"
    );
    let err = Heightfield::from_raw_f32_le(&bytes, 2, 2, 5.0).unwrap_err();
    assert!(err.to_string().contains("expected 16"), "{err}");
}

#[test]
fn zero_size_and_limits() {
    let err = Heightfield::from_raw_f32_le(&[], 0, 4, 1.0).unwrap_err();
    assert!(
        matches!(err, TerrainError::ZeroSize { field: "width" }),
        "{err}"
    );
    let err = Heightfield::from_raw_f32_le(&[], 4, 0, 1.0).unwrap_err();
    assert!(
        matches!(err, TerrainError::ZeroSize { field: "height" }),
        "{err}"
    );
    let err = Heightfield::from_raw_f32_le(&[], 40_000, 1, 1.0).unwrap_err();
    assert!(err.to_string().contains("`width` = 40000"), "{err}");
    // Each side within limits but the product too large: no allocation attempted.
    let err = Heightfield::from_raw_f32_le(&[], 20_000, 20_000, 1.0).unwrap_err();
    assert!(
        matches!(
            err,
            TerrainError::TooLarge {
                field: "width * height",
                ..
            }
        ),
        "{err}"
    );
}

#[test]
fn non_finite_heights_name_the_texel() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mut values = [0.0f32; 12];
        values[7] = bad;
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let err = Heightfield::from_raw_f32_le(&bytes, 4, 3, 1.0).unwrap_err();
        assert!(
            matches!(err, TerrainError::NonFiniteHeight { x: 3, y: 1, .. }),
            "{err}"
        );
    }
    // Finite samples that overflow after scaling are caught too.
    let err = Heightfield::new(1, 1, 1.0, 1e300, vec![f32::MAX]).unwrap_err();
    assert!(matches!(err, TerrainError::NonFiniteHeight { .. }), "{err}");
}

#[test]
fn bad_parameters_name_field_and_value() {
    for spacing in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = Heightfield::new(1, 1, spacing, 1.0, vec![0.0]).unwrap_err();
        assert!(err.to_string().contains("`spacing`"), "{err}");
    }
    let err = Heightfield::new(1, 1, 1.0, 0.0, vec![0.0]).unwrap_err();
    assert!(err.to_string().contains("`vertical_scale` = 0"), "{err}");
    let err = Heightfield::new(2, 2, 1.0, 1.0, vec![0.0; 3]).unwrap_err();
    assert!(
        err.to_string()
            .contains("`samples` has length 3, expected 4"),
        "{err}"
    );
    let png = png16(&[1], 1, 1);
    assert!(
        Heightfield::from_png16(&png, 1.0, -1.0, 0.0)
            .unwrap_err()
            .to_string()
            .contains("`scale`")
    );
    assert!(
        Heightfield::from_png16(&png, 1.0, 1.0, f64::NAN)
            .unwrap_err()
            .to_string()
            .contains("`offset`")
    );
    let err = Heightfield::open_png16("/nonexistent/terrain.png", 1.0, 1.0, 0.0).unwrap_err();
    assert!(
        matches!(err, TerrainError::Io { .. })
            && err.to_string().contains("/nonexistent/terrain.png")
    );
}

#[test]
fn vertical_scale_multiplies_elevation() {
    let hf = Heightfield::new(2, 1, 1.0, 1.0, vec![1.0, 2.0]).unwrap();
    let hf = hf.with_vertical_scale(3.0).unwrap();
    assert_eq!(hf.elevation(1, 0).unwrap(), 6.0);
    assert_eq!(hf.elevations(), vec![3.0, 6.0]);
}

#[test]
fn generator_is_deterministic_and_seed_dependent() {
    for noise in [Noise::Value, Noise::Gradient] {
        for fractal in [Fractal::Fbm, Fractal::Ridged] {
            let params = GeneratorParams {
                noise,
                fractal,
                ..GeneratorParams::new(64, 48, 10.0, 42)
            };
            let a = generate(&params).unwrap();
            assert_eq!(a, generate(&params).unwrap());
            let b = generate(&GeneratorParams { seed: 43, ..params }).unwrap();
            assert_ne!(a, b);
            let (lo, hi) = a
                .samples()
                .iter()
                .fold((f32::MAX, f32::MIN), |(l, h), &v| (l.min(v), h.max(v)));
            assert!(
                lo >= 0.0 && hi <= 1000.0,
                "{noise:?} {fractal:?}: {lo}..{hi}"
            );
            // Real relief, not a constant.
            assert!(hi - lo > 50.0, "{noise:?} {fractal:?}: {lo}..{hi}");
        }
    }
    let fbm = generate(&GeneratorParams::new(32, 32, 10.0, 1)).unwrap();
    let ridged = generate(&GeneratorParams {
        fractal: Fractal::Ridged,
        ..GeneratorParams::new(32, 32, 10.0, 1)
    })
    .unwrap();
    assert_ne!(fbm, ridged);
    // Pinned value: the generator must not drift between platforms or versions.
    let pinned = generate(&GeneratorParams::new(8, 8, 1.0, 2026)).unwrap();
    assert_eq!(pinned.samples()[27], 447.511_05);
}

#[test]
fn generator_rejects_bad_parameters() {
    let base = GeneratorParams::new(8, 8, 1.0, 0);
    let cases = [
        (GeneratorParams { octaves: 0, ..base }, "octaves"),
        (
            GeneratorParams {
                octaves: 25,
                ..base
            },
            "octaves",
        ),
        (
            GeneratorParams {
                wavelength: 0.0,
                ..base
            },
            "wavelength",
        ),
        (
            GeneratorParams {
                amplitude: f64::NAN,
                ..base
            },
            "amplitude",
        ),
        (
            GeneratorParams {
                spacing: -1.0,
                ..base
            },
            "spacing",
        ),
        (GeneratorParams { width: 0, ..base }, "width"),
    ];
    for (params, field) in cases {
        let err = generate(&params).unwrap_err();
        assert!(err.to_string().contains(field), "{field}: {err}");
    }
}
