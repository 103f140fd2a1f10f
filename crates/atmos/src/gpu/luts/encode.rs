//! Encoding the bake passes, the accessors, and [`AtmosphereLuts`]' delegation to its
//! tables and its one view.

use super::passes::*;
use super::*;
use crate::frame::FrameCamera;
use crate::gpu::resources::READ_STAGES;
use crate::lut::multiple_scattering_moments::MULTIPLE_SCATTERING_LAYERS;
use crate::lut::{LutSettings, LutSettingsUniform, StaticLuts};
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

    /// Writes static tables baked on the CPU ([`StaticLuts`]: a preparation's, or read
    /// back from a cache) into the transmittance and multiple-scattering textures, in
    /// place of [`Self::encode_static_luts`]: the f32 twin's texels as they are (layer
    /// `m` of the multiple-scattering table at entry `x + w·(y + h·m)`, the bake's own
    /// layout), so a frame reads exactly what the CPU renderer reads. A queue write (a
    /// `prepare` step); worth it where a GPU bake costs more than an upload, as on a CPU
    /// adapter. Errors naming the field when `luts` were baked for another atmosphere
    /// or with other table settings than these textures'.
    pub fn write_static_luts(
        &self,
        queue: &wgpu::Queue,
        luts: &StaticLuts,
    ) -> Result<(), AtmosError> {
        let mismatch = |field: &str, value: f64, reason: &'static str| AtmosError::InvalidSetting {
            setting: "static tables",
            field: field.to_owned(),
            value,
            reason,
        };
        if luts.atmosphere != self.atmosphere {
            return Err(mismatch(
                "atmosphere",
                f64::from(luts.atmosphere.planet_radius),
                "baked for another atmosphere than the GPU tables'",
            ));
        }
        if luts.settings != self.settings {
            return Err(mismatch(
                "settings.transmittance_width",
                f64::from(luts.settings.transmittance_width),
                "baked with other table settings than the GPU tables'",
            ));
        }
        if luts.multiple_scattering_orders != self.multiple_scattering_orders {
            return Err(mismatch(
                "multiple_scattering_orders",
                f64::from(luts.multiple_scattering_orders),
                "baked with another number of scattering orders than the GPU tables'",
            ));
        }
        for (table, lut, layers) in [
            (&self.transmittance, &luts.transmittance, 1),
            (
                &self.multiple_scattering,
                &luts.multiple_scattering,
                MULTIPLE_SCATTERING_LAYERS,
            ),
        ] {
            let size = table.texture.size();
            if lut.texels.len() as u64
                != u64::from(size.width) * u64::from(size.height) * u64::from(layers)
            {
                return Err(mismatch(
                    "texels",
                    lut.texels.len() as f64,
                    "a table's texel count differs from its texture's",
                ));
            }
            queue.write_texture(
                table.texture.as_image_copy(),
                bytemuck::cast_slice(&lut.texels),
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(size.width * 16),
                    rows_per_image: Some(size.height),
                },
                wgpu::Extent3d {
                    width: size.width,
                    height: size.height,
                    depth_or_array_layers: layers,
                },
            );
        }
        Ok(())
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

    /// Writes CPU-baked static tables ([`AtmosphereTables::write_static_luts`]).
    pub fn write_static_luts(
        &self,
        queue: &wgpu::Queue,
        luts: &StaticLuts,
    ) -> Result<(), AtmosError> {
        self.tables.write_static_luts(queue, luts)
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
