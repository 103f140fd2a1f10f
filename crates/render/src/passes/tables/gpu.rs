//! The tables pass on the GPU: atmos' LUT bakes per light (the static tables once, the
//! per-frame tables every frame), or a rung's sky evaluation per light.

use crate::RenderError;
use crate::gpu::frame::{GpuPass, GpuShared};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// Records the lights' table bakes or sky evaluations.
#[derive(Debug)]
struct TablesPass {
    /// The static tables are baked once per atmosphere, by the first encoder that
    /// records this pass.
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
        match (&mut shared.moon_luts, &scene.moonlit) {
            (Some(luts), Some(moon)) => luts.prepare(queue, &moon.camera(camera)),
            (None, None) => {}
            // A rung without tables draws its moonlit sky itself (prepared below).
            (None, Some(_)) if shared.rung.is_some() => {}
            (built, _) => {
                return Err(RenderError::InvalidParameter {
                    field: "moonlit sky",
                    value: if built.is_some() { "off" } else { "on" }.into(),
                    reason: "differs from the scene the renderer was built for",
                });
            }
        }
        if let Some(luts) = &mut shared.luts {
            luts.prepare(queue, camera);
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
            for luts in [&shared.luts, &shared.moon_luts].into_iter().flatten() {
                luts.encode_static_luts(encoder, None);
            }
            self.static_luts_pending = false;
        }
        if let Some(luts) = &shared.luts {
            luts.encode_frame_luts(
                encoder,
                times.and_then(|t| t.compute_writes("atmosphere LUT bakes")),
            );
        }
        if let Some(luts) = &shared.moon_luts {
            luts.encode_frame_luts(
                encoder,
                times.and_then(|t| t.compute_writes("moonlit sky LUT bakes")),
            );
        }
        if let Some(rung) = &shared.rung {
            rung.encode_sky_evaluation(encoder, times)?;
        }
        Ok(())
    }
}
