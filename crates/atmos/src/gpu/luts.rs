//! The precomputed rung's lookup tables on the GPU: textures a caller can bind in their
//! own pipelines, and the compute passes that bake them (one WGSL file per pass in
//! `shaders/atmos/lut_*.wgsl`). Bring your own device: [`AtmosphereLuts::new`] creates
//! the textures, bind groups and pipelines (uniforms initialised at creation, no queue
//! work), [`AtmosphereLuts::prepare`] writes the frame camera, and each `encode_*`
//! records one compute pass into the caller's encoder, optionally timed.
//!
//! **Reading the tables in your own shader.** The lookups of `atmos::lut_sampling`
//! (`lookup_transmittance`, `lookup_sky_view`, `lookup_aerial_perspective`,
//! `sun_transmittance`, …) read module-scope bindings declared by
//! `atmos::lut_bindings`: the uniforms (atmosphere, settings, frame camera) in one bind
//! group and the tables in another. Compose your shader with
//! [`composer_with_lut_groups`] to put them at the groups your pipeline has free, put
//! [`LutLayouts::uniforms`] and [`LutLayouts::tables`] at those indices of your
//! pipeline layout, and set [`AtmosphereLuts::uniform_bind_group`] and
//! [`AtmosphereLuts::table_bind_group`] there.
//!
//! | group (default) | binding | WGSL name | resource |
//! |---|---|---|---|
//! | uniforms (0) | 0 | `lut_atmosphere` | `AtmosphereParameters` |
//! | uniforms (0) | 1 | `lut_settings` | `LutSettings` ([`crate::lut::LutSettingsUniform`]) |
//! | uniforms (0) | 2 | `frame_camera` | [`FrameCamera`] |
//! | tables (1) | 0 | `transmittance_lut` | `texture_2d<f32>` |
//! | tables (1) | 1 | `multiple_scattering_lut` | `texture_2d_array<f32>`, 6 layers |
//! | tables (1) | 2 | `sky_view_lut` | `texture_2d_array<f32>`: radiance, transmittance |
//! | tables (1) | 3 | `aerial_perspective_radiance` | `texture_3d<f32>` |
//! | tables (1) | 4 | `aerial_perspective_transmittance` | `texture_3d<f32>` |
//!
//! Every table is `rgba32float` (the CPU twin's values exactly; writable by compute
//! passes on every WebGPU adapter), read with `textureLoad` and filtered by hand in
//! the WGSL, so no sampler is needed and adapters without float32 filtering work.
//! Texel (x, y) of layer m is entry `x + w·(y + h·m)` of the CPU twin's table.

use crate::frame::FrameCamera;
use crate::gpu::resources::{
    READ_STAGES, check_texture_support, float_texture_entry, shared_uniform_entry, storage_entry,
    storage_texture_entry,
};
use crate::lut::multiple_scattering_moments::MULTIPLE_SCATTERING_LAYERS;
use crate::lut::{LutSettings, LutSettingsUniform};
use crate::{AtmosError, Atmosphere, GpuError};
use wgpu::TextureViewDimension as Dim;
use wgpu::util::DeviceExt as _;

const WORKGROUP: u32 = 8;
const FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// The WGSL of `atmos::lut_bindings` with its uniforms at `@group(uniform_group)` and
/// its tables at `@group(table_group)`: the file's own text, the two group attributes
/// rewritten (nothing else differs).
pub fn lut_bindings_wgsl(uniform_group: u32, table_group: u32) -> String {
    let source = include_str!("../../shaders/lut_bindings.wgsl");
    source
        .lines()
        .map(|line| {
            if let Some(rest) = line.strip_prefix("@group(0) ") {
                format!("@group({uniform_group}) {rest}")
            } else if let Some(rest) = line.strip_prefix("@group(1) ") {
                format!("@group({table_group}) {rest}")
            } else {
                line.to_owned()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// A composer that knows every module of `atmos` (and the common ones), with the LUT
/// bindings (`atmos::lut_bindings`) at the groups a caller's pipeline has free: compose
/// your shader, which `#import`s `atmos::lut_sampling`, with it. Errors when the two
/// groups are equal (they hold different layouts).
pub fn composer_with_lut_groups(
    uniform_group: u32,
    table_group: u32,
) -> Result<skyscape_wgsl::Composer, AtmosError> {
    if uniform_group == table_group {
        return Err(AtmosError::InvalidSetting {
            setting: "LUT bind groups",
            field: "table_group".to_owned(),
            value: f64::from(table_group),
            reason: "must differ from uniform_group (the uniforms and the tables are two layouts)",
        });
    }
    let mut composer = skyscape_wgsl::Composer::with_common();
    composer
        .add_modules(crate::WGSL_MODULES)
        .expect("atmos WGSL module names are unique and well formed");
    let bindings = lut_bindings_wgsl(uniform_group, table_group);
    // `Module` holds `&'static str`: a composer lives for a pipeline's creation, and
    // one bindings text per (uniform, table) pair a program asks for is leaked once.
    let bindings: &'static str = Box::leak(bindings.into_boxed_str());
    let modules: Vec<skyscape_wgsl::Module> = crate::lut::WGSL_MODULES
        .iter()
        .map(|module| {
            if module.name == "atmos::lut_bindings" {
                skyscape_wgsl::Module {
                    name: module.name,
                    source: bindings,
                }
            } else {
                *module
            }
        })
        .collect();
    composer
        .add_modules(&modules)
        .expect("atmos LUT WGSL module names are unique and well formed");
    Ok(composer)
}

/// The two bind-group layouts of the LUTs: the uniforms and the tables (see the module
/// documentation for the bindings). Readable from compute, vertex and fragment stages.
#[derive(Debug)]
pub struct LutLayouts {
    /// Atmosphere, settings, frame camera (uniform buffers at bindings 0, 1, 2).
    pub uniforms: wgpu::BindGroupLayout,
    /// The five tables (unfilterable-float textures at bindings 0 … 4).
    pub tables: wgpu::BindGroupLayout,
}

impl LutLayouts {
    /// Creates both layouts.
    pub fn new(device: &wgpu::Device) -> Self {
        let uniforms = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUT uniforms"),
            entries: &[
                shared_uniform_entry(0),
                shared_uniform_entry(1),
                shared_uniform_entry(2),
            ],
        });
        let tables = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUT tables"),
            entries: &[
                float_texture_entry(0, Dim::D2),
                float_texture_entry(1, Dim::D2Array),
                float_texture_entry(2, Dim::D2Array),
                float_texture_entry(3, Dim::D3),
                float_texture_entry(4, Dim::D3),
            ],
        });
        Self { uniforms, tables }
    }
}

/// One table: its texture and the view of all its layers.
#[derive(Debug)]
struct Table {
    texture: wgpu::Texture,
    view: wgpu::TextureView,
}

impl Table {
    fn new(device: &wgpu::Device, label: &str, size: [u32; 3], dimension: Dim) -> Self {
        let texture = device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: size[0],
                height: size[1],
                depth_or_array_layers: size[2],
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: if dimension == Dim::D3 {
                wgpu::TextureDimension::D3
            } else {
                wgpu::TextureDimension::D2
            },
            format: FORMAT,
            usage: wgpu::TextureUsages::STORAGE_BINDING
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        });
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            label: Some(label),
            dimension: Some(dimension),
            ..Default::default()
        });
        Self { texture, view }
    }
}

/// One bake dispatch: its pipeline, the tables it reads (group 1), its outputs
/// (group 2) and its workgroup counts.
#[derive(Debug)]
struct BakePass {
    pipeline: wgpu::ComputePipeline,
    tables: wgpu::BindGroup,
    outputs: wgpu::BindGroup,
    workgroups: [u32; 2],
    label: &'static str,
}

const TRANSMITTANCE: usize = 0;
const MULTIPLE_SCATTERING: usize = 1;
const SKY_VIEW: usize = 2;
const AERIAL_PERSPECTIVE: usize = 3;

/// Composes a WGSL module of this crate and creates its compute pipeline.
pub(crate) fn compute_pipeline(
    device: &wgpu::Device,
    layout: &wgpu::PipelineLayout,
    module: &str,
    entry: &str,
) -> Result<wgpu::ComputePipeline, AtmosError> {
    let source = crate::composer().compose_module(module)?;
    let shader = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some(module),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    Ok(
        device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some(module),
            layout: Some(layout),
            module: &shader,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            cache: None,
        }),
    )
}

/// The precomputed rung's tables and the passes that bake them.
#[derive(Debug)]
pub struct AtmosphereLuts {
    pub(crate) device: wgpu::Device,
    settings: LutSettingsUniform,
    camera: wgpu::Buffer,
    transmittance: Table,
    multiple_scattering: Table,
    sky_view: Table,
    aerial_perspective_radiance: Table,
    aerial_perspective_transmittance: Table,
    layouts: LutLayouts,
    uniforms: wgpu::BindGroup,
    tables: wgpu::BindGroup,
    passes: [BakePass; 4],
    /// Orders 3… of the multiple-scattering bake, each reading the order before (two
    /// ping-pong textures) and adding to the sum; then the copy of the sum into the
    /// LUT. Recorded right after the order-2 pass.
    higher_orders: Vec<BakePass>,
}

impl AtmosphereLuts {
    /// Validates the inputs, creates the tables, bind groups and pipelines. Errors
    /// naming the table when one exceeds the device's texture limits.
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
        let sky_view_layers = s.sky_view_entries_per_texel();
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
        let sky_view = Table::new(
            device,
            "atmos sky-view LUT",
            [s.sky_view_width, s.sky_view_height, sky_view_layers],
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
            "atmos LUT frame camera",
            bytemuck::bytes_of(&<FrameCamera as bytemuck::Zeroable>::zeroed()),
        );

        let layouts = LutLayouts::new(device);
        let uniforms = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("atmos LUT uniforms"),
            layout: &layouts.uniforms,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: atmosphere_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: settings_buffer.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: camera.as_entire_binding(),
                },
            ],
        });
        let table_group = |label: &str, views: [&Table; 5]| {
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
                layout: &layouts.tables,
                entries: &entries,
            })
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
                tables: table_group("atmos tables for transmittance", [p2, pa, pa, p3, p3]),
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
                    [&transmittance, pa, pa, p3, p3],
                ),
                outputs: order_outputs("atmos scattering order 2 outputs", &orders[0]),
                workgroups: ms_workgroups,
                label: "atmos multiple-scattering LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &pipeline_layout("atmos sky-view bake", &sky_view_out),
                    "atmos::lut_sky_view",
                    "bake_sky_view_lut",
                )?,
                tables: table_group(
                    "atmos tables for the sky view",
                    [&transmittance, &multiple_scattering, pa, p3, p3],
                ),
                outputs: texture_outputs("atmos sky-view output", &sky_view_out, &[&sky_view]),
                workgroups: [groups(s.sky_view_width), groups(s.sky_view_height)],
                label: "atmos sky-view LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &pipeline_layout("atmos aerial-perspective bake", &aerial_perspective_out),
                    "atmos::lut_aerial_perspective",
                    "bake_aerial_perspective",
                )?,
                tables: table_group(
                    "atmos tables for aerial perspective",
                    [&transmittance, &multiple_scattering, pa, p3, p3],
                ),
                outputs: texture_outputs(
                    "atmos aerial-perspective outputs",
                    &aerial_perspective_out,
                    &[
                        &aerial_perspective_radiance,
                        &aerial_perspective_transmittance,
                    ],
                ),
                workgroups: [
                    groups(s.aerial_perspective_width),
                    groups(s.aerial_perspective_height),
                ],
                label: "atmos aerial-perspective volume",
            },
        ];
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
                        [&transmittance, previous, pa, p3, p3],
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
                [&transmittance, last, pa, p3, p3],
            ),
            outputs: order_outputs("atmos multiple-scattering sum outputs", scratch),
            workgroups: ms_workgroups,
            label: "atmos multiple-scattering sum",
        });
        let tables = table_group(
            "atmos LUT tables",
            [
                &transmittance,
                &multiple_scattering,
                &sky_view,
                &aerial_perspective_radiance,
                &aerial_perspective_transmittance,
            ],
        );
        Ok(Self {
            device: device.clone(),
            settings: s,
            camera,
            transmittance,
            multiple_scattering,
            sky_view,
            aerial_perspective_radiance,
            aerial_perspective_transmittance,
            layouts,
            uniforms,
            tables,
            passes,
            higher_orders,
        })
    }

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
