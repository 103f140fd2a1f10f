//! The volume cloud's GPU passes: cloudlight's march, the air in front of it and the
//! composite (`crate::gpu::cloud_composite`), with their uniforms.

use super::{PreparedVolume, pinhole_camera};

/// The GPU side: `cloudlight::gpu::MarchPass` over the scene's pixels (prepared per
/// frame with [`pinhole_camera`]; one per light of the scene) in
/// [`crate::gpu::cloud_composite::CloudComposite`]'s passes: the terrain's depth as a
/// distance per pixel the march stops at, the air in front of the cloud per pixel and
/// light (atmos' `aerial_perspective`, the CPU's function) and the composite render pass
/// (`shaders/render/volume_clouds.wgsl`).
pub(crate) type VolumeCloudPass =
    crate::gpu::cloud_composite::CloudComposite<cloudlight::gpu::MarchPass>;

impl VolumeCloudPass {
    /// The march, air and composite pipelines, one march per light of `airs` (each light's
    /// air, the sun's first: the cloud's [`PreparedVolume::lights`]).
    pub(crate) fn new_volume(
        device: &wgpu::Device,
        airs: &[crate::gpu::cloud_air::CloudAir<'_>],
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        Self::new(device, "volume", "clouds.volume", airs, target, || {
            Ok(cloudlight::gpu::MarchPass::new(device)?)
        })
    }

    /// The frame's marches (the scene camera as a pinhole camera in the volume's frame,
    /// one ray per pixel up to `distance`'s buffer; one per light), the air passes'
    /// and the composite's uniforms and bind groups.
    pub(crate) fn prepare_volume(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        cloud: &PreparedVolume,
        distance: &crate::gpu::cloud_composite::CloudDistance,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), crate::RenderError> {
        let camera = &scene.camera;
        let pinhole = pinhole_camera(camera, scene.atmosphere.planet_radius)?;
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
                // Lit through the deck's shadow map for this light (crate::mutual_shadow),
                // its values uploaded once and kept while unchanged.
                let deck = scene
                    .shell_cloud
                    .as_ref()
                    .and_then(|shell| crate::mutual_shadow::deck_on_volume(shell, light));
                let deck = kept.upload(device, queue, deck);
                // The march stops at the terrain: a ridge cuts the cloud where it stands.
                Ok(march.prepare_lit_through(
                    device,
                    queue,
                    &cloud.volume,
                    &pinhole,
                    size,
                    &cloud.settings,
                    lighting,
                    Some(distances),
                    deck.map(|d| crate::mutual_shadow::outside(d, 0.0)).as_ref(),
                )?)
            },
        )
    }
}
