//! Shadow queries and the shading term (CPU side).

use glam::Vec3;
use terrain::shadow::{
    SUN_ANGULAR_RADIUS, azimuth_layers, self_shadow_east_west, soft_shadow, sun_azimuth,
    sun_elevation, terrain_shading,
};
use terrain::twins::{
    decode_horizon_angle, hard_shadow, soft_shadow_f64, sun_disc_visible_fraction,
    sun_disc_visible_fraction_f64,
};

#[test]
fn soft_shadow_limits() {
    let r = SUN_ANGULAR_RADIUS;
    assert_eq!(soft_shadow(0.1, 0.0, r), 1.0);
    assert_eq!(soft_shadow(0.0, 0.1, r), 0.0);
    assert_eq!(soft_shadow(0.05 + r, 0.05, r), 1.0);
    assert_eq!(soft_shadow(0.05 - 2.0 * r, 0.05, r), 0.0);
    assert!((soft_shadow(0.3, 0.3, r) - 0.5).abs() < 1e-6);
    assert_eq!(sun_disc_visible_fraction(1.0), 1.0);
    assert_eq!(sun_disc_visible_fraction(-1.0), 0.0);
    // A few f32 ulps (asin, sin and pi rounding): 0.5000001 measured.
    assert!(
        (sun_disc_visible_fraction(0.0) - 0.5).abs() < 3e-7,
        "{}",
        sun_disc_visible_fraction(0.0)
    );
    // Zero radius is the hard shadow.
    assert_eq!(soft_shadow(0.1, 0.0, 0.0), 1.0);
    assert_eq!(soft_shadow(0.0, 0.1, 0.0), 0.0);
    assert_eq!(soft_shadow(0.0, 0.0, 0.0), 0.0);
}

#[test]
fn soft_shadow_matches_the_f64_segment_area_and_is_monotonic() {
    let mut previous = -1.0f32;
    let mut max_err = 0.0f64;
    let n = 200_000;
    for i in 0..=n {
        let x = -1.2 + 2.4 * i as f32 / n as f32;
        let f = sun_disc_visible_fraction(x);
        assert!((0.0..=1.0).contains(&f), "x={x} f={f}");
        assert!(f >= previous, "not monotonic at x={x}: {previous} -> {f}");
        previous = f;
        max_err = max_err.max((f64::from(f) - sun_disc_visible_fraction_f64(f64::from(x))).abs());
        // Symmetry: f(-x) = 1 - f(x).
        assert!((sun_disc_visible_fraction(-x) - (1.0 - f)).abs() < 1e-6);
    }
    assert!(max_err < 1e-6, "max error vs f64 {max_err:e}");
    // Independent check of the area formula: Monte-Carlo-free numerical integration of
    // the chord lengths of a unit disc above y = -x.
    for x in [-0.9f64, -0.3, 0.2, 0.75] {
        let steps = 200_000;
        let mut area = 0.0;
        for k in 0..steps {
            let y = -1.0 + (k as f64 + 0.5) * 2.0 / steps as f64;
            if y > -x {
                area += 2.0 * (1.0 - y * y).sqrt() * 2.0 / steps as f64;
            }
        }
        let fraction = area / std::f64::consts::PI;
        assert!(
            (fraction - sun_disc_visible_fraction_f64(x)).abs() < 1e-4,
            "x={x}"
        );
    }
    assert!((soft_shadow_f64(0.0, 0.0, 0.01) - 0.5).abs() < 1e-12);
}

#[test]
fn hard_shadow_and_decoding() {
    assert_eq!(hard_shadow(0.2, 0.1), 1.0);
    assert_eq!(hard_shadow(0.1, 0.2), 0.0);
    assert_eq!(hard_shadow(0.1, 0.1), 0.0);
    assert!((decode_horizon_angle(0.0) + std::f32::consts::FRAC_PI_2).abs() < 1e-7);
    assert!((decode_horizon_angle(1.0) - std::f32::consts::FRAC_PI_2).abs() < 1e-7);
    assert!(decode_horizon_angle(0.5).abs() < 1e-7);
    // u8 round trip error bound.
    for i in 0..=1000 {
        let angle = -1.5 + 3.0 * i as f32 / 1000.0;
        let a8 = (terrain::encode_horizon_angle(angle).unwrap() * 255.0).round() as f32 / 255.0;
        assert!(
            (decode_horizon_angle(a8) - angle).abs() <= 0.5 * std::f32::consts::PI / 255.0 + 1e-6
        );
    }
}

#[test]
fn sun_angles_and_azimuth_layers() {
    let east_low = Vec3::new(1.0, 0.0, 0.1).normalize();
    assert!((sun_elevation(east_low) - 0.1f32.atan()).abs() < 1e-6);
    assert!((sun_azimuth(east_low) - std::f32::consts::FRAC_PI_2).abs() < 1e-6);
    assert!((sun_azimuth(Vec3::new(-1.0, 0.0, 0.0)) - 1.5 * std::f32::consts::PI).abs() < 1e-6);
    assert_eq!(sun_azimuth(Vec3::new(0.0, 1.0, 0.0)), 0.0);

    let l = azimuth_layers(0.0, 8).unwrap();
    assert_eq!((l.lower, l.upper, l.weight), (0, 1, 0.0));
    let l = azimuth_layers(std::f32::consts::FRAC_PI_2, 4).unwrap();
    assert_eq!((l.lower, l.upper), (1, 2));
    assert!(l.weight.abs() < 1e-6);
    let l = azimuth_layers(-0.25 * std::f32::consts::FRAC_PI_2, 4).unwrap();
    assert_eq!((l.lower, l.upper), (3, 0));
    assert!((l.weight - 0.75).abs() < 1e-5);
    let l = azimuth_layers(std::f32::consts::TAU, 16).unwrap();
    assert!(l.lower < 16 && l.upper < 16 && (0.0..1.0).contains(&l.weight));
}

#[test]
fn east_west_selection_and_shading_term() {
    let east_sun = Vec3::new(1.0, 0.0, 0.2).normalize();
    let west_sun = Vec3::new(-1.0, 0.0, 0.2).normalize();
    // East horizon high, west horizon low.
    assert_eq!(
        self_shadow_east_west(0.5, -0.5, east_sun, SUN_ANGULAR_RADIUS),
        0.0
    );
    assert_eq!(
        self_shadow_east_west(0.5, -0.5, west_sun, SUN_ANGULAR_RADIUS),
        1.0
    );

    let up = Vec3::Z;
    let albedo = Vec3::new(0.2, 0.4, 0.6);
    let c = terrain_shading(up, east_sun, albedo, 0.5, 0.8);
    let expected = albedo * (east_sun.z * 0.5 * 0.8);
    assert!((c - expected).abs().max_element() < 1e-7);
    // Sun below the surface: no light, never negative.
    assert_eq!(terrain_shading(up, -east_sun, albedo, 1.0, 1.0), Vec3::ZERO);
}
