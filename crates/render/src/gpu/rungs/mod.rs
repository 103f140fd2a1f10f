//! The GPU passes of the rungs without tables: SGSky's dome (`dome`: celestial's
//! `SkyDomeRenderer` for the sky, the closed form's passes for terrain and clouds),
//! rung 1, the closed form per pixel
//! (`closed-form`) or per vertex of Hoffman and Preetham's sky dome (`closed-form-vertex`), and rung 2,
//! single scattering (`single`). The precomputed rung keeps `atmos`' tables and sky
//! pass ([`crate::gpu::scene`]); the reference rungs (f64, orders of scattering or Monte
//! Carlo) have no GPU passes and stay on the CPU.
//!
//! Per light (the sun, and the moon on a moonlit night):
//!
//! * **sky**: `atmos`' frame renderer of the rung ([`atmos::gpu::ClosedFormRenderer`]
//!   per pixel or per dome vertex, [`atmos::gpu::SingleScatteringRenderer`]) writes
//!   each pixel's view-ray radiance and transmittance into an
//!   [`atmos::gpu::FrameOutput`] (a compute pass, timed as "sky evaluation"), then a
//!   full-screen triangle (`shaders/render/sky_rung.wgsl`, drawn first, depth writes
//!   off; the moon's added) adds the sun's disc through the transmittance with
//!   `render::present`'s `present_radiance`, as the CPU renderer does for these rungs;
//! * **terrain**: the terrain pass with the rungs' fragment stage
//!   (`shaders/render/terrain_rung.wgsl`: the same `terrain_surface` of
//!   `render::terrain`, lit by the rung's light at the point, seen through the rung's
//!   segment camera → point) and the light and the rung's parameters in bind group 3;
//!   the segment is a compute pass per pixel after the draws
//!   (`shaders/render/rung_air.wgsl`), or per vertex (`[terrain] aerial_perspective =
//!   "per-vertex"`) a compute pass over the drawn tiles' vertices before them, read by
//!   the vertex stage (`crate::gpu::vertex_air`);
//! * **marched clouds' air** (`[clouds.volume]`, `[clouds.shell]`): the light's
//!   `crate::gpu::cloud_air::RungCloudAir` (its camera and the rung's parameters of its
//!   atmosphere), bound by the clouds' air pass where the precomputed rung binds its
//!   tables (`crate::gpu::cloud_air`).
//!
//! Each of these passes' shaders is written once for every rung without tables, against
//! the slot `render::rung_sky` (what a rung provides: its parameters, a segment's air,
//! the light at a terrain point), and composed with the slot bound to the rung's module
//! (`crate::gpu::rung_kind`: `render::rung_closed_form`, `render::rung_single`) rather
//! than switching on an `override` constant: the closed form and single scattering read
//! different uniforms (`ClosedFormSkyParameters`, `AtmosphereParameters`) and the
//! precomputed terrain reads the tables in groups 0 and 1; one shader switching on a
//! constant would bind all of them in every scene (and make a closed-form scene
//! allocate tables it never reads). Each rung's pipeline binds what its rung reads, and
//! the precomputed pipeline is unchanged. The single scattering's sample counts are
//! `override` constants of its module.

mod air;
mod sky;
mod uniforms;

use atmos::gpu::FrameOutput;
use wgpu::util::DeviceExt as _;

use crate::RenderError;
use crate::present::PresentParameters;
use crate::scene::Rung;
use crate::scene::prepare::PreparedScene;

use crate::gpu::rung_kind::{air_constants, compose_rung_entry, rung_parameters};
pub use crate::gpu::rung_kind::{has_rung_passes, no_gpu_passes, volume_needs_tables};

use crate::gpu::layout::{fragment_texture, fragment_uniform};
use air::AirPass;
use sky::{LightPasses, SkyRenderer};
pub use uniforms::{RungAirUniform, RungLightUniform};

/// The sky and terrain passes of a rung without tables (see the module documentation).
#[derive(Debug)]
pub struct RungPasses {
    rung: Rung,
    sky_pipeline: wgpu::RenderPipeline,
    /// The sky of the lights after the sun, added (built when there are any).
    added_sky_pipeline: Option<wgpu::RenderPipeline>,
    terrain_layout: wgpu::BindGroupLayout,
    terrain_module: wgpu::ShaderModule,
    /// Each light's passes, in the scene's lights' order (the sun first).
    lights: Vec<LightPasses>,
    /// The terrain's aerial perspective per pixel; `None` per vertex (`vertex_air`).
    air: Option<AirPass>,
    /// The terrain's aerial perspective per vertex (`crate::gpu::vertex_air`), when asked for.
    vertex_air: Option<crate::gpu::vertex_air::VertexAirPlan>,
}

impl RungPasses {
    /// The passes of `scene`'s rung, or `None` for the precomputed rung (its tables and
    /// sky pass are the scene renderer's own); an error for the reference rungs.
    /// `hdr` and `depth` are the scene's targets' formats. A pipeline the device
    /// rejects is a [`RenderError::Device`] (caught by device error scopes).
    pub fn new(
        device: &wgpu::Device,
        scene: &PreparedScene,
        hdr: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
    ) -> Result<Option<Self>, RenderError> {
        crate::gpu::validation::scoped(device, "RungPasses::new", || {
            Self::new_unscoped(device, scene, hdr, depth)
        })
    }

    fn new_unscoped(
        device: &wgpu::Device,
        scene: &PreparedScene,
        hdr: wgpu::TextureFormat,
        depth: wgpu::TextureFormat,
    ) -> Result<Option<Self>, RenderError> {
        let rung = scene.rung;
        if rung == Rung::Precomputed {
            return Ok(None);
        }
        if !has_rung_passes(rung) {
            return Err(no_gpu_passes(rung));
        }
        let composer = crate::composer();
        let sky_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render sky (rung)"),
            source: wgpu::ShaderSource::Wgsl(composer.compose_module("render::sky_rung")?.into()),
        });
        let terrain_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render::terrain_rung"),
            source: wgpu::ShaderSource::Wgsl(
                compose_rung_entry(rung, "render::terrain_rung")?.into(),
            ),
        });
        let sky_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render sky (rung)"),
            entries: &[
                fragment_uniform(0),
                fragment_uniform(1),
                fragment_texture(2),
                fragment_texture(3),
            ],
        });
        let terrain_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render terrain (rung)"),
            entries: &[
                fragment_uniform(0),
                fragment_uniform(1),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: true },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let sky_pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render sky (rung)"),
            bind_group_layouts: &[Some(&sky_layout)],
            immediate_size: 0,
        });
        let sky_pipeline = |additive: bool| {
            let add = wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::One,
                operation: wgpu::BlendOperation::Add,
            };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(if additive {
                    "render added light's sky (rung)"
                } else {
                    "render sky (rung)"
                }),
                layout: Some(&sky_pipeline_layout),
                vertex: wgpu::VertexState {
                    module: &sky_module,
                    entry_point: Some("rung_sky_vertex"),
                    compilation_options: Default::default(),
                    buffers: &[],
                },
                primitive: wgpu::PrimitiveState::default(),
                depth_stencil: Some(wgpu::DepthStencilState {
                    format: depth,
                    depth_write_enabled: Some(false),
                    depth_compare: Some(wgpu::CompareFunction::Always),
                    stencil: Default::default(),
                    bias: Default::default(),
                }),
                multisample: Default::default(),
                fragment: Some(wgpu::FragmentState {
                    module: &sky_module,
                    entry_point: Some("rung_sky_fragment"),
                    compilation_options: Default::default(),
                    targets: &[Some(wgpu::ColorTargetState {
                        blend: additive.then_some(wgpu::BlendState {
                            color: add,
                            alpha: add,
                        }),
                        ..hdr.into()
                    })],
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let (width, height) = (scene.camera.width, scene.camera.height);
        let light = |atmosphere: &atmos::Atmosphere, label: &str| {
            let renderer = SkyRenderer::new(device, rung, atmosphere)?;
            let output = FrameOutput::new(device, width, height)?;
            let uniform = |what: &str, size: usize| {
                device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some(&format!("render {label} {what}")),
                    size: size as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                })
            };
            let sky_camera = uniform(
                "sky camera",
                std::mem::size_of::<atmos::frame::FrameCamera>(),
            );
            let sky_present = uniform("sky parameters", std::mem::size_of::<PresentParameters>());
            let [radiance, transmittance] = output.bind_group_entries(2);
            let sky_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("render sky (rung)"),
                layout: &sky_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: sky_camera.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: sky_present.as_entire_binding(),
                    },
                    radiance,
                    transmittance,
                ],
            });
            let terrain_light = uniform("terrain light", std::mem::size_of::<RungLightUniform>());
            // The rung's parameters for this light's atmosphere (fixed per renderer, as
            // the atmosphere is).
            let parameters = rung_parameters(rung, atmosphere)?;
            let parameters = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(&format!("render {label} terrain rung parameters")),
                contents: &parameters,
                usage: wgpu::BufferUsages::UNIFORM,
            });
            let light_table = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(&format!("render {label} terrain light table")),
                size: (crate::passes::terrain::lighting::SUN_TABLE_SIZE * 16) as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let terrain_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("render terrain (rung)"),
                layout: &terrain_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: terrain_light.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: parameters.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: light_table.as_entire_binding(),
                    },
                ],
            });
            let cloud_air = crate::gpu::cloud_air::RungCloudAir::new(device, rung, &parameters);
            Ok::<_, RenderError>(LightPasses {
                cloud_air,
                renderer,
                output,
                sky_camera,
                sky_present,
                sky_group,
                terrain_light,
                light_table,
                terrain_group,
            })
        };
        let lights = scene
            .lights()
            .iter()
            .map(|l| light(l.atmosphere, l.name))
            .collect::<Result<Vec<_>, _>>()?;
        let vertex_air = crate::gpu::vertex_air::VertexAirPlan::new(scene)?;
        let air = match vertex_air {
            Some(_) => None,
            None => Some(AirPass::new(device, scene, hdr, &air_constants(rung))?),
        };
        Ok(Some(Self {
            rung,
            sky_pipeline: sky_pipeline(false),
            added_sky_pipeline: (lights.len() > 1).then(|| sky_pipeline(true)),
            terrain_layout,
            terrain_module,
            lights,
            air,
            vertex_air,
        }))
    }

    /// The terrain's aerial perspective per vertex (`crate::gpu::vertex_air`), when the scene
    /// asks for it.
    pub(crate) fn vertex_air(&self) -> Option<&crate::gpu::vertex_air::VertexAirPlan> {
        self.vertex_air.as_ref()
    }

    /// The rung drawn.
    pub fn rung(&self) -> Rung {
        self.rung
    }

    /// How many lights the passes were built for (the sun, and the moon on a moonlit
    /// night: each light's sky added, the terrain drawn once per light).
    pub fn light_count(&self) -> usize {
        self.lights.len()
    }

    /// The air in front of a marched cloud lit by light `index` of the scene's lights
    /// (`None` past the lights the passes were built for).
    pub(crate) fn cloud_air(&self, index: usize) -> Option<crate::gpu::cloud_air::CloudAir<'_>> {
        let light = self.lights.get(index)?;
        Some(crate::gpu::cloud_air::CloudAir::Rung(&light.cloud_air))
    }

    /// The terrain pipeline's rung parts: its shader module (vertex `terrain_vertex`,
    /// fragment [`Self::terrain_fragment`]) and bind group 3's layout.
    pub fn terrain_shader(&self) -> (&wgpu::ShaderModule, &wgpu::BindGroupLayout) {
        (&self.terrain_module, &self.terrain_layout)
    }

    /// The terrain's fragment entry point (`render::terrain_rung`'s, every rung's).
    pub fn terrain_fragment(&self) -> &'static str {
        "terrain_rung_fragment"
    }

    /// Writes the frame's cameras and lights and binds the rung's outputs; the terrain's
    /// aerial perspective reads `hdr_view` and `depth_view` (the scene's targets, the
    /// same every frame) and writes into a texture copied back into the HDR target.
    pub fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        hdr_view: &wgpu::TextureView,
        depth_view: &wgpu::TextureView,
    ) -> Result<(), RenderError> {
        let camera = &scene.camera;
        if let Some(air) = &mut self.air {
            air.prepare(device, queue, scene, hdr_view, depth_view);
        }
        // The terrain's elevations (the CPU renderer's span for its light table).
        let range = scene.terrain.as_ref().map_or([0.0, 0.0], |t| {
            terrain::intersect::HeightfieldTracer::new(&t.heightfield).elevation_range()
        });
        let light_uniform =
            |atmosphere: &atmos::Atmosphere, direction: glam::DVec3| RungLightUniform {
                camera_position: scene.camera_position.as_vec3().to_array(),
                top_radius: atmosphere.top_radius as f32,
                direction: direction.as_vec3().to_array(),
                planet_radius: atmosphere.planet_radius as f32,
                elevation_range: range.map(|e| e as f32),
                padding: [0.0; 2],
            };
        // Single scattering's light is tabulated as the CPU renderer tabulates it (the
        // same function, `light_irradiance_at`, at the same elevations).
        let rung = self.rung;
        let table = |light: &crate::scene::Illuminant<'_>| -> Result<_, RenderError> {
            if rung != Rung::Single || scene.terrain.is_none() {
                return Ok(None);
            }
            let n = crate::passes::terrain::lighting::SUN_TABLE_SIZE;
            (0..n)
                .map(|k| {
                    let elevation = range[0] + (range[1] - range[0]) * k as f64 / (n - 1) as f64;
                    crate::passes::terrain::lighting::light_irradiance_at(scene, light, elevation)
                        .map(|e| [e.x, e.y, e.z, 0.0])
                })
                .collect::<Result<Vec<_>, _>>()
                .map(Some)
        };
        let lights = scene.lights();
        if lights.len() != self.lights.len() {
            return Err(RenderError::InvalidParameter {
                field: "lights",
                value: format!("{} lights", lights.len()),
                reason: "differs from the scene the renderer was built for",
            });
        }
        for (passes, light) in self.lights.iter_mut().zip(&lights) {
            // After the sun no disc: celestial draws the moon (the CPU adds its sky alone).
            let present = if light.index == 0 {
                scene.present
            } else {
                PresentParameters {
                    sun_disc_radiance: [0.0; 3],
                    ..scene.present
                }
            };
            let light_table = table(light)?;
            passes.prepare(
                queue,
                &light.camera(camera),
                &present,
                &light_uniform(light.atmosphere, light.direction),
                light_table.as_deref(),
            )?;
        }
        Ok(())
    }

    /// Records the rung's sky evaluation per light (compute passes, before the scene's
    /// render pass), the sun's timed as "sky evaluation", the others as "moonlit sky
    /// evaluation".
    pub fn encode_sky_evaluation(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&crate::gpu::timer::PassTimes>,
    ) -> Result<(), RenderError> {
        for (index, light) in self.lights.iter().enumerate() {
            let label = evaluation_label(index);
            light
                .renderer
                .encode(encoder, times.and_then(|t| t.compute_writes(label)))?;
        }
        Ok(())
    }

    /// Records the terrain's aerial perspective (after the terrain's draws, timed as
    /// "terrain aerial perspective") and copies its result into `hdr`.
    pub fn encode_air(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        hdr: &wgpu::Texture,
        times: Option<&crate::gpu::timer::PassTimes>,
    ) -> Result<(), RenderError> {
        // Per vertex, the terrain's draws applied it (`crate::gpu::vertex_air`).
        let Some(air) = &self.air else {
            return Ok(());
        };
        let targets = air.targets.as_ref().ok_or(RenderError::NotPrepared)?;
        let size = air.scratch.size();
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render terrain air (rung)"),
                timestamp_writes: times
                    .and_then(|t| t.compute_writes("terrain aerial perspective")),
            });
            pass.set_pipeline(&air.pipeline);
            pass.set_bind_group(0, targets, &[]);
            pass.set_bind_group(1, &air.parameters, &[]);
            pass.dispatch_workgroups(size.width.div_ceil(8), size.height.div_ceil(8), 1);
        }
        encoder.copy_texture_to_texture(air.scratch.as_image_copy(), hdr.as_image_copy(), size);
        Ok(())
    }

    /// Draws the sky (and each other light's sky, added) into the scene's render pass.
    pub fn draw_sky(&self, pass: &mut wgpu::RenderPass<'_>) {
        for (index, light) in self.lights.iter().enumerate() {
            let pipeline = match (index, &self.added_sky_pipeline) {
                (0, _) => &self.sky_pipeline,
                (_, Some(added)) => added,
                (_, None) => continue,
            };
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &light.sky_group, &[]);
            pass.draw(0..3, 0..1);
        }
    }

    /// Binds group 3 of a terrain draw: light `index`'s (the sun's past the lights built).
    pub fn bind_terrain(&self, pass: &mut wgpu::RenderPass<'_>, index: usize) {
        let light = self.lights.get(index).unwrap_or(&self.lights[0]);
        pass.set_bind_group(3, &light.terrain_group, &[]);
    }

    /// The timestamp spans of the rung's passes.
    pub fn timestamp_labels(&self, terrain: bool) -> Vec<&'static str> {
        let mut labels: Vec<&'static str> = (0..self.lights.len()).map(evaluation_label).collect();
        labels.dedup();
        if terrain {
            labels.push("terrain aerial perspective");
        }
        labels
    }
}

/// The timestamp span of light `index`'s sky evaluation: "sky evaluation" for the sun,
/// "moonlit sky evaluation" for the lights added to it (`explain`'s plan line; a third
/// light's pass would write the same span).
pub(crate) fn evaluation_label(index: usize) -> &'static str {
    if index == 0 {
        "sky evaluation"
    } else {
        "moonlit sky evaluation"
    }
}
