//! Horizon-angle storage encodings (u8, u16 unorm, f32).

use std::f32::consts::{FRAC_PI_2, PI};

use terrain::{
    BitDepth, HorizonEncoding, NormalMap, decode_horizon_unorm8, decode_horizon_unorm16,
    encode_horizon_unorm8, encode_horizon_unorm16,
};

#[test]
fn endpoints_and_middle_are_exact_codes() {
    assert_eq!(encode_horizon_unorm8(-FRAC_PI_2).unwrap(), 0);
    assert_eq!(encode_horizon_unorm8(FRAC_PI_2).unwrap(), 255);
    assert_eq!(encode_horizon_unorm8(0.0).unwrap(), 128); // 127.5 rounds away from zero
    assert_eq!(encode_horizon_unorm16(-FRAC_PI_2).unwrap(), 0);
    assert_eq!(encode_horizon_unorm16(FRAC_PI_2).unwrap(), 65535);
    assert_eq!(decode_horizon_unorm8(0), -FRAC_PI_2);
    assert!((decode_horizon_unorm8(255) - FRAC_PI_2).abs() < 2e-7);
    assert!((decode_horizon_unorm16(65535) - FRAC_PI_2).abs() < 2e-7);
}

#[test]
fn every_code_round_trips() {
    for q in 0..=255u8 {
        assert_eq!(encode_horizon_unorm8(decode_horizon_unorm8(q)).unwrap(), q);
    }
    for q in 0..=65535u16 {
        assert_eq!(
            encode_horizon_unorm16(decode_horizon_unorm16(q)).unwrap(),
            q
        );
    }
}

#[test]
fn round_trip_error_is_at_most_half_a_step() {
    for encoding in HorizonEncoding::ALL {
        let allowed = encoding.max_quantisation_error() + 4e-7;
        let mut worst = 0.0f64;
        for i in 0..=100_000 {
            let angle = -FRAC_PI_2 + PI * i as f32 / 100_000.0;
            let angle = angle.clamp(-FRAC_PI_2, FRAC_PI_2);
            let error = f64::from((encoding.round_trip(angle).unwrap() - angle).abs());
            worst = worst.max(error);
        }
        assert!(worst <= allowed, "{encoding:?}: {worst} > {allowed}");
        // The bound is tight: half a step is reached (to within 2 %).
        if encoding != HorizonEncoding::F32 {
            assert!(
                worst >= 0.98 * encoding.max_quantisation_error(),
                "{encoding:?}: {worst}"
            );
        } else {
            assert_eq!(worst, 0.0);
        }
    }
    assert_eq!(HorizonEncoding::Unorm8.bytes(), 1);
    assert_eq!(HorizonEncoding::Unorm16.bytes(), 2);
    assert_eq!(HorizonEncoding::F32.bytes(), 4);
}

#[test]
fn rgba_png_alpha_holds_the_same_codes() {
    let hf = terrain::Heightfield::from_fn(16, 8, 10.0, |x, y| ((x * 7 + y * 3) % 11) as f32 * 9.0)
        .unwrap();
    let normals = NormalMap::from_heightfield(&hf);
    let maps = terrain::bake_east_west(
        &hf,
        &terrain::HorizonOptions::default(),
        terrain::Algorithm::HullSweep,
    )
    .unwrap();
    let png8 = normals.to_rgba_png(&maps.east, BitDepth::Eight).unwrap();
    let img8 = image::load_from_memory(&png8).unwrap().to_rgba8();
    let png16 = normals.to_rgba_png(&maps.east, BitDepth::Sixteen).unwrap();
    let img16 = image::load_from_memory(&png16).unwrap().to_rgba16();
    for y in 0..8 {
        for x in 0..16 {
            let angle = maps.east.angle(x, y).unwrap();
            assert_eq!(
                img8.get_pixel(x as u32, y as u32)[3],
                encode_horizon_unorm8(angle).unwrap()
            );
            assert_eq!(
                img16.get_pixel(x as u32, y as u32)[3],
                encode_horizon_unorm16(angle).unwrap()
            );
        }
    }
}
