//! The billboards on the GPU: the particles' air (a rung without tables: a compute pass
//! first) and one render pass of splats, depth-tested against the terrain.

use crate::RenderError;
use crate::billboard_clouds::BillboardCloudPass;
use crate::gpu::frame::{DEPTH, GpuPass, GpuShared, HDR};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// The billboards' pipeline and particles.
#[derive(Debug)]
struct Billboards(BillboardCloudPass);

/// Builds the billboards' pass; its air is the tables, or the rung's functions per light.
pub(crate) fn build(
    shared: &GpuShared,
    scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    // The tables of the lights after the sun are not the billboards' (the CPU lights
    // the particles by each light: `BillboardLight`); under a rung without tables the
    // light added to the sun gets its air pass.
    let lights = scene.billboard_cloud.as_ref().map_or(1, |c| c.lights.len());
    let airs = shared.cloud_airs().ok();
    let added = airs
        .as_ref()
        .and_then(|airs| airs.get(1).copied())
        .filter(|air| !matches!(air, crate::gpu::cloud_air::CloudAir::Tables(_)))
        .filter(|_| lights == 2);
    Ok(Box::new(Billboards(BillboardCloudPass::new(
        &shared.device,
        airs.as_ref().and_then(|airs| airs.first().copied()),
        added,
        HDR,
        DEPTH,
    )?)))
}

impl GpuPass for Billboards {
    fn prepare(
        &mut self,
        shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let cloud = scene
            .billboard_cloud
            .as_ref()
            .ok_or_else(|| crate::gpu::frame::differs("clouds.volume", true))?;
        self.0.prepare(&shared.device, queue, scene, cloud)
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        // After the terrain: its depth hides the particles behind it.
        self.0.encode(
            encoder,
            &shared.hdr_view,
            &shared.depth_view,
            shared.sun_tables(),
            times.and_then(|t| t.render_writes("billboard clouds")),
        )
    }
}
