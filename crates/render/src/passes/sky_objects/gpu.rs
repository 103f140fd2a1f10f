//! The sky objects on the GPU: celestial's `SkyObjectsPass`, additive, depth-tested
//! behind the terrain.

use crate::RenderError;
use crate::gpu::frame::{DEPTH, GpuPass, GpuShared, HDR};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// celestial's pass over the scene's targets.
#[derive(Debug)]
struct SkyObjects(celestial::gpu::SkyObjectsPass);

/// Builds celestial's pass, depth-tested against the terrain.
pub(crate) fn build(
    shared: &GpuShared,
    _scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    let mut objects = celestial::gpu::SkyObjectsSettings::new(HDR);
    objects.depth = Some(celestial::gpu::DepthTest {
        format: DEPTH,
        compare: wgpu::CompareFunction::GreaterEqual,
    });
    Ok(Box::new(SkyObjects(celestial::gpu::SkyObjectsPass::new(
        &shared.device,
        &objects,
    )?)))
}

impl GpuPass for SkyObjects {
    fn prepare(
        &mut self,
        _shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let frame = scene
            .sky_objects
            .as_ref()
            .ok_or_else(|| crate::gpu::frame::differs("sky_objects", true))?;
        // The HDR target holds radiance × the exposure.
        let exposure = scene.present.exposure;
        let mut frame = frame.clone();
        for disc in &mut frame.discs {
            disc.radiance = disc.radiance.map(|r| r * exposure);
        }
        frame.uniforms.lux_per_unit /= exposure;
        self.0.prepare(queue, &frame)?;
        Ok(())
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        self.0.encode(
            encoder,
            &shared.hdr_view,
            Some(&shared.depth_view),
            times.and_then(|t| t.render_writes("sky objects")),
        )?;
        Ok(())
    }
}
