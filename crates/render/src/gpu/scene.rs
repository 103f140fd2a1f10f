//! A scene on the GPU: `atmos`' tables and sky pass, the terrain's tiles, `celestial`'s
//! sky objects, the cloud layers, the display pass. Bring your own device;
//! [`SceneRenderer::new`] builds only the passes the scene needs (no terrain: no terrain
//! pipeline, no buffers; no `[time]`: no sky objects, no moonlit tables; no cloud
//! layers: no cloud pipeline; no `[clouds.volume]`: no march, no composite), [`SceneRenderer::prepare`] writes the frame's uniforms
//! and tile list, [`SceneRenderer::encode`] records:
//!
//! 1. compute: the LUT bakes (the static ones once, the sky view and aerial
//!    perspective per frame), and the moonlit sky's when the moon lights the night;
//! 2. render: the sky (drawn first, depth writes off, seed 000), the moonlit sky added
//!    to it, then the terrain (reverse-z depth, cloud shadows) and, at night, the
//!    terrain again lit by the moon through the moonlit tables (additive, depth-equal);
//! 3. render: the sun, moon, planets and stars, additive, depth-tested behind terrain;
//! 4. render: the cloud layers, farthest first, hidden where the terrain is nearer;
//!    then the `[clouds.volume]` cloud: the terrain's depth as a distance per pixel
//!    and cloudlight's march up to it (two compute passes), composited over the scene
//!    (`render::volume_clouds`); with the `[clouds.shell]` deck too, the two are
//!    composited by depth per pixel in one pass (`render::cloud_order`);
//! 5. compute: the display pass (tone map, sRGB, dither) into RGBA8 pixels.
//!
//! The half-float HDR target holds radiance × the scene's exposure (a night's radiance
//! would flush in f16's subnormals otherwise). The CPU twin is `render::cpu_renderer`
//! (the same shading functions, ray cast instead of rasterised). The precomputed rung's
//! passes are here; the closed form's and single scattering's sky, terrain and cloud air
//! are in `render::gpu::rungs` and `render::gpu::cloud_air`; the reference rungs (f64)
//! render on the CPU only.

use atmos::gpu::AtmosphereLuts;
use atmos::gpu::sky::{SkyPass, SkyPassDescriptor};
use atmos::lut::drop_in::SkyPassParameters;
use glam::Vec3;
use wgpu::util::DeviceExt as _;

use crate::RenderError;
use crate::cpu_renderer::{TerrainLighting, terrain_lighting, terrain_lighting_for};
use crate::gpu::timer::PassTimes;
use crate::scene::Illuminant;
use crate::scene::prepare::{HorizonMaps, PreparedScene, PreparedTerrain};
use crate::terrain_mesh::{TerrainLod, Tile, tile_mesh};
use crate::terrain_shading::AlbedoRampUniform;

const HDR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Quality choices of the GPU renderer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneRendererSettings {
    /// The terrain's largest projected geometric error, pixels (0: every tile at full
    /// resolution).
    pub terrain_error_px: f64,
    /// Record GPU timestamps per pass (when the device can).
    pub timestamps: bool,
}

impl Default for SceneRendererSettings {
    fn default() -> Self {
        Self {
            terrain_error_px: crate::aerial_vertex::TERRAIN_ERROR_PX,
            timestamps: false,
        }
    }
}

/// The terrain pass's uniform (layout identical to WGSL `TerrainUniform`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct TerrainUniform {
    /// Clip from world.
    pub view_projection: [[f32; 4]; 4],
    /// The camera's world position (m).
    pub camera: [f32; 3],
    /// Metres per texel.
    pub spacing: f32,
    /// World (x, z) + this = map (x, y), metres.
    pub map_offset: [f32; 2],
    /// Texels (width, height).
    pub map_size: [u32; 2],
    /// The sun, east–north–up.
    pub sun_enu: [f32; 3],
    /// The sun's angular radius (rad), from the atmosphere.
    pub sun_angular_radius: f32,
    /// The sky's irradiance on a horizontal surface.
    pub sky_irradiance: [f32; 3],
    /// The sun's elevation (rad).
    pub sun_elevation: f32,
    /// The sun's azimuth (rad).
    pub sun_azimuth: f32,
    /// 0: east/west pair; N: N azimuth layers.
    pub horizon_layers: u32,
    /// The viewer's distance from the planet's centre (m): celestial's cloud frame.
    pub viewer_radius: f32,
    /// Cloud layers casting shadows (the first `cloud_layer_count` of the buffer).
    pub cloud_layer_count: u32,
    /// The albedo ramp.
    pub albedo: AlbedoRampUniform,
    /// Multiplies the radiance written (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
    /// Alignment.
    pub padding0: f32,
    /// Alignment.
    pub padding1: f32,
    /// Alignment.
    pub padding2: f32,
}

/// One marched cloud's shadow map parameters of a terrain draw (layout identical to WGSL
/// `VolumeShadowUniform` in `shaders/render/terrain.wgsl`; a draw holds two, the volume's
/// and the shell's: `super::cloud_shadow`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct VolumeShadowUniform {
    /// East/north of texel (0, 0)'s corner, metres.
    pub origin: [f32; 2],
    /// Texel edge, metres.
    pub cell_size: f32,
    /// The map plane's altitude, metres.
    pub plane: f32,
    /// Unit direction toward the light, east/north/up.
    pub to_sun: [f32; 3],
    /// 1 when a map is bound, 0 otherwise (no such cloud, or none toward this light).
    pub enabled: u32,
    /// Texels east × north.
    pub resolution: [u32; 2],
    /// Where the map's values start in the terrain pass's values buffer (elements).
    pub offset: u32,
    /// The casting cloud's top altitude, metres (the fade above the plane).
    pub top: f32,
}

impl VolumeShadowUniform {
    /// No volume shadow.
    pub const DISABLED: Self = Self {
        origin: [0.0; 2],
        cell_size: 1.0,
        plane: 0.0,
        to_sun: [0.0, 0.0, 1.0],
        enabled: 0,
        resolution: [1, 1],
        offset: 0,
        top: 1.0,
    };

    /// The parameters of `shadow`'s map, its values from element `offset` on.
    pub fn of(shadow: &crate::volume_clouds::CloudShadow, offset: u32) -> Self {
        Self {
            origin: shadow.origin,
            cell_size: shadow.cell_size,
            plane: shadow.plane,
            to_sun: shadow.to_sun,
            enabled: 1,
            resolution: shadow.resolution,
            offset,
            top: shadow.top,
        }
    }
}

/// The display pass's uniform (WGSL `DisplayParameters`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct DisplayParameters {
    /// Pixels.
    pub width: u32,
    /// Pixels.
    pub height: u32,
    /// Exposure before `1 − exp(−x)`.
    pub exposure: f32,
    /// Dither seed.
    pub dither_seed: u32,
}

/// The terrain's GPU resources.
#[derive(Debug)]
struct TerrainPass {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    grid: wgpu::Buffer,
    indices: wgpu::Buffer,
    index_count: u32,
    tiles: wgpu::Buffer,
    tile_capacity: usize,
    tile_count: u32,
    lod: TerrainLod,
    cloud_layers: wgpu::Buffer,
    cloud_layer_capacity: usize,
    /// The marched clouds' shadow map parameters (sun draw) and values
    /// (`super::cloud_shadow`), and which clouds have room (the volume, the shell).
    volume_shadow: wgpu::Buffer,
    volume_shadow_values: wgpu::Buffer,
    shadow_clouds: [bool; 2],
    /// The shell deck's shadow map baked on the GPU (`super::shell_shadow`).
    shell_shadow: Option<super::shell_shadow::ShellShadowGpu>,
    /// The terrain lit by the moon (scenes with a moonlit sky): drawn again over the
    /// sunlit terrain with the moonlit tables, added.
    moon: Option<MoonTerrain>,
    /// The aerial perspective per vertex of a rung without tables (`super::vertex_air`).
    vertex_air: Option<super::vertex_air::VertexAir>,
}

/// The moonlit terrain draw: the terrain pipeline with additive blending, depth-equal
/// against the sunlit draw's depth, with the moon's uniform and cloud layers.
#[derive(Debug)]
struct MoonTerrain {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    cloud_layers: wgpu::Buffer,
    /// The clouds' shadow map parameters toward the moon (their values share the sun
    /// draw's buffer: a scene the moon lights has the sun down, hence no sun map).
    volume_shadow: wgpu::Buffer,
}

/// Every pass of a scene on the GPU.
#[derive(Debug)]
pub struct SceneRenderer {
    device: wgpu::Device,
    width: u32,
    height: u32,
    settings: SceneRendererSettings,
    /// The precomputed rung's tables and sky pass (`None` for a rung without tables).
    luts: Option<AtmosphereLuts>,
    sky: Option<SkyPass>,
    moonlit: Option<(AtmosphereLuts, SkyPass)>,
    /// The sky and terrain passes of a rung without tables (`super::rungs`).
    rung: Option<super::rungs::RungPasses>,
    terrain: Option<TerrainPass>,
    sky_objects: Option<celestial::gpu::SkyObjectsPass>,
    clouds: Option<CloudPass>,
    volume_cloud: Option<crate::volume_clouds::VolumeCloudPass>,
    billboard_cloud: Option<crate::billboard_clouds::BillboardCloudPass>,
    shell_cloud: Option<crate::shell_clouds::ShellCloudPass>,
    /// The terrain's distance per pixel the marched clouds stop at (with a volume or a
    /// shell cloud): one pass a frame for both.
    cloud_distance: Option<super::cloud_composite::CloudDistance>,
    /// The shell and the volume cloud composited by depth (a scene with both).
    cloud_order: Option<super::cloud_order::CloudOrderPass>,
    hdr: wgpu::Texture,
    hdr_view: wgpu::TextureView,
    depth_view: wgpu::TextureView,
    display_pipeline: wgpu::ComputePipeline,
    display_uniform: wgpu::Buffer,
    display_group: wgpu::BindGroup,
    pixels: wgpu::Buffer,
    static_luts_pending: bool,
    prepared: bool,
    times: Option<PassTimes>,
}

fn storage_read(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: true },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

fn uniform_entry(binding: u32, visibility: wgpu::ShaderStages) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Uniform,
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}

/// The passes a scene needs on the GPU, and those it skips, with the reason (what
/// `skyscape explain` prints).
pub fn planned_passes(scene: &PreparedScene) -> Vec<(&'static str, Result<String, String>)> {
    let mut plan = vec![
        (
            "atmosphere LUT bakes",
            Ok(
                "transmittance and multiple scattering once; sky view and aerial perspective per frame"
                    .into(),
            ),
        ),
        (
            "sky",
            Ok("atmos' sky pass, drawn first with depth writes off (seed 000)".into()),
        ),
    ];
    plan.push((
        "moonlit sky LUT bakes",
        if scene.moonlit.is_some() {
            Ok(
                "the tables lit by the moon (celestial's MoonLight) per frame; its sky pass adds \
                to the sunlit sky's (timed with \"sky\")"
                    .into(),
            )
        } else {
            Err("no [time], or the sun is up or the moon below −2°: no moonlit tables".into())
        },
    ));
    plan.push((
        "terrain",
        if let Some(terrain) = &scene.terrain {
            let aerial = crate::aerial_vertex::plan(terrain.aerial_perspective);
            Ok(if scene.moonlit.is_some() {
                format!(
                    "instanced quadtree tiles, seed 000's shading, {aerial}; drawn again lit by \
                     the moon through the moonlit tables, added (timed with \"terrain\")"
                )
            } else {
                format!("instanced quadtree tiles, seed 000's shading, {aerial}")
            })
        } else {
            Err("the scene has no [terrain]: no terrain pipeline, no horizon maps".into())
        },
    ));
    plan.push((
        "sky objects",
        match (&scene.sky_objects, scene.sun_elevation_deg()) {
            (Some(frame), elevation) => Ok(if elevation < -18.0 {
                format!(
                    "celestial's moon, planets and {} point sources (the sun {elevation:.1}° is below −18°: \
                     astronomical night, no sun disc)",
                    frame.points.len()
                )
            } else {
                format!(
                    "celestial's sun disc and aureole, moon, planets and {} point sources above \
                     the eye's threshold against the sky, depth-tested behind terrain",
                    frame.points.len()
                )
            }),
            (None, _) => Err(
                "no [time] in the scene (or [sky_objects] enabled = false): no sky-objects \
                 pipeline; the sky pass draws the sun's disc"
                    .into(),
            ),
        },
    ));
    plan.push((
        "clouds",
        if scene.cloud_layers.is_empty() {
            Err("no [[clouds.layers]] in front of the viewer: no cloud pipeline".into())
        } else {
            Ok(format!(
                "{} celestial layer(s) farthest first over the opaque scene, each hidden \
                 where the terrain's depth is nearer",
                scene.cloud_layers.len()
            ))
        },
    ));
    plan.push((
        "volume cloud march",
        match &scene.volume_cloud {
            Some(_) => Ok(
                "the terrain's depth as a distance per pixel, then cloudlight's march of \
                 the [clouds.volume] cloud up to it (a ridge cuts the cloud where it stands)"
                    .into(),
            ),
            None => Err("no [clouds.volume] to march (none, or draw = \"billboards\")".into()),
        },
    ));
    plan.push((
        "moonlit cloud march",
        crate::volume_clouds::moonlit_march_plan(scene),
    ));
    plan.push((
        "volume clouds",
        match &scene.volume_cloud {
            Some(cloud) => Ok(format!(
                "the composite of cloudlight's march of the [clouds.volume] cumulus ({}×{}×{} cells, \
                 {} of density > 0, grown by cloudsim in {} steps; {} view × {} light steps per \
                 pixel) over the scene, through atmos' aerial perspective to its depth per pixel \
                 and light (a compute pass, untimed: the table within its range, a march of the \
                 tables beyond)",
                cloud.volume.dims()[0],
                cloud.volume.dims()[1],
                cloud.volume.dims()[2],
                cloud.cloudy_cells,
                cloud.steps,
                cloud.settings.config().view_steps,
                match cloud.settings.config().light {
                    cloudlight::march::LightMarch::Full { steps } => steps.get(),
                    _ => 0,
                },
            )),
            None => {
                Err("no [clouds.volume] to march (none, or draw = \"billboards\"): no march \
                     pass, no composite, nothing allocated for it"
                    .into())
            }
        },
    ));
    plan.push(("billboard clouds", crate::billboard_clouds::explain(scene)));
    plan.extend(crate::shell_clouds::shell_pass_plans(scene));
    crate::cloud_order::adjust_plan(scene, &mut plan);
    plan.push((
        "display",
        Ok("exposure, 1 − exp(−x), sRGB, dither to RGBA8".into()),
    ));
    super::rungs::adjust_plan(scene, &mut plan);
    plan
}

/// The cloud pass's uniform (WGSL `CloudComposite`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct CloudComposite {
    /// The scene's camera.
    pub camera: atmos::frame::FrameCamera,
    /// The viewer's distance from the planet's centre (m).
    pub viewer_radius: f32,
    /// The reverse-z projection's near plane (m).
    pub near: f32,
    /// Layers in the storage buffer.
    pub layer_count: u32,
    /// Multiplies the layers' own light (the HDR target holds radiance × exposure).
    pub radiance_scale: f32,
}

/// The cloud layers' compositing pass (`render::clouds`).
#[derive(Debug)]
struct CloudPass {
    pipeline: wgpu::RenderPipeline,
    uniform: wgpu::Buffer,
    layers: wgpu::Buffer,
    capacity: usize,
    bind_group: wgpu::BindGroup,
}

impl CloudPass {
    fn new(
        device: &wgpu::Device,
        capacity: usize,
        depth_view: &wgpu::TextureView,
    ) -> Result<Self, RenderError> {
        let source = crate::composer().compose_module("render::clouds")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render clouds"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render clouds"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::FRAGMENT),
                storage_read(1, wgpu::ShaderStages::FRAGMENT),
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
            ],
        });
        let uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render clouds uniform"),
            size: std::mem::size_of::<CloudComposite>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let layers = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render cloud layers"),
            size: (capacity.max(1) * std::mem::size_of::<celestial::clouds::CloudLayerUniforms>())
                as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render clouds"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: layers.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(depth_view),
                },
            ],
        });
        // Premultiplied: the fragment's colour is the layers' own light, its alpha the
        // fraction of the scene they hide.
        let blend = wgpu::BlendState {
            color: wgpu::BlendComponent {
                src_factor: wgpu::BlendFactor::One,
                dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                operation: wgpu::BlendOperation::Add,
            },
            alpha: wgpu::BlendComponent::OVER,
        };
        let pipeline = super::cloud_composite::fullscreen_pipeline(
            device,
            "render clouds",
            &layout,
            &module,
            ["clouds_vertex", "clouds_fragment"],
            HDR,
            blend,
        );
        Ok(Self {
            pipeline,
            uniform,
            layers,
            capacity,
            bind_group,
        })
    }

    fn prepare(&self, queue: &wgpu::Queue, scene: &PreparedScene) -> Result<(), RenderError> {
        if scene.cloud_layers.len() > self.capacity {
            return Err(RenderError::InvalidParameter {
                field: "clouds.layers",
                value: format!("{} layers", scene.cloud_layers.len()),
                reason: "more than the renderer was built for",
            });
        }
        let uniform = CloudComposite {
            camera: scene.camera,
            viewer_radius: scene.viewer_radius as f32,
            near: scene.near.max(0.01) as f32,
            layer_count: scene.cloud_layers.len() as u32,
            radiance_scale: scene.present.exposure,
        };
        queue.write_buffer(&self.uniform, 0, bytemuck::bytes_of(&uniform));
        if !scene.cloud_layers.is_empty() {
            queue.write_buffer(&self.layers, 0, bytemuck::cast_slice(&scene.cloud_layers));
        }
        Ok(())
    }
}

impl SceneRenderer {
    /// Builds the passes `scene` needs. Errors for a rung without GPU passes (render
    /// it on the CPU), for resources beyond the device's limits, and for a pipeline,
    /// shader or bind group the device rejects ([`RenderError::Device`], caught by a
    /// device error scope: e.g. the shell clouds' pipeline on the GL backend).
    pub fn new(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        settings: SceneRendererSettings,
    ) -> Result<Self, RenderError> {
        super::validation::scoped(device, "SceneRenderer::new", || {
            Self::new_unscoped(device, queue, scene, settings)
        })
    }

    fn new_unscoped(
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
        settings: SceneRendererSettings,
    ) -> Result<Self, RenderError> {
        let (width, height) = (scene.camera.width, scene.camera.height);
        let limit = device.limits().max_texture_dimension_2d;
        if width > limit || height > limit {
            return Err(RenderError::InvalidParameter {
                field: "output.width",
                value: format!("{width}×{height}"),
                reason: "beyond the device's largest texture side",
            });
        }
        // The closed form and single scattering: their own sky and terrain passes, no
        // tables (`super::rungs`); the reference rungs have none (an error).
        let rung = super::rungs::RungPasses::new(device, scene, HDR, DEPTH)?;
        let luts = match rung {
            Some(_) => None,
            None => Some(AtmosphereLuts::new(
                device,
                &scene.atmosphere,
                &Default::default(),
            )?),
        };
        let sky = match &luts {
            Some(luts) => Some(SkyPass::new(
                device,
                luts,
                &SkyPassDescriptor {
                    depth_format: Some(DEPTH),
                    ..SkyPassDescriptor::new(HDR)
                },
            )?),
            None => None,
        };
        // The moonlit sky: a second table set lit by the moon, its sky pass added.
        let moonlit = match scene.moonlit.as_ref().filter(|_| luts.is_some()) {
            Some(moon) => {
                let luts = AtmosphereLuts::new(device, &moon.atmosphere, &Default::default())?;
                let additive = wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Add,
                };
                let pass = SkyPass::new(
                    device,
                    &luts,
                    &SkyPassDescriptor {
                        depth_format: Some(DEPTH),
                        blend: Some(wgpu::BlendState {
                            color: additive,
                            alpha: additive,
                        }),
                        ..SkyPassDescriptor::new(HDR)
                    },
                )?;
                Some((luts, pass))
            }
            None => None,
        };
        let target = |format, usage| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some("render scene target"),
                size: wgpu::Extent3d {
                    width,
                    height,
                    depth_or_array_layers: 1,
                },
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        // COPY_DST: a rung without tables copies its terrain's aerial perspective back.
        let hdr = target(
            HDR,
            wgpu::TextureUsages::RENDER_ATTACHMENT
                | wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_SRC
                | wgpu::TextureUsages::COPY_DST,
        );
        // The cloud pass reads the terrain's depth.
        let depth = target(
            DEPTH,
            wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
        );
        let hdr_view = hdr.create_view(&Default::default());
        let depth_view = depth.create_view(&Default::default());
        let terrain = match &scene.terrain {
            Some(terrain) => Some(Self::terrain_pass(
                device,
                luts.as_ref(),
                moonlit.as_ref().map(|(moon_luts, _)| moon_luts),
                rung.as_ref(),
                terrain,
                scene.cloud_layers.len(),
                [
                    scene.volume_cloud.is_some() || scene.billboard_cloud.is_some(),
                    scene.shell_cloud.is_some(),
                ],
            )?),
            None => None,
        };
        // Only a scene with cloud layers builds the cloud pipeline.
        let clouds = if scene.cloud_layers.is_empty() {
            None
        } else {
            Some(CloudPass::new(
                device,
                scene.cloud_layers.len(),
                &depth_view,
            )?)
        };

        // A marched cloud's air: the sun's, and at night (`moonlit_cloud`) the moon's,
        // which light the cloud too (its march and air passes): the tables, or the
        // rung's functions (`super::cloud_air`).
        let cloud_luts = |moonlit_cloud: bool| {
            let (sun, moon) = super::cloud_air::cloud_airs(
                luts.as_ref(),
                moonlit.as_ref().map(|(l, _)| l),
                rung.as_ref(),
                scene.rung,
            )?;
            Ok::<_, RenderError>((sun, moon.filter(|_| moonlit_cloud)))
        };
        // Only a scene with [clouds.volume] builds the march and its composite.
        let volume_cloud = match &scene.volume_cloud {
            Some(cloud) => {
                let (luts, moon_luts) = cloud_luts(cloud.moon.is_some())?;
                Some(crate::volume_clouds::VolumeCloudPass::new_volume(
                    device, luts, moon_luts, HDR,
                )?)
            }
            None => None,
        };
        // Only a scene with [clouds.shell] builds the shell's march and composite.
        let shell_cloud = match &scene.shell_cloud {
            Some(cloud) => {
                let (luts, moon_luts) = cloud_luts(cloud.moon.is_some())?;
                Some(crate::shell_clouds::ShellCloudPass::new_shell(
                    device, luts, moon_luts, HDR,
                )?)
            }
            None => None,
        };
        let cloud_distance = if volume_cloud.is_some() || shell_cloud.is_some() {
            Some(super::cloud_composite::CloudDistance::new(device)?)
        } else {
            None
        };
        // Both marched clouds: one composite of the two by depth per pixel.
        let cloud_order = if volume_cloud.is_some() && shell_cloud.is_some() {
            Some(super::cloud_order::CloudOrderPass::new(device, HDR)?)
        } else {
            None
        };

        // Only a scene drawing [clouds.volume] as billboards builds their pipeline.
        let billboard_cloud = match &scene.billboard_cloud {
            // The air: the tables, or the rung's functions per light (`super::cloud_air`).
            Some(cloud) => {
                let airs =
                    super::cloud_air::cloud_airs(luts.as_ref(), None, rung.as_ref(), scene.rung)
                        .ok();
                Some(crate::billboard_clouds::BillboardCloudPass::new(
                    device,
                    airs.map(|(sun, _)| sun),
                    airs.and_then(|(_, moon)| moon)
                        .filter(|_| cloud.moon.is_some()),
                    HDR,
                    DEPTH,
                )?)
            }
            None => None,
        };

        // Display: HDR texture → packed RGBA8.
        let source = crate::composer().compose_module("render::display")?;
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("render display"),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        });
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("render display"),
            entries: &[
                uniform_entry(0, wgpu::ShaderStages::COMPUTE),
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Float { filterable: false },
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 2,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                },
            ],
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("render display"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let display_pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("render display"),
            layout: Some(&pipeline_layout),
            module: &module,
            entry_point: Some("display_main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let display_uniform = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render display parameters"),
            size: std::mem::size_of::<DisplayParameters>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let pixels = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("render display pixels"),
            size: 4 * u64::from(width) * u64::from(height),
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let display_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("render display"),
            layout: &layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: display_uniform.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&hdr_view),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: pixels.as_entire_binding(),
                },
            ],
        });
        // Only a scene with [time] and sky objects on builds the pass.
        let sky_objects = match &scene.sky_objects {
            Some(_) => {
                let mut objects = celestial::gpu::SkyObjectsSettings::new(HDR);
                objects.depth = Some(celestial::gpu::DepthTest {
                    format: DEPTH,
                    compare: wgpu::CompareFunction::GreaterEqual,
                });
                Some(celestial::gpu::SkyObjectsPass::new(device, &objects)?)
            }
            None => None,
        };
        let times = if settings.timestamps {
            let mut labels = match &rung {
                Some(rung) => rung.timestamp_labels(scene.terrain.is_some()),
                None => vec!["atmosphere LUT bakes"],
            };
            labels.push("sky");
            if scene.moonlit.is_some() && rung.is_none() {
                labels.push("moonlit sky LUT bakes");
            }
            if terrain.as_ref().is_some_and(|t| t.shell_shadow.is_some()) {
                labels.push("shell cloud shadow");
            }
            if terrain.is_some() {
                labels.push("terrain");
            }
            if scene.sky_objects.is_some() {
                labels.push("sky objects");
            }
            if !scene.cloud_layers.is_empty() {
                labels.push("clouds");
            }
            if let Some(cloud) = &scene.volume_cloud {
                labels.push("volume cloud march");
                if cloud.moon.is_some() {
                    labels.push("moonlit cloud march");
                }
                labels.push("volume clouds");
            }
            if scene.billboard_cloud.is_some() {
                labels.push("billboard clouds");
            }
            if let Some(shell) = &scene.shell_cloud {
                labels.push("shell cloud march");
                if shell.moon.is_some() {
                    labels.push("moonlit shell march");
                }
                labels.push("shell clouds");
            }
            if cloud_order.is_some() {
                // Their one composite by depth replaces "volume clouds" and "shell clouds".
                labels.retain(|l| !matches!(*l, "volume clouds" | "shell clouds"));
                labels.push("clouds by depth");
            }
            labels.push("display");
            PassTimes::new(device, queue, labels)
        } else {
            None
        };
        Ok(Self {
            device: device.clone(),
            width,
            height,
            settings,
            luts,
            sky,
            moonlit,
            rung,
            terrain,
            sky_objects,
            clouds,
            volume_cloud,
            billboard_cloud,
            shell_cloud,
            cloud_distance,
            cloud_order,
            hdr,
            hdr_view,
            depth_view,
            display_pipeline,
            display_uniform,
            display_group,
            pixels,
            static_luts_pending: true,
            prepared: false,
            times,
        })
    }

    fn terrain_pass(
        device: &wgpu::Device,
        luts: Option<&AtmosphereLuts>,
        moon_luts: Option<&AtmosphereLuts>,
        rung: Option<&super::rungs::RungPasses>,
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
        let cloud_layers = layers_buffer("render terrain cloud layers");
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
        let uniform = uniform_buffer("render terrain uniform");
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
        let volume_shadow = shadow_uniform("render terrain volume shadow");
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
                    ],
                })
            };
        let bind_group = bind_group_with(&uniform, &cloud_layers, &volume_shadow);
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
            Some(plan) => Some(super::vertex_air::VertexAir::new(device, plan, &layout)?),
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
        // `moon`: the additive, depth-equal draw of the moonlit terrain over the sunlit
        // one (the same vertices give the same depths: the clip position is invariant).
        let make_pipeline = |luts: Option<&AtmosphereLuts>, moon: bool| {
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
                blend: moon.then_some(wgpu::BlendState {
                    color: additive,
                    alpha: additive,
                }),
                ..HDR.into()
            };
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(if moon {
                    "render terrain (moonlit)"
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
                    depth_write_enabled: Some(!moon),
                    // Reverse z: near 1, infinitely far 0.
                    depth_compare: Some(if moon {
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
        let pipeline = make_pipeline(luts, false);
        // The moon's tables, or (a rung without tables) none.
        let moon_light = match rung {
            Some(rung) => rung.has_moon().then_some(None),
            None => moon_luts.map(Some),
        };
        let moon = moon_light.map(|moon_luts| {
            let uniform = uniform_buffer("render moonlit terrain uniform");
            let cloud_layers = layers_buffer("render moonlit terrain cloud layers");
            let volume_shadow = shadow_uniform("render moonlit terrain volume shadow");
            MoonTerrain {
                pipeline: make_pipeline(moon_luts, true),
                bind_group: bind_group_with(&uniform, &cloud_layers, &volume_shadow),
                uniform,
                cloud_layers,
                volume_shadow,
            }
        });
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
            pipeline,
            uniform,
            bind_group,
            grid,
            indices,
            index_count,
            tiles,
            tile_capacity,
            tile_count: 0,
            lod,
            cloud_layers,
            cloud_layer_capacity,
            volume_shadow,
            volume_shadow_values,
            shadow_clouds,
            shell_shadow: if shadow_clouds[1] {
                Some(super::shell_shadow::ShellShadowGpu::new(device)?)
            } else {
                None
            },
            moon,
            vertex_air,
        })
    }

    /// The marched clouds' air (the sun's, the moon's on a moonlit night): the tables or
    /// the rung's functions (`super::cloud_air`); `None` without either.
    fn cloud_airs(
        &self,
    ) -> Option<(
        super::cloud_air::CloudAir<'_>,
        Option<super::cloud_air::CloudAir<'_>>,
    )> {
        super::cloud_air::cloud_airs(
            self.luts.as_ref(),
            self.moonlit.as_ref().map(|(luts, _)| luts),
            self.rung.as_ref(),
            self.rung
                .as_ref()
                .map_or(crate::scene::Rung::Precomputed, |r| r.rung()),
        )
        .ok()
    }

    /// Writes the frame's uniforms: the LUTs' camera, the sky pass's sun disc, the
    /// terrain's view and lighting and its tiles, the display's exposure.
    ///
    /// Everything that depends on the view is written here, so one renderer draws any
    /// number of frames of its scene: a panorama's six faces are the scene turned by
    /// `PreparedScene::look_along` and prepared again (same size), each bit for bit the
    /// face a renderer built for it draws (`tests/panorama_gpu.rs`).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let device = self.device.clone();
        super::validation::scoped(&device, "SceneRenderer::prepare", || {
            self.prepare_unscoped(queue, scene)
        })
    }

    fn prepare_unscoped(
        &mut self,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let camera = &scene.camera;
        if (camera.width, camera.height) != (self.width, self.height) {
            return Err(RenderError::InvalidParameter {
                field: "output.width",
                value: format!("{}×{}", camera.width, camera.height),
                reason: "differs from the size the renderer was built for",
            });
        }
        match (&mut self.sky_objects, &scene.sky_objects) {
            (Some(pass), Some(frame)) => {
                let exposure = scene.present.exposure;
                let mut frame = frame.clone();
                for disc in &mut frame.discs {
                    disc.radiance = disc.radiance.map(|r| r * exposure);
                }
                frame.uniforms.lux_per_unit /= exposure;
                pass.prepare(queue, &frame)?;
            }
            (None, None) => {}
            (built, _) => {
                return Err(RenderError::InvalidParameter {
                    field: "sky_objects",
                    value: if built.is_some() { "off" } else { "on" }.into(),
                    reason: "differs from the scene the renderer was built for",
                });
            }
        }
        match &self.clouds {
            Some(clouds) => clouds.prepare(queue, scene)?,
            None if scene.cloud_layers.is_empty() => {}
            None => {
                return Err(RenderError::InvalidParameter {
                    field: "clouds.layers",
                    value: format!("{} layers", scene.cloud_layers.len()),
                    reason: "the renderer was built for a scene without cloud layers",
                });
            }
        }
        if let Some(distance) = &mut self.cloud_distance {
            distance.prepare(&self.device, queue, scene, &self.depth_view);
        }
        // The marched clouds: each stops at the distance prepared above.
        let (device, depth) = (&self.device, &self.depth_view);
        let distance = self.cloud_distance.as_ref();
        let differs = |field: &'static str, built: bool| RenderError::InvalidParameter {
            field,
            value: if built { "absent" } else { "given" }.into(),
            reason: "differs from the scene the renderer was built for",
        };
        match (&mut self.volume_cloud, &scene.volume_cloud) {
            (Some(pass), Some(cloud)) => {
                let distance = distance.ok_or(RenderError::NotPrepared)?;
                pass.prepare_volume(device, queue, scene, cloud, distance, depth)?;
            }
            (None, None) => {}
            (built, _) => return Err(differs("clouds.volume", built.is_some())),
        }
        match (&mut self.shell_cloud, &scene.shell_cloud) {
            (Some(pass), Some(cloud)) => {
                let distance = distance.ok_or(RenderError::NotPrepared)?;
                pass.prepare_shell(device, queue, scene, cloud, distance, depth)?;
            }
            (None, None) => {}
            (built, _) => return Err(differs("clouds.shell", built.is_some())),
        }
        if let (Some(order), Some(volume), Some(shell)) =
            (&mut self.cloud_order, &self.volume_cloud, &self.shell_cloud)
        {
            // After both clouds' marches and air: their buffers.
            order.prepare(device, queue, scene, volume, shell, depth)?;
        }
        match (&mut self.billboard_cloud, &scene.billboard_cloud) {
            (Some(pass), Some(cloud)) => pass.prepare(&self.device, queue, scene, cloud)?,
            (None, None) => {}
            (built, _) => {
                return Err(RenderError::InvalidParameter {
                    field: "clouds.volume.draw",
                    value: if built.is_some() {
                        "march"
                    } else {
                        "billboards"
                    }
                    .into(),
                    reason: "differs from the scene the renderer was built for",
                });
            }
        }
        // Every pass writes radiance × the exposure into the half-float target: a night
        // sky's ~1e-7 (the sun's irradiance as unit) would sink into f16's subnormals
        // (below 6.1e-5) and flush; exposed, the image's values are near 1.
        let radiance_scale = scene.present.exposure;
        match (&mut self.moonlit, &scene.moonlit) {
            (Some((luts, pass)), Some(moon)) => {
                luts.prepare(queue, &moon.camera(camera));
                pass.prepare(
                    queue,
                    &SkyPassParameters::new(&moon.atmosphere, false, radiance_scale, 0.0)?,
                );
            }
            (None, None) => {}
            // A rung without tables draws its moonlit sky itself (prepared below).
            (None, Some(_)) if self.rung.is_some() => {}
            (built, _) => {
                return Err(RenderError::InvalidParameter {
                    field: "moonlit sky",
                    value: if built.is_some() { "off" } else { "on" }.into(),
                    reason: "differs from the scene the renderer was built for",
                });
            }
        }
        if let (Some(luts), Some(sky)) = (&mut self.luts, &mut self.sky) {
            luts.prepare(queue, camera);
            sky.prepare(
                queue,
                &SkyPassParameters::new(
                    &scene.atmosphere,
                    scene.sky_objects.is_none(),
                    radiance_scale,
                    0.0,
                )?,
            );
        }
        if let Some(rung) = &mut self.rung {
            rung.prepare(&self.device, queue, scene, &self.hdr_view, &self.depth_view)?;
        }
        queue.write_buffer(
            &self.display_uniform,
            0,
            bytemuck::bytes_of(&DisplayParameters {
                width: self.width,
                height: self.height,
                // The HDR target already holds radiance × exposure.
                exposure: 1.0,
                dither_seed: scene.present.dither_seed,
            }),
        );
        if let (Some(pass), Some(terrain)) = (&mut self.terrain, &scene.terrain) {
            let lighting = terrain_lighting(scene, terrain)?;
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
                padding0: 0.0,
                padding1: 0.0,
                padding2: 0.0,
            };
            let uniform = uniform_for(&lighting, &scene.sun_light());
            queue.write_buffer(&pass.uniform, 0, bytemuck::bytes_of(&uniform));
            // The clouds' shadow maps (the CPU renderer reads the same values; the deck's
            // baked on the GPU by the same formula).
            let [sun_shadow, moon_shadow] = super::cloud_shadow::write(
                &self.device,
                queue,
                &pass.volume_shadow_values,
                scene,
                pass.shadow_clouds,
                pass.shell_shadow.as_mut(),
            )?;
            queue.write_buffer(&pass.volume_shadow, 0, bytemuck::bytes_of(&sun_shadow));
            match (&pass.moon, scene.moon_light()) {
                (Some(moon_pass), Some(moon)) => {
                    queue.write_buffer(
                        &moon_pass.volume_shadow,
                        0,
                        bytemuck::bytes_of(&moon_shadow),
                    );
                    let moon_lighting = terrain_lighting_for(scene, terrain, &moon)?;
                    let uniform = uniform_for(&moon_lighting, &moon);
                    queue.write_buffer(&moon_pass.uniform, 0, bytemuck::bytes_of(&uniform));
                    if !moon.cloud_layers.is_empty()
                        && moon.cloud_layers.len() <= pass.cloud_layer_capacity
                    {
                        queue.write_buffer(
                            &moon_pass.cloud_layers,
                            0,
                            bytemuck::cast_slice(moon.cloud_layers),
                        );
                    }
                }
                (None, None) => {}
                (built, _) => {
                    return Err(RenderError::InvalidParameter {
                        field: "moonlit terrain",
                        value: if built.is_some() { "off" } else { "on" }.into(),
                        reason: "differs from the scene the renderer was built for",
                    });
                }
            }
            if scene.cloud_layers.len() > pass.cloud_layer_capacity {
                return Err(RenderError::InvalidParameter {
                    field: "clouds.layers",
                    value: format!("{} layers", scene.cloud_layers.len()),
                    reason: "more than the renderer was built for",
                });
            }
            if !scene.cloud_layers.is_empty() {
                queue.write_buffer(
                    &pass.cloud_layers,
                    0,
                    bytemuck::cast_slice(&scene.cloud_layers),
                );
            }
            let pixels_per_radian =
                f64::from(camera.height) / (2.0 * f64::from(camera.tan_half_fov_y));
            let camera_map = [eye.x + offset[0], eye.z + offset[1], eye.y];
            let tiles = pass.lod.select(
                camera_map,
                pixels_per_radian,
                self.settings.terrain_error_px,
            );
            if tiles.len() > pass.tile_capacity {
                pass.tile_capacity = tiles.len().next_power_of_two();
                pass.tiles = self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("render terrain tiles"),
                    size: (pass.tile_capacity * std::mem::size_of::<Tile>()) as u64,
                    usage: wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
            }
            queue.write_buffer(&pass.tiles, 0, bytemuck::cast_slice(&tiles));
            pass.tile_count = tiles.len() as u32;
            if let Some(air) = &mut pass.vertex_air {
                air.prepare(&self.device, queue, scene, &tiles)?;
            }
        }
        self.prepared = true;
        Ok(())
    }

    /// Records the frame (see the module documentation).
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder) -> Result<(), RenderError> {
        if !self.prepared {
            return Err(RenderError::NotPrepared);
        }
        let times = self.times.as_ref();
        // The static bakes once (untimed: per atmosphere, not per frame).
        if self.static_luts_pending {
            if let Some(luts) = &self.luts {
                luts.encode_static_luts(encoder, None);
            }
            if let Some((luts, _)) = &self.moonlit {
                luts.encode_static_luts(encoder, None);
            }
            self.static_luts_pending = false;
        }
        if let Some(luts) = &self.luts {
            luts.encode_frame_luts(
                encoder,
                times.and_then(|t| t.compute_writes("atmosphere LUT bakes")),
            );
        }
        if let Some(rung) = &self.rung {
            rung.encode_sky_evaluation(encoder, times)?;
        }
        if let Some((luts, _)) = &self.moonlit {
            luts.encode_frame_luts(
                encoder,
                times.and_then(|t| t.compute_writes("moonlit sky LUT bakes")),
            );
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("render scene"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.hdr_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::BLACK),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(0.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: times.and_then(|t| t.render_writes("sky")),
                ..Default::default()
            });
            match (&self.sky, &self.luts, &self.rung) {
                (Some(sky), Some(luts), _) => sky.draw(&mut pass, luts)?,
                (_, _, Some(rung)) => rung.draw_sky(&mut pass),
                _ => {}
            }
            if let Some((luts, moon_sky)) = &self.moonlit {
                moon_sky.draw(&mut pass, luts)?;
            }
        }
        // The shell deck's shadow map, when `prepare` found it changed: baked and copied
        // into the terrain pass's shadow values before the pass reads them.
        if let Some(terrain) = &mut self.terrain
            && let Some(shell_shadow) = &mut terrain.shell_shadow
        {
            shell_shadow.encode(
                encoder,
                &terrain.volume_shadow_values,
                times.and_then(|t| t.compute_writes("shell cloud shadow")),
            )?;
        }
        if let Some(terrain) = &self.terrain {
            // Per vertex with a rung without tables: the vertices' segments first.
            if let Some(air) = &terrain.vertex_air {
                air.encode(encoder, &terrain.bind_group, times);
            }
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("render terrain"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: &self.hdr_view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    },
                })],
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &self.depth_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Load,
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: times.and_then(|t| t.render_writes("terrain")),
                ..Default::default()
            });
            pass.set_pipeline(&terrain.pipeline);
            if let Some(luts) = &self.luts {
                pass.set_bind_group(0, luts.uniform_bind_group(), &[]);
                pass.set_bind_group(1, luts.table_bind_group(), &[]);
            }
            if let Some(rung) = &self.rung {
                rung.bind_terrain(&mut pass, false);
            }
            if let Some(air) = &terrain.vertex_air {
                air.bind(&mut pass, false);
            }
            pass.set_bind_group(2, &terrain.bind_group, &[]);
            pass.set_vertex_buffer(0, terrain.grid.slice(..));
            pass.set_vertex_buffer(1, terrain.tiles.slice(..));
            pass.set_index_buffer(terrain.indices.slice(..), wgpu::IndexFormat::Uint32);
            pass.draw_indexed(0..terrain.index_count, 0, 0..terrain.tile_count);
            if let (Some(moon), Some((moon_luts, _))) = (&terrain.moon, &self.moonlit) {
                pass.set_pipeline(&moon.pipeline);
                pass.set_bind_group(0, moon_luts.uniform_bind_group(), &[]);
                pass.set_bind_group(1, moon_luts.table_bind_group(), &[]);
                pass.set_bind_group(2, &moon.bind_group, &[]);
                pass.draw_indexed(0..terrain.index_count, 0, 0..terrain.tile_count);
            }
            if let (Some(moon), Some(rung)) = (&terrain.moon, &self.rung) {
                pass.set_pipeline(&moon.pipeline);
                rung.bind_terrain(&mut pass, true);
                if let Some(air) = &terrain.vertex_air {
                    air.bind(&mut pass, true);
                }
                pass.set_bind_group(2, &moon.bind_group, &[]);
                pass.draw_indexed(0..terrain.index_count, 0, 0..terrain.tile_count);
            }
            drop(pass);
            // A rung without tables: the aerial perspective per pixel (compute).
            if let Some(rung) = &self.rung {
                rung.encode_air(encoder, &self.hdr, times)?;
            }
        }
        if let Some(objects) = &self.sky_objects {
            objects.encode(
                encoder,
                &self.hdr_view,
                Some(&self.depth_view),
                times.and_then(|t| t.render_writes("sky objects")),
            )?;
        }
        if let Some(clouds) = &self.clouds {
            super::cloud_composite::draw_fullscreen(
                encoder,
                "render clouds",
                &self.hdr_view,
                times.and_then(|t| t.render_writes("clouds")),
                &clouds.pipeline,
                &clouds.bind_group,
            );
        }
        if let Some(distance) = &self.cloud_distance {
            // After the terrain (the marches stop at its depth), once for both clouds.
            distance.encode(encoder)?;
        }
        if let (Some(order), Some(shell), Some(volume), Some((luts, moon_luts))) = (
            &self.cloud_order,
            &self.shell_cloud,
            &self.volume_cloud,
            self.cloud_airs(),
        ) {
            // Both marched clouds: their marches and air, then one composite by depth.
            let compute = |label| times.and_then(|t| t.compute_writes(label));
            let (march, moon) = (compute("shell cloud march"), compute("moonlit shell march"));
            shell.encode_marches(encoder, luts, moon_luts, march, moon)?;
            let (march, moon) = (
                compute("volume cloud march"),
                compute("moonlit cloud march"),
            );
            volume.encode_marches(encoder, luts, moon_luts, march, moon)?;
            let composite = times.and_then(|t| t.render_writes("clouds by depth"));
            order.encode(encoder, &self.hdr_view, composite)?;
        }
        let alone = self.cloud_order.is_none();
        if let (Some(shell), Some((luts, moon_luts)), true) =
            (&self.shell_cloud, self.cloud_airs(), alone)
        {
            // After the terrain (the march stops at its depth), before the volume cloud.
            shell.encode(
                encoder,
                &self.hdr_view,
                luts,
                moon_luts,
                super::cloud_composite::CloudTimes {
                    march: times.and_then(|t| t.compute_writes("shell cloud march")),
                    moon: times.and_then(|t| t.compute_writes("moonlit shell march")),
                    composite: times.and_then(|t| t.render_writes("shell clouds")),
                },
            )?;
        }
        if let (Some(volume), Some((luts, moon_luts)), true) =
            (&self.volume_cloud, self.cloud_airs(), alone)
        {
            // After the terrain: the march stops at its depth.
            volume.encode(
                encoder,
                &self.hdr_view,
                luts,
                moon_luts,
                super::cloud_composite::CloudTimes {
                    march: times.and_then(|t| t.compute_writes("volume cloud march")),
                    moon: times.and_then(|t| t.compute_writes("moonlit cloud march")),
                    composite: times.and_then(|t| t.render_writes("volume clouds")),
                },
            )?;
        }
        if let Some(billboards) = &self.billboard_cloud {
            // After the terrain: its depth hides the particles behind it.
            billboards.encode(
                encoder,
                &self.hdr_view,
                &self.depth_view,
                self.luts.as_ref(),
                times.and_then(|t| t.render_writes("billboard clouds")),
            )?;
        }
        {
            let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
                label: Some("render display"),
                timestamp_writes: times.and_then(|t| t.compute_writes("display")),
            });
            pass.set_pipeline(&self.display_pipeline);
            pass.set_bind_group(0, &self.display_group, &[]);
            pass.dispatch_workgroups(self.width.div_ceil(8), self.height.div_ceil(8), 1);
        }
        if let Some(times) = times {
            times.resolve(encoder);
        }
        Ok(())
    }

    /// The frame's RGBA8 pixels (one `u32` each, R in the low byte; `COPY_SRC`).
    pub fn pixel_buffer(&self) -> &wgpu::Buffer {
        &self.pixels
    }

    /// The frame's HDR radiance × the scene's exposure (`rgba16float`: exposed, so a
    /// night's radiance stays inside f16's normal range; divide by
    /// `PreparedScene::present.exposure` for radiance).
    pub fn radiance_texture(&self) -> &wgpu::Texture {
        &self.hdr
    }

    /// Tiles the terrain drew in the prepared frame.
    pub fn terrain_tiles(&self) -> u32 {
        self.terrain.as_ref().map_or(0, |t| t.tile_count)
    }

    /// GPU seconds per pass of the last submitted frame (after its submission), when
    /// timestamps were asked for and the device has them.
    pub fn pass_seconds(&self) -> Option<Result<Vec<(&'static str, f64)>, String>> {
        self.times.as_ref().map(|t| t.read(&self.device))
    }
}
