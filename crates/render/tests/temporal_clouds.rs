//! `SceneRendererSettings::temporal_clouds` (what `skyscape view` draws with): a still
//! camera's frames of a marched-cloud scene converge within four frames to the picture
//! the full march draws on the same device: every pixel within 2 LSB (the same march;
//! only the reprojection's bilinear weights at a pixel's own centre, 1 up to f32
//! rounding, stand between them), while the first frame after the camera turned is not
//! (the check can fail).

mod common;

use common::{Agreement, draw, exact_settings};
use render::gpu::{SceneRenderer, SceneRendererSettings};

#[test]
fn amortised_clouds_converge_to_the_full_march() {
    let Some(gpu) = common::gpu_or_skip("render::temporal_clouds") else {
        return;
    };
    for name in ["cumulus", "stratocumulus"] {
        let scene = common::shipped(name, 96, 54).prepare_for_gpu().unwrap();
        // The same scene looking 1.5 km further east at its target.
        let mut other = common::shipped(name, 96, 54);
        let target = other
            .file
            .camera
            .look_at
            .as_mut()
            .expect("the scene looks at a point");
        target[0] += 1500.0;
        let turned = other.prepare_for_gpu().unwrap();
        let full = common::gpu_pixels_with(gpu, &scene, exact_settings());
        let settings = SceneRendererSettings {
            temporal_clouds: true,
            ..exact_settings()
        };
        let mut renderer = SceneRenderer::new(&gpu.device, &gpu.queue, &scene, settings).unwrap();
        draw(gpu, &mut renderer, &turned);
        let agreement = |image: &[u32]| Agreement::of(image, &full, 96);
        let after_jump = draw(gpu, &mut renderer, &scene);
        let jumped = agreement(&after_jump);
        eprintln!("{name}: the first frame after a turn: {jumped}");
        let mut image = after_jump;
        for _ in 0..3 {
            image = draw(gpu, &mut renderer, &scene);
        }
        let converged = agreement(&image);
        eprintln!("{name}: four still frames after the turn: {converged}");
        assert!(converged.two == 1.0, "{name}: {converged}");
        assert!(jumped.two < 1.0, "{name}: {jumped}");
    }
}
