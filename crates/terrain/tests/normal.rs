//! Normal maps and their export.

use terrain::twins::decode_horizon_angle;
use terrain::{
    Algorithm, BitDepth, Heightfield, HorizonOptions, NormalMap, bake_east_west,
    encode_horizon_angle,
};

fn close(a: [f32; 3], b: [f64; 3]) -> bool {
    let len = (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt();
    a.iter()
        .zip(b)
        .all(|(&x, y)| (f64::from(x) - y / len).abs() < 1e-6)
}

#[test]
fn flat_and_planes_use_the_true_spacing() {
    let flat = NormalMap::from_heightfield(&Heightfield::from_fn(5, 4, 7.0, |_, _| 3.0).unwrap());
    assert!(flat.normals().iter().all(|&n| n == [0.0, 0.0, 1.0]));
    // Rising to the east by 1 m per texel at 2 m spacing: slope 0.5, facing west.
    let east =
        NormalMap::from_heightfield(&Heightfield::from_fn(6, 3, 2.0, |x, _| x as f32).unwrap());
    for y in 0..3 {
        for x in 0..6 {
            assert!(
                close(east.normal(x, y).unwrap(), [-0.5, 0.0, 1.0]),
                "({x},{y}) {:?}",
                east.normal(x, y).unwrap()
            );
        }
    }
    // Rising to the south (rows) faces north: +y.
    let south =
        NormalMap::from_heightfield(&Heightfield::from_fn(3, 6, 4.0, |_, y| y as f32).unwrap());
    assert!(south.normals().iter().all(|&n| close(n, [0.0, 0.25, 1.0])));
}

#[test]
fn central_inside_one_sided_at_edges() {
    // h = x^2: central difference 2x inside, (h1 - h0) = 1 at x = 0, (h4 - h3) = 7 at x = 4.
    let n = NormalMap::from_heightfield(
        &Heightfield::from_fn(5, 1, 1.0, |x, _| (x * x) as f32).unwrap(),
    );
    assert!(close(n.normal(0, 0).unwrap(), [-1.0, 0.0, 1.0]));
    assert!(close(n.normal(2, 0).unwrap(), [-4.0, 0.0, 1.0]));
    assert!(close(n.normal(4, 0).unwrap(), [-7.0, 0.0, 1.0]));
    // A single texel (or a single row's y derivative) has zero slope.
    let one = NormalMap::from_heightfield(&Heightfield::from_fn(1, 1, 1.0, |_, _| 9000.0).unwrap());
    assert_eq!(one.normals(), &[[0.0, 0.0, 1.0]]);
}

#[test]
fn steep_extremes_stay_unit_and_finite() {
    for spacing in [0.01, 1000.0] {
        let hf = Heightfield::from_fn(
            4,
            4,
            spacing,
            |x, y| if (x + y) % 2 == 0 { 9000.0 } else { 0.0 },
        )
        .unwrap();
        for n in NormalMap::from_heightfield(&hf).normals() {
            let len = n.iter().map(|c| c * c).sum::<f32>().sqrt();
            assert!(
                n.iter().all(|c| c.is_finite()) && (len - 1.0).abs() < 1e-5,
                "{n:?}"
            );
        }
    }
}

#[test]
fn png_and_f32_exports_decode_back() {
    let hf = Heightfield::from_fn(6, 5, 3.0, |x, y| (x * y) as f32).unwrap();
    let normals = NormalMap::from_heightfield(&hf);
    let maps = bake_east_west(&hf, &HorizonOptions::flat(), Algorithm::HullSweep).unwrap();

    let rgb8 = image::load_from_memory(&normals.to_png(BitDepth::Eight).unwrap())
        .unwrap()
        .to_rgb8();
    let flat_px = rgb8.get_pixel(0, 0).0;
    let n0 = normals.normal(0, 0).unwrap();
    for c in 0..3 {
        let decoded = f32::from(flat_px[c]) / 255.0 * 2.0 - 1.0;
        assert!(
            (decoded - n0[c]).abs() <= 1.0 / 255.0 + 1e-6,
            "{c}: {decoded} vs {} ({flat_px:?})",
            n0[c]
        );
    }

    let rgba16 =
        image::load_from_memory(&normals.to_rgba_png(&maps.east, BitDepth::Sixteen).unwrap())
            .unwrap()
            .to_rgba16();
    assert_eq!(rgba16.dimensions(), (6, 5));
    for y in 0..5u32 {
        for x in 0..6u32 {
            let px = rgba16.get_pixel(x, y).0;
            let angle = decode_horizon_angle(f32::from(px[3]) / 65535.0);
            let exact = maps.east.angle(x as usize, y as usize).unwrap();
            assert!(
                (angle - exact).abs() <= std::f32::consts::PI / 65535.0,
                "({x},{y}) {angle} vs {exact}"
            );
            let n = normals.normal(x as usize, y as usize).unwrap();
            for c in 0..3 {
                assert!(
                    (f32::from(px[c]) / 65535.0 * 2.0 - 1.0 - n[c]).abs() <= 1.0 / 65535.0 + 1e-6
                );
            }
        }
    }
    let rgba8 = image::load_from_memory(&normals.to_rgba_png(&maps.west, BitDepth::Eight).unwrap())
        .unwrap()
        .to_rgba8();
    let angle = decode_horizon_angle(f32::from(rgba8.get_pixel(0, 0).0[3]) / 255.0);
    assert_eq!(maps.west.angle(0, 0).unwrap(), -std::f32::consts::FRAC_PI_2);
    assert!((angle - maps.west.angle(0, 0).unwrap()).abs() <= std::f32::consts::PI / 255.0);

    let rgba_f32 = normals.to_rgba_f32(&maps.east).unwrap();
    assert_eq!(rgba_f32[7][3], maps.east.angles()[7]);
    assert_eq!(normals.to_f32_le().len(), 6 * 5 * 12);
    assert_eq!(
        &normals.to_f32_le()[12..16],
        &normals.normal(1, 0).unwrap()[0].to_le_bytes()
    );

    // Encoding endpoints.
    assert_eq!(
        encode_horizon_angle(-std::f32::consts::FRAC_PI_2).unwrap(),
        0.0
    );
    assert!((encode_horizon_angle(0.0).unwrap() - 0.5).abs() < 1e-9);

    // A horizon map of another size is rejected.
    let other = bake_east_west(
        &Heightfield::from_fn(2, 2, 1.0, |_, _| 0.0).unwrap(),
        &HorizonOptions::flat(),
        Algorithm::HullSweep,
    )
    .unwrap();
    assert!(normals.to_rgba_png(&other.east, BitDepth::Eight).is_err());
    assert!(normals.to_rgba_f32(&other.east).is_err());
}
