//! [`AtmosphereView`]: one camera's uniforms, tables and bind groups.

use std::sync::atomic::{AtomicBool, Ordering};

use super::create::{table_group, uniform_group};
use super::passes::*;
use super::*;
use crate::frame::FrameCamera;
use crate::gpu::resources::uniform_buffer;
use crate::view::{FrameView, ViewCamera};
use crate::{AtmosError, GpuError};
use wgpu::TextureViewDimension as Dim;

impl AtmosphereView {
    /// Creates this view's tables, uniforms and bind groups for `tables`' atmosphere
    /// and settings (no queue writes).
    pub fn new(tables: &AtmosphereTables) -> Self {
        let device = &tables.device;
        let s = &tables.settings;
        let ap_size = [
            s.aerial_perspective_width,
            s.aerial_perspective_height,
            s.aerial_perspective_depth,
        ];
        let sky_view = Table::new(
            device,
            "atmos sky-view LUT",
            [
                s.sky_view_width,
                s.sky_view_height,
                s.sky_view_entries_per_texel(),
            ],
            Dim::D2Array,
        );
        let aerial_perspective_radiance = Table::new(
            device,
            "atmos aerial-perspective radiance",
            ap_size,
            Dim::D3,
        );
        let aerial_perspective_transmittance = Table::new(
            device,
            "atmos aerial-perspective transmittance",
            ap_size,
            Dim::D3,
        );
        let camera = uniform_buffer(
            device,
            "atmos view camera",
            std::mem::size_of::<FrameCamera>() as u64,
        );
        let frame_view = uniform_buffer(
            device,
            "atmos view projection",
            std::mem::size_of::<FrameView>() as u64,
        );
        let uniforms = uniform_group(
            device,
            &tables.layouts,
            [
                &tables.atmosphere_buffer,
                &tables.settings_buffer,
                &camera,
                &frame_view,
            ],
        );
        let table_bind_group = table_group(
            device,
            &tables.layouts,
            "atmos view tables",
            [
                &tables.transmittance.view,
                &tables.multiple_scattering.view,
                &sky_view.view,
                &aerial_perspective_radiance.view,
                &aerial_perspective_transmittance.view,
                &tables.sky_irradiance.view,
            ],
        );
        let outputs = |label: &str, layout: &wgpu::BindGroupLayout, views: &[&Table]| {
            let entries: Vec<wgpu::BindGroupEntry> = views
                .iter()
                .zip(0..)
                .map(|(table, binding)| wgpu::BindGroupEntry {
                    binding,
                    resource: wgpu::BindingResource::TextureView(&table.view),
                })
                .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout,
                entries: &entries,
            })
        };
        let shared = &tables.view_bakes;
        let bakes = [
            BakePass {
                pipeline: shared.sky_view.clone(),
                tables: shared.tables.clone(),
                outputs: outputs(
                    "atmos sky-view output",
                    &shared.sky_view_outputs,
                    &[&sky_view],
                ),
                workgroups: shared.sky_view_workgroups,
                label: "atmos sky-view LUT",
            },
            BakePass {
                pipeline: shared.aerial_perspective.clone(),
                tables: shared.tables.clone(),
                outputs: outputs(
                    "atmos aerial-perspective outputs",
                    &shared.aerial_perspective_outputs,
                    &[
                        &aerial_perspective_radiance,
                        &aerial_perspective_transmittance,
                    ],
                ),
                workgroups: shared.aerial_perspective_workgroups,
                label: "atmos aerial-perspective volume",
            },
        ];
        Self {
            camera,
            frame_view,
            sky_view,
            aerial_perspective_radiance,
            aerial_perspective_transmittance,
            uniforms,
            tables: table_bind_group,
            bakes,
            prepared: AtomicBool::new(false),
        }
    }

    /// Writes this view's camera through the queue: the only queue write of a view.
    /// Other views' buffers are untouched, so views prepared one after the other and
    /// recorded into one encoder each see their own camera.
    pub fn prepare(&self, queue: &wgpu::Queue, view: &ViewCamera) {
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(&view.camera));
        queue.write_buffer(&self.frame_view, 0, bytemuck::bytes_of(&view.view));
        self.prepared.store(true, Ordering::Relaxed);
    }

    /// Records this view's bakes (sky view, aerial perspective) in one compute pass.
    /// They read the shared tables: record [`AtmosphereTables::encode_static_luts`]
    /// earlier in the same or an earlier submit. Errors before [`Self::prepare`].
    pub fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::ComputePassTimestampWrites<'_>>,
    ) -> Result<(), AtmosError> {
        if !self.prepared.load(Ordering::Relaxed) {
            return Err(GpuError::NotPrepared {
                pass: "AtmosphereView",
            }
            .into());
        }
        self.encode_bakes(encoder, &[0, 1], "atmos per-view LUTs", timestamp_writes);
        Ok(())
    }

    pub(super) fn encode_bakes(
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
        for &bake in which {
            record_bake(&mut pass, &self.uniforms, &self.bakes[bake]);
        }
    }

    /// Records both bakes into an open pass.
    pub(crate) fn record_into(&self, pass: &mut wgpu::ComputePass<'_>) {
        for bake in &self.bakes {
            record_bake(pass, &self.uniforms, bake);
        }
    }

    /// The uniforms' bind group ([`LutLayouts::uniforms`]): this view's camera.
    pub fn uniform_bind_group(&self) -> &wgpu::BindGroup {
        &self.uniforms
    }

    /// The tables' bind group ([`LutLayouts::tables`]): the shared tables and this
    /// view's; valid to read once the static bakes and this view's bakes are submitted.
    pub fn table_bind_group(&self) -> &wgpu::BindGroup {
        &self.tables
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
