//! The rungs without tables on the GPU (`render::gpu::rungs`): SGSky's dome, the closed
//! form per pixel and per dome vertex, and single scattering. Each draws a small scene (sky +
//! terrain) on the GPU and on the CPU reference renderer: the images agree (the sky
//! pixel for pixel, the terrain up to the rasteriser-vs-ray-caster gap that
//! `tests/scene_gpu.rs` measures), the terrain is lit and the zenith blue under every
//! one of them, and the reference rungs keep their clear error.
//!
//! GPU policy: an adapter found → run; none and `SKYSCAPE_REQUIRE_GPU=1` → fail; none →
//! skip with a visible line.

mod common;

use common::{code, compare, gpu_pixels};
use render::scene::{Rung, Scene};

const GPU_RUNGS: [Rung; 4] = [
    Rung::Dome,
    Rung::ClosedForm,
    Rung::ClosedFormVertex,
    Rung::Single,
];

fn shipped(name: &str, width: u32, height: u32, rung: Rung) -> Scene {
    let mut scene = common::shipped(name, width, height);
    scene.file.atmosphere.rung = rung;
    scene
}

/// GPU vs CPU for `name` with each GPU rung at 160×90 (the size of `tests/scene_gpu.rs`;
/// the precomputed rung first, as the baseline of the rasterisation gap): the whole
/// image with that test's metric (within 2 and 8 LSB, within 2 LSB of the other image's
/// 3×3 neighbourhood, mean signed and absolute difference), and the sky pixels (no
/// terrain hit on the CPU) on their own, where no rasterisation gap applies.
fn agree(gpu: &skyscape_harness::GpuContext, name: &str) {
    let (width, height) = (160u32, 90u32);
    for rung in [Rung::Precomputed].into_iter().chain(GPU_RUNGS) {
        let scene = shipped(name, width, height, rung).prepare().unwrap();
        let (gpu_image, cpu_image, agreement) = compare(gpu, &scene);
        let hits = render::cpu_renderer::render_radiance(&scene).unwrap();
        let (mut sky_gpu, mut sky_cpu) = (Vec::new(), Vec::new());
        for ((g, c), hit) in gpu_image.iter().zip(&cpu_image).zip(&hits) {
            if hit.terrain_distance.is_none() {
                sky_gpu.push(*g);
                sky_cpu.push(*c);
            }
        }
        let sky_two = render::tonemap::fraction_within_lsb(&sky_gpu, &sky_cpu, 2).unwrap();
        eprintln!(
            "{name} {} {width}×{height}: {:.3} % of pixels within 2 LSB, {:.3} % within 8, \
             {:.3} % within 2 LSB of the other image's 3×3 neighbourhood; sky {:.3} % of {} \
             within 2 LSB; mean difference (GPU − CPU) {:.3?} LSB, mean |difference| \
             {:.3?} LSB",
            rung.name(),
            100.0 * agreement.two,
            100.0 * agreement.eight,
            100.0 * agreement.shifted,
            100.0 * sky_two,
            sky_gpu.len(),
            agreement.signed,
            agreement.absolute,
        );
        assert!(!sky_gpu.is_empty(), "{name} {}: no sky", rung.name());
        assert!(sky_two >= 0.999, "{name} {}: sky {sky_two}", rung.name());
        assert!(
            agreement.close(),
            "{name} {}: {}",
            rung.name(),
            agreement.fractions()
        );
        assert!(
            agreement.unbiased(1.0),
            "{name} {}: {}",
            rung.name(),
            agreement.biases()
        );
    }
}

#[test]
fn every_gpu_rung_agrees_with_the_cpu_on_the_default_scene() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu default") else {
        return;
    };
    agree(gpu, "default");
}

#[test]
fn every_gpu_rung_agrees_with_the_cpu_at_sunset_and_at_night() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu sunset, night") else {
        return;
    };
    agree(gpu, "sunset");
    // The moon lights the sky and the terrain: both added by a second draw.
    agree(gpu, "night");
}

#[test]
fn every_gpu_rung_draws_lit_terrain_under_a_blue_zenith() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu lit terrain") else {
        return;
    };
    for rung in GPU_RUNGS {
        // Terrain: the default scene's mountains in the afternoon sun.
        let scene = shipped("default", 96, 54, rung).prepare().unwrap();
        let image = gpu_pixels(gpu, &scene);
        let hits = render::cpu_renderer::render_radiance(&scene).unwrap();
        let terrain: Vec<u32> = image
            .iter()
            .zip(&hits)
            .filter(|(_, hit)| hit.terrain_distance.is_some())
            .map(|(p, _)| *p)
            .collect();
        assert!(
            terrain.len() > 500,
            "{}: {} terrain pixels",
            rung.name(),
            terrain.len()
        );
        let mean = |channel| {
            terrain
                .iter()
                .map(|p| f64::from(code(*p, channel)))
                .sum::<f64>()
                / terrain.len() as f64
        };
        let brightest = terrain
            .iter()
            .map(|p| (0..3).map(|c| code(*p, c)).sum::<u32>())
            .max()
            .unwrap_or(0);
        let black = terrain
            .iter()
            .filter(|p| (0..3).all(|c| code(**p, c) <= 2))
            .count();
        eprintln!(
            "{}: {} terrain pixels on the GPU, mean code ({:.1}, {:.1}, {:.1}), brightest sum \
             {brightest}, {black} black",
            rung.name(),
            terrain.len(),
            mean(0),
            mean(1),
            mean(2)
        );
        assert!(
            mean(0) > 20.0 && mean(1) > 20.0 && brightest > 200 && black == 0,
            "{}: the terrain is dark",
            rung.name()
        );
        // The zenith, between the cumulus.
        let mut up = shipped("default", 8, 8, rung);
        up.file.camera.look_at = None;
        up.file.camera.look_direction = Some([0.0, 1.0, -0.01]);
        up.file.clouds = None;
        let up = up.prepare().unwrap();
        let pixel = gpu_pixels(gpu, &up)[4 * 8 + 4];
        let [r, g, b] = [code(pixel, 0), code(pixel, 1), code(pixel, 2)];
        eprintln!("{}: zenith RGBA8 ({r}, {g}, {b})", rung.name());
        assert!(b > g && g > r, "{}: zenith {r} {g} {b}", rung.name());
    }
}

#[test]
fn the_reference_rungs_keep_their_error_and_the_tables_are_not_baked() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu reference") else {
        return;
    };
    // The closed form's plan skips the LUT bakes and names its sky evaluation.
    let scene = shipped("default", 16, 9, Rung::ClosedForm)
        .prepare()
        .unwrap();
    let plan = render::passes::planned_passes(&scene);
    let bakes = plan
        .iter()
        .find(|(name, _)| *name == "atmosphere LUT bakes")
        .unwrap();
    assert!(bakes.1.is_err(), "{plan:?}");
    assert!(
        plan.iter()
            .any(|(name, what)| *name == "sky evaluation" && what.is_ok()),
        "{plan:?}"
    );
    // The reference rungs (f64; preparing one takes 20–40 s, so the check is on the
    // error `SceneRenderer::new` returns for them) have no GPU passes.
    for rung in [Rung::Reference, Rung::ReferenceSpectral] {
        assert!(!render::gpu::rungs::has_rung_passes(rung));
        let error = render::gpu::rungs::no_gpu_passes(rung).to_string();
        assert!(
            error.contains("atmosphere.rung")
                && error.contains(rung.name())
                && error.contains("--cpu"),
            "{error}"
        );
    }
    let _ = gpu;
}

/// The shipped cumulus (`[clouds.volume]`, marched) under the closed form and single
/// scattering (the precomputed rung first, as the baseline): the cloud's air is the
/// rung's own functions on the GPU (`render::gpu::cloud_air`, a compute pass) and the
/// rung's segment model on the CPU (`air::air_in_front`); the cloud's pixels
/// (the march's transmittance below 1) agree within 2 LSB as the precomputed rung's do
/// (`tests/volume_clouds.rs`), and the whole image with scene_gpu's metric.
#[test]
fn the_cumulus_agrees_on_the_gpu_and_the_cpu_under_every_gpu_rung() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu cumulus") else {
        return;
    };
    let (width, height) = (160u32, 90u32);
    let mut precomputed: Option<Vec<u32>> = None;
    for rung in [Rung::Precomputed, Rung::ClosedForm, Rung::Single] {
        let scene = shipped("cumulus", width, height, rung).prepare().unwrap();
        let (gpu_image, cpu_image, agreement) = compare(gpu, &scene);
        // `skyscape explain` names the rung's air, not the tables, for the cloud.
        let plan = render::passes::planned_passes(&scene);
        let (_, composite) = plan.iter().find(|(n, _)| *n == "volume clouds").unwrap();
        let composite = composite.as_ref().unwrap();
        assert_eq!(
            composite.contains("atmos' aerial perspective"),
            rung == Rung::Precomputed,
            "{}: {composite}",
            rung.name()
        );
        let cloud = scene.volume_cloud.as_ref().unwrap();
        let pinhole =
            render::volume_clouds::pinhole_camera(&scene.camera, scene.atmosphere.planet_radius)
                .unwrap();
        let mut drawn = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let march = render::volume_clouds::march_pixel(
                    cloud,
                    &pinhole,
                    [width, height],
                    [x, y],
                    f32::INFINITY,
                );
                if march.transmittance < 1.0 {
                    drawn.push((y * width + x) as usize);
                }
            }
        }
        // The rung's own air: its cloud pixels differ from the precomputed rung's.
        let baseline = precomputed.get_or_insert_with(|| gpu_image.clone());
        let differing = drawn
            .iter()
            .filter(|&&i| baseline[i] != gpu_image[i])
            .count();
        let (cloud_pixels, cloud_within, worst) =
            common::within_two_over(&gpu_image, &cpu_image, drawn);
        eprintln!(
            "cumulus {} {width}×{height} GPU vs CPU: {:.3} % of pixels within 2 LSB, {:.3} % \
             within 8, {:.3} % within 2 LSB of the other image's 3×3 neighbourhood; cloud \
             pixels {cloud_within} of {cloud_pixels} within 2 LSB, worst {worst} LSB; \
             {differing} cloud pixels differ from the precomputed rung's GPU image",
            rung.name(),
            100.0 * agreement.two,
            100.0 * agreement.eight,
            100.0 * agreement.shifted,
        );
        assert!(
            agreement.close(),
            "{}: {}",
            rung.name(),
            agreement.fractions()
        );
        assert!(cloud_pixels > 100, "{}: {cloud_pixels}", rung.name());
        assert!(
            rung == Rung::Precomputed || differing > 0,
            "{}: the same cloud as the precomputed rung's",
            rung.name()
        );
        assert!(
            cloud_within as f64 >= 0.99 * cloud_pixels as f64,
            "{}: {cloud_within} of {cloud_pixels}, worst {worst}",
            rung.name()
        );
    }
}

/// The shipped stratocumulus deck (`[clouds.shell]`) under the closed form and single
/// scattering (the precomputed rung first, as the baseline), as the cumulus above: the
/// deck's pixels (its march's transmittance below 1, marched unlit: the transmittance
/// does not depend on the light) within 2 LSB GPU vs CPU, and the rungs' own air.
#[test]
fn the_shell_agrees_on_the_gpu_and_the_cpu_under_every_gpu_rung() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu stratocumulus") else {
        return;
    };
    deck_agrees(gpu, "stratocumulus", |rung| {
        shipped("stratocumulus", 64, 36, rung)
    });
}

/// At night a deck lit by the moon (the shipped night scene with a deck, as
/// `tests/shell_clouds.rs`' night test): its moonlit march's air is the rung's
/// functions with the moon's parameters; the deck's pixels agree as by day.
#[test]
fn the_moonlit_shell_agrees_on_the_gpu_and_the_cpu_under_every_gpu_rung() {
    let Some(gpu) = common::gpu_or_skip("render::rungs_gpu night deck") else {
        return;
    };
    let night = std::fs::read_to_string(common::scene_path("night")).unwrap();
    let deck = "[clouds.shell]\nbottom_m = 3500.0\ntop_m = 4300.0\ncoverage = 0.35\n\
                coverage_contrast = 0.25\ncloud_type = 0.5\ncloud_type_contrast = 0.0\n\
                shape_period_m = 6000.0\ndetail_period_m = 800.0\nview_steps = 12\n\
                light_steps = 3\nambient_steps = 1\noctaves = 4\n";
    deck_agrees(gpu, "night deck", |rung| {
        let mut scene = Scene::parse(&format!("{night}{deck}"), ".").unwrap();
        scene.file.output.width = 64;
        scene.file.output.height = 36;
        scene.file.atmosphere.rung = rung;
        scene
    });
}

/// GPU vs CPU of `scene(rung)`'s `[clouds.shell]` deck under the precomputed rung (the
/// baseline), the closed form and single scattering: the deck's pixels (its march's
/// transmittance below 1, marched unlit: the transmittance does not depend on the
/// light) within 2 LSB, and the rung's own air (its deck pixels differ from the
/// precomputed rung's GPU image).
fn deck_agrees(gpu: &skyscape_harness::GpuContext, name: &str, scene: impl Fn(Rung) -> Scene) {
    let mut precomputed: Option<Vec<u32>> = None;
    for rung in [Rung::Precomputed, Rung::ClosedForm, Rung::Single] {
        let scene = scene(rung).prepare().unwrap();
        let (width, height) = (scene.camera.width, scene.camera.height);
        let (gpu_image, cpu_image, agreement) = compare(gpu, &scene);
        let mut cloud = scene.shell_cloud.clone().unwrap();
        cloud.lights[0].lighting =
            cloudlight::march::Lighting::new([0.0, 0.0, 1.0], [0.0; 3], [0.0; 3], [0.0, 0.0, 1.0])
                .unwrap();
        cloud.lights.truncate(1);
        let camera = render::shell_clouds::shell_camera(&scene.camera).unwrap();
        let mut deck = Vec::new();
        for y in 0..height {
            for x in 0..width {
                let march = render::shell_clouds::march_shell_pixel(
                    &cloud,
                    &camera,
                    [width, height],
                    [x, y],
                    f32::INFINITY,
                );
                if march.transmittance < 1.0 {
                    deck.push((y * width + x) as usize);
                }
            }
        }
        let baseline = precomputed.get_or_insert_with(|| gpu_image.clone());
        let differing = deck
            .iter()
            .filter(|&&i| baseline[i] != gpu_image[i])
            .count();
        let (cloud_pixels, cloud_within, worst) =
            common::within_two_over(&gpu_image, &cpu_image, deck);
        eprintln!(
            "{name} {} {width}×{height} GPU vs CPU: {:.3} % of pixels within 2 LSB, \
             {:.3} % within 8; deck pixels {cloud_within} of {cloud_pixels} within 2 LSB, \
             worst {worst} LSB; {differing} deck pixels differ from the precomputed rung's \
             GPU image",
            rung.name(),
            100.0 * agreement.two,
            100.0 * agreement.eight,
        );
        if !scene.other_lights.is_empty() {
            assert!(
                scene.shell_cloud.as_ref().unwrap().lights.len() > 1,
                "{name}"
            );
        }
        assert!(cloud_pixels > 200, "{}: {cloud_pixels}", rung.name());
        assert!(
            rung == Rung::Precomputed || differing > 0,
            "{}: the same deck as the precomputed rung's",
            rung.name()
        );
        assert!(
            cloud_within as f64 >= 0.99 * cloud_pixels as f64,
            "{}: {cloud_within} of {cloud_pixels}, worst {worst}",
            rung.name()
        );
    }
}
