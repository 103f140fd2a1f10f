//! The deck's GPU passes: cloudlight's `MarchShellPass` in the marched clouds' shared
//! passes (`crate::gpu::cloud_composite`).

use super::{PreparedShell, shell_camera};

/// The GPU side: `cloudlight::gpu::MarchShellPass` over the scene's pixels (prepared per
/// frame with [`shell_camera`]; one per light of the scene) in the volume
/// cloud's passes ([`crate::gpu::cloud_composite::CloudComposite`]: the terrain's depth
/// as a distance per pixel the march stops at, the air in front of the deck per pixel
/// and light, the composite render pass `shaders/render/volume_clouds.wgsl`). Built only
/// for scenes with `[clouds.shell]`.
#[cfg(feature = "gpu")]
pub(crate) type ShellCloudPass =
    crate::gpu::cloud_composite::CloudComposite<cloudlight::gpu::MarchShellPass>;

#[cfg(feature = "gpu")]
impl ShellCloudPass {
    /// The march, distance, air and composite pipelines, one march per light of `airs` (each light's
    /// air, the sun's first: the cloud's [`PreparedShell::lights`]).
    pub(crate) fn new_shell(
        device: &wgpu::Device,
        airs: &[crate::gpu::cloud_air::CloudAir<'_>],
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        Self::new(device, "shell", "clouds.shell", airs, target, || {
            Ok(cloudlight::gpu::MarchShellPass::new(device)?)
        })
    }

    /// The frame's marches (the scene camera in the shell's frame, one ray per pixel up
    /// to `distance`'s buffer; one per light), the air and composite passes'
    /// uniforms and bind groups.
    pub(crate) fn prepare_shell(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        cloud: &PreparedShell,
        distance: &crate::gpu::cloud_composite::CloudDistance,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), crate::RenderError> {
        let camera = &scene.camera;
        let pinhole = shell_camera(camera)?;
        let size = [camera.width, camera.height];
        let lightings: Vec<_> = cloud.lights.iter().map(|light| &light.lighting).collect();
        self.prepare(
            device,
            queue,
            scene,
            distance,
            depth_view,
            &lightings,
            |march, light, lighting, distances, kept| {
                // Lit through the volume cloud's shadow map for this light
                // (crate::mutual_shadow; uploaded once, kept while unchanged), read the
                // planet's radius below the march's frame.
                let volume = scene
                    .volume_cloud
                    .as_ref()
                    .and_then(|volume| crate::mutual_shadow::volume_on_deck(volume, light));
                let volume = kept.upload(device, queue, volume);
                let planet = cloud.shell.planet_radius() as f32;
                // The march stops at the terrain: a hill hides the deck behind it.
                Ok(march.prepare_lit_through(
                    device,
                    queue,
                    &cloud.shell,
                    &pinhole,
                    size,
                    &cloud.settings,
                    lighting,
                    Some(distances),
                    volume
                        .map(|v| crate::mutual_shadow::outside(v, planet))
                        .as_ref(),
                )?)
            },
        )
    }
}
