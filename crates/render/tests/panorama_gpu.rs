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
