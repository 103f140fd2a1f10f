//! The tables pass on the GPU: atmos' LUT bakes per light (the static tables once —
//! the preparation's CPU tables written, or baked — the per-frame tables every frame),
//! or a rung's sky evaluation per light.

use crate::RenderError;
use crate::gpu::frame::{GpuPass, GpuShared};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// The per-frame bake of light `index` as a step of the plan: the sun's, then the
/// lights' added to it (the moon's; a third light's bake would write the same span).
fn frame_bake(index: usize) -> &'static str {
    if index == 0 {
        "atmosphere LUT bakes"
    } else {
        "moonlit sky LUT bakes"
    }
}

/// Records the lights' table bakes or sky evaluations.
#[derive(Debug)]
struct TablesPass {
    /// The static tables are written once per atmosphere: from the preparation's CPU
    /// tables when it has them, else baked by the first encoder that records this pass.
    static_luts_pending: bool,
}

/// Builds the tables pass (the tables themselves are shared: [`GpuShared`]).
pub(crate) fn build(
    _shared: &GpuShared,
    _scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    Ok(Box::new(TablesPass {
        static_luts_pending: true,
    }))
}

impl GpuPass for TablesPass {
    fn prepare(
        &mut self,
        shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let camera = &scene.camera;
        // Each light's camera: the scene's with its `sun` the light's direction.
        let cameras: Vec<_> = scene
            .lights()
            .iter()
            .map(|light| light.camera(camera))
            .collect();
        // A rung without tables prepares its own per light (below).
        if !shared.tables.is_empty() && shared.tables.len() != cameras.len() {
            return Err(RenderError::InvalidParameter {
                field: "lights",
                value: format!("{} lights", cameras.len()),
                reason: "differs from the scene the renderer was built for",
            });
        }
        for (luts, camera) in shared.tables.iter().zip(&cameras) {
            luts.prepare(queue, camera);
        }
        // The preparation holds each light's static tables (its CPU side reads them):
        // written as they are, no GPU bake (the renderer draws one atmosphere; a new
        // one builds a new renderer).
        if self.static_luts_pending {
            let prepared: Vec<_> = scene.lights().iter().map(|l| l.precomputed).collect();
            if !shared.tables.is_empty() && prepared.iter().all(Option::is_some) {
                for (luts, cpu) in shared.tables.iter().zip(prepared.into_iter().flatten()) {
                    luts.write_static_luts(queue, cpu.static_luts())
                        .map_err(RenderError::Atmosphere)?;
                }
                self.static_luts_pending = false;
            }
        }
        let GpuShared {
            device,
            hdr_view,
            depth_view,
            rung,
            ..
        } = shared;
        if let Some(rung) = rung {
            rung.prepare(device, queue, scene, hdr_view, depth_view)?;
        }
        Ok(())
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        // The static bakes once (untimed: per atmosphere, not per frame).
        if self.static_luts_pending {
            for luts in &shared.tables {
                luts.encode_static_luts(encoder, None);
            }
            self.static_luts_pending = false;
        }
        for (index, luts) in shared.tables.iter().enumerate() {
            let step = frame_bake(index);
            luts.encode_frame_luts(encoder, times.and_then(|t| t.compute_writes(step)));
        }
        if let Some(rung) = &shared.rung {
            rung.encode_sky_evaluation(encoder, times)?;
        }
        Ok(())
    }
}
