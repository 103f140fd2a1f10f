//! The drop-in path: a caller's local frame, the LUT bindings at groups of the
//! caller's choosing, and the aerial perspective a caller's shader applies to its
//! geometry against a direct march. The GPU sides (the sky pass drawn into a colour
//! target, aerial perspective and sunlight in a caller's shader at groups 2 and 3) are
//! checked against these CPU twins by `cargo xtask parity`
//! (`xtask/src/parity/passes/atmos_drop_in_passes.rs`).

use atmos::frame::{FrameCamera, LocalFrame};
use atmos::gpu::{composer_with_lut_groups, lut_bindings_wgsl};
use atmos::lut::drop_in::aerial_perspective;
use atmos::lut::{FrameLuts, LutSettings, StaticLuts};
use atmos::twins::frame_screen_position;
use atmos::{Atmosphere, SUN_ANGULAR_RADIUS};
use glam::DVec3;

fn earth() -> Atmosphere {
    Atmosphere::earth()
}

/// A camera 2 m above a local origin 300 m up, looking north-east and a little down,
/// the sun low in the west (local frame: +y up, −z north, +x east).
fn local_camera(frame: &LocalFrame, width: u32, height: u32) -> FrameCamera {
    frame
        .frame_camera(
            DVec3::new(0.0, 2.0, 0.0),
            DVec3::new(1.0, -0.05, -1.0),
            DVec3::Y,
            1.1,
            width,
            height,
            DVec3::new(-1.0, 0.35, 0.2),
            None,
        )
        .unwrap()
}

#[test]
fn the_local_frame_is_a_rotation_and_keeps_altitudes() {
    let frame = LocalFrame::new(&earth(), 300.0).unwrap();
    // Up is the planet's zenith at the origin, north is +y, east +x.
    assert_eq!(frame.to_planet_direction(DVec3::Y), DVec3::Z);
    assert_eq!(frame.to_planet_direction(DVec3::NEG_Z), DVec3::Y);
    assert_eq!(frame.to_planet_direction(DVec3::X), DVec3::X);
    // Right-handed: east × north = up in both frames.
    let (east, north) = (DVec3::X, DVec3::NEG_Z);
    assert_eq!(
        frame.to_planet_direction(east.cross(north)),
        frame
            .to_planet_direction(east)
            .cross(frame.to_planet_direction(north))
    );
    for p in [
        DVec3::ZERO,
        DVec3::new(1234.5, -20.0, 987.0),
        DVec3::new(-5e4, 3e3, 7e4),
    ] {
        let back = frame.to_local_position(frame.to_planet_position(p));
        assert!((back - p).length() < 1e-6, "{p} -> {back}");
    }
    assert!((frame.altitude(DVec3::new(0.0, 2.0, 0.0)) - 302.0).abs() < 1e-6);
    // Curvature: 100 km away at the origin's height is d²/2R higher above the sphere.
    let far = frame.altitude(DVec3::new(1e5, 0.0, 0.0)) - 300.0;
    assert!(
        (far - 1e10 / (2.0 * frame.planet_radius)).abs() < 0.5,
        "{far}"
    );
    assert!(LocalFrame::new(&earth(), f64::NAN).is_err());
    let error = LocalFrame::new(&earth(), -7e6).unwrap_err().to_string();
    assert!(error.contains("origin_altitude"), "{error}");
}

#[test]
fn screen_positions_invert_the_view_directions() {
    let frame = LocalFrame::new(&earth(), 0.0).unwrap();
    let camera = local_camera(&frame, 40, 30);
    for (x, y) in [(0, 0), (39, 0), (20, 15), (7, 29)] {
        let direction = atmos::frame::frame_view_direction([x, y], &camera);
        let [u, v, depth] = frame_screen_position(&camera, direction);
        assert!(depth > 0.0);
        assert!((u - (x as f32 + 0.5) / 40.0).abs() < 1e-5, "{x}: {u}");
        assert!((v - (y as f32 + 0.5) / 30.0).abs() < 1e-5, "{y}: {v}");
    }
}

#[test]
fn the_sun_disc_is_one_formula_with_the_mean_radius() {
    let earth = earth();
    assert_eq!(earth.sun_angular_radius, SUN_ANGULAR_RADIUS);
    // E / (2π(1 − cos α)), against its small-angle limit E / (πα²).
    let disc = earth.sun_disc_radiance()[0];
    let small_angle = 1.0 / (std::f64::consts::PI * SUN_ANGULAR_RADIUS * SUN_ANGULAR_RADIUS);
    assert!(
        (disc / small_angle - 1.0).abs() < 1e-5,
        "{disc} vs {small_angle}"
    );
    let exact = 1.0 / (2.0 * std::f64::consts::PI * (1.0 - SUN_ANGULAR_RADIUS.cos()));
    assert!((disc / exact - 1.0).abs() < 1e-9);
}

#[test]
fn lut_bindings_move_to_the_groups_asked_for() {
    let source = lut_bindings_wgsl(2, 3);
    let composer = composer_with_lut_groups(2, 3).unwrap();
    let composed = composer
        .compose_module("atmos::aerial_perspective")
        .unwrap();
    // Only the group attributes differ from the file's text.
    assert!(source.contains("@group(2) @binding(0) var<uniform> lut_atmosphere"));
    assert!(source.contains("@group(3) @binding(0) var transmittance_lut"));
    assert_eq!(
        source.lines().count(),
        lut_bindings_wgsl(0, 1).lines().count()
    );
    let module = skyscape_wgsl::validate("aerial_perspective at 2, 3", &composed).unwrap();
    let mut groups: Vec<(String, u32)> = module
        .global_variables
        .iter()
        .filter_map(|(_, variable)| {
            variable
                .binding
                .as_ref()
                .map(|b| (variable.name.clone().unwrap_or_default(), b.group))
        })
        .collect();
    groups.sort();
    assert!(groups.contains(&("lut_atmosphere".into(), 2)), "{groups:?}");
    assert!(
        groups.contains(&("transmittance_lut".into(), 3)),
        "{groups:?}"
    );
    assert!(groups.iter().all(|(_, g)| *g == 2 || *g == 3), "{groups:?}");
    let error = composer_with_lut_groups(1, 1).unwrap_err().to_string();
    assert!(error.contains("table_group"), "{error}");
}

/// A camera 30 m up: points on a flat local ground out to 30 km sit within a few
/// hundredths of a degree of its horizon, where neighbouring froxel columns of the
/// aerial-perspective volume meet the curved ground a few kilometres out. The lookup
/// must still match a direct march of the same ray (it read 0.74 instead of 0.47 for
/// the blue transmittance at 20 km when columns stopped at the ground).
#[test]
fn aerial_perspective_at_a_low_cameras_horizon_matches_a_direct_march() {
    use atmos::lut::aerial_perspective::view_cosines;
    use atmos::lut::raymarch::march_view_segment;
    let earth = earth();
    let frame = LocalFrame::new(&earth, 0.0).unwrap();
    let camera = frame
        .frame_camera(
            DVec3::new(0.0, 30.0, 0.0),
            DVec3::new(0.0, -0.02, -1.0),
            DVec3::Y,
            0.9,
            640,
            360,
            DVec3::new(-0.6, 0.28, 0.75),
            None,
        )
        .unwrap();
    let luts = StaticLuts::bake(&earth, &LutSettings::default()).unwrap();
    let frame_luts = FrameLuts::bake(&luts, &camera);
    let mut worst = 0.0f32;
    for distance in [2_000.0f32, 5_000.0, 10_000.0, 20_000.0, 30_000.0] {
        for (x, y) in [(200.0, -30.0), (-3_000.0, 500.0), (0.0, -10.0)] {
            let offset = atmos::frame::local_to_planet_direction([x, y, -distance]);
            let lookup = aerial_perspective(&luts, &frame_luts, offset);
            let length = offset.iter().map(|c| c * c).sum::<f32>().sqrt();
            let direction = offset.map(|c| c / length);
            let [r, mu, mu_s, nu] = view_cosines(&camera, direction, earth.planet_radius as f32);
            let march = march_view_segment(&luts.bindings(), r, mu, mu_s, nu, length, 256);
            for c in 0..3 {
                let t = (lookup.transmittance[c] - march.transmittance[c]).abs()
                    / march.transmittance[c];
                let l = (lookup.radiance[c] - march.radiance[c]).abs() / march.radiance[c];
                worst = worst.max(t).max(l);
            }
        }
    }
    eprintln!("aerial perspective at the horizon vs a direct march: worst {worst:.2e}");
    assert!(worst < 0.01, "{worst}");
}
