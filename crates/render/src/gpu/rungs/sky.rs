//! A rung's sky evaluation per light: atmos' frame renderer and its output, and the
//! light's bind groups of the sky and terrain draws.

use atmos::gpu::{ClosedFormRenderer, EvaluationFrequency, FrameOutput, SingleScatteringRenderer};

use super::uniforms::RungLightUniform;
use crate::RenderError;
use crate::gpu::rung_kind::no_gpu_passes;
use crate::present::PresentParameters;
use crate::scene::Rung;

/// `atmos`' frame renderer of the rung.
#[derive(Debug)]
pub(super) enum SkyRenderer {
    /// SGSky's dome: painted on the CPU from the closed form at each prepare, drawn by
    /// celestial's pass.
    Dome(
        celestial::gpu::SkyDomeRenderer,
        Box<celestial::dome_sky::SgskyDomeSky<atmos::closed_form_sky::ClosedFormSky>>,
    ),
    ClosedForm(ClosedFormRenderer),
    Single(SingleScatteringRenderer),
}

impl SkyRenderer {
    pub(super) fn new(
        device: &wgpu::Device,
        rung: Rung,
        atmosphere: &atmos::Atmosphere,
    ) -> Result<Self, RenderError> {
        Ok(match rung {
            Rung::Dome => Self::Dome(
                celestial::gpu::SkyDomeRenderer::new(device)?,
                Box::new(celestial::dome_sky::SgskyDomeSky::new(
                    atmos::closed_form_sky::ClosedFormSky::new(atmosphere)?,
                    atmosphere,
                    celestial::dome::DomeColouring::SeedWeights,
                )?),
            ),
            Rung::ClosedForm => Self::ClosedForm(ClosedFormRenderer::new(
                device,
                atmosphere,
                EvaluationFrequency::PerPixel,
            )?),
            Rung::ClosedFormVertex => Self::ClosedForm(ClosedFormRenderer::new(
                device,
                atmosphere,
                EvaluationFrequency::PerVertex(crate::scene::prepare::DOME),
            )?),
            Rung::Single => Self::Single(SingleScatteringRenderer::new(
                device,
                atmosphere,
                atmos::single_scattering::SingleScatteringSettings::default(),
            )?),
            other => return Err(no_gpu_passes(other)),
        })
    }

    pub(super) fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &atmos::frame::FrameCamera,
        output: &FrameOutput,
    ) -> Result<(), RenderError> {
        match self {
            Self::Dome(r, sky) => {
                let position = glam::Vec3::from_array(camera.position).as_dvec3();
                let sun = glam::Vec3::from_array(camera.sun).as_dvec3().normalize();
                let dome = sky.uniforms(position, sun)?;
                r.prepare(queue, camera, &dome, output)?
            }
            Self::ClosedForm(r) => r.prepare(queue, camera, output)?,
            Self::Single(r) => r.prepare(queue, camera, output)?,
        }
        Ok(())
    }

    pub(super) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        match self {
            Self::Dome(r, _) => r.encode(encoder, timestamp_writes)?,
            Self::ClosedForm(r) => r.encode(encoder, timestamp_writes)?,
            Self::Single(r) => r.encode(encoder, timestamp_writes)?,
        }
        Ok(())
    }
}

/// One light's sky evaluation and draw, and its terrain group.
#[derive(Debug)]
pub(super) struct LightPasses {
    pub(super) renderer: SkyRenderer,
    pub(super) output: FrameOutput,
    pub(super) sky_camera: wgpu::Buffer,
    pub(super) sky_present: wgpu::Buffer,
    pub(super) sky_group: wgpu::BindGroup,
    pub(super) terrain_light: wgpu::Buffer,
    /// The light's irradiance at `cpu_renderer::SUN_TABLE_SIZE` elevations (filled for
    /// single scattering).
    pub(super) light_table: wgpu::Buffer,
    pub(super) terrain_group: wgpu::BindGroup,
    /// The air in front of a marched cloud lit by this light (its camera and the
    /// rung's parameters of its atmosphere; `crate::gpu::cloud_air`).
    pub(super) cloud_air: crate::gpu::cloud_air::RungCloudAir,
}

impl LightPasses {
    pub(super) fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &atmos::frame::FrameCamera,
        present: &PresentParameters,
        light: &RungLightUniform,
        table: Option<&[[f32; 4]]>,
    ) -> Result<(), RenderError> {
        self.renderer.prepare(queue, camera, &self.output)?;
        if let Some(table) = table {
            queue.write_buffer(&self.light_table, 0, bytemuck::cast_slice(table));
        }
        queue.write_buffer(&self.sky_camera, 0, bytemuck::bytes_of(camera));
        queue.write_buffer(&self.sky_present, 0, bytemuck::bytes_of(present));
        queue.write_buffer(&self.terrain_light, 0, bytemuck::bytes_of(light));
        self.cloud_air.prepare(queue, camera);
        Ok(())
    }
}
