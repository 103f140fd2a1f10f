//! The GPU passes a marched cloud shares, whichever march it is (the volume's
//! `cloudlight::gpu::MarchPass`, the shell's `cloudlight::gpu::MarchShellPass`): the
//! terrain's depth as a distance per pixel ([`CloudDistance`],
//! `shaders/render/volume_distance.wgsl`: once a frame, for every cloud of the scene),
//! the air in front of the cloud per pixel and light (`shaders/render/volume_air.wgsl`:
//! atmos' `aerial_perspective`, the CPU's function) and the composite render pass
//! (`shaders/render/volume_clouds.wgsl`). Each cloud supplies only its march, prepared
//! per frame up to the distance buffer. A scene with both the shell and the volume cloud
//! records only their marches and air here ([`CloudComposite::encode_marches`]) and
//! composites the two by depth in one pass (`super::cloud_order`).

use crate::gpu::layout::{buffer_entry, compute_pipeline, depth_entry};
use crate::light::LightIndex;
use cloudlight::gpu::TemporalMarch;
use cloudlight::march::Lighting;

/// A march whose image the composite reads (one `MarchResult` of 32 bytes per pixel).
pub(crate) trait CloudMarch {
    /// The march's output (after its `prepare`).
    fn image(&self) -> Option<&wgpu::Buffer>;
    /// Records the march, a pass of its own (a render pass on the fragment stage, a
    /// compute pass on the compute fallback: `cloudlight::gpu::MarchStage`).
    fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), crate::RenderError>;
    /// Marches, from the next prepare, only the pixels `temporal`'s reprojection leaves
    /// it (its phase for a `size` image), or every pixel without it.
    fn set_phase(&mut self, temporal: Option<&TemporalMarch>, size: [u32; 2]);
    /// After the march's prepare: binds it to `temporal`'s history.
    fn prepare_temporal(
        &self,
        temporal: &mut TemporalMarch,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<(), crate::RenderError>;
    /// Records the reprojection, the march and the history's update.
    fn encode_temporal(
        &self,
        temporal: &TemporalMarch,
        encoder: &mut wgpu::CommandEncoder,
        timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    ) -> Result<(), crate::RenderError>;
}

/// `CloudMarch` for a cloudlight march pass (its `image_buffer` and `encode_timed`).
macro_rules! cloud_march {
    ($pass:ty) => {
        impl CloudMarch for $pass {
            fn image(&self) -> Option<&wgpu::Buffer> {
                self.image_buffer()
            }
            fn encode(
                &self,
                encoder: &mut wgpu::CommandEncoder,
                timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
            ) -> Result<(), crate::RenderError> {
                Ok(self.encode_timed(encoder, timestamp_writes)?)
            }
            fn set_phase(&mut self, temporal: Option<&TemporalMarch>, size: [u32; 2]) {
                <$pass>::set_phase(self, temporal.and_then(|t| t.phase(size)));
            }
            fn prepare_temporal(
                &self,
                temporal: &mut TemporalMarch,
                device: &wgpu::Device,
                queue: &wgpu::Queue,
            ) -> Result<(), crate::RenderError> {
                Ok(temporal.prepare(device, queue, self)?)
            }
            fn encode_temporal(
                &self,
                temporal: &TemporalMarch,
                encoder: &mut wgpu::CommandEncoder,
                timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
            ) -> Result<(), crate::RenderError> {
                Ok(temporal.encode(encoder, self, timestamp_writes)?)
            }
        }
    };
}
cloud_march!(cloudlight::gpu::MarchPass);
cloud_march!(cloudlight::gpu::MarchShellPass);

/// One light's march and air pass.
#[derive(Debug)]
struct LitMarch<M> {
    march: M,
    /// `shaders/render/volume_air.wgsl` with this light's tables' layouts.
    air_pipeline: wgpu::ComputePipeline,
    /// The air per pixel and its bind group (after `prepare`; kept across frames of one
    /// size).
    air: Option<(wgpu::Buffer, wgpu::BindGroup)>,
    /// The other cloud's shadow map for this light on the GPU (`crate::mutual_shadow`;
    /// kept across prepares while its values are unchanged).
    shadow: crate::mutual_shadow::ShadowValues,
    /// The march amortised over frames ([`CloudComposite::amortise`]), if it is.
    temporal: Option<TemporalMarch>,
}

/// The timestamp writes of one cloud's passes (each `None` when untimed).
pub(crate) struct CloudTimes<'a> {
    /// Each light's march, in the scene's lights' order (a render pass's writes: the
    /// march's `encode_timed`).
    pub marches: Vec<Option<wgpu::RenderPassTimestampWrites<'a>>>,
    /// The composite render pass.
    pub composite: Option<wgpu::RenderPassTimestampWrites<'a>>,
}

/// The distance, air and composite passes over a cloud's marches (module docs).
#[derive(Debug)]
pub(crate) struct CloudComposite<M> {
    /// "volume" or "shell": the passes' labels ("render volume air", ...).
    name: &'static str,
    /// The scene's section, named when the scene's lights differ from the built ones.
    field: &'static str,
    /// Each light's march, the sun's first (the composite reads the first two).
    lights: Vec<LitMarch<M>>,
    /// The air passes' dispatch size (after `prepare`).
    groups: Option<[u32; 2]>,
    air_layout: wgpu::BindGroupLayout,
    air_uniform: wgpu::Buffer,
    pipeline: wgpu::RenderPipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    bind_group: Option<wgpu::BindGroup>,
}

/// A render pipeline drawing one full-screen triangle (no vertex buffers, no depth)
/// into one `format` target with `blend`: `module`'s `[vertex, fragment]` entry points
/// over bind group 0 of `layout` (the marched clouds' composite, the cloud layers).
pub(crate) fn fullscreen_pipeline(
    device: &wgpu::Device,
    label: &str,
    layout: &wgpu::BindGroupLayout,
    module: &wgpu::ShaderModule,
    [vertex, fragment]: [&str; 2],
    format: wgpu::TextureFormat,
    blend: wgpu::BlendState,
) -> wgpu::RenderPipeline {
    let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some(label),
        bind_group_layouts: &[Some(layout)],
        immediate_size: 0,
    });
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(label),
        layout: Some(&pipeline_layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vertex),
            compilation_options: Default::default(),
            buffers: &[],
        },
        primitive: wgpu::PrimitiveState::default(),
        depth_stencil: None,
        multisample: Default::default(),
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fragment),
            compilation_options: Default::default(),
            targets: &[Some(wgpu::ColorTargetState {
                format,
                blend: Some(blend),
                write_mask: wgpu::ColorWrites::ALL,
            })],
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Records a render pass over `target` (kept, not cleared; no depth) drawing
/// [`fullscreen_pipeline`]'s triangle with `bind_group` at group 0.
pub(crate) fn draw_fullscreen(
    encoder: &mut wgpu::CommandEncoder,
    label: &str,
    target: &wgpu::TextureView,
    timestamp_writes: Option<wgpu::RenderPassTimestampWrites<'_>>,
    pipeline: &wgpu::RenderPipeline,
    bind_group: &wgpu::BindGroup,
) {
    let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some(label),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view: target,
            depth_slice: None,
            resolve_target: None,
            ops: wgpu::Operations {
                load: wgpu::LoadOp::Load,
                store: wgpu::StoreOp::Store,
            },
        })],
        depth_stencil_attachment: None,
        timestamp_writes,
        ..Default::default()
    });
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    pass.draw(0..3, 0..1);
}

fn entry(binding: u32, resource: wgpu::BindingResource<'_>) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry { binding, resource }
}

impl<M: CloudMarch> CloudComposite<M> {
    /// Amortises each light's march over frames (`cloudlight::gpu::TemporalMarch`:
    /// a quarter of the pixels marched a frame, the rest reprojected from the last
    /// frame), for a renderer that draws a sequence of frames, such as a viewer.
    pub(crate) fn amortise(&mut self, device: &wgpu::Device) -> Result<(), crate::RenderError> {
        for lit in &mut self.lights {
            lit.temporal = Some(TemporalMarch::new(device)?);
        }
        Ok(())
    }

    /// The air and composite pipelines and the marches `march` builds, one per light of
    /// `airs` (each light's air: its tables or its rung's passes, the sun's first),
    /// each light's layouts in its air pass's groups 0 and 1. `name` labels the passes,
    /// `field` is the scene section named in `prepare`'s errors. The composite adds the
    /// first two lights' marches (WGSL `VolumeComposite::moonlit`): more is an error
    /// naming `field`.
    pub(crate) fn new(
        device: &wgpu::Device,
        name: &'static str,
        field: &'static str,
        airs: &[super::cloud_air::CloudAir<'_>],
        target: wgpu::TextureFormat,
        march: impl Fn() -> Result<M, crate::RenderError>,
    ) -> Result<Self, crate::RenderError> {
        if airs.is_empty() || airs.len() > crate::gpu::frame::MAX_LIGHTS {
            return Err(crate::RenderError::InvalidParameter {
                field,
                value: format!("lit by {} lights", airs.len()),
                reason: "the GPU composite adds the marches of one to two lights",
            });
        }
        use wgpu::BufferBindingType::{Storage, Uniform};
        let compute = wgpu::ShaderStages::COMPUTE;
        let module =
            |module: &str, label: &str| -> Result<wgpu::ShaderModule, crate::RenderError> {
                let source = crate::composer().compose_module(module)?;
                Ok(device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(label),
                    source: wgpu::ShaderSource::Wgsl(source.into()),
                }))
            };
        let uniform_buffer = |label: &str, size: usize| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: size as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            })
        };
        // The air per pixel: groups 0 and 1 are the light's tables (or, for a rung
        // without tables, its camera and parameters: `super::cloud_air`).
        let air_label = format!("render {name} air");
        let air_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&air_label),
            entries: &[
                buffer_entry(0, compute, Uniform),
                buffer_entry(1, compute, Storage { read_only: true }),
                buffer_entry(2, compute, Storage { read_only: false }),
            ],
        });
        let air_uniform = uniform_buffer(
            &format!("{air_label} uniform"),
            std::mem::size_of::<VolumeAirParams>(),
        );
        let lit = |luts: super::cloud_air::CloudAir<'_>,
                   label: &str|
         -> Result<LitMarch<M>, crate::RenderError> {
            Ok(LitMarch {
                march: march()?,
                air_pipeline: luts.pipeline(device, label, &air_layout)?,
                air: None,
                shadow: Default::default(),
                temporal: None,
            })
        };
        let lights = airs
            .iter()
            .enumerate()
            .map(|(index, air)| match index {
                0 => lit(*air, &air_label),
                _ => lit(*air, &format!("{air_label} (light {index})")),
            })
            .collect::<Result<Vec<_>, _>>()?;
        let label = format!("render {name} clouds");
        let composite_module = module("render::volume_clouds", &label)?;
        let fragment = wgpu::ShaderStages::FRAGMENT;
        let read = Storage { read_only: true };
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(&label),
            entries: &[
                buffer_entry(0, fragment, Uniform),
                buffer_entry(1, fragment, read),
                depth_entry(2, fragment),
                buffer_entry(3, fragment, read),
                buffer_entry(4, fragment, read),
                buffer_entry(5, fragment, read),
            ],
        });
        let uniform = uniform_buffer(
            &format!("{label} uniform"),
            std::mem::size_of::<VolumeComposite>(),
        );
        let blend = over_transmittance_blend();
        let pipeline = fullscreen_pipeline(
            device,
            &label,
            &layout,
            &composite_module,
            ["volume_clouds_vertex", "volume_clouds_fragment"],
            target,
            blend,
        );
        Ok(Self {
            name,
            field,
            lights,
            groups: None,
            air_layout,
            air_uniform,
            pipeline,
            layout,
            uniform,
            bind_group: None,
        })
    }

    /// The frame's air and composite uniforms and bind groups, and the marches prepared
    /// by `prepare_march` (each march with the index of its light and the cloud's
    /// lighting for it, one of `lightings`, the cloud's per light in the scene's order;
    /// `distance`'s buffer it stops at: the terrain cuts the cloud where it stands,
    /// `distance` prepared this frame; and that light's kept upload of the other cloud's
    /// shadow map, `crate::mutual_shadow::ShadowValues`).
    #[allow(clippy::too_many_arguments)] // the frame's resources and the lights
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        distance: &CloudDistance,
        depth_view: &wgpu::TextureView,
        lightings: &[&Lighting<f32>],
        mut prepare_march: impl FnMut(
            &mut M,
            LightIndex,
            &Lighting<f32>,
            &wgpu::Buffer,
            &mut crate::mutual_shadow::ShadowValues,
        ) -> Result<(), crate::RenderError>,
    ) -> Result<(), crate::RenderError> {
        let name = self.name;
        if self.lights.len() != lightings.len() {
            return Err(crate::RenderError::InvalidParameter {
                field: self.field,
                value: format!("lit by {} lights", lightings.len()),
                reason: "differs from the scene the renderer was built for",
            });
        }
        let camera = &scene.camera;
        let near = scene.near.max(0.01) as f32;
        queue.write_buffer(
            &self.air_uniform,
            0,
            bytemuck::bytes_of(&VolumeAirParams {
                width: camera.width,
                height: camera.height,
                padding: [0; 2],
            }),
        );
        queue.write_buffer(
            &self.uniform,
            0,
            bytemuck::bytes_of(&VolumeComposite {
                camera: *camera,
                near,
                radiance_scale: scene.present.exposure,
                width: camera.width,
                moonlit: u32::from(self.lights.len() > 1),
            }),
        );
        // The air buffers follow the image: kept across frames of one size.
        let pixels = u64::from(camera.width) * u64::from(camera.height);
        let storage = |label: &str, bytes: u64, kept: Option<wgpu::Buffer>| match kept {
            Some(buffer) if buffer.size() == bytes => buffer,
            _ => device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }),
        };
        let (distances, _, groups) = distance
            .distance
            .as_ref()
            .ok_or(crate::RenderError::NotPrepared)?;
        let air_label = format!("render {name} air");
        let size = [camera.width, camera.height];
        for (light, (lit, lighting)) in self.lights.iter_mut().zip(lightings).enumerate() {
            lit.march.set_phase(lit.temporal.as_ref(), size);
            prepare_march(&mut lit.march, light, lighting, distances, &mut lit.shadow)?;
            if let Some(temporal) = &mut lit.temporal {
                lit.march.prepare_temporal(temporal, device, queue)?;
            }
            let image = lit.march.image().ok_or(crate::RenderError::NotPrepared)?;
            let air = storage(
                &air_label,
                pixels * 32,
                lit.air.take().map(|(buffer, _)| buffer),
            );
            let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some(&air_label),
                layout: &self.air_layout,
                entries: &[
                    entry(0, self.air_uniform.as_entire_binding()),
                    entry(1, image.as_entire_binding()),
                    entry(2, air.as_entire_binding()),
                ],
            });
            lit.air = Some((air, group));
        }
        // With one light the second light's bindings hold its buffers (unread: moonlit = 0).
        let [image, air, moon_image, moon_air] = self.seen_buffers()?;
        self.bind_group = Some(device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some(&format!("render {name} clouds")),
            layout: &self.layout,
            entries: &[
                entry(0, self.uniform.as_entire_binding()),
                entry(1, image.as_entire_binding()),
                entry(2, wgpu::BindingResource::TextureView(depth_view)),
                entry(3, air.as_entire_binding()),
                entry(4, moon_image.as_entire_binding()),
                entry(5, moon_air.as_entire_binding()),
            ],
        }));
        self.groups = Some(*groups);
        Ok(())
    }

    /// Records the marches (after [`CloudDistance::encode`]), the air passes with each
    /// light's `airs`, each a compute pass of its own, then the composite (one
    /// full-screen triangle) over `target`.
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        target: &wgpu::TextureView,
        airs: &[super::cloud_air::CloudAir<'_>],
        times: CloudTimes<'_>,
    ) -> Result<(), crate::RenderError> {
        let bind_group = self
            .bind_group
            .as_ref()
            .ok_or(crate::RenderError::NotPrepared)?;
        self.encode_marches(encoder, airs, times.marches)?;
        draw_fullscreen(
            encoder,
            &format!("render {} clouds", self.name),
            target,
            times.composite,
            &self.pipeline,
            bind_group,
        );
        Ok(())
    }

    /// How many lights the cloud was built lit by (a march and an air pass each).
    pub(crate) fn light_count(&self) -> usize {
        self.lights.len()
    }

    /// The buffers a composite reads (after `prepare`): the sun's march and its air,
    /// then the second light's march and its air (the sun's again with one light).
    pub(crate) fn seen_buffers(&self) -> Result<[&wgpu::Buffer; 4], crate::RenderError> {
        fn buffers<M: CloudMarch>(
            lit: &LitMarch<M>,
        ) -> Result<(&wgpu::Buffer, &wgpu::Buffer), crate::RenderError> {
            let image = lit.march.image().ok_or(crate::RenderError::NotPrepared)?;
            let (air, _) = lit.air.as_ref().ok_or(crate::RenderError::NotPrepared)?;
            Ok((image, air))
        }
        let sun = self.lights.first().ok_or(crate::RenderError::NotPrepared)?;
        let (image, air) = buffers(sun)?;
        let (moon_image, moon_air) = buffers(self.lights.get(1).unwrap_or(sun))?;
        Ok([image, air, moon_image, moon_air])
    }

    /// Records each light's march (after [`CloudDistance::encode`]; `marches`: their
    /// timestamp writes, the lights' order; each a pass of its own) and the air passes
    /// with each light's `airs`, each a compute pass of its own: what a composite reads.
    pub(crate) fn encode_marches(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        airs: &[super::cloud_air::CloudAir<'_>],
        marches: Vec<Option<wgpu::RenderPassTimestampWrites<'_>>>,
    ) -> Result<(), crate::RenderError> {
        let name = self.name;
        let groups = self.groups.ok_or(crate::RenderError::NotPrepared)?;
        if airs.len() < self.lights.len() {
            return Err(crate::RenderError::NotPrepared);
        }
        let mut marches = marches.into_iter();
        for lit in &self.lights {
            match &lit.temporal {
                Some(temporal) => {
                    lit.march
                        .encode_temporal(temporal, encoder, marches.next().flatten())?
                }
                None => lit.march.encode(encoder, marches.next().flatten())?,
            }
        }
        let air_label = format!("render {name} air");
        for (lit, tables) in self.lights.iter().zip(airs.iter().copied()) {
            let (_, air_group) = lit.air.as_ref().ok_or(crate::RenderError::NotPrepared)?;
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some(&air_label),
                timestamp_writes: None,
            });
            pass.set_pipeline(&lit.air_pipeline);
            tables.bind(&mut pass);
            pass.set_bind_group(2, air_group, &[]);
            pass.dispatch_workgroups(groups[0], groups[1], 1);
        }
        Ok(())
    }
}

/// The terrain's depth as a distance per pixel (`shaders/render/volume_distance.wgsl`):
/// the buffer every marched cloud of the scene stops at, computed once a frame for all.
#[derive(Debug)]
pub(crate) struct CloudDistance {
    pipeline: wgpu::ComputePipeline,
    layout: wgpu::BindGroupLayout,
    uniform: wgpu::Buffer,
    /// The distance buffer, its bind group and the dispatch size (after `prepare`).
    distance: Option<(wgpu::Buffer, wgpu::BindGroup, [u32; 2])>,
}

impl CloudDistance {
    /// The distance pipeline and its uniform.
    pub(crate) fn new(device: &wgpu::Device) -> Result<Self, crate::RenderError> {
        use wgpu::BufferBindingType::{Storage, Uniform};
        let compute = wgpu::ShaderStages::COMPUTE;
        let label = "render cloud distance";
        let source = crate::composer().compose_module("render::volume_distance")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(label),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some(label),
            entries: &[
                buffer_entry(0, compute, Uniform),
                depth_entry(1, compute),
                buffer_entry(2, compute, Storage { read_only: false }),
            ],
        });
        let pipeline = compute_pipeline(
            device,
            label,
            &module,
            "volume_distance_main",
            &[Some(&layout)],
        );
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render cloud distance uniform"),
            size: std::mem::size_of::<VolumeDistanceParams>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        Ok(Self {
            pipeline,
            layout,
            uniform,
            distance: None,
        })
    }

    /// The frame's uniform, buffer (kept across frames of one size) and bind group over
    /// the terrain's `depth_view`.
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &crate::scene::PreparedScene,
        depth_view: &wgpu::TextureView,
    ) {
        let camera = &scene.camera;
        queue.write_buffer(
            &self.uniform,
            0,
            bytemuck::bytes_of(&VolumeDistanceParams {
                camera: *camera,
                near: scene.near.max(0.01) as f32,
                width: camera.width,
                height: camera.height,
                padding0: 0,
            }),
        );
        let bytes = u64::from(camera.width) * u64::from(camera.height) * 4;
        let distances = match self.distance.take() {
            Some((buffer, _, _)) if buffer.size() == bytes => buffer,
            _ => device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("render cloud distances"),
                size: bytes,
                usage: wgpu::BufferUsages::STORAGE,
                mapped_at_creation: false,
            }),
        };
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render cloud distance"),
            layout: &self.layout,
            entries: &[
                entry(0, self.uniform.as_entire_binding()),
                entry(1, wgpu::BindingResource::TextureView(depth_view)),
                entry(2, distances.as_entire_binding()),
            ],
        });
        self.distance = Some((
            distances,
            group,
            [camera.width.div_ceil(8), camera.height.div_ceil(8)],
        ));
    }

    /// Records the distance pass (after the terrain has written the depth, before the
    /// clouds' marches), a compute pass of its own.
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
    ) -> Result<(), crate::RenderError> {
        let (_, group, groups) = self
            .distance
            .as_ref()
            .ok_or(crate::RenderError::NotPrepared)?;
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("render cloud distance"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(groups[0], groups[1], 1);
        Ok(())
    }
}

/// `dst · T + src`: a cloud's own light (premultiplied, rgb) over what is behind it,
/// whose transmittance `T` is the fragment's alpha; the target's alpha is kept.
pub(crate) fn over_transmittance_blend() -> wgpu::BlendState {
    wgpu::BlendState {
        color: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::SrcAlpha,
            operation: wgpu::BlendOperation::Add,
        },
        alpha: wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::Zero,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        },
    }
}

/// The composite pass's uniform (layout identical to WGSL `VolumeComposite`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeComposite {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Multiplies the cloud's own light (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
    /// The march image's width (pixels).
    pub width: u32,
    /// 1: the moonlit march is added (night), 0: the sun's only.
    pub moonlit: u32,
}

/// The uniform of the distance pass (layout identical to WGSL `VolumeDistanceParams` in
/// `shaders/render/volume_distance.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeDistanceParams {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Keeps the struct a multiple of 16 bytes.
    pub padding0: u32,
}

/// The uniform of the cloud air passes (layout identical to WGSL `CloudAirParams` in
/// `shaders/render/cloud_air_io.wgsl`, group 2 of every cloud air pass).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeAirParams {
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Keeps the struct 16 bytes.
    pub padding: [u32; 2],
}
