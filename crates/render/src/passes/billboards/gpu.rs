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
    let moonlit = scene
        .billboard_cloud
        .as_ref()
        .is_some_and(|cloud| cloud.moon.is_some());
    // The moon's tables are not the billboards' (the CPU lights its particles by the
    // moon: `MoonlitBillboards`); a rung without tables gives the moon's air pass.
    let airs = shared.cloud_airs().ok().map(|(sun, moon)| {
        let moon = moon.filter(|air| !matches!(air, crate::gpu::cloud_air::CloudAir::Tables(_)));
        (sun, moon)
    });
    Ok(Box::new(Billboards(BillboardCloudPass::new(
        &shared.device,
        airs.map(|(sun, _)| sun),
        airs.and_then(|(_, moon)| moon).filter(|_| moonlit),
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
