//! The volume cloud's GPU passes: cloudlight's march, the air in front of it and the
//! composite (`crate::gpu::cloud_composite`), with their uniforms.

use super::{PreparedVolume, pinhole_camera};

/// The GPU side: `cloudlight::gpu::MarchPass` over the scene's pixels (prepared per
/// frame with [`pinhole_camera`]; at night a second one lit by the moon) in
/// [`crate::gpu::cloud_composite::CloudComposite`]'s passes: the terrain's depth as a
/// distance per pixel the march stops at, the air in front of the cloud per pixel and
/// light (atmos' `aerial_perspective`, the CPU's function) and the composite render pass
/// (`shaders/render/volume_clouds.wgsl`).
pub(crate) type VolumeCloudPass =
    crate::gpu::cloud_composite::CloudComposite<cloudlight::gpu::MarchPass>;

impl VolumeCloudPass {
    /// The march, air and composite pipelines; `moon_luts`: the moonlit tables when the
    /// scene's cloud is lit by the moon too ([`PreparedVolume::moon`]).
    pub(crate) fn new_volume(
        device: &wgpu::Device,
        luts: crate::gpu::cloud_air::CloudAir<'_>,
        moon_luts: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        target: wgpu::TextureFormat,
    ) -> Result<Self, crate::RenderError> {
        Self::new(
            device,
            "volume",
            "clouds.volume",
            luts,
            moon_luts,
            target,
            || Ok(cloudlight::gpu::MarchPass::new(device)?),
        )
    }

    /// The frame's marches (the scene camera as a pinhole camera in the volume's frame,
    /// one ray per pixel up to `distance`'s buffer; the moon's at night), the air passes'
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
        let moon = cloud.moon.as_ref().map(|moon| &moon.lighting);
        self.prepare(
            device,
            queue,
            scene,
            distance,
            depth_view,
            &cloud.lighting,
            moon,
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
