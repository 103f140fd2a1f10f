//! The billboards on the GPU: cloudlight's billboard pipeline over the HDR target, the
//! particles' air from the tables or from a rung's compute pass.

use cloudlight::billboard::Billboard;

use crate::RenderError;
use crate::scene::PreparedScene;

use super::*;

/// The billboard pass's uniform bytes: `cloudlight::billboard`'s frame (64 bytes), the
/// near plane, the radiance scale, which moonlit air is added (WGSL
/// `BillboardCloudParams`: 0 none, 1 the CPU's per instance, 2 a rung's pass's).
pub fn params_bytes(
    frame: &cloudlight::billboard::ScreenFrame<f32>,
    near: f32,
    radiance_scale: f32,
    moonlit: u32,
) -> [u8; PARAMS_BYTES as usize] {
    let mut bytes = [0u8; PARAMS_BYTES as usize];
    bytes[..64].copy_from_slice(&cloudlight::gpu::billboard::frame_bytes(frame));
    bytes[64..68].copy_from_slice(&near.to_ne_bytes());
    bytes[68..72].copy_from_slice(&radiance_scale.to_ne_bytes());
    bytes[72..76].copy_from_slice(&moonlit.to_ne_bytes());
    bytes
}

/// The billboard pass's group 2: the uniform (vertex stage) and the moonlit air per
/// instance (a read-only storage buffer of `vec4<f32>`); with `rung_air` (a rung without
/// tables) the sun's and the moon's air per instance too
/// (`shaders/render/billboard_clouds_rung.wgsl`).
fn params_layout(device: &wgpu::Device, rung_air: bool) -> wgpu::BindGroupLayout {
    let entry = |binding, ty| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::VERTEX,
        ty,
        count: None,
    };
    let storage = |binding| {
        entry(
            binding,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only: true },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(16),
            },
        )
    };
    let entries = [
        entry(
            0,
            wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(PARAMS_BYTES),
            },
        ),
        storage(1),
        storage(2),
        storage(3),
    ];
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("render billboard clouds"),
        entries: &entries[..if rung_air { 4 } else { 2 }],
    })
}

fn needs_tables() -> RenderError {
    RenderError::InvalidParameter {
        field: "clouds.volume.draw",
        value: "\"billboards\"".into(),
        reason: "the GPU billboards see their air through the precomputed rung's tables or \
                 the closed form's or single scattering's passes; render this scene with one \
                 of those rungs, or on the CPU (--cpu)",
    }
}

fn added_air_buffer(device: &wgpu::Device, size: u64) -> wgpu::Buffer {
    device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("render billboard added lights' air"),
        size,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

fn params_bind_group(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    uniform: &wgpu::Buffer,
    added_air: &wgpu::Buffer,
    rung_air: Option<[&wgpu::Buffer; 2]>,
) -> wgpu::BindGroup {
    let [sun, moon] = rung_air.map_or([None; 2], |airs| airs.map(Some));
    let entries: Vec<wgpu::BindGroupEntry<'_>> = [Some(uniform), Some(added_air), sun, moon]
        .into_iter()
        .enumerate()
        .filter_map(|(binding, buffer)| {
            Some(wgpu::BindGroupEntry {
                binding: binding as u32,
                resource: buffer?.as_entire_binding(),
            })
        })
        .collect();
    device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("render billboard clouds"),
        layout,
        entries: &entries,
    })
}

/// Bytes of WGSL `BillboardCloudParams`.
pub const PARAMS_BYTES: u64 = 80;

/// The particles per workgroup of the rungs' billboard air passes
/// (`shaders/render/billboard_air_rung.wgsl`).
const AIR_WORKGROUP: u32 = 64;

/// The air in front of every particle under a rung without tables, per light (the sun,
/// and the light added to it: the moon on a moonlit night): a compute pass of the rung's functions
/// (`shaders/render/billboard_air_rung.wgsl` with the rung's module) per
/// particle, with the light's camera and the rung's parameters of its atmosphere
/// (`crate::gpu::cloud_air::RungCloudAir`, written each frame by the rung's passes) in
/// groups 0 and 1, the particles' world offsets in and their air out in group 2
/// (`shaders/render/billboard_air_io.wgsl`). The twin of the CPU's segment models in
/// [`composite_billboards_cpu`] (the sun's) and [`other_lights_air`] (the added light's).
#[derive(Debug)]
struct RungBillboardAir {
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    /// The particles' world offsets (one `vec4<f32>` each).
    offsets: wgpu::Buffer,
    /// Each light's pass, the sun's first.
    lights: Vec<LightAir>,
}

/// One light's billboard air pass and its output.
#[derive(Debug)]
struct LightAir {
    pipeline: wgpu::ComputePipeline,
    /// The light's camera and the rung's parameters (groups 0 and 1).
    light: [wgpu::BindGroup; 2],
    /// The particles' air (two `vec4<f32>` each: radiance, transmittance), read by the
    /// draw's vertex stage.
    air: wgpu::Buffer,
    group: wgpu::BindGroup,
}

impl RungBillboardAir {
    fn new(
        device: &wgpu::Device,
        airs: &[&crate::gpu::cloud_air::RungCloudAir],
    ) -> Result<Self, RenderError> {
        let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
            binding,
            visibility: wgpu::ShaderStages::COMPUTE,
            ty: wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Storage { read_only },
                has_dynamic_offset: false,
                min_binding_size: wgpu::BufferSize::new(16),
            },
            count: None,
        };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render billboard air"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: false,
                        min_binding_size: wgpu::BufferSize::new(16),
                    },
                    count: None,
                },
                storage(1, true),
                storage(2, false),
            ],
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render billboard air uniform"),
            size: 16,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let offsets = Self::buffer(device, "render billboard offsets", 16);
        let light = |air: &crate::gpu::cloud_air::RungCloudAir, label: &str| {
            let pipeline = air.pipeline(
                device,
                label,
                ("render::billboard_air_rung", "billboard_air_rung"),
                &layout,
            )?;
            let light = air.groups().map(Clone::clone);
            let air = Self::buffer(device, label, 32);
            let group = Self::group(device, &layout, &uniform, &offsets, &air);
            Ok::<_, RenderError>(LightAir {
                pipeline,
                light,
                air,
                group,
            })
        };
        let lights = airs
            .iter()
            .map(|air| light(air, "render billboard air"))
            .collect::<Result<Vec<_>, _>>()?;
        if lights.is_empty() {
            return Err(needs_tables());
        }
        Ok(Self {
            layout,
            uniform,
            offsets,
            lights,
        })
    }

    fn buffer(device: &wgpu::Device, label: &str, size: u64) -> wgpu::Buffer {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    fn group(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        uniform: &wgpu::Buffer,
        offsets: &wgpu::Buffer,
        air: &wgpu::Buffer,
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry<'_>> = [uniform, offsets, air]
            .into_iter()
            .enumerate()
            .map(|(binding, buffer)| wgpu::BindGroupEntry {
                binding: binding as u32,
                resource: buffer.as_entire_binding(),
            })
            .collect();
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render billboard air"),
            layout,
            entries: &entries,
        })
    }

    /// The sun's air and the added light's (the sun's again without one: unread).
    fn airs(&self) -> [&wgpu::Buffer; 2] {
        let sun = &self.lights[0];
        [&sun.air, &self.lights.get(1).unwrap_or(sun).air]
    }

    /// Uploads the particles' world offsets (the draw's order) and their count; `true`
    /// when the air buffers were replaced (the draw's group 2 must be made again).
    fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        particles: &[Billboard],
    ) -> Result<bool, RenderError> {
        let count = particles.len() as u64;
        let groups = count.div_ceil(u64::from(AIR_WORKGROUP));
        let limits = device.limits();
        if groups > u64::from(limits.max_compute_workgroups_per_dimension)
            || 32 * count > limits.max_storage_buffer_binding_size
        {
            return Err(RenderError::InvalidParameter {
                field: "clouds.volume.billboards",
                value: format!("{count} billboards"),
                reason: "more particles than the device's compute dispatch or storage \
                         binding limits allow for their air",
            });
        }
        let replaced = self.offsets.size() < 16 * count;
        if replaced {
            self.offsets = Self::buffer(device, "render billboard offsets", 16 * count);
            for light in &mut self.lights {
                light.air = Self::buffer(device, "render billboard air", 32 * count);
                light.group = Self::group(
                    device,
                    &self.layout,
                    &self.uniform,
                    &self.offsets,
                    &light.air,
                );
            }
        }
        let offsets: Vec<f32> = particles
            .iter()
            .flat_map(|p| {
                let [x, y, z] = world_offset(p.relative);
                [x, y, z, 0.0]
            })
            .collect();
        if !offsets.is_empty() {
            queue.write_buffer(&self.offsets, 0, bytemuck::cast_slice(&offsets));
        }
        let params = [count as u32, 0, 0, 0];
        queue.write_buffer(&self.uniform, 0, bytemuck::cast_slice(&params));
        Ok(replaced)
    }

    /// Records the compute passes of `count` particles' air: the sun's, and the added
    /// light's when `added` (the draw reads it, `moonlit` = 2).
    fn encode(&self, encoder: &mut wgpu::CommandEncoder, count: u32, added: bool) {
        let lights = if added {
            &self.lights[..]
        } else {
            &self.lights[..1]
        };
        for light in lights {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render billboard air"),
                timestamp_writes: None,
            });
            pass.set_pipeline(&light.pipeline);
            pass.set_bind_group(0, &light.light[0], &[]);
            pass.set_bind_group(1, &light.light[1], &[]);
            pass.set_bind_group(2, &light.group, &[]);
            pass.dispatch_workgroups(count.div_ceil(AIR_WORKGROUP), 1, 1);
        }
    }
}

/// The GPU side: cloudlight's instanced quads (`cloudlight::gpu::billboard`'s instance
/// layout, pipeline and pass) drawn by `shaders/render/billboard_clouds.wgsl` into the HDR target with the
/// terrain's depth as a read-only depth attachment (test `Greater`), the LUTs in groups
/// 0 and 1 for the aerial perspective (the precomputed rung), or each particle's air
/// from [`RungBillboardAir`]'s pass in group 2 (the closed form, single scattering).
use cloudlight::gpu::billboard::{
    BillboardPipelineDescriptor, begin_billboard_pass, billboard_pipeline, draw_billboards,
};

#[derive(Debug)]
pub(crate) struct BillboardCloudPass {
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    bind_group: wgpu::BindGroup,
    uniform: wgpu::Buffer,
    /// The other lights' air per instance (16 bytes, unread, with the sun alone).
    added_air: wgpu::Buffer,
    /// The air per particle under a rung without tables (`None`: the precomputed rung's
    /// tables in groups 0 and 1).
    rung_air: Option<RungBillboardAir>,
    /// This frame's other lights' air: 0 none, 1 the CPU's per instance, 2 the rung's
    /// pass (one light added to the sun under a rung without tables).
    moonlit: u32,
    instances: Option<wgpu::Buffer>,
    count: u32,
}

impl BillboardCloudPass {
    /// The pipeline for an HDR target of `target` and a depth attachment of `depth`;
    /// the particles' air is the sun's `air` (`crate::gpu::cloud_air::cloud_airs`): the
    /// precomputed rung's tables, read in the vertex stage, or a rung's functions, a
    /// compute pass per particle before the draw (an error without either). Under a
    /// rung without tables the light added to the sun (`added`: the moon on a moonlit
    /// night) gets its pass too; on the precomputed rung the other lights' air is the
    /// CPU's ([`other_lights_air`]).
    pub(crate) fn new(
        device: &wgpu::Device,
        air: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        added: Option<crate::gpu::cloud_air::CloudAir<'_>>,
        target: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
    ) -> Result<Self, RenderError> {
        use crate::gpu::cloud_air::CloudAir;
        let (module_name, vertex_entry, fragment_entry) = match air {
            Some(CloudAir::Tables(_)) => (
                "render::billboard_clouds",
                "billboard_clouds_vertex",
                "billboard_clouds_fragment",
            ),
            Some(CloudAir::Rung(_)) => (
                "render::billboard_clouds_rung",
                "billboard_clouds_rung_vertex",
                "billboard_clouds_rung_fragment",
            ),
            None => return Err(needs_tables()),
        };
        let rung_air = match air {
            Some(CloudAir::Rung(rung)) => {
                let mut airs = vec![rung];
                if let Some(CloudAir::Rung(added)) = added {
                    airs.push(added);
                }
                Some(RungBillboardAir::new(device, &airs)?)
            }
            _ => None,
        };
        let source = crate::composer().compose_module(module_name)?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render billboard clouds"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = params_layout(device, rung_air.is_some());
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render billboard clouds uniform"),
            size: PARAMS_BYTES,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let added_air = added_air_buffer(device, 16);
        let bind_group = params_bind_group(
            device,
            &layout,
            &uniform,
            &added_air,
            rung_air.as_ref().map(RungBillboardAir::airs),
        );
        // The rungs' pipeline binds group 2 alone (its air is in group 2).
        let tables = match air {
            Some(CloudAir::Tables(luts)) => {
                [Some(&luts.layouts().uniforms), Some(&luts.layouts().tables)]
            }
            _ => [None, None],
        };
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render billboard clouds"),
            bind_group_layouts: &[tables[0], tables[1], Some(&layout)],
            immediate_size: 0,
        });
        let pipeline = billboard_pipeline(
            device,
            &BillboardPipelineDescriptor {
                label: "render billboard clouds",
                layout: &pipeline_layout,
                module: &module,
                vertex_entry,
                fragment_entry,
                target,
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: depth,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(wgpu::CompareFunction::Greater),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
            },
        );
        Ok(Self {
            pipeline,
            layout,
            bind_group,
            uniform,
            added_air,
            rung_air,
            moonlit: 0,
            instances: None,
            count: 0,
        })
    }

    /// Selects and sorts the particles for the scene's camera (on the CPU, as the twin
    /// does) and uploads them and the frame's uniform; the instance buffer is kept while
    /// it is large enough.
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        cloud: &PreparedBillboards,
    ) -> Result<(), RenderError> {
        let (camera, particles) = particles(scene, cloud)?;
        let bytes = cloudlight::gpu::billboard::instance_bytes(&particles);
        let limit = device.limits().max_buffer_size;
        let count = u32::try_from(particles.len())
            .ok()
            .filter(|_| bytes.len() as u64 <= limit)
            .ok_or_else(|| RenderError::InvalidParameter {
                field: "clouds.volume.billboards",
                value: format!("{} billboards ({} bytes)", particles.len(), bytes.len()),
                reason: "more instance bytes than the device's max_buffer_size",
            })?;
        if count > 0 {
            let fits = self
                .instances
                .as_ref()
                .is_some_and(|b| b.size() >= bytes.len() as u64);
            if !fits {
                self.instances = Some(device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("render billboard instances"),
                    size: bytes.len() as u64,
                    usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }));
            }
            if let Some(buffer) = &self.instances {
                queue.write_buffer(buffer, 0, &bytes);
            }
        }
        self.count = count;
        // The added light's air from the rung's pass (one light added to the sun under
        // a rung without tables), else the CPU's sum over the other lights.
        let rung_added = self.rung_air.as_ref().is_some_and(|r| r.lights.len() == 2)
            && cloud.lights.len() == 2
            && scene.lights().len() == 2;
        let added_air = if rung_added {
            None
        } else {
            other_lights_air(scene, cloud, &particles)?
        };
        self.moonlit = match (rung_added, &added_air) {
            (true, _) => 2,
            (false, Some(_)) => 1,
            (false, None) => 0,
        };
        if let Some(air) = &added_air
            && !air.is_empty()
        {
            let bytes: Vec<u8> = air
                .iter()
                .flat_map(|l| [l[0], l[1], l[2], 0.0])
                .flat_map(f32::to_ne_bytes)
                .collect();
            if self.added_air.size() < bytes.len() as u64 {
                self.added_air = added_air_buffer(device, bytes.len() as u64);
                self.bind_group = self.params_group(device);
            }
            queue.write_buffer(&self.added_air, 0, &bytes);
        }
        // A rung without tables: the particles' offsets for the air passes.
        if let Some(rung_air) = &mut self.rung_air
            && rung_air.prepare(device, queue, &particles)?
        {
            self.bind_group = self.params_group(device);
        }
        let frame = cloudlight::billboard::ScreenFrame::<f32>::new(
            &camera,
            cloud.settings.size,
            cloud.settings.opacity,
        );
        queue.write_buffer(
            &self.uniform,
            0,
            &params_bytes(
                &frame,
                cloud.settings.near as f32,
                scene.present.exposure,
                self.moonlit,
            ),
        );
        Ok(())
    }

    /// The draw's group 2 over the current buffers.
    fn params_group(&self, device: &wgpu::Device) -> wgpu::BindGroup {
        params_bind_group(
            device,
            &self.layout,
            &self.uniform,
            &self.added_air,
            self.rung_air.as_ref().map(RungBillboardAir::airs),
        )
    }

    /// Records one render pass drawing the particles over `target`, depth-tested against
    /// `depth` (read only); under a rung without tables, the particles' air pass first
    /// (compute, untimed), else the precomputed rung's `luts` bound in groups 0 and 1.
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        depth: &wgpu::TextureView,
        luts: Option<&atmos::gpu::AtmosphereLuts>,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), RenderError> {
        let luts = match &self.rung_air {
            Some(air) => {
                if self.count > 0 {
                    air.encode(encoder, self.count, self.moonlit == 2);
                }
                None
            }
            None => Some(luts.ok_or_else(needs_tables)?),
        };
        let mut pass = begin_billboard_pass(
            encoder,
            "render billboard clouds",
            target,
            Some(wgpu::RenderPassDepthStencilAttachment {
                view: depth,
                depth_ops: None,
                stencil_ops: None,
            }),
            timestamp_writes,
        );
        if let (Some(instances), true) = (&self.instances, self.count > 0) {
            if let Some(luts) = luts {
                pass.set_bind_group(0, luts.uniform_bind_group(), &[]);
                pass.set_bind_group(1, luts.table_bind_group(), &[]);
            }
            pass.set_bind_group(2, &self.bind_group, &[]);
            draw_billboards(&mut pass, &self.pipeline, instances, self.count);
        }
        Ok(())
    }
}
