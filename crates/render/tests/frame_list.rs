//! The frame is one list (`render::passes::FRAME`): the GPU renderer builds exactly the
//! passes the list gives a scene, in its order, and records exactly the timestamp spans
//! of the plan `skyscape explain` prints, in its order — for every shipped scene, each
//! rung with GPU passes (alone and with the passes that depend on it), the per-vertex
//! aerial perspective, a moonlit cumulus and both marched clouds together. The CPU renderer runs the same list by construction
//! (`render::cpu_renderer`).

mod common;

use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::passes::{FRAME, frame_passes, plan, timestamp_spans};
use render::scene::{PreparedScene, Scene};

/// The variants checked: a name and the scene at 32×18 (prepared once for the tests of
/// this file).
fn variants() -> &'static [(String, PreparedScene)] {
    static VARIANTS: std::sync::OnceLock<Vec<(String, PreparedScene)>> = std::sync::OnceLock::new();
    VARIANTS.get_or_init(prepare_variants)
}

fn prepare_variants() -> Vec<(String, PreparedScene)> {
    let mut scenes = Vec::new();
    let mut add = |name: String, mut scene: Scene| {
        scene.file.output.width = 32;
        scene.file.output.height = 18;
        scenes.push((name, scene));
    };
    for shipped in render::scene::shipped::SHIPPED {
        add(shipped.name.into(), common::shipped(shipped.name, 32, 18));
    }
    // Each GPU rung once with terrain, sky objects and layers, and each with another
    // pass that depends on the rung: a moonlit night, the billboards' air, the deck's air.
    for (name, rung) in [
        ("default", "closed-form"),
        ("default", "closed-form-vertex"),
        ("default", "single"),
        ("night", "single"),
        ("billboards", "closed-form-vertex"),
        ("stratocumulus", "closed-form"),
    ] {
        let mut scene = common::shipped(name, 32, 18);
        scene.file.atmosphere.rung = render::scene::Rung::from_name(rung).unwrap();
        add(format!("{name} ({rung})"), scene);
    }
    for rung in ["precomputed", "closed-form"] {
        let mut scene = common::shipped("default", 32, 18);
        scene.file.terrain.as_mut().unwrap().aerial_perspective =
            render::aerial_vertex::AerialPerspective::PerVertex;
        scene.file.atmosphere.rung = render::scene::Rung::from_name(rung).unwrap();
        add(format!("default per vertex ({rung})"), scene);
    }
    add(
        "night with a moonlit cumulus".into(),
        common::night_with(
            "position = [0.0, 1800.0, 6000.0]\nlook_at = [0.0, 2500.0, 0.0]",
            "seed = 2026\nsteps = 250\ngrid = [24, 24, 6]\ncell_size_m = 100.0\n\
             base_m = 2000.0\ncentre_m = [0.0, 0.0]",
            32,
            18,
        ),
    );
    let both = "[camera]\nposition = [0.0, 3200.0, 0.0]\nlook_at = [0.0, -200.0, -4000.0]\n\
                [sun]\nelevation_deg = 40.0\nazimuth_deg = 230.0\n\
                [clouds.shell]\nbottom_m = 1000.0\ntop_m = 1800.0\nview_steps = 8\n\
                light_steps = 3\n\
                [clouds.volume]\nseed = 2026\nsteps = 100\ngrid = [16, 16, 6]\n\
                cell_size_m = 100.0\nbase_m = 300.0\ncentre_m = [0.0, -3000.0]\n";
    add("shell and volume".into(), Scene::parse(both, ".").unwrap());
    // Prepared on both cores: most of this file's time.
    use rayon::prelude::*;
    scenes
        .into_par_iter()
        .map(|(name, scene)| {
            let prepared = scene.prepare().unwrap_or_else(|e| panic!("{name}: {e}"));
            (name, prepared)
        })
        .collect()
}

/// Plans that cannot disagree with themselves: a pass the scene skips has only
/// skipped steps, and no two steps share a label (a label is a timestamp span).
#[test]
fn each_plan_is_consistent() {
    for (name, scene) in variants() {
        let mut labels = Vec::new();
        for entry in &FRAME {
            let runs = (entry.runs)(scene);
            for line in (entry.plan)(scene) {
                assert!(
                    runs || line.status.is_err(),
                    "{name}: {} runs `{}` in a pass it skips",
                    entry.name,
                    line.label
                );
                assert!(
                    !labels.contains(&line.label),
                    "{name}: `{}` twice",
                    line.label
                );
                labels.push(line.label);
            }
        }
        assert_eq!(plan(scene).len(), labels.len());
    }
}

#[test]
fn the_gpu_builds_and_records_the_list() {
    let Some(gpu) = common::gpu_or_skip("render::frame_list") else {
        return;
    };
    let timestamps = gpu
        .device
        .features()
        .contains(wgpu::Features::TIMESTAMP_QUERY);
    for (name, scene) in variants() {
        let settings = SceneRendererSettings {
            timestamps: true,
            ..Default::default()
        };
        let mut renderer = SceneRenderer::new(&gpu.device, &gpu.queue, scene, settings)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let listed: Vec<_> = frame_passes(scene).map(|entry| entry.name).collect();
        assert_eq!(renderer.pass_names(), listed, "{name}: the passes built");
        renderer.prepare(&gpu.queue, scene).unwrap();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder).unwrap();
        gpu.queue.submit([encoder.finish()]);
        if timestamps {
            assert_eq!(
                renderer.recorded_spans(),
                timestamp_spans(scene),
                "{name}: the steps recorded against the plan's timed steps"
            );
        }
        eprintln!(
            "{name}: {listed:?}, {} timed steps",
            timestamp_spans(scene).len()
        );
    }
    if !timestamps {
        eprintln!("SKIPPED the recorded steps: the adapter has no TIMESTAMP_QUERY");
    }
}

/// A renderer built for one scene refuses a scene that runs other passes (the sunset has
/// no sky objects and no cloud layers; the default scene has both).
#[test]
fn a_renderer_refuses_a_scene_with_other_passes() {
    let Some(gpu) = common::gpu_or_skip("render::frame_list") else {
        return;
    };
    let find = |name: &str| &variants().iter().find(|(n, _)| n == name).unwrap().1;
    let (default, sunset) = (find("default"), find("sunset"));
    let names = |scene| frame_passes(scene).map(|e| e.name).collect::<Vec<_>>();
    assert_ne!(names(default), names(sunset));
    let mut renderer =
        SceneRenderer::new(&gpu.device, &gpu.queue, default, Default::default()).unwrap();
    let error = renderer.prepare(&gpu.queue, sunset).unwrap_err();
    assert!(error.to_string().contains("built for"), "{error}");
    renderer.prepare(&gpu.queue, default).unwrap();
}
