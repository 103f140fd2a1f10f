//! The precomputed rung's GPU renderer: per-frame LUT bakes (sky view, aerial
//! perspective) and a per-pixel lookup pass writing a [`FrameOutput`]. Twin of
//! [`crate::lut::precomputed_sky::shade_pixel`].
//!
//! Passes and timing: [`PrecomputedRenderer::encode`] records **one** compute pass
//! holding every dispatch of a frame (the static bakes too on the first frame after
//! `new`, see [`PrecomputedRenderer::prepare`]), so one timestamp pair times a whole
//! frame. To time the parts, call instead [`PrecomputedRenderer::encode_static_luts`]
//! (per atmosphere), [`PrecomputedRenderer::encode_frame_luts`] (per frame: sky view +
//! aerial perspective) and [`PrecomputedRenderer::encode_pixels`] (per pixel), one
//! pass and one optional `ComputePassTimestampWrites` each.

use crate::frame::FrameCamera;
use crate::gpu::FrameOutput;
use crate::gpu::luts::{LutBaker, compute_pipeline};
use crate::lut::LutSettings;
use crate::{AtmosError, Atmosphere};

/// Renders frames with the precomputed rung.
#[derive(Debug)]
pub struct PrecomputedRenderer {
    baker: LutBaker,
    pipeline: wgpu::ComputePipeline,
    camera: Option<FrameCamera>,
    static_luts_baked: bool,
    bake_static_luts_in_encode: bool,
}

impl PrecomputedRenderer {
    /// Validates the atmosphere and settings; creates pipelines and LUT buffers.
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        settings: LutSettings,
    ) -> Result<Self, AtmosError> {
        let baker = LutBaker::new(device, atmosphere, &settings)?;
        let pipeline = compute_pipeline(
            device,
            &baker.layout,
            "atmos::lut_render",
            "render_precomputed",
        )?;
        Ok(Self {
            baker,
            pipeline,
            camera: None,
            static_luts_baked: false,
            bake_static_luts_in_encode: false,
        })
    }

    /// Writes the camera uniform. The first call after `new` also schedules the static
    /// bakes (transmittance, multiple scattering) into the next [`Self::encode`]: submit
    /// that encoder before relying on later frames (or bake them yourself with
    /// [`Self::encode_static_luts`] and use the split API).
    pub fn prepare(&mut self, queue: &wgpu::Queue, camera: &FrameCamera) {
        self.baker.prepare(queue, camera);
        self.camera = Some(*camera);
        self.bake_static_luts_in_encode = !self.static_luts_baked;
        self.static_luts_baked = true;
    }

    /// The LUT passes and buffers (for reading the LUTs back or timing single bakes).
    pub fn baker(&self) -> &LutBaker {
        &self.baker
    }

    fn output_group(&self, output: &FrameOutput) -> Result<wgpu::BindGroup, AtmosError> {
        let camera = self.camera.as_ref().ok_or_else(|| {
            AtmosError::Gpu("PrecomputedRenderer::prepare must run before encoding".into())
        })?;
        output.check_camera(camera)?;
        Ok(self
            .baker
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("atmos precomputed frame output"),
                layout: &self.baker.output_layout,
                entries: &output.bind_group_entries(0),
            }))
    }

    fn record_pixels(&self, pass: &mut wgpu::ComputePass<'_>, group: &wgpu::BindGroup) {
        let camera = self.camera.as_ref().expect("checked by output_group");
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, &self.baker.uniforms, &[]);
        pass.set_bind_group(1, &self.baker.render_luts, &[]);
        pass.set_bind_group(2, group, &[]);
        pass.dispatch_workgroups(camera.width.div_ceil(8), camera.height.div_ceil(8), 1);
    }

    /// A whole frame in one compute pass: [static bakes on the first frame], sky view,
    /// aerial perspective, per-pixel lookups.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        output: &FrameOutput,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        let group = self.output_group(output)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmos precomputed frame"),
            timestamp_writes,
        });
        self.baker
            .record_into(&mut pass, self.bake_static_luts_in_encode);
        self.record_pixels(&mut pass, &group);
        Ok(())
    }

    /// Per atmosphere: transmittance and multiple-scattering bakes (one pass).
    pub fn encode_static_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.baker.encode_static_luts(encoder, timestamp_writes);
    }

    /// Per frame: sky-view and aerial-perspective bakes (one pass).
    pub fn encode_frame_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.baker.encode_frame_luts(encoder, timestamp_writes);
    }

    /// Per pixel: the lookup pass (one pass), reading LUTs baked earlier.
    pub fn encode_pixels(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        output: &FrameOutput,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        let group = self.output_group(output)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmos precomputed pixels"),
            timestamp_writes,
        });
        self.record_pixels(&mut pass, &group);
        Ok(())
    }
}
