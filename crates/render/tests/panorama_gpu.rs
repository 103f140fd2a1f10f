//! A panorama's six faces on the GPU share one `SceneRenderer` (what `skyscape render
//! --projection equirectangular|cubemap|fisheye` does): its pipelines and bakes are
//! built once and only `prepare` runs again with each face's camera. Every face must be
//! the image a renderer built for that face alone draws, bit for bit — nothing of the
//! faces drawn before it may leak into it (the aerial-perspective volume, the sky
//! view, the cloud distance, the terrain's tiles, the billboards' order, the sky
//! objects). Run on lavapipe in CI (`WGPU_BACKEND=vulkan`).

mod common;

use glam::DVec3;
use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::projection::CUBE_FACES;
use render::scene::PreparedScene;
use skyscape_harness::GpuContext;

/// The face's HDR target (rgba16float bytes) and display pixels after drawing `scene`
/// with `renderer`.
fn draw(
    gpu: &GpuContext,
    renderer: &mut SceneRenderer,
    scene: &PreparedScene,
) -> (Vec<u8>, Vec<u8>) {
    renderer.prepare(&gpu.queue, scene).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    renderer.encode(&mut encoder).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let radiance =
        skyscape_harness::read_texture(gpu, "face radiance", renderer.radiance_texture()).unwrap();
    let buffer = renderer.pixel_buffer();
    let pixels =
        skyscape_harness::read_buffer(gpu, "face pixels", buffer, 0, buffer.size()).unwrap();
    (radiance, pixels)
}

/// The shipped scenes cover every pass a face can have: terrain and cloud layers
/// (default), the moonlit sky and the sky objects (night), the marched volume
/// (cumulus), the shell (stratocumulus) and the billboards.
#[test]
fn one_renderer_draws_every_face_as_a_renderer_built_for_it() {
    let Some(gpu) = common::gpu_or_skip("panorama_gpu") else {
        return;
    };
    let side = 16;
    // A fresh renderer for the last face drawn (north), after five other views.
    let checked = [5usize];
    for name in ["default", "night", "cumulus", "stratocumulus", "billboards"] {
        let start = std::time::Instant::now();
        let mut view = common::shipped(name, 32, 18).prepare().unwrap();
        let prepared = start.elapsed().as_secs_f64();
        let mut reused: Option<SceneRenderer> = None;
        let mut images = Vec::new();
        for (face, forward) in CUBE_FACES.iter().enumerate() {
            view.look_along(
                DVec3::from_array(*forward),
                std::f64::consts::FRAC_PI_2,
                side,
                side,
            )
            .unwrap();
            let renderer = reused.get_or_insert_with(|| {
                SceneRenderer::new(
                    &gpu.device,
                    &gpu.queue,
                    &view,
                    SceneRendererSettings::default(),
                )
                .unwrap()
            });
            let got = draw(gpu, renderer, &view);
            if checked.contains(&face) {
                let mut fresh = SceneRenderer::new(
                    &gpu.device,
                    &gpu.queue,
                    &view,
                    SceneRendererSettings::default(),
                )
                .unwrap();
                let expected = draw(gpu, &mut fresh, &view);
                assert!(
                    got.0 == expected.0,
                    "{name}: face {face} {forward:?}: the reused renderer's radiance differs"
                );
                assert!(
                    got.1 == expected.1,
                    "{name}: face {face} {forward:?}: the reused renderer's pixels differ"
                );
            }
            images.push(got.0);
        }
        // The faces are six different views (the camera did turn).
        for a in 0..images.len() {
            for b in a + 1..images.len() {
                assert!(
                    images[a] != images[b],
                    "{name}: faces {a} and {b} are equal"
                );
            }
        }
        println!(
            "{name}: six {side}×{side} faces from one renderer, face {checked:?} identical to a \
             fresh renderer's ({prepared:.1} s to prepare, {:.1} s to draw)",
            start.elapsed().as_secs_f64() - prepared
        );
    }
}

/// `skyscape render --projection … --compare`: the GPU's projection (six faces from one
/// renderer) against the CPU's six faces resampled the same way — not against the
/// scene camera's rectilinear view. A closed-form sky, cheap to prepare.
#[test]
fn the_cli_compares_a_projection_with_the_cpus_projection() {
    if common::gpu_or_skip("panorama_gpu cli").is_none() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("skyscape-panorama-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("sky.toml");
    std::fs::write(&scene, common::VALID).unwrap();
    for (projection, width, height) in [("cubemap", "96", "16"), ("equirectangular", "64", "32")] {
        let out = dir.join(format!("{projection}.png"));
        let output = std::process::Command::new(env!("CARGO_BIN_EXE_skyscape"))
            .args([
                "render",
                scene.to_str().unwrap(),
                "--projection",
                projection,
            ])
            .args(["--width", width, "--height", height, "--compare", "-o"])
            .arg(&out)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&output.stdout);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(output.status.success(), "{projection}: {stdout}{stderr}");
        assert!(
            stdout.contains("(six 16×16 faces)") && !stdout.contains("CPU reference renderer (six"),
            "{projection}: the faces are drawn on the GPU: {stdout}"
        );
        let within = stdout
            .split("--compare: ")
            .nth(1)
            .and_then(|rest| rest.split(' ').next())
            .and_then(|percent| percent.parse::<f64>().ok())
            .unwrap_or_else(|| panic!("{projection}: no --compare line: {stdout}"));
        println!("{projection}: {within} % of pixels within 2 LSB of the CPU's {projection}");
        assert!(within >= 99.0, "{projection}: {stdout}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
