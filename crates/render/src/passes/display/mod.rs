//! The display: exposure, the scene's display transform (hue-preserving neutral or
//! per-channel `1 − exp(−x)`), sRGB and a triangular dither to RGBA8
//! ([`crate::tonemap`]).

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use rayon::prelude::*;

use super::{PassEntry, PlanLine};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::present::PresentParameters;
use crate::scene::prepare::PreparedScene;
use crate::tonemap::{DisplayTransform, display_transform, pack_rgba8, quantize_srgb8};

/// The display's entry in the frame.
pub(crate) const ENTRY: PassEntry = PassEntry {
    name: "display",
    runs: |_| true,
    plan,
    cpu,
    #[cfg(feature = "gpu")]
    gpu: gpu::build,
};

/// The display pass's uniform (WGSL `DisplayParameters`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DisplayParameters {
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Exposure before the display transform.
    pub exposure: f32,
    /// Dither seed.
    pub dither_seed: u32,
    /// [`crate::tonemap::DisplayTransform::code`].
    pub display_transform: u32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding_a: u32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding_b: u32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding_c: u32,
}

fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    let transform = DisplayTransform::from_code(scene.present.display_transform);
    let curve = match transform {
        DisplayTransform::Neutral => "the neutral hue-preserving curve",
        DisplayTransform::PerChannel => "1 − exp(−x) per channel",
    };
    vec![PlanLine::timed(
        "display",
        Ok(format!("exposure, {curve}, sRGB, dither to RGBA8")),
    )]
}

/// The CPU twin: the frame's radiance to RGBA8.
fn cpu(frame: &mut CpuFrame<'_>) -> Result<(), RenderError> {
    let radiance: Vec<[f32; 3]> = frame.pixels.iter().map(|p| p.radiance).collect();
    let scene = frame.scene;
    frame.display = Some(display_pixels(
        &radiance,
        scene.camera.width,
        &scene.present,
    ));
    Ok(())
}

/// Row-major radiance `width` pixels wide to display pixels: the exposure, the
/// display transform, sRGB and the triangular dither of `present` (the display pass's twin), packed
/// RGBA8.
pub fn display_pixels(radiance: &[[f32; 3]], width: u32, present: &PresentParameters) -> Vec<u32> {
    let width = width.max(1) as usize;
    radiance
        .par_iter()
        .enumerate()
        .map(|(i, radiance)| {
            let pixel = [(i % width) as u32, (i / width) as u32];
            let transform = DisplayTransform::from_code(present.display_transform);
            let display = display_transform(*radiance, present.exposure, transform);
            pack_rgba8(quantize_srgb8(display, pixel, present.dither_seed))
        })
        .collect()
}
