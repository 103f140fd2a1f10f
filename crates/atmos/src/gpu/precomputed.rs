//! The precomputed rung's GPU renderer: per-frame LUT bakes (sky view, aerial
//! perspective) and a per-pixel lookup pass writing a [`FrameOutput`]. To draw the sky
//! into your own colour target instead, see [`crate::gpu::sky::SkyPass`]. Twin of
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
use crate::gpu::luts::{AtmosphereLuts, compute_pipeline};
use crate::gpu::resources::storage_texture_entry;
use crate::lut::LutSettings;
use crate::{AtmosError, Atmosphere, GpuError};

/// Renders frames with the precomputed rung.
#[derive(Debug)]
pub struct PrecomputedRenderer {
    luts: AtmosphereLuts,
    pipeline: wgpu::ComputePipeline,
    output_layout: wgpu::BindGroupLayout,
    /// The camera and the output's bind group, made by [`Self::prepare`].
    prepared: Option<(FrameCamera, wgpu::BindGroup)>,
    /// True until an encoder holds the static bakes ([`Self::encode`] or
    /// [`Self::encode_static_luts`] recorded them). Only recording clears it, so any
    /// number of `prepare` calls before the first `encode` keep the bakes scheduled.
    static_luts_pending: AtomicBool,
}

impl PrecomputedRenderer {
    /// Validates the atmosphere and settings; creates pipelines and LUT textures.
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        settings: LutSettings,
    ) -> Result<Self, AtmosError> {
        let luts = AtmosphereLuts::new(device, atmosphere, &settings)?;
        let output_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos precomputed frame output"),
            entries: &[
                storage_texture_entry(0, wgpu::TextureViewDimension::D2),
                storage_texture_entry(1, wgpu::TextureViewDimension::D2),
            ],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("atmos precomputed frame"),
            bind_group_layouts: &[
                Some(&luts.layouts().uniforms),
                Some(&luts.layouts().tables),
                Some(&output_layout),
            ],
            immediate_size: 0,
        });
        let pipeline =
            compute_pipeline(device, &layout, "atmos::lut_render", "render_precomputed")?;
        Ok(Self {
            luts,
            pipeline,
            output_layout,
            prepared: None,
            static_luts_pending: AtomicBool::new(true),
        })
    }

    /// Writes the camera uniform and binds `output` (checked against the camera's
    /// frame size). Until an encoder has recorded the static bakes (transmittance,
    /// multiple scattering), the next [`Self::encode`] records them first: submit that
    /// encoder before relying on later frames (or bake them yourself with
    /// [`Self::encode_static_luts`] and use the split API). Calling `prepare` again
    /// before encoding only replaces the camera and the output.
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        camera: &FrameCamera,
        output: &FrameOutput,
    ) -> Result<(), AtmosError> {
        self.prepared = None;
        output.check_camera(camera)?;
        let group = self
            .luts
            .tables()
            .device
            .create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("atmos precomputed frame output"),
                layout: &self.output_layout,
                entries: &output.bind_group_entries(0),
            });
        self.luts.prepare(queue, camera);
        self.prepared = Some((*camera, group));
        Ok(())
    }

    /// The LUT textures and their bake passes (to bind the tables in another pipeline,
    /// read them back, or time single bakes).
    pub fn luts(&self) -> &AtmosphereLuts {
        &self.luts
    }

    fn prepared(&self) -> Result<&(FrameCamera, wgpu::BindGroup), AtmosError> {
        self.prepared.as_ref().ok_or_else(|| {
            GpuError::NotPrepared {
                pass: "PrecomputedRenderer",
            }
            .into()
        })
    }

    fn record_pixels(
        &self,
        pass: &mut wgpu::ComputePass<'_>,
        prepared: &(FrameCamera, wgpu::BindGroup),
    ) {
        let (camera, group) = prepared;
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, self.luts.uniform_bind_group(), &[]);
        pass.set_bind_group(1, self.luts.table_bind_group(), &[]);
        pass.set_bind_group(2, group, &[]);
        pass.dispatch_workgroups(camera.width.div_ceil(8), camera.height.div_ceil(8), 1);
    }

    /// A whole frame in one compute pass: [static bakes on the first frame], sky view,
    /// aerial perspective, per-pixel lookups.
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        let prepared = self.prepared()?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmos precomputed frame"),
            timestamp_writes,
        });
        // Checked and cleared only once the pass exists, so a failed `encode` (missing
        // `prepare`) leaves the bakes scheduled.
        let static_luts = self.static_luts_pending.swap(false, Ordering::Relaxed);
        self.luts.record_into(&mut pass, static_luts);
        self.record_pixels(&mut pass, prepared);
        Ok(())
    }

    /// Per atmosphere: transmittance and multiple-scattering bakes (one pass).
    pub fn encode_static_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.luts.encode_static_luts(encoder, timestamp_writes);
        self.static_luts_pending.store(false, Ordering::Relaxed);
    }

    /// Per frame: sky-view and aerial-perspective bakes (one pass).
    pub fn encode_frame_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.luts.encode_frame_luts(encoder, timestamp_writes);
    }

    /// Per pixel: the lookup pass (one pass), reading LUTs baked earlier.
    pub fn encode_pixels(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        let prepared = self.prepared()?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("atmos precomputed pixels"),
            timestamp_writes,
        });
        self.record_pixels(&mut pass, prepared);
        Ok(())
    }
}
