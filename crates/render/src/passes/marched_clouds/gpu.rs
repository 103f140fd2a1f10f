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
    // A marched cloud's air per light that lights it (its march and air passes).
    let airs = |lights: usize| {
        let mut airs = shared.cloud_airs()?;
        airs.truncate(lights);
        Ok::<_, RenderError>(airs)
    };
    let volume = match &scene.volume_cloud {
        Some(cloud) => Some(VolumeCloudPass::new_volume(
            device,
            &airs(cloud.lights.len())?,
            HDR,
        )?),
        None => None,
    };
    let shell = match &scene.shell_cloud {
        Some(cloud) => Some(ShellCloudPass::new_shell(
            device,
            &airs(cloud.lights.len())?,
            HDR,
        )?),
        None => None,
    };
    let (mut volume, mut shell) = (volume, shell);
    if shared.settings.temporal_clouds {
        if let Some(volume) = &mut volume {
            volume.amortise(device)?;
        }
        if let Some(shell) = &mut shell {
            shell.amortise(device)?;
        }
    }
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
        let airs = shared.cloud_airs()?;
        // Each light's march is a step: the sun's, and the light added to it (the moon).
        let marches = |count: usize, labels: [&'static str; 2]| -> Vec<_> {
            (0..count)
                .map(|index| match index {
                    0 => times.and_then(|t| t.render_writes(labels[0])),
                    1 => times.and_then(|t| t.render_writes(labels[1])),
                    _ => None,
                })
                .collect()
        };
        const SHELL: [&str; 2] = ["shell cloud march", "moonlit shell march"];
        const VOLUME: [&str; 2] = ["volume cloud march", "moonlit cloud march"];
        if let (Some(order), Some(shell), Some(volume)) = (&self.order, &self.shell, &self.volume) {
            // Both marched clouds: their marches and air, then one composite by depth.
            shell.encode_marches(encoder, &airs, marches(shell.light_count(), SHELL))?;
            volume.encode_marches(encoder, &airs, marches(volume.light_count(), VOLUME))?;
            let composite = times.and_then(|t| t.render_writes("clouds by depth"));
            return order.encode(encoder, &shared.hdr_view, composite);
        }
        if let Some(shell) = &self.shell {
            shell.encode(
                encoder,
                &shared.hdr_view,
                &airs,
                CloudTimes {
                    marches: marches(shell.light_count(), SHELL),
                    composite: times.and_then(|t| t.render_writes("shell clouds")),
                },
            )?;
        }
        if let Some(volume) = &self.volume {
            volume.encode(
                encoder,
                &shared.hdr_view,
                &airs,
                CloudTimes {
                    marches: marches(volume.light_count(), VOLUME),
                    composite: times.and_then(|t| t.render_writes("volume clouds")),
                },
            )?;
        }
        Ok(())
    }
}
