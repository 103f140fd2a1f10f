//! [`AtmosphereTables::new`]: the shared tables, bind groups and pipelines.

use super::passes::*;
use super::*;
use crate::frame::FrameCamera;
use crate::gpu::resources::{check_texture_support, storage_entry, storage_texture_entry};
use crate::lut::LutSettings;
use crate::lut::multiple_scattering_moments::MULTIPLE_SCATTERING_LAYERS;
use crate::lut::sky_irradiance::{
    SKY_IRRADIANCE_HEIGHT, SKY_IRRADIANCE_LAYERS, SKY_IRRADIANCE_WIDTH,
};
use crate::view::FrameView;
use crate::{AtmosError, Atmosphere, GpuError};
use wgpu::TextureViewDimension as Dim;
use wgpu::util::DeviceExt as _;

impl AtmosphereTables {
    /// Validates the inputs, creates the shared tables, bind groups and the pipelines
    /// of every bake (no queue writes). Errors naming the table when one (the per-view
    /// ones included) exceeds the device's texture limits.
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        settings: &LutSettings,
    ) -> Result<Self, AtmosError> {
        check_texture_support(device)?;
        let atmosphere_uniform = atmosphere.to_uniforms()?;
        let s = settings.to_uniforms()?;
        let limits = device.limits();
        let layers = MULTIPLE_SCATTERING_LAYERS;
        let ap_size = [
            s.aerial_perspective_width,
            s.aerial_perspective_height,
            s.aerial_perspective_depth,
        ];
        for (table, size, limit) in [
            (
                "the transmittance LUT",
                s.transmittance_width.max(s.transmittance_height),
                limits.max_texture_dimension_2d,
            ),
            (
                "the multiple-scattering LUT",
                s.multiple_scattering_width
                    .max(s.multiple_scattering_height),
                limits.max_texture_dimension_2d,
            ),
            (
                "the sky-view LUT",
                s.sky_view_width.max(s.sky_view_height),
                limits.max_texture_dimension_2d,
            ),
            (
                "the aerial-perspective volume",
                ap_size.into_iter().max().unwrap_or(0),
                limits.max_texture_dimension_3d,
            ),
            (
                "the sky-irradiance LUT (one layer per normal)",
                SKY_IRRADIANCE_LAYERS,
                limits.max_texture_array_layers,
            ),
        ] {
            if size > limit {
                return Err(GpuError::TextureTooLarge {
                    resource: table.to_owned(),
                    size,
                    limit,
                }
                .into());
            }
        }
        let ms_size = [
            s.multiple_scattering_width,
            s.multiple_scattering_height,
            layers,
        ];
        let transmittance = Table::new(
            device,
            "atmos transmittance LUT",
            [s.transmittance_width, s.transmittance_height, 1],
            Dim::D2,
        );
        let multiple_scattering = Table::new(
            device,
            "atmos multiple-scattering LUT",
            ms_size,
            Dim::D2Array,
        );
        let sky_irradiance = Table::new(
            device,
            "atmos sky-irradiance LUT",
            [
                SKY_IRRADIANCE_WIDTH,
                SKY_IRRADIANCE_HEIGHT,
                SKY_IRRADIANCE_LAYERS,
            ],
            Dim::D2Array,
        );
        let orders = [
            Table::new(
                device,
                "atmos scattering order (even)",
                ms_size,
                Dim::D2Array,
            ),
            Table::new(
                device,
                "atmos scattering order (odd)",
                ms_size,
                Dim::D2Array,
            ),
        ];
        // What a bake that runs before a table exists binds in its place (never the
        // texture it writes).
        let placeholders = [
            Table::new(device, "atmos LUT placeholder 2d", [1, 1, 1], Dim::D2),
            Table::new(
                device,
                "atmos LUT placeholder array",
                [1, 1, 1],
                Dim::D2Array,
            ),
            Table::new(device, "atmos LUT placeholder 3d", [1, 1, 1], Dim::D3),
        ];
        let sum = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("atmos multiple-scattering sum"),
            size: u64::from(ms_size[0] * ms_size[1] * ms_size[2]) * 16,
            usage: wgpu::BufferUsages::STORAGE,
            mapped_at_creation: false,
        });

        let uniform = |label: &str, bytes: &[u8]| {
            device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: bytes,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            })
        };
        let atmosphere_buffer = uniform(
            "atmos LUT atmosphere",
            bytemuck::bytes_of(&atmosphere_uniform),
        );
        let settings_buffer = uniform("atmos LUT settings", bytemuck::bytes_of(&s));
        let camera = uniform(
            "atmos static bakes' frame camera (unread)",
            bytemuck::bytes_of(&<FrameCamera as bytemuck::Zeroable>::zeroed()),
        );
        let frame_view = uniform(
            "atmos static bakes' frame view (unread)",
            bytemuck::bytes_of(&<FrameView as bytemuck::Zeroable>::zeroed()),
        );

        let layouts = LutLayouts::new(device);
        let uniforms = uniform_group(
            device,
            &layouts,
            [&atmosphere_buffer, &settings_buffer, &camera, &frame_view],
        );
        let table_group = |label: &str, views: [&Table; 6]| {
            table_group(device, &layouts, label, views.map(|table| &table.view))
        };
        let [p2, pa, p3] = &placeholders;

        // Each bake's outputs (group 2) have their own layout.
        let output_layout = |label: &str, entries: &[wgpu::BindGroupLayoutEntry]| {
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries,
            })
        };
        let transmittance_out = output_layout(
            "atmos transmittance bake outputs",
            &[storage_texture_entry(0, Dim::D2)],
        );
        let multiple_scattering_out = output_layout(
            "atmos multiple-scattering bake outputs",
            &[
                storage_texture_entry(0, Dim::D2Array),
                storage_entry(1, false),
                storage_texture_entry(2, Dim::D2Array),
            ],
        );
        let sky_irradiance_out = output_layout(
            "atmos sky-irradiance bake outputs",
            &[storage_texture_entry(0, Dim::D2Array)],
        );
        let sky_view_out = output_layout(
            "atmos sky-view bake outputs",
            &[storage_texture_entry(0, Dim::D2Array)],
        );
        let aerial_perspective_out = output_layout(
            "atmos aerial-perspective bake outputs",
            &[
                storage_texture_entry(0, Dim::D3),
                storage_texture_entry(1, Dim::D3),
            ],
        );
        let pipeline_layout = |label: &str, outputs: &wgpu::BindGroupLayout| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: &[
                    Some(&layouts.uniforms),
                    Some(&layouts.tables),
                    Some(outputs),
                ],
                immediate_size: 0,
            })
        };
        let texture_outputs = |label: &str, layout: &wgpu::BindGroupLayout, views: &[&Table]| {
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
        let order_outputs = |label: &str, order: &Table| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &multiple_scattering_out,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: wgpu::BindingResource::TextureView(&order.view),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: sum.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: wgpu::BindingResource::TextureView(&multiple_scattering.view),
                    },
                ],
            })
        };
        let groups = |n: u32| n.div_ceil(WORKGROUP);
        let ms_workgroups = [
            groups(s.multiple_scattering_width),
            groups(s.multiple_scattering_height),
        ];
        let ms_layout = pipeline_layout("atmos multiple-scattering bake", &multiple_scattering_out);
        let passes = [
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &pipeline_layout("atmos transmittance bake", &transmittance_out),
                    "atmos::lut_transmittance",
                    "bake_transmittance_lut",
                )?,
                tables: table_group("atmos tables for transmittance", [p2, pa, pa, p3, p3, pa]),
                outputs: texture_outputs(
                    "atmos transmittance output",
                    &transmittance_out,
                    &[&transmittance],
                ),
                workgroups: [
                    groups(s.transmittance_width),
                    groups(s.transmittance_height),
                ],
                label: "atmos transmittance LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &ms_layout,
                    "atmos::lut_multiple_scattering",
                    "bake_multiple_scattering_lut",
                )?,
                tables: table_group(
                    "atmos tables for multiple scattering",
                    [&transmittance, pa, pa, p3, p3, pa],
                ),
                outputs: order_outputs("atmos scattering order 2 outputs", &orders[0]),
                workgroups: ms_workgroups,
                label: "atmos multiple-scattering LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &pipeline_layout("atmos sky-irradiance bake", &sky_irradiance_out),
                    "atmos::lut_sky_irradiance",
                    "bake_sky_irradiance_lut",
                )?,
                tables: table_group(
                    "atmos tables for the sky irradiance",
                    [&transmittance, &multiple_scattering, pa, p3, p3, pa],
                ),
                outputs: texture_outputs(
                    "atmos sky-irradiance output",
                    &sky_irradiance_out,
                    &[&sky_irradiance],
                ),
                // One workgroup per texel, one invocation per normal layer.
                workgroups: [SKY_IRRADIANCE_WIDTH, SKY_IRRADIANCE_HEIGHT],
                label: "atmos sky-irradiance LUT",
            },
        ];
        let view_bakes = ViewBakes {
            sky_view: compute_pipeline(
                device,
                &pipeline_layout("atmos sky-view bake", &sky_view_out),
                "atmos::lut_sky_view",
                "bake_sky_view_lut",
            )?,
            aerial_perspective: compute_pipeline(
                device,
                &pipeline_layout("atmos aerial-perspective bake", &aerial_perspective_out),
                "atmos::lut_aerial_perspective",
                "bake_aerial_perspective",
            )?,
            tables: table_group(
                "atmos tables for the per-view bakes",
                [&transmittance, &multiple_scattering, pa, p3, p3, pa],
            ),
            sky_view_outputs: sky_view_out,
            aerial_perspective_outputs: aerial_perspective_out,
            sky_view_workgroups: [groups(s.sky_view_width), groups(s.sky_view_height)],
            aerial_perspective_workgroups: [
                groups(s.aerial_perspective_width),
                groups(s.aerial_perspective_height),
            ],
        };
        let next_order_pipeline = compute_pipeline(
            device,
            &ms_layout,
            "atmos::lut_multiple_scattering",
            "bake_multiple_scattering_next_order",
        )?;
        let mut higher_orders: Vec<BakePass> = (3..=settings.multiple_scattering_orders)
            .map(|order| {
                // Order k reads order k − 1 (even orders sit in texture 0).
                let previous = &orders[(order as usize - 1) % 2];
                let next = &orders[order as usize % 2];
                BakePass {
                    pipeline: next_order_pipeline.clone(),
                    tables: table_group(
                        "atmos tables for a scattering order",
                        [&transmittance, previous, pa, p3, p3, pa],
                    ),
                    outputs: order_outputs("atmos scattering order outputs", next),
                    workgroups: ms_workgroups,
                    label: "atmos multiple-scattering order",
                }
            })
            .collect();
        // The sum into the LUT (binding 2 of the outputs); the last order written is
        // bound at binding 0 unused, never read in this dispatch.
        let last = &orders[settings.multiple_scattering_orders as usize % 2];
        let scratch = &orders[(settings.multiple_scattering_orders as usize + 1) % 2];
        higher_orders.push(BakePass {
            pipeline: compute_pipeline(
                device,
                &ms_layout,
                "atmos::lut_multiple_scattering",
                "finish_multiple_scattering_lut",
            )?,
            tables: table_group(
                "atmos tables for the multiple-scattering sum",
                [&transmittance, last, pa, p3, p3, pa],
            ),
            outputs: order_outputs("atmos multiple-scattering sum outputs", scratch),
            workgroups: ms_workgroups,
            label: "atmos multiple-scattering sum",
        });
        Ok(Self {
            device: device.clone(),
            settings: s,
            atmosphere: atmosphere_uniform,
            multiple_scattering_orders: settings.multiple_scattering_orders,
            atmosphere_buffer,
            settings_buffer,
            transmittance,
            multiple_scattering,
            sky_irradiance,
            layouts,
            uniforms,
            passes,
            higher_orders,
            view_bakes,
        })
    }
}

/// The uniforms' bind group ([`LutLayouts::uniforms`]) of four buffers.
pub(super) fn uniform_group(
    device: &wgpu::Device,
    layouts: &LutLayouts,
    buffers: [&wgpu::Buffer; 4],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = buffers
        .iter()
        .zip(0..)
        .map(|(buffer, binding)| wgpu::BindGroupEntry {
            binding,
            resource: buffer.as_entire_binding(),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("atmos LUT uniforms"),
        layout: &layouts.uniforms,
        entries: &entries,
    })
}

/// A tables' bind group ([`LutLayouts::tables`]) of six views.
pub(super) fn table_group(
    device: &wgpu::Device,
    layouts: &LutLayouts,
    label: &str,
    views: [&wgpu::TextureView; 6],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = views
        .iter()
        .zip(0..)
        .map(|(view, binding)| wgpu::BindGroupEntry {
            binding,
            resource: wgpu::BindingResource::TextureView(view),
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout: &layouts.tables,
        entries: &entries,
    })
}
