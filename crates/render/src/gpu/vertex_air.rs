//! The terrain's aerial perspective per vertex (`[terrain] aerial_perspective =
//! "per-vertex"`, Hoffman and Preetham 2002) for the rungs without tables (`closed-form`,
//! `closed-form-vertex`, `single`).
//!
//! The precomputed rung evaluates the segment camera → vertex in the terrain's vertex
//! stage (`shaders/render/terrain_aerial_vertex.wgsl`, atmos' tables). These rungs
//! evaluate it with their own functions (the rung's module bound to `render::rung_sky`,
//! `super::rung_kind`: its `segment_air`, which `render::rung_air` evaluates per pixel)
//! in a compute pass over the vertices of the tiles drawn this frame
//! (`shaders/render/vertex_air_compute.wgsl`, one invocation per tile vertex, its position from `render::terrain`'s
//! `tile_vertex_world`), one dispatch per light (the sun, and the moon on a moonlit
//! night: each light's own segment, as the CPU twin adds each light's
//! `surface × T + L`); the terrain draw's vertex stage reads its vertex's segment
//! (`shaders/render/terrain_rung_aerial_vertex.wgsl`) and the rasteriser interpolates
//! it. A compute pass rather than the vertex stage: lavapipe (Mesa 22.3) crashes
//! compiling the closed form's path length and the single-scattering march into a
//! graphics stage. The per-pixel aerial-perspective pass of these rungs
//! (`super::rungs`' compute pass over the drawn frame) is then not built.
//!
//! The segments are bound in group 0 of the terrain pipeline (the precomputed rung's
//! tables' group, which these rungs leave unbound). CPU twin:
//! [`crate::aerial_vertex::VertexAerial`] with [`crate::air::segment_to`]
//! without tables (the same vertices and the same segment, interpolated at the
//! triangle the pixel's ray crosses).

use wgpu::util::DeviceExt as _;

use crate::RenderError;
use crate::gpu::layout::buffer_entry;
use crate::scene::Rung;
use crate::scene::prepare::PreparedScene;
use crate::terrain_mesh::{Tile, tile_mesh};

/// The light and the dispatch of a pass (layout identical to WGSL `VertexAirUniform` in
/// `shaders/render/vertex_air.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VertexAirUniform {
    /// The camera, planet-centred (m).
    pub camera_position: [f32; 3],
    /// Vertices of one tile's mesh (grid and skirts).
    pub grid_vertices: u32,
    /// Unit direction toward the light.
    pub light: [f32; 3],
    /// Tiles drawn this frame.
    pub tile_count: u32,
}

/// Bytes of one vertex's segment: transmittance and in-scatter, a `vec4` each.
const SEGMENT_BYTES: u64 = 32;

/// Invocations per workgroup along the tile's vertices (`@workgroup_size(64)`).
const WORKGROUP: u32 = 64;

/// One light's segments: its uniform, and the groups that write (compute) and read
/// (draw) the segments of every drawn tile vertex (the groups hold the buffers).
#[derive(Debug)]
struct LightAir {
    uniform: wgpu::Buffer,
    compute_group: wgpu::BindGroup,
    draw_group: wgpu::BindGroup,
}

/// The compute pass of the per-vertex aerial perspective and the terrain draw's parts
/// (see the module documentation).
#[derive(Debug)]
pub(crate) struct VertexAir {
    pipeline: wgpu::ComputePipeline,
    compute_layout: wgpu::BindGroupLayout,
    draw_layout: wgpu::BindGroupLayout,
    draw_module: wgpu::ShaderModule,
    grid: wgpu::Buffer,
    grid_vertices: u32,
    tiles: wgpu::Buffer,
    tile_capacity: usize,
    tile_count: u32,
    /// The parameters of the sun's atmosphere, then the moon's (moonlit nights).
    light_parameters: Vec<Vec<u8>>,
    lights: Vec<LightAir>,
}

/// Whether the GPU renderer draws `scene`'s terrain per vertex with these passes: a
/// terrain asking for it, drawn by a rung without tables.
pub(crate) fn wanted(scene: &PreparedScene) -> bool {
    scene
        .terrain
        .as_ref()
        .is_some_and(|t| t.aerial_perspective.per_vertex())
        && scene.rung != Rung::Precomputed
        && super::rung_kind::has_rung_passes(scene.rung)
}

/// What the per-vertex passes need of the scene, taken when the rung's passes are built
/// (`super::rungs::RungPasses::new`): the rung and its parameters of each light's
/// atmosphere (the sun's, then the moon's on a moonlit night).
#[derive(Debug, Clone)]
pub(crate) struct VertexAirPlan {
    rung: Rung,
    light_parameters: Vec<Vec<u8>>,
}

fn bind(binding: u32, buffer: &wgpu::Buffer) -> wgpu::BindGroupEntry<'_> {
    wgpu::BindGroupEntry {
        binding,
        resource: buffer.as_entire_binding(),
    }
}

impl VertexAirPlan {
    /// The plan for `scene`, `None` unless [`wanted`].
    pub(crate) fn new(scene: &PreparedScene) -> Result<Option<Self>, RenderError> {
        if !wanted(scene) {
            return Ok(None);
        }
        // The rung's parameters of each light's atmosphere (those of `super::rungs`).
        let light_parameters = scene
            .lights()
            .iter()
            .map(|light| super::rung_kind::rung_parameters(scene.rung, light.atmosphere))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Some(Self {
            rung: scene.rung,
            light_parameters,
        }))
    }
}

impl VertexAir {
    /// The passes of `plan`; `terrain_layout` is the terrain's group 2 (its uniform and
    /// heights visible to compute).
    pub(crate) fn new(
        device: &wgpu::Device,
        plan: &VertexAirPlan,
        terrain_layout: &wgpu::BindGroupLayout,
    ) -> Result<Self, RenderError> {
        let compose = |entry| super::rung_kind::compose_rung_entry(plan.rung, entry);
        let compute_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render::vertex_air_compute"),
            source: wgpu::ShaderSource::Wgsl(compose("render::vertex_air_compute")?.into()),
        });
        let draw_module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render::terrain_rung_aerial_vertex"),
            source: wgpu::ShaderSource::Wgsl(compose("render::terrain_rung_aerial_vertex")?.into()),
        });
        let compute = wgpu::ShaderStages::COMPUTE;
        let read = wgpu::BufferBindingType::Storage { read_only: true };
        let compute_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render terrain vertex air (compute)"),
            entries: &[
                buffer_entry(4, compute, wgpu::BufferBindingType::Uniform),
                buffer_entry(
                    5,
                    compute,
                    wgpu::BufferBindingType::Storage { read_only: false },
                ),
                buffer_entry(6, compute, read),
                buffer_entry(7, compute, read),
                buffer_entry(8, compute, wgpu::BufferBindingType::Uniform),
            ],
        });
        let vertex = wgpu::ShaderStages::VERTEX;
        let draw_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render terrain vertex air (draw)"),
            entries: &[
                buffer_entry(4, vertex, wgpu::BufferBindingType::Uniform),
                buffer_entry(5, vertex, read),
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render terrain vertex air"),
            bind_group_layouts: &[Some(&compute_layout), None, Some(terrain_layout)],
            immediate_size: 0,
        });
        let constants = super::rung_kind::air_constants(plan.rung);
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("render terrain vertex air"),
            layout: Some(&pipeline_layout),
            module: &compute_module,
            entry_point: Some("vertex_air_compute"),
            compilation_options: wgpu::PipelineCompilationOptions {
                constants: &constants,
                ..Default::default()
            },
            cache: None,
        });
        let (grid, _) = tile_mesh();
        let grid_vertices = grid.len() as u32;
        let grid = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("render terrain vertex air grid"),
            contents: bytemuck::cast_slice(&grid),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let mut air = Self {
            pipeline,
            compute_layout,
            draw_layout,
            draw_module,
            grid,
            grid_vertices,
            tiles: device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("render terrain vertex air tiles"),
                size: std::mem::size_of::<Tile>() as u64,
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            }),
            tile_capacity: 0,
            tile_count: 0,
            light_parameters: plan.light_parameters.clone(),
            lights: Vec::new(),
        };
        air.allocate(device, 1)?;
        Ok(air)
    }

    /// (Re)allocates the tiles and every light's segments for `tiles` tiles.
    fn allocate(&mut self, device: &wgpu::Device, tiles: usize) -> Result<(), RenderError> {
        let bytes = tiles as u64 * u64::from(self.grid_vertices) * SEGMENT_BYTES;
        let limit = device.limits().max_storage_buffer_binding_size;
        if bytes > limit {
            return Err(RenderError::InvalidParameter {
                field: "terrain.aerial_perspective",
                value: format!("\"per-vertex\" over {tiles} tiles"),
                reason: "their vertices' segments exceed the device's storage-buffer binding \
                         size; draw it per pixel, or with a larger terrain error",
            });
        }
        self.tile_capacity = tiles;
        self.tiles = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render terrain vertex air tiles"),
            size: (tiles * std::mem::size_of::<Tile>()) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let lights = self
            .light_parameters
            .iter()
            .map(|parameters| {
                let uniform = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("render terrain vertex air uniform"),
                    size: std::mem::size_of::<VertexAirUniform>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                let parameters = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("render terrain vertex air parameters"),
                    contents: parameters,
                    usage: wgpu::BufferUsages::UNIFORM,
                });
                let segments = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("render terrain vertex air segments"),
                    size: bytes,
                    usage: wgpu::BufferUsages::STORAGE,
                    mapped_at_creation: false,
                });
                let compute_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("render terrain vertex air (compute)"),
                    layout: &self.compute_layout,
                    entries: &[
                        bind(4, &uniform),
                        bind(5, &segments),
                        bind(6, &self.grid),
                        bind(7, &self.tiles),
                        bind(8, &parameters),
                    ],
                });
                let draw_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("render terrain vertex air (draw)"),
                    layout: &self.draw_layout,
                    entries: &[bind(4, &uniform), bind(5, &segments)],
                });
                LightAir {
                    uniform,
                    compute_group,
                    draw_group,
                }
            })
            .collect();
        self.lights = lights;
        Ok(())
    }

    /// The terrain pipeline's parts: group 0's layout, the shader module (the rung's
    /// `render::terrain_rung_aerial_vertex`) and its vertex and fragment entry points.
    pub(crate) fn draw_shader(
        &self,
    ) -> (
        &wgpu::BindGroupLayout,
        &wgpu::ShaderModule,
        &'static str,
        &'static str,
    ) {
        (
            &self.draw_layout,
            &self.draw_module,
            "terrain_rung_aerial_vertex",
            "terrain_rung_aerial_fragment",
        )
    }

    /// Writes the frame's tiles (those the terrain draws, in its order) and each
    /// light's uniform; grows the buffers when the frame draws more tiles than they hold.
    pub(crate) fn prepare(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        tiles: &[Tile],
    ) -> Result<(), RenderError> {
        let lights = scene.lights();
        if lights.len() != self.light_parameters.len() {
            return Err(RenderError::InvalidParameter {
                field: "lights",
                value: format!("{} lights", lights.len()),
                reason: "differs from the scene the renderer was built for",
            });
        }
        if tiles.len() > self.tile_capacity {
            self.allocate(device, tiles.len().next_power_of_two())?;
        }
        queue.write_buffer(&self.tiles, 0, bytemuck::cast_slice(tiles));
        self.tile_count = tiles.len() as u32;
        let directions = lights.iter().map(|light| light.direction);
        for (light, direction) in self.lights.iter().zip(directions) {
            let uniform = VertexAirUniform {
                camera_position: scene.camera_position.as_vec3().to_array(),
                grid_vertices: self.grid_vertices,
                light: direction.as_vec3().to_array(),
                tile_count: self.tile_count,
            };
            queue.write_buffer(&light.uniform, 0, bytemuck::bytes_of(&uniform));
        }
        Ok(())
    }

    /// Records the segments of every drawn vertex for each light (one compute pass,
    /// timed as "terrain aerial perspective"), before the terrain's draws;
    /// `terrain_group` is the terrain's group 2 (the sun draw's).
    pub(crate) fn encode(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        terrain_group: &wgpu::BindGroup,
        times: Option<&super::timer::PassTimes>,
    ) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("render terrain vertex air"),
            timestamp_writes: times.and_then(|t| t.compute_writes("terrain aerial perspective")),
        });
        if self.tile_count == 0 {
            return;
        }
        pass.set_pipeline(&self.pipeline);
        pass.set_bind_group(2, terrain_group, &[]);
        for light in &self.lights {
            pass.set_bind_group(0, &light.compute_group, &[]);
            pass.dispatch_workgroups(self.grid_vertices.div_ceil(WORKGROUP), self.tile_count, 1);
        }
    }

    /// Binds group 0 of light `index`'s terrain draw: that light's segments.
    pub(crate) fn bind(&self, pass: &mut wgpu::RenderPass<'_>, index: usize) {
        if let Some(light) = self.lights.get(index) {
            pass.set_bind_group(0, &light.draw_group, &[]);
        }
    }
}
