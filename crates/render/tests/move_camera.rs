//! `PreparedScene::move_camera` (what `skyscape view` does every frame instead of
//! preparing the scene again): a scene prepared at one viewpoint and moved to another
//! at the same altitude draws, on the CPU reference renderer, the picture of the scene
//! prepared at the second viewpoint; a move to another altitude says that the sky's
//! paint is the prepared altitude's; what a move cannot carry is refused with its
//! reason.

mod common;

use glam::DVec3;
use render::scene::{CameraMove, PreparedScene, Scene};

/// The default scene's camera at `position`, looking along `forward`.
fn at(mut scene: Scene, position: [f64; 3], forward: [f64; 3]) -> Scene {
    scene.file.camera.position = position;
    scene.file.camera.look_at = None;
    scene.file.camera.look_direction = Some(forward);
    scene
}

fn pixels(scene: &PreparedScene) -> Vec<u32> {
    render::cpu_renderer::render_cpu(scene).unwrap().pixels
}

#[test]
fn a_moved_scene_draws_what_a_scene_prepared_there_draws() {
    let scene = common::shipped("default", 96, 54);
    let (first, forward_a) = ([-2000.0, 3300.0, 14500.0], [0.1, -0.1, -1.0]);
    // 3.2 km west-north-west at the same altitude, looking north-east and down.
    let (second, forward_b) = ([-5000.0, 3300.0, 13500.0], [0.6, -0.25, -0.75]);
    let mut moved = at(scene.clone(), first, forward_a).prepare().unwrap();
    let outcome = moved
        .move_camera(
            DVec3::from_array(second),
            DVec3::from_array(forward_b),
            50f64.to_radians(),
        )
        .unwrap();
    assert_eq!(outcome, CameraMove::Moved);
    // Prepared there after the same travel (the cloud layers' texture offset is the
    // camera's travel from the scene's start: they keep their place on the ground).
    let mut there = at(scene, second, forward_b);
    there.file.camera.travel_m = std::array::from_fn(|a| second[a] - first[a]);
    let there = there.prepare().unwrap();
    assert_eq!(moved.camera_position, there.camera_position);
    assert_eq!(moved.viewer_radius, there.viewer_radius);
    assert_eq!(moved.cloud_layers, there.cloud_layers);
    let (a, b) = (pixels(&moved), pixels(&there));
    let differing = a.iter().zip(&b).filter(|(x, y)| x != y).count();
    assert_eq!(differing, 0, "{differing} of {} pixels differ", a.len());
}

#[test]
fn a_climb_through_the_layer_keeps_the_paint_and_says_so() {
    // Crossing the cumulus layer (base 4.3 km, 0.7 km thick) changes its drawing; the
    // layer's colours stay the prepared altitude's until the scene is prepared there.
    let scene = common::shipped("default", 32, 18);
    let mut moved = at(scene.clone(), [0.0, 3300.0, 14500.0], [0.0, -0.2, -1.0])
        .prepare()
        .unwrap();
    let above = [0.0, 6000.0, 14500.0];
    let outcome = moved
        .move_camera(
            DVec3::from_array(above),
            DVec3::new(0.0, -0.2, -1.0),
            50f64.to_radians(),
        )
        .unwrap();
    assert_eq!(
        outcome,
        CameraMove::MovedKeepingPaint {
            altitude_change_m: 2700.0
        }
    );
    let there = at(scene, above, [0.0, -0.2, -1.0]).prepare().unwrap();
    assert_eq!(moved.viewer_radius, there.viewer_radius);
    let geometry = |p: &PreparedScene| -> Vec<(f32, f32)> {
        p.cloud_layers
            .iter()
            .map(|l| (l.base_radius, l.top_radius))
            .collect()
    };
    assert_eq!(geometry(&moved), geometry(&there));
    assert_ne!(
        moved.cloud_layers[0].fog_colour, there.cloud_layers[0].fog_colour,
        "the paint is the prepared altitude's (else this test checks nothing)"
    );
}

#[test]
fn what_a_move_cannot_carry_is_refused_with_its_reason() {
    let mut scene = common::shipped("default", 32, 18);
    scene.file.atmosphere.rung = render::scene::Rung::ClosedFormVertex;
    let mut prepared = scene.prepare().unwrap();
    let before = prepared.camera_position;
    let outcome = prepared
        .move_camera(DVec3::new(0.0, 3000.0, 0.0), DVec3::NEG_Z, 1.0)
        .unwrap();
    assert!(
        matches!(outcome, CameraMove::NeedsPrepare(reason) if reason.contains("per-vertex")),
        "{outcome:?}"
    );
    assert_eq!(
        prepared.camera_position, before,
        "a refused move changes nothing"
    );
    // Under the ground (below the planet's surface) is an error naming the position.
    let mut prepared = common::shipped("sunset", 32, 18).prepare().unwrap();
    let error = prepared
        .move_camera(DVec3::new(0.0, -1.0e5, 0.0), DVec3::NEG_Z, 1.0)
        .unwrap_err()
        .to_string();
    assert!(!error.is_empty());
    let error = prepared
        .move_camera(DVec3::new(f64::NAN, 0.0, 0.0), DVec3::NEG_Z, 1.0)
        .unwrap_err()
        .to_string();
    assert!(error.contains("camera.position"), "{error}");
}

#[test]
fn the_layers_texture_stays_on_the_world_as_the_camera_travels() {
    // The default scene's cumulus layer: its texture offset is 0 where the scene starts
    // the camera (SGSky's offset: the viewer's travel plus the wind's drift), and a move
    // of 3 km east and 1 km north at the same altitude adds exactly that travel to it
    // (east, north), so the clouds stay where they were over the ground.
    let scene = common::shipped("default", 32, 18);
    let mut moved = at(scene, [-2000.0, 3300.0, 14500.0], [0.0, -0.1, -1.0])
        .prepare()
        .unwrap();
    let before = moved.cloud_layers[0].offset;
    assert_eq!(before, [0.0, 0.0], "no travel yet");
    moved
        .move_camera(
            DVec3::new(1000.0, 3300.0, 13500.0),
            DVec3::new(0.0, -0.1, -1.0),
            50f64.to_radians(),
        )
        .unwrap();
    assert_eq!(moved.cloud_layers[0].offset, [3000.0, 1000.0]);
}
