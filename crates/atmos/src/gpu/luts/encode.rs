//! Writing the frame camera, encoding the bake passes, and the accessors.

use super::passes::*;
use super::*;
use crate::frame::FrameCamera;
use crate::gpu::resources::READ_STAGES;
use crate::lut::LutSettingsUniform;

impl AtmosphereLuts {
    /// Writes the frame camera the per-frame passes (sky view, aerial perspective)
    /// bake for, and the lookups of a caller's shader read. The static passes
    /// (transmittance, multiple scattering) ignore it.
    pub fn prepare(&self, queue: &wgpu::Queue, camera: &FrameCamera) {
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
    }

    /// The settings the tables were sized for.
    pub fn settings(&self) -> &LutSettingsUniform {
        &self.settings
    }

    /// The two bind-group layouts (uniforms, tables).
    pub fn layouts(&self) -> &LutLayouts {
        &self.layouts
    }

    /// The uniforms' bind group ([`LutLayouts::uniforms`]).
    pub fn uniform_bind_group(&self) -> &wgpu::BindGroup {
        &self.uniforms
    }

    /// The tables' bind group ([`LutLayouts::tables`]): valid to read once the static
    /// bakes and this frame's bakes are submitted.
    pub fn table_bind_group(&self) -> &wgpu::BindGroup {
        &self.tables
    }

    /// The stages the layouts expose the LUTs to.
    pub const STAGES: wgpu::ShaderStages = READ_STAGES;

    fn record(&self, pass: &mut wgpu::ComputePass<'_>, which: usize) {
        let bake = &self.passes[which];
        pass.set_pipeline(&bake.pipeline);
        pass.set_bind_group(0, &self.uniforms, &[]);
        pass.set_bind_group(1, &bake.tables, &[]);
        pass.set_bind_group(2, &bake.outputs, &[]);
        pass.dispatch_workgroups(bake.workgroups[0], bake.workgroups[1], 1);
        if which == MULTIPLE_SCATTERING {
            for order in &self.higher_orders {
                pass.set_pipeline(&order.pipeline);
                pass.set_bind_group(1, &order.tables, &[]);
                pass.set_bind_group(2, &order.outputs, &[]);
                pass.dispatch_workgroups(order.workgroups[0], order.workgroups[1], 1);
            }
        }
    }

    fn encode_passes(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        which: &[usize],
        label: &str,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some(label),
            timestamp_writes,
        });
        for &w in which {
            self.record(&mut pass, w);
        }
    }

    /// Records the transmittance bake (one pass).
    pub fn encode_transmittance(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[TRANSMITTANCE],
            self.passes[TRANSMITTANCE].label,
            timestamp_writes,
        );
    }

    /// Records the multiple-scattering bake (one pass of one dispatch per scattering
    /// order and one for the sum; reads the transmittance LUT).
    pub fn encode_multiple_scattering(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[MULTIPLE_SCATTERING],
            self.passes[MULTIPLE_SCATTERING].label,
            timestamp_writes,
        );
    }

    /// Records both static bakes in one pass (transmittance, then multiple scattering).
    pub fn encode_static_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[TRANSMITTANCE, MULTIPLE_SCATTERING],
            "atmos static LUTs",
            timestamp_writes,
        );
    }

    /// Records the sky-view bake for the prepared camera (one pass).
    pub fn encode_sky_view(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[SKY_VIEW],
            self.passes[SKY_VIEW].label,
            timestamp_writes,
        );
    }

    /// Records the aerial-perspective bake for the prepared camera (one pass).
    pub fn encode_aerial_perspective(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[AERIAL_PERSPECTIVE],
            self.passes[AERIAL_PERSPECTIVE].label,
            timestamp_writes,
        );
    }

    /// Records both per-frame bakes in one pass (sky view, aerial perspective).
    pub fn encode_frame_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[SKY_VIEW, AERIAL_PERSPECTIVE],
            "atmos per-frame LUTs",
            timestamp_writes,
        );
    }

    /// Records the given bakes (`static_luts`: transmittance + multiple scattering;
    /// always the two per-frame ones) into an open pass.
    pub(crate) fn record_into(&self, pass: &mut wgpu::ComputePass<'_>, static_luts: bool) {
        if static_luts {
            self.record(pass, TRANSMITTANCE);
            self.record(pass, MULTIPLE_SCATTERING);
        }
        self.record(pass, SKY_VIEW);
        self.record(pass, AERIAL_PERSPECTIVE);
    }

    /// Transmittance LUT (`transmittance_width × _height`).
    pub fn transmittance_texture(&self) -> &wgpu::Texture {
        &self.transmittance.texture
    }
    /// Multiple-scattering LUT (six layers: the field's moments).
    pub fn multiple_scattering_texture(&self) -> &wgpu::Texture {
        &self.multiple_scattering.texture
    }
    /// Sky-view LUT (layer 0 radiance; layer 1 transmittance when stored).
    pub fn sky_view_texture(&self) -> &wgpu::Texture {
        &self.sky_view.texture
    }
    /// Aerial-perspective radiance (3-D: froxel x, y, depth slice).
    pub fn aerial_perspective_radiance_texture(&self) -> &wgpu::Texture {
        &self.aerial_perspective_radiance.texture
    }
    /// Aerial-perspective transmittance (3-D, as the radiance).
    pub fn aerial_perspective_transmittance_texture(&self) -> &wgpu::Texture {
        &self.aerial_perspective_transmittance.texture
    }
}
