//! Any rung of the atmos ladder, presented by `render` on the GPU, agrees with the same
//! rung presented on the CPU twin: ≥ 99.9 % of pixels within 2 LSB per channel. Small
//! frames (software rasterisers are slow).

use atmos::frame::FrameCamera;
use atmos::gpu::FrameOutput;
use atmos::{Atmosphere, SkyModel};
use glam::DVec3;
use render::present::{PresentParameters, render_model_cpu};

const WIDTH: u32 = 96;
const HEIGHT: u32 = 54;

fn camera(earth: &Atmosphere) -> FrameCamera {
    FrameCamera::look_at(
        DVec3::new(0.0, 0.0, earth.planet_radius + 2.0),
        DVec3::new(1.0, 0.0, 0.25),
        DVec3::Z,
        1.4,
        WIDTH,
        HEIGHT,
        DVec3::new(0.9, 0.2, 0.3),
        None,
    )
    .expect("valid camera")
}

fn present_on_gpu(
    gpu: &skyscape_harness::GpuContext,
    camera: &FrameCamera,
    present: &PresentParameters,
    encode_rung: impl FnOnce(&mut wgpu::CommandEncoder, &FrameOutput),
) -> Vec<u32> {
    let frame = FrameOutput::new(&gpu.device, WIDTH, HEIGHT).expect("frame fits");
    let mut presenter = render::gpu::Presenter::new(&gpu.device).expect("present pass compiles");
    presenter
        .prepare(&gpu.queue, camera, present, &frame)
        .expect("frame matches the camera");
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    encode_rung(&mut encoder, &frame);
    presenter.encode(&mut encoder).expect("prepared");
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "presented pixels",
        presenter.pixel_buffer().expect("prepared"),
        0,
        u64::from(WIDTH * HEIGHT) * 4,
    )
    .expect("readback");
    bytemuck::cast_slice(&bytes).to_vec()
}

fn agree(name: &str, gpu: &[u32], cpu: &[u32]) {
    let close = render::tonemap::fraction_within_lsb(gpu, cpu, 2).expect("same size");
    assert!(
        close >= 0.999,
        "{name}: only {:.3} % within 2 LSB",
        100.0 * close
    );
    // The image is a sky, not a blank: the top row is blue and brighter than black.
    let top = cpu[WIDTH as usize / 2].to_le_bytes();
    assert!(top[2] > top[0] && top[2] > 60, "{name}: top row {top:?}");
}

#[test]
fn presented_closed_form_and_single_scattering_agree_with_the_cpu() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("tests::ladder_image") else {
        return;
    };
    let earth = Atmosphere::earth();
    let camera = camera(&earth);
    let present = PresentParameters::new(&earth, 20.0, 7).expect("valid");

    let closed_form = atmos::closed_form_sky::ClosedFormSky::new(&earth).unwrap();
    let cpu = render_model_cpu(&closed_form, earth.planet_radius, &camera, &present).unwrap();
    let gpu_pixels = present_on_gpu(gpu, &camera, &present, |encoder, frame| {
        let mut sky = atmos::gpu::ClosedFormRenderer::new(
            &gpu.device,
            &earth,
            atmos::gpu::EvaluationFrequency::PerPixel,
        )
        .unwrap();
        sky.prepare(&gpu.queue, &camera, frame).unwrap();
        sky.encode(encoder, None).unwrap();
    });
    agree(&closed_form.label(), &gpu_pixels, &cpu);

    let settings = atmos::single_scattering::SingleScatteringSettings::default();
    let single = atmos::single_scattering::SingleScatteringSky::new(&earth, settings).unwrap();
    let cpu = render_model_cpu(&single, earth.planet_radius, &camera, &present).unwrap();
    let gpu_pixels = present_on_gpu(gpu, &camera, &present, |encoder, frame| {
        let mut sky =
            atmos::gpu::SingleScatteringRenderer::new(&gpu.device, &earth, settings).unwrap();
        sky.prepare(&gpu.queue, &camera, frame).unwrap();
        sky.encode(encoder, None).unwrap();
    });
    agree(&single.label(), &gpu_pixels, &cpu);
}

#[test]
fn bad_display_parameters_are_rejected_naming_the_field() {
    let err = PresentParameters::new(&Atmosphere::earth(), 0.0, 0).unwrap_err();
    assert!(err.to_string().contains("exposure"), "{err}");
    let mut bad = Atmosphere::earth();
    bad.mie_g = 1.5;
    let err = PresentParameters::new(&bad, 1.0, 0).unwrap_err();
    assert!(err.to_string().contains("mie_g"), "{err}");
}
