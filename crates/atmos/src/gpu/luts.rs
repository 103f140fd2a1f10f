//! GPU bakes of the precomputed rung's LUTs (compute; one WGSL file per pass in
//! `shaders/atmos/lut_*.wgsl`). Bring your own device: [`LutBaker::new`] creates
//! pipelines and buffers (uniforms initialised at creation, no queue work),
//! [`LutBaker::prepare`] writes the frame camera, and each `encode_*` records one
//! compute pass into the caller's encoder, optionally timed.
//!
//! Every pass shares one pipeline layout (see `lut_sampling.wgsl`): group 0 the
//! uniforms, group 1 the LUTs read (passes that run before a LUT exists bind a
//! 16-byte placeholder there, never the buffer they write), group 2 the outputs.
//! LUTs are `array<vec4<f32>>` storage buffers (usage `STORAGE | COPY_SRC`), read with
//! manual bilinear filtering — portable to adapters without float32 filtering.

use wgpu::util::DeviceExt as _;

use crate::frame::FrameCamera;
use crate::gpu::resources::{storage_entry, uniform_entry};
use crate::lut::multiple_scattering_moments::MULTIPLE_SCATTERING_LAYERS;
use crate::lut::{LutSettings, LutSettingsUniform};
use crate::{AtmosError, Atmosphere, GpuError};

const WORKGROUP: u32 = 8;

/// The four LUT passes with their buffers.
#[derive(Debug)]
pub struct LutBaker {
    pub(crate) device: wgpu::Device,
    settings: LutSettingsUniform,
    camera: wgpu::Buffer,
    transmittance: wgpu::Buffer,
    multiple_scattering: wgpu::Buffer,
    sky_view: wgpu::Buffer,
    aerial_perspective: wgpu::Buffer,
    pub(crate) layout: wgpu::PipelineLayout,
    pub(crate) output_layout: wgpu::BindGroupLayout,
    pub(crate) uniforms: wgpu::BindGroup,
    pub(crate) render_luts: wgpu::BindGroup,
    passes: [BakePass; 4],
    /// Orders 3… of the multiple-scattering bake, each reading the order before (two
    /// ping-pong buffers) and adding to the LUT; recorded right after its order-2 pass.
    higher_orders: Vec<BakePass>,
}

#[derive(Debug)]
struct BakePass {
    pipeline: wgpu::ComputePipeline,
    luts: wgpu::BindGroup,
    output: wgpu::BindGroup,
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

impl LutBaker {
    /// Validates the inputs, creates the pipelines and the LUT buffers.
    pub fn new(
        device: &wgpu::Device,
        atmosphere: &Atmosphere,
        settings: &LutSettings,
    ) -> Result<Self, AtmosError> {
        let atmosphere_uniform = atmosphere.to_uniforms()?;
        let s = settings.to_uniforms()?;
        let texel_bytes = 16u64;
        let sizes = [
            u64::from(s.transmittance_width * s.transmittance_height),
            u64::from(s.multiple_scattering_width * s.multiple_scattering_height)
                * u64::from(MULTIPLE_SCATTERING_LAYERS),
            // radiance, and the transmittance when the table stores it
            u64::from(s.sky_view_entries_per_texel() * s.sky_view_width * s.sky_view_height),
            2 * u64::from(
                s.aerial_perspective_width
                    * s.aerial_perspective_height
                    * s.aerial_perspective_depth,
            ),
        ];
        let limit = device.limits().max_storage_buffer_binding_size;
        if let Some(bytes) = sizes.iter().map(|n| n * texel_bytes).find(|&b| b > limit) {
            return Err(GpuError::StorageBufferTooLarge {
                resource: "a LUT".to_owned(),
                bytes,
                limit,
            }
            .into());
        }
        let lut_buffer = |label: &str, texels: u64| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: texels * texel_bytes,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            })
        };
        let transmittance = lut_buffer("atmos transmittance LUT", sizes[0]);
        let multiple_scattering = lut_buffer("atmos multiple-scattering LUT", sizes[1]);
        let scattering_orders = [
            lut_buffer("atmos multiple-scattering order (even)", sizes[1]),
            lut_buffer("atmos multiple-scattering order (odd)", sizes[1]),
        ];
        let sky_view = lut_buffer("atmos sky-view LUT", sizes[2]);
        let aerial_perspective = lut_buffer("atmos aerial-perspective volume", sizes[3]);
        let placeholder_read = lut_buffer("atmos LUT placeholder (read)", 1);
        let placeholder_write = lut_buffer("atmos LUT placeholder (write)", 1);

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

        let uniform_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUT uniforms"),
            entries: &[uniform_entry(0), uniform_entry(1), uniform_entry(2)],
        });
        let lut_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUTs"),
            entries: &[
                storage_entry(0, true),
                storage_entry(1, true),
                storage_entry(2, true),
                storage_entry(3, true),
            ],
        });
        let output_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("atmos LUT outputs"),
            entries: &[storage_entry(0, false), storage_entry(1, false)],
        });
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("atmos LUT passes"),
            bind_group_layouts: &[
                Some(&uniform_layout),
                Some(&lut_layout),
                Some(&output_layout),
            ],
            immediate_size: 0,
        });
        let uniforms = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("atmos LUT uniforms"),
            layout: &uniform_layout,
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
        let luts = |label: &str, buffers: [&wgpu::Buffer; 4]| {
            let entries: Vec<wgpu::BindGroupEntry> = buffers
                .iter()
                .enumerate()
                .map(|(i, b)| wgpu::BindGroupEntry {
                    binding: i as u32,
                    resource: b.as_entire_binding(),
                })
                .collect();
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &lut_layout,
                entries: &entries,
            })
        };
        let outputs = |label: &str, first: &wgpu::Buffer, second: &wgpu::Buffer| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(label),
                layout: &output_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: first.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: second.as_entire_binding(),
                    },
                ],
            })
        };
        let output =
            |label: &str, buffer: &wgpu::Buffer| outputs(label, buffer, &placeholder_write);
        let p = &placeholder_read;
        let groups = |n: u32| n.div_ceil(WORKGROUP);
        let passes = [
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &layout,
                    "atmos::lut_transmittance",
                    "bake_transmittance_lut",
                )?,
                luts: luts("atmos LUTs for transmittance", [p, p, p, p]),
                output: output("atmos transmittance output", &transmittance),
                workgroups: [
                    groups(s.transmittance_width),
                    groups(s.transmittance_height),
                ],
                label: "atmos transmittance LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &layout,
                    "atmos::lut_multiple_scattering",
                    "bake_multiple_scattering_lut",
                )?,
                luts: luts(
                    "atmos LUTs for multiple scattering",
                    [&transmittance, p, p, p],
                ),
                output: outputs(
                    "atmos multiple-scattering outputs (order 2)",
                    &scattering_orders[0],
                    &multiple_scattering,
                ),
                workgroups: [
                    groups(s.multiple_scattering_width),
                    groups(s.multiple_scattering_height),
                ],
                label: "atmos multiple-scattering LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &layout,
                    "atmos::lut_sky_view",
                    "bake_sky_view_lut",
                )?,
                luts: luts(
                    "atmos LUTs for the sky view",
                    [&transmittance, &multiple_scattering, p, p],
                ),
                output: output("atmos sky-view output", &sky_view),
                workgroups: [groups(s.sky_view_width), groups(s.sky_view_height)],
                label: "atmos sky-view LUT",
            },
            BakePass {
                pipeline: compute_pipeline(
                    device,
                    &layout,
                    "atmos::lut_aerial_perspective",
                    "bake_aerial_perspective",
                )?,
                luts: luts(
                    "atmos LUTs for aerial perspective",
                    [&transmittance, &multiple_scattering, p, p],
                ),
                output: output("atmos aerial-perspective output", &aerial_perspective),
                workgroups: [
                    groups(s.aerial_perspective_width),
                    groups(s.aerial_perspective_height),
                ],
                label: "atmos aerial-perspective volume",
            },
        ];
        let next_order_pipeline = compute_pipeline(
            device,
            &layout,
            "atmos::lut_multiple_scattering",
            "bake_multiple_scattering_next_order",
        )?;
        let higher_orders = (3..=settings.multiple_scattering_orders)
            .map(|order| {
                // Order k reads order k − 1 (even orders sit in buffer 0).
                let previous = &scattering_orders[(order as usize - 1) % 2];
                let next = &scattering_orders[order as usize % 2];
                BakePass {
                    pipeline: next_order_pipeline.clone(),
                    luts: luts(
                        "atmos LUTs for a multiple-scattering order",
                        [&transmittance, previous, p, p],
                    ),
                    output: outputs(
                        "atmos multiple-scattering outputs (next order)",
                        next,
                        &multiple_scattering,
                    ),
                    workgroups: [
                        groups(s.multiple_scattering_width),
                        groups(s.multiple_scattering_height),
                    ],
                    label: "atmos multiple-scattering order",
                }
            })
            .collect();
        let render_luts = luts(
            "atmos LUTs for rendering",
            [
                &transmittance,
                &multiple_scattering,
                &sky_view,
                &aerial_perspective,
            ],
        );
        Ok(Self {
            device: device.clone(),
            settings: s,
            camera,
            transmittance,
            multiple_scattering,
            sky_view,
            aerial_perspective,
            layout,
            output_layout,
            uniforms,
            render_luts,
            passes,
            higher_orders,
        })
    }

    /// Writes the frame camera the per-frame passes (sky view, aerial perspective)
    /// bake for. The static passes (transmittance, multiple scattering) ignore it.
    pub fn prepare(&self, queue: &wgpu::Queue, camera: &FrameCamera) {
        queue.write_buffer(&self.camera, 0, bytemuck::bytes_of(camera));
    }

    /// The settings the buffers were sized for.
    pub fn settings(&self) -> &LutSettingsUniform {
        &self.settings
    }

    fn record(&self, pass: &mut wgpu::ComputePass<'_>, which: usize) {
        let bake = &self.passes[which];
        pass.set_pipeline(&bake.pipeline);
        pass.set_bind_group(0, &self.uniforms, &[]);
        pass.set_bind_group(1, &bake.luts, &[]);
        pass.set_bind_group(2, &bake.output, &[]);
        pass.dispatch_workgroups(bake.workgroups[0], bake.workgroups[1], 1);
        if which == MULTIPLE_SCATTERING {
            for order in &self.higher_orders {
                pass.set_pipeline(&order.pipeline);
                pass.set_bind_group(1, &order.luts, &[]);
                pass.set_bind_group(2, &order.output, &[]);
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
    /// order; reads the transmittance LUT).
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

    /// Transmittance LUT (`vec4<f32>` texels, row-major).
    pub fn transmittance_lut(&self) -> &wgpu::Buffer {
        &self.transmittance
    }
    /// Multiple-scattering LUT.
    pub fn multiple_scattering_lut(&self) -> &wgpu::Buffer {
        &self.multiple_scattering
    }
    /// Sky-view LUT.
    pub fn sky_view_lut(&self) -> &wgpu::Buffer {
        &self.sky_view
    }
    /// Aerial-perspective volume (two texels per froxel, see
    /// [`crate::lut::aerial_perspective`]).
    pub fn aerial_perspective_volume(&self) -> &wgpu::Buffer {
        &self.aerial_perspective
    }
}
