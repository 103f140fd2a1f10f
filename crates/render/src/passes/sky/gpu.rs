//! The sky pass on the GPU: the render pass that clears the frame's targets and draws
//! each light's sky (atmos' sky pass over its tables, or a rung's full-screen triangle),
//! the moon's added.

use atmos::gpu::sky::{SkyPass, SkyPassDescriptor};
use atmos::lut::drop_in::SkyPassParameters;

use crate::RenderError;
use crate::gpu::frame::{DEPTH, GpuPass, GpuShared, HDR};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// atmos' sky pass per light of the precomputed rung, the sun's first, each next one
/// added (a rung without tables draws its own: `crate::gpu::rungs`).
#[derive(Debug)]
struct SkyDraws(Vec<SkyPass>);

/// Builds the sky pass: atmos' sky pass over each light's tables.
pub(crate) fn build(
    shared: &GpuShared,
    _scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    let sky_pass = |luts, blend| {
        SkyPass::new(
            &shared.device,
            luts,
            &SkyPassDescriptor {
                depth_format: Some(DEPTH),
                blend,
                ..SkyPassDescriptor::new(HDR)
            },
        )
    };
    let additive = wgpu::BlendComponent {
        src_factor: wgpu::BlendFactor::One,
        dst_factor: wgpu::BlendFactor::One,
        operation: wgpu::BlendOperation::Add,
    };
    let added = wgpu::BlendState {
        color: additive,
        alpha: additive,
    };
    let draws = shared
        .tables
        .iter()
        .enumerate()
        .map(|(index, luts)| sky_pass(luts, (index > 0).then_some(added)))
        .collect::<Result<_, _>>()?;
    Ok(Box::new(SkyDraws(draws)))
}

impl GpuPass for SkyDraws {
    fn prepare(
        &mut self,
        _shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        // Every pass writes radiance × the exposure into the half-float target: a night
        // sky's ~1e-7 (the sun's irradiance as unit) would sink into f16's subnormals
        // (below 6.1e-5) and flush; exposed, the image's values are near 1.
        let radiance_scale = scene.present.exposure;
        // The sun's disc unless celestial draws it; no disc for the moon (celestial's).
        let lights = std::iter::once((&scene.atmosphere, scene.sky_objects.is_none())).chain(
            scene
                .other_lights
                .iter()
                .map(|light| (&light.atmosphere, false)),
        );
        for (pass, (atmosphere, disc)) in self.0.iter_mut().zip(lights) {
            pass.prepare(
                queue,
                &SkyPassParameters::new(atmosphere, disc, radiance_scale, 0.0)?,
            );
        }
        Ok(())
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("render scene"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &shared.hdr_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &shared.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Clear(0.0),
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: times.and_then(|t| t.render_writes("sky")),
            ..Default::default()
        });
        for (sky, luts) in self.0.iter().zip(&shared.tables) {
            sky.draw(&mut pass, luts)?;
        }
        if let Some(rung) = &shared.rung {
            rung.draw_sky(&mut pass);
        }
        Ok(())
    }
}
