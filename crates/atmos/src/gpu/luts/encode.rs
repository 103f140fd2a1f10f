//! Encoding the bake passes, the accessors, and [`AtmosphereLuts`]' delegation to its
//! tables and its one view.

use super::passes::*;
use super::*;
use crate::frame::FrameCamera;
use crate::gpu::resources::READ_STAGES;
use crate::lut::{LutSettings, LutSettingsUniform};
use crate::view::ViewCamera;
use crate::{AtmosError, Atmosphere};

impl AsRef<LutLayouts> for LutLayouts {
    fn as_ref(&self) -> &LutLayouts {
        self
    }
}

impl AsRef<LutLayouts> for AtmosphereTables {
    fn as_ref(&self) -> &LutLayouts {
        &self.layouts
    }
}

impl AsRef<LutLayouts> for AtmosphereLuts {
    fn as_ref(&self) -> &LutLayouts {
        &self.tables.layouts
    }
}

impl AtmosphereTables {
    /// The settings the tables were sized for.
    pub fn settings(&self) -> &LutSettingsUniform {
        &self.settings
    }

    /// The two bind-group layouts (uniforms, tables) every view's bind groups follow.
    pub fn layouts(&self) -> &LutLayouts {
        &self.layouts
    }

    /// The stages the layouts expose the LUTs to.
    pub const STAGES: wgpu::ShaderStages = READ_STAGES;

    fn record(&self, pass: &mut wgpu::ComputePass<'_>, which: usize) {
        record_bake(pass, &self.uniforms, &self.passes[which]);
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

    /// Records the sky-irradiance bake (one pass; reads the transmittance and
    /// multiple-scattering LUTs, so record it after [`Self::encode_static_luts`]): once
    /// per atmosphere, before a shader reads `sky_irradiance`. Not part of the static
    /// bakes: a program that never reads the table does not pay for it (1,024 view
    /// marches per texel, 64 × 32 texels).
    pub fn encode_sky_irradiance(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.encode_passes(
            encoder,
            &[SKY_IRRADIANCE],
            self.passes[SKY_IRRADIANCE].label,
            timestamp_writes,
        );
    }

    /// Records both static bakes in one pass (transmittance, then multiple scattering):
    /// once per atmosphere, before any view's bakes.
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

    /// Sky-irradiance LUT (μ_s × r, one layer per normal).
    pub fn sky_irradiance_texture(&self) -> &wgpu::Texture {
        &self.sky_irradiance.texture
    }

    /// Transmittance LUT (`transmittance_width × _height`).
    pub fn transmittance_texture(&self) -> &wgpu::Texture {
        &self.transmittance.texture
    }
    /// Multiple-scattering LUT (six layers: the field's moments).
    pub fn multiple_scattering_texture(&self) -> &wgpu::Texture {
        &self.multiple_scattering.texture
    }
}

impl AtmosphereLuts {
    /// The shared tables of `atmosphere` and one view ([`AtmosphereTables::new`],
    /// [`AtmosphereView::new`]).
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        settings: &LutSettings,
    ) -> Result<Self, AtmosError> {
        let tables = AtmosphereTables::new(device, atmosphere, settings)?;
        let view = AtmosphereView::new(&tables);
        Ok(Self { tables, view })
    }

    /// Writes the frame camera (a pinhole filling the target,
    /// [`ViewCamera::from_frame_camera`]) that the per-frame bakes (sky view, aerial
    /// perspective) bake for and the lookups of a caller's shader read: the only queue
    /// write of this type. See the type's documentation for two cameras.
    pub fn prepare(&self, queue: &wgpu::Queue, camera: &FrameCamera) {
        self.view
            .prepare(queue, &ViewCamera::from_frame_camera(camera));
    }

    /// Writes a camera given by view and projection matrices and a viewport
    /// ([`ViewCamera::from_matrices`]).
    pub fn prepare_view(&self, queue: &wgpu::Queue, view: &ViewCamera) {
        self.view.prepare(queue, view);
    }

    /// The shared tables.
    pub fn tables(&self) -> &AtmosphereTables {
        &self.tables
    }

    /// The one view.
    pub fn view(&self) -> &AtmosphereView {
        &self.view
    }

    /// The settings the tables were sized for.
    pub fn settings(&self) -> &LutSettingsUniform {
        self.tables.settings()
    }

    /// The two bind-group layouts (uniforms, tables).
    pub fn layouts(&self) -> &LutLayouts {
        self.tables.layouts()
    }

    /// The uniforms' bind group ([`LutLayouts::uniforms`]).
    pub fn uniform_bind_group(&self) -> &wgpu::BindGroup {
        self.view.uniform_bind_group()
    }

    /// The tables' bind group ([`LutLayouts::tables`]): valid to read once the static
    /// bakes and this frame's bakes are submitted.
    pub fn table_bind_group(&self) -> &wgpu::BindGroup {
        self.view.table_bind_group()
    }

    /// The stages the layouts expose the LUTs to.
    pub const STAGES: wgpu::ShaderStages = READ_STAGES;

    /// Records the transmittance bake (one pass).
    pub fn encode_transmittance(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.tables.encode_transmittance(encoder, timestamp_writes);
    }

    /// Records the multiple-scattering bake (one pass of one dispatch per scattering
    /// order and one for the sum; reads the transmittance LUT).
    pub fn encode_multiple_scattering(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.tables
            .encode_multiple_scattering(encoder, timestamp_writes);
    }

    /// Records both static bakes in one pass (transmittance, then multiple scattering).
    pub fn encode_static_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.tables.encode_static_luts(encoder, timestamp_writes);
    }

    /// Records the sky-irradiance bake ([`AtmosphereTables::encode_sky_irradiance`]).
    pub fn encode_sky_irradiance(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.tables.encode_sky_irradiance(encoder, timestamp_writes);
    }

    /// Records the sky-view bake for the prepared camera (one pass).
    pub fn encode_sky_view(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.view
            .encode_bakes(encoder, &[0], "atmos sky-view LUT", timestamp_writes);
    }

    /// Records the aerial-perspective bake for the prepared camera (one pass).
    pub fn encode_aerial_perspective(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.view.encode_bakes(
            encoder,
            &[1],
            "atmos aerial-perspective volume",
            timestamp_writes,
        );
    }

    /// Records both per-frame bakes in one pass (sky view, aerial perspective).
    pub fn encode_frame_luts(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) {
        self.view
            .encode_bakes(encoder, &[0, 1], "atmos per-frame LUTs", timestamp_writes);
    }

    /// Records the given bakes (`static_luts`: transmittance + multiple scattering;
    /// always the two per-frame ones) into an open pass.
    pub(crate) fn record_into(&self, pass: &mut wgpu::ComputePass<'_>, static_luts: bool) {
        if static_luts {
            self.tables.record(pass, TRANSMITTANCE);
            self.tables.record(pass, MULTIPLE_SCATTERING);
        }
        self.view.record_into(pass);
    }

    /// Transmittance LUT (`transmittance_width × _height`).
    pub fn transmittance_texture(&self) -> &wgpu::Texture {
        self.tables.transmittance_texture()
    }
    /// Multiple-scattering LUT (six layers: the field's moments).
    pub fn multiple_scattering_texture(&self) -> &wgpu::Texture {
        self.tables.multiple_scattering_texture()
    }
    /// Sky-irradiance LUT (μ_s × r, one layer per normal).
    pub fn sky_irradiance_texture(&self) -> &wgpu::Texture {
        self.tables.sky_irradiance_texture()
    }
    /// Sky-view LUT (layer 0 radiance; layer 1 transmittance when stored).
    pub fn sky_view_texture(&self) -> &wgpu::Texture {
        self.view.sky_view_texture()
    }
    /// Aerial-perspective radiance (3-D: froxel x, y, depth slice).
    pub fn aerial_perspective_radiance_texture(&self) -> &wgpu::Texture {
        self.view.aerial_perspective_radiance_texture()
    }
    /// Aerial-perspective transmittance (3-D, as the radiance).
    pub fn aerial_perspective_transmittance_texture(&self) -> &wgpu::Texture {
        self.view.aerial_perspective_transmittance_texture()
    }
}
