//! Every shipped scene on the GPU and on the CPU reference renderer: the images agree
//! (the same shading functions; the terrain rasterised as triangles on one side and
//! ray cast against the bilinear surface on the other, so silhouettes may differ).

mod common;

use common::{compare, shipped};

#[test]
fn every_shipped_scene_agrees_on_the_gpu_and_the_cpu() {
    let Some(gpu) = common::gpu_or_skip("render::scene_gpu") else {
        return;
    };
    for shipped_scene in render::scene::shipped::SHIPPED {
        agree(gpu, shipped_scene.name);
    }
}

fn agree(gpu: &skyscape_harness::GpuContext, name: &str) {
    let scene = shipped(name, 160, 90).prepare().unwrap();
    // Rasterised triangles and the ray-cast bilinear surface hit neighbouring points
    // of terrain finer than a pixel (60 m texels, ~130 m pixels at 14 km here), so
    // single pixels of ridged terrain differ by tens of code values either way. The
    // metric: most pixels within 2 LSB, nearly all within 8, and no bias — the mean
    // signed and absolute differences over the image stay below a code value, which a
    // shading mismatch between the twins would not.
    let (_, _, agreement) = compare(gpu, &scene);
    eprintln!(
        "{name} 160×90: {:.3} % of pixels within 2 LSB, {:.3} % within 8, \
         {:.3} % within 2 LSB of a pixel in the other image's 3×3 neighbourhood; \
         mean difference (GPU − CPU) {:.3?} LSB, mean |difference| {:.3?} LSB",
        100.0 * agreement.two,
        100.0 * agreement.eight,
        100.0 * agreement.shifted,
        agreement.signed,
        agreement.absolute,
    );
    assert!(agreement.close(), "{name}: {}", agreement.fractions());
    assert!(agreement.unbiased(1.0), "{name}: {}", agreement.biases());
}
