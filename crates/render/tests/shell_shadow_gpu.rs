//! The `[clouds.shell]` deck's shadow map of the shipped `stratocumulus` scene baked on
//! the GPU (cloudlight's `ShellShadowMapPass` over `shell_shadow_map_plan`, what the GPU
//! renderer's terrain pass reads) against the CPU's bake at prepare (what the CPU
//! renderer reads), both timed. Skipped without an adapter (adapter → run; none and
//! SKYSCAPE_REQUIRE_GPU=1 → fail; none → a visible SKIPPED line).
#![cfg(feature = "gpu")]

mod common;

use cloudlight::gpu::ShellShadowMapPass;
use cloudlight::shell_shadow::ShellField;

#[test]
fn the_deck_map_baked_on_the_gpu_is_the_cpu_bake() {
    let Some(gpu) = common::gpu_or_skip("render::shell_shadow_gpu") else {
        return;
    };
    let scene = common::shipped("stratocumulus", 96, 54).prepare().unwrap();
    let cloud = scene.shell_cloud.as_ref().unwrap();
    let map = cloud.lights[0]
        .shadow
        .as_ref()
        .expect("a shadow map over the terrain");
    let plan = render::shell_clouds::shell_shadow_map_plan(&cloud.shell, map, scene.sun).unwrap();
    assert_eq!(plan.grid.resolution(), map.resolution);
    let field = ShellField::<f32>::of(&cloud.shell);
    let mut pass = ShellShadowMapPass::new(&gpu.device).unwrap();
    // Twice: the first includes the driver's first dispatch of the pipeline.
    let mut seconds = Vec::new();
    let mut values = Vec::new();
    for _ in 0..2 {
        let started = std::time::Instant::now();
        pass.prepare(&gpu.device, &gpu.queue, &field, &plan)
            .unwrap();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        pass.encode(&mut encoder).unwrap();
        gpu.queue.submit([encoder.finish()]);
        let bytes = skyscape_harness::read_buffer(
            gpu,
            "shell shadow map",
            pass.buffer().unwrap(),
            0,
            plan.grid.texels() as u64 * 4,
        )
        .unwrap();
        seconds.push(started.elapsed().as_secs_f64());
        values = pass.decode(&bytes).unwrap();
    }
    let worst = values
        .iter()
        .zip(&map.values)
        .map(|(g, c)| (g - c).abs())
        .fold(0.0f32, f32::max);
    let shaded = map.values.iter().filter(|&&t| t < 0.5).count();
    eprintln!(
        "stratocumulus deck map {}×{} texels of {:.1} m, {} steps: {shaded} texels < 0.5; CPU \
         bake at prepare (rayon, {} threads) {:.3} s; GPU bake on {} {:.3} s then {:.3} s \
         (prepare + dispatch + readback; a CPU adapter's time is not GPU speed); max |GPU − \
         CPU| {worst:.2e}",
        map.resolution[0],
        map.resolution[1],
        map.cell_size,
        render::shell_clouds::SHADOW_STEPS,
        rayon::current_num_threads(),
        cloud.shadow_seconds,
        skyscape_harness::describe_adapter(&gpu.adapter.get_info()),
        seconds[0],
        seconds[1],
    );
    assert!(shaded > 0, "the deck shades the terrain");
    // The same formula in the same order (the CPU bake is the pass's f32 twin bit for
    // bit): WGSL's division, sqrt and exp against Rust's; cloudlight's shell_shadow_gpu
    // test and the parity pass measure ≤ 1.3e-6 on lavapipe.
    assert!(worst <= 1e-5, "worst {worst:e}");
}

/// `Scene::prepare_for_gpu` leaves the deck's map to the GPU: the same grid without
/// values, no CPU time; the CPU renderer refuses it (naming the key) until
/// `bake_shell_shadow_on_cpu`, which gives `prepare`'s values; the GPU renderer draws it
/// pixel for pixel as it draws `prepare`'s scene.
#[test]
fn a_scene_prepared_for_the_gpu_leaves_the_bake_to_it() {
    let scene = common::shipped("stratocumulus", 96, 54);
    let started = std::time::Instant::now();
    let mut for_gpu = scene.prepare_for_gpu().unwrap();
    let gpu_prepare = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let full = scene.prepare().unwrap();
    let cpu_prepare = started.elapsed().as_secs_f64();
    let (lazy, baked) = (
        for_gpu.shell_cloud.as_ref().unwrap(),
        full.shell_cloud.as_ref().unwrap(),
    );
    let (lazy_map, map) = (
        lazy.lights[0].shadow.as_ref().unwrap(),
        baked.lights[0].shadow.as_ref().unwrap(),
    );
    assert!(lazy_map.values.is_empty() && !lazy.shadows_baked_on_cpu());
    assert_eq!(lazy.shadow_seconds, 0.0);
    assert_eq!(
        (lazy_map.origin, lazy_map.cell_size, lazy_map.resolution),
        (map.origin, map.cell_size, map.resolution)
    );
    assert_eq!((lazy_map.plane, lazy_map.to_sun), (map.plane, map.to_sun));
    eprintln!(
        "stratocumulus 96×54 prepared for the GPU in {gpu_prepare:.2} s, with the CPU's deck \
         map in {cpu_prepare:.2} s (its bake {:.2} s)",
        baked.shadow_seconds
    );
    let err = render::cpu_renderer::render_cpu(&for_gpu).unwrap_err();
    assert!(err.to_string().contains("clouds.shell"), "{err}");
    if let Some(gpu) = common::gpu_or_skip("render::shell_shadow_gpu prepare_for_gpu") {
        assert_eq!(
            common::gpu_pixels(gpu, &for_gpu),
            common::gpu_pixels(gpu, &full)
        );
    }
    for_gpu.bake_shell_shadow_on_cpu();
    let rebaked = for_gpu.shell_cloud.as_ref().unwrap();
    assert!(rebaked.shadows_baked_on_cpu() && rebaked.shadow_seconds > 0.0);
    assert_eq!(
        rebaked.lights[0].shadow.as_ref().unwrap().values,
        map.values
    );
}

/// The GPU renderer times the deck's bake as "shell cloud shadow" (`skyscape explain`):
/// a span on the frame that bakes the map and on a frame that reuses it (an empty pass
/// then, not the last bake's figure). Only where the device has timestamps.
#[test]
fn the_gpu_bake_is_a_timed_pass() {
    use render::gpu::{SceneRenderer, SceneRendererSettings};
    let Some(gpu) = common::gpu_or_skip("render::shell_shadow_gpu timed bake") else {
        return;
    };
    let scene = common::shipped("stratocumulus", 48, 27)
        .prepare_for_gpu()
        .unwrap();
    let settings = SceneRendererSettings {
        timestamps: true,
        ..Default::default()
    };
    let mut renderer = SceneRenderer::new(&gpu.device, &gpu.queue, &scene, settings).unwrap();
    let mut spans = Vec::new();
    for _ in 0..2 {
        renderer.prepare(&gpu.queue, &scene).unwrap();
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder).unwrap();
        gpu.queue.submit([encoder.finish()]);
        let Some(seconds) = renderer.pass_seconds() else {
            eprintln!("the device has no timestamps: nothing to check");
            return;
        };
        let seconds = seconds.unwrap();
        let bake = seconds
            .iter()
            .find(|(label, _)| *label == "shell cloud shadow");
        spans.push(bake.expect("the bake has a span").1);
    }
    eprintln!(
        "\"shell cloud shadow\" span: {:.3} ms baking, {:.3} ms reusing the map",
        spans[0] * 1e3,
        spans[1] * 1e3
    );
    assert!(
        spans.iter().all(|s| s.is_finite() && *s >= 0.0),
        "{spans:?}"
    );
}

/// A terrain point inside a cloud's altitudes is shaded by the faded column of its map
/// (cloudlight's `shadow_depth_above`, as the clouds' mutual shadows), one below the base
/// by the whole column, one at or above the top not at all.
#[test]
fn a_peak_in_the_cloud_reads_the_column_above_it() {
    let map = render::volume_clouds::CloudShadow {
        origin: [0.0, 0.0],
        cell_size: 100.0,
        resolution: [4, 4],
        plane: 1000.0,
        top: 1800.0,
        to_sun: [0.0, 0.0, 1.0],
        values: vec![0.1; 16],
    };
    let at = |height: f32| map.on_terrain([200.0, 200.0, height]);
    assert_eq!(at(600.0), 0.1);
    assert_eq!(at(1000.0), 0.1);
    assert_eq!(at(1800.0), 1.0);
    assert_eq!(at(2500.0), 1.0);
    // Halfway up: f = ½, τ = −ln 0.1 · ¼.
    let half = at(1400.0);
    assert!((half - 0.1f32.powf(0.25)).abs() < 1e-6, "{half}");
    // Monotone from the base to the top.
    let steps: Vec<f32> = (0..=8).map(|k| at(1000.0 + 100.0 * k as f32)).collect();
    assert!(steps.windows(2).all(|w| w[0] <= w[1]), "{steps:?}");
}

/// The shipped `stratocumulus` with its deck lowered to 200–500 m, under all of its
/// terrain (600–1,200 m): the deck's map is baked and dark, but no terrain point lies
/// below the deck's top, so the terrain is drawn as without the map, on the CPU and on the
/// GPU (no point reads the whole column along the light).
#[test]
fn terrain_above_the_deck_is_not_in_its_shadow() {
    let mut scene = common::shipped("stratocumulus", 64, 36);
    let shell = scene.file.clouds.as_mut().unwrap().shell.as_mut().unwrap();
    shell.bottom_m = 200.0;
    shell.top_m = 500.0;
    let mut prepared = scene.prepare().unwrap();
    let terrain = prepared.terrain.as_ref().unwrap();
    let low = terrain
        .heightfield
        .elevations()
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    assert!(low > 500.0, "the terrain's lowest point {low}");
    let map = prepared.shell_cloud.as_ref().unwrap().lights[0]
        .shadow
        .as_ref()
        .expect("the deck's map over the terrain");
    let (dark, texels) = (
        map.values.iter().filter(|&&v| v < 0.5).count(),
        map.values.len(),
    );
    assert!(dark > 100, "{dark} dark texels");
    let with = render::cpu_renderer::render_radiance(&prepared).unwrap();
    let gpu = common::gpu_or_skip("render::shell_shadow_gpu terrain above the deck").map(|gpu| {
        (
            common::gpu_pixels(gpu, &prepared),
            common::cpu_pixels(&prepared),
        )
    });
    prepared.shell_cloud.as_mut().unwrap().lights[0].shadow = None;
    let without = render::cpu_renderer::render_radiance(&prepared).unwrap();
    let terrain_pixels: Vec<usize> = (0..with.len())
        .filter(|&i| with[i].terrain_distance.is_some())
        .collect();
    assert!(terrain_pixels.len() > 500, "{}", terrain_pixels.len());
    for &i in &terrain_pixels {
        assert_eq!(with[i].radiance, without[i].radiance, "pixel {i}");
    }
    eprintln!(
        "deck at 200-500 m under terrain of {low:.0} m and up: {dark} of {} map texels below \
         0.5, {} terrain pixels as without the map",
        texels,
        terrain_pixels.len()
    );
    if let Some((gpu, cpu)) = gpu {
        let (pixels, within, worst) = common::within_two_over(&gpu, &cpu, terrain_pixels);
        eprintln!("GPU vs CPU: {within} of {pixels} terrain pixels within 2 LSB, worst {worst}");
        // A whole column on the GPU leaves 19 of 965 within 2 LSB (worst 50).
        assert!(
            within as f64 >= 0.99 * pixels as f64,
            "{within} of {pixels}"
        );
    }
}
