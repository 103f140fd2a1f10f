//! Every shipped scene on the GPU and on the CPU reference renderer: the images agree
//! (the same shading functions; the terrain rasterised as triangles on one side and
//! ray cast against the bilinear surface on the other, so silhouettes may differ).

use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::scene::Scene;

fn shipped(name: &str, width: u32, height: u32) -> Scene {
    let path = format!("{}/../../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut scene = Scene::open(&path).unwrap();
    scene.file.output.width = width;
    scene.file.output.height = height;
    scene
}

fn gpu_pixels(
    gpu: &skyscape_harness::GpuContext,
    scene: &render::scene::PreparedScene,
) -> Vec<u32> {
    let settings = SceneRendererSettings {
        terrain_error_px: 0.0,
        timestamps: false,
    };
    let mut renderer = SceneRenderer::new(&gpu.device, &gpu.queue, scene, settings).unwrap();
    renderer.prepare(&gpu.queue, scene).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    renderer.encode(&mut encoder).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let buffer = renderer.pixel_buffer();
    let bytes =
        skyscape_harness::read_buffer(gpu, "scene pixels", buffer, 0, buffer.size()).unwrap();
    bytemuck::cast_slice(&bytes).to_vec()
}

#[test]
fn every_shipped_scene_agrees_on_the_gpu_and_the_cpu() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("render::scene_gpu") else {
        return;
    };
    for shipped_scene in render::scene::shipped::SHIPPED {
        agree(gpu, shipped_scene.name);
    }
}

fn agree(gpu: &skyscape_harness::GpuContext, name: &str) {
    let scene = shipped(name, 160, 90).prepare().unwrap();
    let gpu_image = gpu_pixels(gpu, &scene);
    let cpu_image = render::cpu_renderer::render_cpu(&scene).unwrap().pixels;
    // Rasterised triangles and the ray-cast bilinear surface hit neighbouring points
    // of terrain finer than a pixel (60 m texels, ~130 m pixels at 14 km here), so
    // single pixels of ridged terrain differ by tens of code values either way. The
    // metric: most pixels within 2 LSB, nearly all within 8, and no bias — the mean
    // signed and absolute differences over the image stay below a code value, which a
    // shading mismatch between the twins would not.
    let within = |lsb| render::tonemap::fraction_within_lsb(&gpu_image, &cpu_image, lsb).unwrap();
    let shifted =
        render::tonemap::fraction_within_lsb_of_neighbourhood(&gpu_image, &cpu_image, 160, 2, 1)
            .unwrap();
    let (two, eight) = (within(2), within(8));
    let mut signed = [0.0f64; 3];
    let mut absolute = [0.0f64; 3];
    for (a, b) in gpu_image.iter().zip(&cpu_image) {
        for channel in 0..3 {
            let code = |p: u32| f64::from((p >> (8 * channel)) & 255);
            let difference = code(*a) - code(*b);
            signed[channel] += difference / gpu_image.len() as f64;
            absolute[channel] += difference.abs() / gpu_image.len() as f64;
        }
    }
    eprintln!(
        "{name} 160×90: {:.3} % of pixels within 2 LSB, {:.3} % within 8, \
         {:.3} % within 2 LSB of a pixel in the other image's 3×3 neighbourhood; \
         mean difference (GPU − CPU) {signed:.3?} LSB, mean |difference| {absolute:.3?} LSB",
        100.0 * two,
        100.0 * eight,
        100.0 * shifted
    );
    assert!(
        two >= 0.96 && eight >= 0.985 && shifted >= 0.975,
        "{name}: {two} {eight} {shifted}"
    );
    for channel in 0..3 {
        assert!(
            signed[channel].abs() <= 0.5 && absolute[channel] <= 1.0,
            "{name}: {signed:?} {absolute:?}"
        );
    }
}
