//! The marched clouds on the GPU: the terrain's depth as a distance per pixel (once
//! for every marched cloud), each cloud's march and air per light, and its composite
//! (or, with both clouds, one composite by depth: `crate::gpu::cloud_order`).

use crate::RenderError;
use crate::gpu::cloud_composite::{CloudDistance, CloudTimes};
use crate::gpu::cloud_order::CloudOrderPass;
use crate::gpu::frame::{GpuPass, GpuShared, HDR};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;
use crate::shell_clouds::ShellCloudPass;
use crate::volume_clouds::VolumeCloudPass;

/// The scene's marched clouds and what they share.
#[derive(Debug)]
struct MarchedClouds {
    distance: CloudDistance,
    shell: Option<ShellCloudPass>,
    volume: Option<VolumeCloudPass>,
    /// Both clouds: their one composite by depth.
    order: Option<CloudOrderPass>,
}

/// Builds the marches and composites of the scene's marched clouds.
pub(crate) fn build(
    shared: &GpuShared,
    scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    let device = &shared.device;
    // A marched cloud's air: the sun's, and at night (`moonlit`) the moon's, which
    // lights the cloud too (its march and air passes).
    let airs = |moonlit: bool| {
        let (sun, moon) = shared.cloud_airs()?;
        Ok::<_, RenderError>((sun, moon.filter(|_| moonlit)))
    };
    let volume = match &scene.volume_cloud {
        Some(cloud) => {
            let (sun, moon) = airs(cloud.moon.is_some())?;
            Some(VolumeCloudPass::new_volume(device, sun, moon, HDR)?)
        }
        None => None,
    };
    let shell = match &scene.shell_cloud {
        Some(cloud) => {
            let (sun, moon) = airs(cloud.moon.is_some())?;
            Some(ShellCloudPass::new_shell(device, sun, moon, HDR)?)
        }
        None => None,
    };
    let order = if volume.is_some() && shell.is_some() {
        Some(CloudOrderPass::new(device, HDR)?)
    } else {
        None
    };
    Ok(Box::new(MarchedClouds {
        distance: CloudDistance::new(device)?,
        shell,
        volume,
        order,
    }))
}

impl GpuPass for MarchedClouds {
    fn prepare(
        &mut self,
        shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let (device, depth) = (&shared.device, &shared.depth_view);
        self.distance.prepare(device, queue, scene, depth);
        // Each cloud stops at the distance prepared above.
        if let (Some(pass), Some(cloud)) = (&mut self.volume, &scene.volume_cloud) {
            pass.prepare_volume(device, queue, scene, cloud, &self.distance, depth)?;
        }
        if let (Some(pass), Some(cloud)) = (&mut self.shell, &scene.shell_cloud) {
            pass.prepare_shell(device, queue, scene, cloud, &self.distance, depth)?;
        }
        if let (Some(order), Some(volume), Some(shell)) =
            (&mut self.order, &self.volume, &self.shell)
        {
            // After both clouds' marches and air: their buffers.
            order.prepare(device, queue, scene, volume, shell, depth)?;
        }
        Ok(())
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        // After the terrain (the marches stop at its depth), once for every cloud.
        self.distance.encode(encoder)?;
        let (sun, moon) = shared.cloud_airs()?;
        let compute = |label| times.and_then(|t| t.compute_writes(label));
        // The moon's march is a step only where the moon lights the cloud.
        let moon_compute = |moonlit: bool, label| if moonlit { compute(label) } else { None };
        if let (Some(order), Some(shell), Some(volume)) = (&self.order, &self.shell, &self.volume) {
            // Both marched clouds: their marches and air, then one composite by depth.
            let (march, moon_march) = (
                compute("shell cloud march"),
                moon_compute(shell.moonlit(), "moonlit shell march"),
            );
            shell.encode_marches(encoder, sun, moon, march, moon_march)?;
            let (march, moon_march) = (
                compute("volume cloud march"),
                moon_compute(volume.moonlit(), "moonlit cloud march"),
            );
            volume.encode_marches(encoder, sun, moon, march, moon_march)?;
            let composite = times.and_then(|t| t.render_writes("clouds by depth"));
            return order.encode(encoder, &shared.hdr_view, composite);
        }
        if let Some(shell) = &self.shell {
            shell.encode(
                encoder,
                &shared.hdr_view,
                sun,
                moon,
                CloudTimes {
                    march: compute("shell cloud march"),
                    moon: moon_compute(shell.moonlit(), "moonlit shell march"),
                    composite: times.and_then(|t| t.render_writes("shell clouds")),
                },
            )?;
        }
        if let Some(volume) = &self.volume {
            volume.encode(
                encoder,
                &shared.hdr_view,
                sun,
                moon,
                CloudTimes {
                    march: compute("volume cloud march"),
                    moon: moon_compute(volume.moonlit(), "moonlit cloud march"),
                    composite: times.and_then(|t| t.render_writes("volume clouds")),
                },
            )?;
        }
        Ok(())
    }
}
