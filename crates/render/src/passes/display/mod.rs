//! The display: exposure, the tone map `1 − exp(−x)`, sRGB and a triangular dither to
//! RGBA8 ([`crate::tonemap`]).

#[cfg(feature = "gpu")]
pub(crate) mod gpu;

use rayon::prelude::*;

use super::{PassEntry, PlanLine};
use crate::RenderError;
use crate::cpu_frame::CpuFrame;
use crate::present::PresentParameters;
use crate::scene::prepare::PreparedScene;
use crate::tonemap::{pack_rgba8, quantize_srgb8, tonemap_exposure};

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
    /// Exposure before `1 − exp(−x)`.
    pub exposure: f32,
    /// Dither seed.
    pub dither_seed: u32,
}

fn plan(_scene: &PreparedScene) -> Vec<PlanLine> {
    vec![PlanLine::timed(
        "display",
        Ok("exposure, 1 − exp(−x), sRGB, dither to RGBA8".into()),
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

/// Row-major radiance `width` pixels wide to display pixels: the exposure, the tone
/// map, sRGB and the triangular dither of `present` (the display pass's twin), packed
/// RGBA8.
pub fn display_pixels(radiance: &[[f32; 3]], width: u32, present: &PresentParameters) -> Vec<u32> {
    let width = width.max(1) as usize;
    radiance
        .par_iter()
        .enumerate()
        .map(|(i, radiance)| {
            let pixel = [(i % width) as u32, (i / width) as u32];
            let display = tonemap_exposure(*radiance, present.exposure);
            pack_rgba8(quantize_srgb8(display, pixel, present.dither_seed))
        })
        .collect()
}
