//! The sky pass on the GPU: the render pass that clears the frame's targets and draws
//! each light's sky (atmos' sky pass over its tables, or a rung's full-screen triangle),
//! the moon's added.

use atmos::gpu::sky::{SkyPass, SkyPassDescriptor};
use atmos::lut::drop_in::SkyPassParameters;

use crate::RenderError;
use crate::gpu::frame::{DEPTH, GpuPass, GpuShared, HDR};
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// atmos' sky pass per light of the precomputed rung (a rung without tables draws its
/// own: `crate::gpu::rungs`).
#[derive(Debug)]
struct SkyDraws {
    sun: Option<SkyPass>,
    moon: Option<SkyPass>,
}

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
    let sun = match &shared.luts {
        Some(luts) => Some(sky_pass(luts, None)?),
        None => None,
    };
    let moon = match &shared.moon_luts {
        Some(luts) => Some(sky_pass(
            luts,
            Some(wgpu::BlendState {
                color: additive,
                alpha: additive,
            }),
        )?),
        None => None,
    };
    Ok(Box::new(SkyDraws { sun, moon }))
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
        if let (Some(pass), Some(moon)) = (&mut self.moon, &scene.moonlit) {
            pass.prepare(
                queue,
                &SkyPassParameters::new(&moon.atmosphere, false, radiance_scale, 0.0)?,
            );
        }
        if let Some(sky) = &mut self.sun {
            sky.prepare(
                queue,
                &SkyPassParameters::new(
                    &scene.atmosphere,
                    scene.sky_objects.is_none(),
                    radiance_scale,
                    0.0,
                )?,
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
        match (&self.sun, &shared.luts, &shared.rung) {
            (Some(sky), Some(luts), _) => sky.draw(&mut pass, luts)?,
            (_, _, Some(rung)) => rung.draw_sky(&mut pass),
            _ => {}
        }
        if let (Some(moon_sky), Some(luts)) = (&self.moon, &shared.moon_luts) {
            moon_sky.draw(&mut pass, luts)?;
        }
        Ok(())
    }
}
