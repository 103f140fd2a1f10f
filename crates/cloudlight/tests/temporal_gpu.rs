//! `TemporalMarch` on a GPU: a still camera's amortised image is the full march's after
//! four frames (to f32 rounding); a moving camera's is, on average, no further from
//! each frame's full march than the last frame's full march is; the march's fragment
//! and compute stages amortise alike (skipped without an adapter, see skyscape-harness).
#![cfg(feature = "gpu")]

use std::num::NonZeroU32;

use cloudlight::CloudVolume;
use cloudlight::gpu::{MarchPass, MarchStage, TemporalMarch};
use cloudlight::march::{
    LightMarch, Lighting, MarchConfig, MarchResult, MarchSettings, PinholeCamera,
};

mod common;

use common::lumpy_blob;

struct Marcher<'a> {
    gpu: &'a skyscape_harness::GpuContext,
    volume: CloudVolume,
    settings: MarchSettings,
    lighting: Lighting<f32>,
    size: [u32; 2],
}

impl Marcher<'_> {
    /// One frame: amortised by `temporal` when given, else the full march.
    fn frame(
        &self,
        pass: &mut MarchPass,
        temporal: Option<&mut TemporalMarch>,
        camera: &PinholeCamera,
    ) -> Vec<MarchResult<f32>> {
        let (device, queue) = (&self.gpu.device, &self.gpu.queue);
        let phase = temporal.as_ref().and_then(|t| t.phase(self.size));
        pass.set_phase(phase);
        pass.prepare(
            device,
            queue,
            &self.volume,
            camera,
            self.size,
            &self.settings,
            &self.lighting,
        )
        .unwrap();
        let mut encoder = device.create_command_encoder(&Default::default());
        match temporal {
            Some(temporal) => {
                temporal.prepare(device, queue, pass).unwrap();
                temporal.encode(&mut encoder, pass, None).unwrap();
            }
            None => pass.encode(&mut encoder).unwrap(),
        }
        queue.submit([encoder.finish()]);
        let bytes = skyscape_harness::read_buffer(
            self.gpu,
            "temporal march image",
            pass.image_buffer().unwrap(),
            0,
            pass.image_size(),
        )
        .unwrap();
        pass.decode(&bytes).unwrap()
    }
}

fn camera(x: f64) -> PinholeCamera {
    PinholeCamera::look_at(
        [x, -1500.0, 1300.0],
        [x * 0.5, 0.0, 1400.0],
        [0.0, 0.0, 1.0],
        0.9,
    )
    .unwrap()
}

/// Mean |radiance difference| over the full march's cloudy pixels, relative to their
/// mean radiance.
fn relative_error(image: &[MarchResult<f32>], full: &[MarchResult<f32>]) -> f64 {
    let cloudy: Vec<usize> = (0..full.len())
        .filter(|&i| full[i].transmittance < 0.99 || image[i].transmittance < 0.99)
        .collect();
    let sum = |f: &dyn Fn(usize) -> f64| cloudy.iter().map(|&i| f(i)).sum::<f64>();
    let difference = sum(&|i| {
        (0..3)
            .map(|c| f64::from((image[i].radiance[c] - full[i].radiance[c]).abs()))
            .sum::<f64>()
    });
    let total = sum(&|i| (0..3).map(|c| f64::from(full[i].radiance[c])).sum::<f64>());
    difference / total
}

#[test]
fn an_amortised_march_converges_and_follows_a_moving_camera() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("temporal march") else {
        return;
    };
    let settings = MarchSettings::new(MarchConfig {
        view_steps: 32,
        light: LightMarch::Full {
            steps: NonZeroU32::new(8).unwrap(),
        },
        ..MarchConfig::default()
    })
    .unwrap();
    let marcher = Marcher {
        gpu,
        volume: lumpy_blob(),
        settings,
        lighting: Lighting::<f32>::white_sun([0.3, 0.2, (1.0f64 - 0.13).sqrt()]).unwrap(),
        size: [64, 48],
    };
    let mut full_pass = MarchPass::new(&gpu.device).unwrap();
    let mut pass = MarchPass::new(&gpu.device).unwrap();
    let mut temporal = TemporalMarch::new(&gpu.device).unwrap();

    // Still: the first frame marches everything; then a frame with a scrambled
    // history (another camera) and four still frames, after which every pixel has been
    // marched at this camera once and reprojected onto itself since.
    let still = camera(0.0);
    let full = marcher.frame(&mut full_pass, None, &still);
    let first = marcher.frame(&mut pass, Some(&mut temporal), &still);
    assert!(first == full, "the first frame marches every pixel");
    marcher.frame(&mut pass, Some(&mut temporal), &camera(300.0));
    let mut converged = Vec::new();
    for frame in 0..4 {
        converged = marcher.frame(&mut pass, Some(&mut temporal), &still);
        let error = relative_error(&converged, &full);
        eprintln!("still camera, frame {frame} after a jump: relative error {error:.4}");
    }
    // Every pixel marched at this camera once since, and resampled onto itself (the
    // bilinear weights at its own centre are 1 up to f32 rounding of the projection).
    let still_error = relative_error(&converged, &full);
    assert!(
        still_error < 1e-4,
        "four still frames: relative error {still_error}"
    );

    // Moving 20 m a frame sideways while turning (the cloud shifts by about a pixel a
    // frame): each frame's image against the full march at that frame's camera, and
    // beside it the error of a full march one frame late (the last frame's exact image
    // shown at this frame).
    let (mut worst, mut sum, mut late_sum) = (0.0f64, 0.0, 0.0);
    let mut last_exact = marcher.frame(&mut full_pass, None, &still);
    let frames = 12;
    for frame in 1..=frames {
        let moving = camera(20.0 * f64::from(frame));
        let amortised = marcher.frame(&mut pass, Some(&mut temporal), &moving);
        let exact = marcher.frame(&mut full_pass, None, &moving);
        let error = relative_error(&amortised, &exact);
        let late = relative_error(&last_exact, &exact);
        worst = worst.max(error);
        sum += error;
        late_sum += late;
        eprintln!(
            "moving 20 m/frame, frame {frame}: relative error {error:.4} (one frame late: {late:.4})"
        );
        last_exact = exact;
    }
    let (mean, late_mean) = (sum / f64::from(frames), late_sum / f64::from(frames));
    eprintln!("moving: mean {mean:.4}, worst {worst:.4}; one frame late: mean {late_mean:.4}");
    // What the reprojection gets wrong (bilinear resampling, parallax inside the
    // cloud, disocclusion) lasts at most three frames (the age bound): on average well
    // under drawing each frame one frame late, and never far off.
    assert!(
        mean <= 0.5 * late_mean,
        "mean {mean} against one frame late {late_mean}"
    );
    assert!(worst < 0.05, "worst relative error {worst}");
}

#[test]
fn the_fragment_and_compute_stages_amortise_alike() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("temporal march stages") else {
        return;
    };
    let Ok(mut fragment) = MarchPass::with_stage(&gpu.device, MarchStage::Fragment) else {
        eprintln!("temporal march stages: no fragment stage on this adapter; nothing to compare");
        return;
    };
    let mut compute = MarchPass::with_stage(&gpu.device, MarchStage::Compute).unwrap();
    let marcher = Marcher {
        gpu,
        volume: lumpy_blob(),
        settings: MarchSettings::default(),
        lighting: Lighting::<f32>::white_sun([0.3, 0.2, (1.0f64 - 0.13).sqrt()]).unwrap(),
        size: [45, 34],
    };
    let mut temporals = [(); 2].map(|()| TemporalMarch::new(&gpu.device).unwrap());
    // The first frame marches every pixel, then a still frame and three moving ones,
    // each marching a quarter of the pixels and reprojecting the rest.
    let mut amortised_pixels = 0;
    for (frame, x) in [0.0, 0.0, 20.0, 40.0, 60.0].into_iter().enumerate() {
        let [on_fragment, on_compute] = &mut temporals;
        let a = marcher.frame(&mut fragment, Some(on_fragment), &camera(x));
        let b = marcher.frame(&mut compute, Some(on_compute), &camera(x));
        assert!(a == b, "frame {frame}: the stages' amortised images differ");
        if frame > 0 {
            amortised_pixels += a.len();
        }
    }
    eprintln!("temporal march: the stages agree over {amortised_pixels} amortised pixels");
}
