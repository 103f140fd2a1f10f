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

use std::sync::atomic::{AtomicBool, Ordering};

use crate::frame::FrameCamera;
use crate::gpu::FrameOutput;
use crate::gpu::luts::{LutBaker, compute_pipeline};
use crate::lut::LutSettings;
use crate::{AtmosError, Atmosphere, GpuError};

/// Renders frames with the precomputed rung.
#[derive(Debug)]
pub struct PrecomputedRenderer {
    baker: LutBaker,
    pipeline: wgpu::ComputePipeline,
    camera: Option<FrameCamera>,
    /// True until an encoder holds the static bakes ([`Self::encode`] or
    /// [`Self::encode_static_luts`] recorded them). Only recording clears it, so any
    /// number of `prepare` calls before the first `encode` keep the bakes scheduled.
    static_luts_pending: AtomicBool,
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
            static_luts_pending: AtomicBool::new(true),
        })
    }

    /// Writes the camera uniform. Until an encoder has recorded the static bakes
    /// (transmittance, multiple scattering), the next [`Self::encode`] records them
    /// first: submit that encoder before relying on later frames (or bake them yourself
    /// with [`Self::encode_static_luts`] and use the split API). Calling `prepare`
    /// again before encoding only replaces the camera.
    pub fn prepare(&mut self, queue: &wgpu::Queue, camera: &FrameCamera) {
        self.baker.prepare(queue, camera);
        self.camera = Some(*camera);
    }

    /// The LUT passes and buffers (for reading the LUTs back or timing single bakes).
    pub fn baker(&self) -> &LutBaker {
        &self.baker
    }

    fn output_group(&self, output: &FrameOutput) -> Result<wgpu::BindGroup, AtmosError> {
        let camera = self.camera.as_ref().ok_or_else(|| {
            AtmosError::from(GpuError::NotPrepared {
                pass: "PrecomputedRenderer",
            })
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
        // Checked and cleared only once the pass exists, so a failed `encode` (missing
        // `prepare`, mismatched output) leaves the bakes scheduled.
        let static_luts = self.static_luts_pending.swap(false, Ordering::Relaxed);
        self.baker.record_into(&mut pass, static_luts);
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
        self.static_luts_pending.store(false, Ordering::Relaxed);
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
