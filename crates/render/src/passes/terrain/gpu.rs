//! The terrain pass on the GPU: one draw of the tiles per light of the frame (the first
//! writes the depth; each next one adds its light, depth-equal), their uniforms and
//! buffers, the deck's shadow bake before them and a rung's aerial perspective around
//! them.

use atmos::gpu::AtmosphereLuts;
use glam::Vec3;
use wgpu::util::DeviceExt as _;

use super::lighting::{TerrainLighting, terrain_lighting_for};
use super::uniforms::TerrainUniform;
use crate::RenderError;
use crate::gpu::frame::{DEPTH, GpuPass, GpuShared, HDR};
use crate::gpu::layout::{storage_read, uniform_entry};
use crate::gpu::timer::PassTimes;
use crate::scene::Illuminant;
use crate::scene::prepare::{HorizonMaps, PreparedScene, PreparedTerrain};
use crate::terrain_mesh::{TerrainLod, Tile, tile_mesh};

/// Builds the terrain pass of `scene` (which has a terrain).
pub(crate) fn build(
    shared: &GpuShared,
    scene: &PreparedScene,
) -> Result<Box<dyn GpuPass>, RenderError> {
    let terrain = scene.terrain.as_ref().ok_or(RenderError::NotPrepared)?;
    Ok(Box::new(new_terrain_pass(
        &shared.device,
        &shared.tables,
        shared.rung.as_ref(),
        terrain,
        scene.cloud_layers.len(),
        [
            scene.volume_cloud.is_some() || scene.billboard_cloud.is_some(),
            scene.shell_cloud.is_some(),
        ],
    )?))
}

/// The terrain's GPU resources.
#[derive(Debug)]
pub(crate) struct TerrainPass {
    /// One draw per light, the sun's first (on a moonlit night the moon's after it).
    draws: Vec<LightDraw>,
    grid: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    tiles: wgpu::Buffer,
    tile_capacity: usize,
    tile_count: u32,
    lod: TerrainLod,
    cloud_layer_capacity: usize,
    /// The marched clouds' shadow map values (`super::cloud_shadow`; every light's
    /// draw reads them through its own parameters), and which clouds have room (the
    /// volume, the shell).
    volume_shadow_values: wgpu::Buffer,
    shadow_clouds: [bool; 2],
    /// The shell deck's shadow map baked on the GPU (`super::shell_shadow`).
    shell_shadow: Option<super::shell_shadow::ShellShadowGpu>,
    /// The aerial perspective per vertex of a rung without tables (`super::vertex_air`).
    vertex_air: Option<crate::gpu::vertex_air::VertexAir>,
}

/// One light's draw of the terrain: the pipeline (the first light's writes the depth,
/// the others add their light where the depth is equal: the same vertices give the same
/// depths), the light's uniform, its cloud layers (their shadows toward it) and the
/// marched clouds' shadow map parameters toward it.
#[derive(Debug)]
struct LightDraw {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    cloud_layers: wgpu::Buffer,
    volume_shadow: wgpu::Buffer,
}

fn new_terrain_pass(
    device: &wgpu::Device,
    tables: &[AtmosphereLuts],

    rung: Option<&crate::gpu::rungs::RungPasses>,
    terrain: &PreparedTerrain,
    cloud_layer_capacity: usize,
    shadow_clouds: [bool; 2],
) -> Result<TerrainPass, RenderError> {
    // The cloud layers whose shadows fall on the terrain (one unused element when
    // the scene has none: a binding may not be empty).
    let layers_buffer = |label| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: (cloud_layer_capacity.max(1)
                * std::mem::size_of::<celestial::clouds::CloudLayerUniforms>())
                as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    };
    let hf = &terrain.heightfield;
    let texels = hf.width() * hf.height();
    let heights: Vec<f32> = hf.elevations().iter().map(|&e| e as f32).collect();
    let normals: Vec<[f32; 4]> = terrain
        .normals
        .normals()
        .iter()
        .map(|n| [n[0], n[1], n[2], 0.0])
        .collect();
    let horizons: Vec<f32> = match &terrain.horizon {
        HorizonMaps::EastWest(maps) => maps
            .east
            .angles()
            .iter()
            .chain(maps.west.angles())
            .copied()
            .collect(),
        HorizonMaps::Azimuths(maps) => maps
            .layers()
            .iter()
            .flat_map(|layer| layer.angles().iter().copied())
            .collect(),
    };
    let limit = device.limits().max_storage_buffer_binding_size;
    let bytes = (horizons.len().max(4 * texels) * 4) as u64;
    if bytes > limit {
        return Err(RenderError::InvalidParameter {
            field: "terrain",
            value: format!("{}×{} texels", hf.width(), hf.height()),
            reason: "its horizon maps exceed the device's storage-buffer binding size",
        });
    }
    let storage = |label: &str, contents: &[u8]| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents,
            usage: wgpu::BufferUsages::STORAGE,
        })
    };
    // `[terrain.colour]`'s linear texels (one unused element without a texture: a
    // binding may not be empty).
    let colour_texels: &[[f32; 4]] = match &terrain.colour {
        Some(colour) => &colour.texels,
        None => &[[0.0; 4]],
    };
    if std::mem::size_of_val(colour_texels) as u64 > limit {
        let size = terrain.colour.as_ref().map_or([1, 1], |c| c.size);
        return Err(RenderError::InvalidParameter {
            field: "terrain.colour.path",
            value: format!("{}×{} pixels", size[0], size[1]),
            reason: "the colour texture exceeds the device's storage-buffer binding size",
        });
    }
    let colour_texels = storage(
        "render terrain colour texels",
        bytemuck::cast_slice(colour_texels),
    );
    let heights = storage("render terrain heights", bytemuck::cast_slice(&heights));
    let normals = storage("render terrain normals", bytemuck::cast_slice(&normals));
    let horizons = storage("render terrain horizons", bytemuck::cast_slice(&horizons));
    let uniform_buffer = |label| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: std::mem::size_of::<TerrainUniform>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    };
    // The clouds' shadow maps: the largest map's size for each marched cloud of the
    // scene (the map's extent follows the sun), one unused element without one.
    let shadow_texels = super::cloud_shadow::capacity(shadow_clouds);
    let volume_shadow_values = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("render terrain volume shadow map"),
        size: (shadow_texels * 4) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    let shadow_uniform = |label| {
        device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some(label),
            contents: bytemuck::bytes_of(&super::cloud_shadow::NONE),
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        })
    };
    // Compute: the per-vertex aerial perspective of a rung without tables reads the
    // uniform and the heights (`super::vertex_air`).
    let stages = wgpu::ShaderStages::VERTEX_FRAGMENT | wgpu::ShaderStages::COMPUTE;
    let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("render terrain"),
        entries: &[
            uniform_entry(0, stages),
            storage_read(1, wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::COMPUTE),
            storage_read(2, wgpu::ShaderStages::FRAGMENT),
            storage_read(3, wgpu::ShaderStages::FRAGMENT),
            storage_read(4, wgpu::ShaderStages::FRAGMENT),
            uniform_entry(5, wgpu::ShaderStages::FRAGMENT),
            storage_read(6, wgpu::ShaderStages::FRAGMENT),
            storage_read(7, wgpu::ShaderStages::FRAGMENT),
        ],
    });
    let bind_group_with =
        |uniform: &wgpu::Buffer, cloud_layers: &wgpu::Buffer, volume_shadow: &wgpu::Buffer| {
            device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("render terrain"),
                layout: &layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: uniform.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: heights.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 2,
                        resource: normals.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 3,
                        resource: horizons.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 4,
                        resource: cloud_layers.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 5,
                        resource: volume_shadow.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 6,
                        resource: volume_shadow_values.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 7,
                        resource: colour_texels.as_entire_binding(),
                    },
                ],
            })
        };
    // `[terrain] aerial_perspective`: render::terrain per pixel, or its per-vertex
    // entry points (render::aerial_vertex).
    let (shader, vertex_entry, fragment_entry) =
        crate::aerial_vertex::terrain_shader(terrain.aerial_perspective);
    // A rung without tables: its own fragment stage and group 3, the tables' groups
    // unbound (`super::rungs`; its aerial perspective per pixel in a compute pass
    // over the frame, or per vertex as below).
    let (vertex_entry, fragment_entry) = match rung {
        Some(rung) => ("terrain_vertex", rung.terrain_fragment()),
        None => (vertex_entry, fragment_entry),
    };
    // Per vertex with a rung without tables: the segments from a compute pass over
    // the tiles' vertices, bound in group 0 (`super::vertex_air`).
    let vertex_air = match rung.and_then(|r| r.vertex_air()) {
        Some(plan) => Some(crate::gpu::vertex_air::VertexAir::new(
            device, plan, &layout,
        )?),
        None => None,
    };
    let (vertex_entry, fragment_entry) = match &vertex_air {
        Some(air) => (air.draw_shader().2, air.draw_shader().3),
        None => (vertex_entry, fragment_entry),
    };
    let module = match (rung, &vertex_air) {
        (Some(_), Some(air)) => air.draw_shader().1.clone(),
        (Some(rung), None) => rung.terrain_shader().0.clone(),
        (None, _) => {
            let source = crate::composer().compose_module(shader)?;
            device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("render terrain"),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            })
        }
    };
    // `added`: a light's additive, depth-equal draw over the first light's (the same
    // vertices give the same depths: the clip position is invariant).
    let make_pipeline = |luts: Option<&AtmosphereLuts>, added: bool| {
        let mut groups = vec![
            luts.map(|l| &l.layouts().uniforms)
                .or(vertex_air.as_ref().map(|air| air.draw_shader().0)),
            luts.map(|l| &l.layouts().tables),
            Some(&layout),
        ];
        if let Some(rung) = rung {
            groups.push(Some(rung.terrain_shader().1));
        }
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render terrain"),
            bind_group_layouts: &groups,
            immediate_size: 0,
        });
        let additive = wgpu::BlendComponent {
            src_factor: wgpu::BlendFactor::One,
            dst_factor: wgpu::BlendFactor::One,
            operation: wgpu::BlendOperation::Add,
        };
        let target = wgpu::ColorTargetState {
            blend: added.then_some(wgpu::BlendState {
                color: additive,
                alpha: additive,
            }),
            ..HDR.into()
        };
        device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some(if added {
                "render terrain (added light)"
            } else {
                "render terrain"
            }),
            layout: Some(&pipeline_layout),
            vertex: wgpu::VertexState {
                module: &module,
                entry_point: Some(vertex_entry),
                compilation_options: Default::default(),
                buffers: &[
                    Some(wgpu::VertexBufferLayout {
                        array_stride: 16,
                        step_mode: wgpu::VertexStepMode::Vertex,
                        attributes: &wgpu::vertex_attr_array![0 => Uint32x4],
                    }),
                    Some(wgpu::VertexBufferLayout {
                        array_stride: std::mem::size_of::<Tile>() as u64,
                        step_mode: wgpu::VertexStepMode::Instance,
                        attributes: &wgpu::vertex_attr_array![1 => Uint32x2, 2 => Uint32, 3 => Float32],
                    }),
                ],
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH,
                depth_write_enabled: Some(!added),
                // Reverse z: near 1, infinitely far 0.
                depth_compare: Some(if added {
                    wgpu::CompareFunction::Equal
                } else {
                    wgpu::CompareFunction::Greater
                }),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: Default::default(),
            fragment: Some(wgpu::FragmentState {
                module: &module,
                entry_point: Some(fragment_entry),
                compilation_options: Default::default(),
                targets: &[Some(target)],
            }),
            multiview_mask: None,
            cache: None,
        })
    };
    // The lights' tables: the sun's and, on a moonlit night, the moon's; a rung without
    // tables binds its own per light (`RungPasses::bind_terrain`).
    let light_tables: Vec<Option<&AtmosphereLuts>> = match rung {
        Some(rung) => (0..rung.light_count()).map(|_| None).collect(),
        None => tables.iter().map(Some).collect(),
    };
    let draws = light_tables
        .into_iter()
        .enumerate()
        .map(|(index, tables)| {
            let (uniform, layers, shadow) = if index == 0 {
                (
                    "render terrain uniform",
                    "render terrain cloud layers",
                    "render terrain volume shadow",
                )
            } else {
                (
                    "render terrain uniform (added light)",
                    "render terrain cloud layers (added light)",
                    "render terrain volume shadow (added light)",
                )
            };
            let uniform = uniform_buffer(uniform);
            let cloud_layers = layers_buffer(layers);
            let volume_shadow = shadow_uniform(shadow);
            LightDraw {
                pipeline: make_pipeline(tables, index > 0),
                bind_group: bind_group_with(&uniform, &cloud_layers, &volume_shadow),
                uniform,
                cloud_layers,
                volume_shadow,
            }
        })
        .collect();
    let (grid, indices) = tile_mesh();
    let grid = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("render terrain tile grid"),
        contents: bytemuck::cast_slice(&grid),
        usage: wgpu::BufferUsages::VERTEX,
    });
    let index_count = indices.len() as u32;
    let indices = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("render terrain tile indices"),
        contents: bytemuck::cast_slice(&indices),
        usage: wgpu::BufferUsages::INDEX,
    });
    let lod = TerrainLod::new(hf);
    let tile_capacity = 256;
    let tiles = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("render terrain tiles"),
        size: (tile_capacity * std::mem::size_of::<Tile>()) as u64,
        usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    Ok(TerrainPass {
        draws,
        grid,
        indices,
        index_count,
        tiles,
        tile_capacity,
        tile_count: 0,
        lod,
        cloud_layer_capacity,
        volume_shadow_values,
        shadow_clouds,
        shell_shadow: if shadow_clouds[1] {
            Some(super::shell_shadow::ShellShadowGpu::new(device)?)
        } else {
            None
        },
        vertex_air,
    })
}

impl GpuPass for TerrainPass {
    fn prepare(
        &mut self,
        shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let Some(terrain) = &scene.terrain else {
            return Err(crate::gpu::frame::differs("terrain", true));
        };
        let camera = &scene.camera;
        let planet = scene.atmosphere.planet_radius;
        let eye = scene.camera_position - glam::DVec3::new(0.0, planet, 0.0);
        let eye32 = eye.as_vec3();
        let view = glam::camera::rh::view::look_to_mat4(
            eye32,
            Vec3::from_array(camera.forward),
            Vec3::from_array(camera.up),
        );
        let fov_y = 2.0 * camera.tan_half_fov_y.atan();
        let aspect = camera.width as f32 / camera.height as f32;
        let projection = glam::camera::rh::proj::directx::perspective_infinite_reverse(
            fov_y,
            aspect,
            scene.near.max(0.01) as f32,
        );
        let offset = terrain.map_offset();
        let hf = &terrain.heightfield;
        let uniform_for = |lighting: &TerrainLighting, light: &Illuminant<'_>| TerrainUniform {
            view_projection: (projection * view).to_cols_array_2d(),
            camera: eye32.to_array(),
            spacing: hf.spacing() as f32,
            map_offset: [offset[0] as f32, offset[1] as f32],
            map_size: [hf.width() as u32, hf.height() as u32],
            sun_enu: lighting.sun_enu.to_array(),
            sun_angular_radius: light.atmosphere.sun_angular_radius as f32,
            sky_irradiance: lighting.sky_irradiance.to_array(),
            sun_elevation: lighting.sun_elevation,
            sun_azimuth: lighting.sun_azimuth,
            horizon_layers: match &terrain.horizon {
                HorizonMaps::EastWest(_) => 0,
                HorizonMaps::Azimuths(maps) => maps.count() as u32,
            },
            viewer_radius: scene.viewer_radius as f32,
            cloud_layer_count: light.cloud_layers.len() as u32,
            albedo: terrain.albedo.uniform(),
            radiance_scale: scene.present.exposure,
            pixel_angle: super::pixel_angle(camera),
            procedural: u32::from(terrain.materials.is_some()),
            colour_enabled: u32::from(terrain.colour.is_some()),
            colour_size: terrain.colour.as_ref().map_or([2, 2], |c| c.size),
            colour_texels_per_metre: terrain.colour.as_ref().map_or(0.0, |c| c.texels_per_metre),
            padding0: 0.0,
            materials: terrain
                .materials
                .map_or(bytemuck::Zeroable::zeroed(), |m| m.uniform()),
        };
        // The clouds' shadow maps (the CPU renderer reads the same values; the deck's
        // baked on the GPU by the same formula), each light's parameters.
        let shadows = super::cloud_shadow::write(
            &shared.device,
            queue,
            &self.volume_shadow_values,
            scene,
            self.shadow_clouds,
            self.shell_shadow.as_mut(),
        )?;
        let lights: Vec<Illuminant<'_>> = scene.lights();
        if lights.len() != self.draws.len() {
            return Err(RenderError::InvalidParameter {
                field: "lights",
                value: format!("{} lights", lights.len()),
                reason: "differs from the scene the renderer was built for",
            });
        }
        for ((draw, light), shadow) in self.draws.iter().zip(&lights).zip(&shadows) {
            let lighting = terrain_lighting_for(scene, terrain, light)?;
            let uniform = uniform_for(&lighting, light);
            queue.write_buffer(&draw.uniform, 0, bytemuck::bytes_of(&uniform));
            queue.write_buffer(&draw.volume_shadow, 0, bytemuck::bytes_of(shadow));
            if light.cloud_layers.len() > self.cloud_layer_capacity {
                return Err(RenderError::InvalidParameter {
                    field: "clouds.layers",
                    value: format!("{} layers", light.cloud_layers.len()),
                    reason: "more than the renderer was built for",
                });
            }
            if !light.cloud_layers.is_empty() {
                queue.write_buffer(
                    &draw.cloud_layers,
                    0,
                    bytemuck::cast_slice(light.cloud_layers),
                );
            }
        }
        let pixels_per_radian = f64::from(camera.height) / (2.0 * f64::from(camera.tan_half_fov_y));
        let camera_map = [eye.x + offset[0], eye.z + offset[1], eye.y];
        let tiles = self.lod.select(
            camera_map,
            pixels_per_radian,
            shared.settings.terrain_error_px,
        );
        if tiles.len() > self.tile_capacity {
            self.tile_capacity = tiles.len().next_power_of_two();
            self.tiles = shared.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("render terrain tiles"),
                size: (self.tile_capacity * std::mem::size_of::<Tile>()) as u64,
                usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
        }
        queue.write_buffer(&self.tiles, 0, bytemuck::cast_slice(&tiles));
        self.tile_count = tiles.len() as u32;
        if let Some(air) = &mut self.vertex_air {
            air.prepare(&shared.device, queue, scene, &tiles)?;
        }
        Ok(())
    }

    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError> {
        // The shell deck's shadow map, when `prepare` found it changed: baked and copied
        // into the terrain pass's shadow values before the draw reads them.
        if let Some(shell_shadow) = &mut self.shell_shadow {
            shell_shadow.encode(
                encoder,
                &self.volume_shadow_values,
                times.and_then(|t| t.compute_writes("shell cloud shadow")),
            )?;
        }
        // Per vertex with a rung without tables: the vertices' segments first.
        if let Some(air) = &self.vertex_air {
            air.encode(encoder, &self.draws[0].bind_group, times);
        }
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("render terrain"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &shared.hdr_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                view: &shared.depth_view,
                depth_ops: Some(wgpu::Operations {
                    load: wgpu::LoadOp::Load,
                    store: wgpu::StoreOp::Store,
                }),
                stencil_ops: None,
            }),
            timestamp_writes: times.and_then(|t| t.render_writes("terrain")),
            ..Default::default()
        });
        pass.set_vertex_buffer(0, self.grid.slice(..));
        pass.set_vertex_buffer(1, self.tiles.slice(..));
        pass.set_index_buffer(self.indices.slice(..), wgpu::IndexFormat::Uint32);
        // Each light's tables, the sun's first (a rung binds its own).
        for (index, draw) in self.draws.iter().enumerate() {
            pass.set_pipeline(&draw.pipeline);
            if let Some(luts) = shared.tables.get(index) {
                pass.set_bind_group(0, luts.uniform_bind_group(), &[]);
                pass.set_bind_group(1, luts.table_bind_group(), &[]);
            }
            if let Some(rung) = &shared.rung {
                rung.bind_terrain(&mut pass, index);
            }
            if let Some(air) = &self.vertex_air {
                air.bind(&mut pass, index);
            }
            pass.set_bind_group(2, &draw.bind_group, &[]);
            pass.draw_indexed(0..self.index_count, 0, 0..self.tile_count);
        }
        drop(pass);
        // A rung without tables: the aerial perspective per pixel (compute).
        if let Some(rung) = &shared.rung {
            rung.encode_air(encoder, &shared.hdr, times)?;
        }
        Ok(())
    }
}

impl TerrainPass {
    /// Tiles the terrain drew in the prepared frame.
    pub(crate) fn tile_count(&self) -> u32 {
        self.tile_count
    }
}
