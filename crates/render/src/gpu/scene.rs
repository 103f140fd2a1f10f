//! A scene on the GPU: the frame's passes ([`crate::passes::FRAME`]) that the scene
//! runs, in order. Bring your own device: [`SceneRenderer::new`] builds only the passes
//! the scene needs (no terrain: no terrain pipeline, no buffers; no `[time]`: no sky
//! objects, no moonlit tables; no cloud layers: no cloud pipeline; no
//! `[clouds.volume]`: no march, no composite), [`SceneRenderer::prepare`] writes the
//! frame's uniforms, [`SceneRenderer::encode`] records each pass into the caller's
//! encoder and never submits.
//!
//! The half-float HDR target holds radiance × the scene's exposure (a night's radiance
//! would flush in f16's subnormals otherwise). The CPU twin is `render::cpu_renderer`,
//! which runs the same list. The precomputed rung's tables are atmos'; the closed
//! form's and single scattering's sky, terrain and cloud air are in
//! `render::gpu::rungs` and `render::gpu::cloud_air`; the reference rungs (f64) render
//! on the CPU only.

use atmos::gpu::AtmosphereLuts;

pub use super::frame::SceneRendererSettings;
use super::frame::{DEPTH, GpuPass, GpuShared, HDR};
use crate::RenderError;
use crate::gpu::timer::PassTimes;
use crate::scene::prepare::PreparedScene;

/// Every pass of a scene on the GPU.
#[derive(Debug)]
pub struct SceneRenderer {
    shared: GpuShared,
    /// The passes the scene runs, in frame order, with their names.
    passes: Vec<(&'static str, Box<dyn GpuPass>)>,
    /// The timestamp spans the plan gives the scene (whether or not they are recorded).
    spans: Vec<&'static str>,
    prepared: bool,
    times: Option<PassTimes>,
    /// What the passes baked at [`SceneRenderer::new`] and `prepare` does not write
    /// again: the lights' atmospheres (tables, rung parameters) and the terrain.
    built_for: BuiltFor,
}

/// The inputs a [`SceneRenderer`] fixes when it is built: a scene whose lights'
/// atmospheres or terrain differ needs a new renderer (`prepare` says so rather than
/// drawing with the old ones).
#[derive(Debug, Clone, PartialEq)]
struct BuiltFor {
    atmospheres: Vec<atmos::Atmosphere>,
    /// The heightfield's size, spacing and a hash of its samples' bits.
    terrain: Option<(usize, usize, u64, u64)>,
}

impl BuiltFor {
    fn of(scene: &PreparedScene) -> Self {
        use std::hash::{Hash, Hasher};
        let terrain = scene.terrain.as_ref().map(|t| {
            let hf = &t.heightfield;
            let mut hasher = std::collections::hash_map::DefaultHasher::new();
            for sample in hf.samples() {
                sample.to_bits().hash(&mut hasher);
            }
            (
                hf.width(),
                hf.height(),
                hf.spacing().to_bits(),
                hasher.finish(),
            )
        });
        Self {
            atmospheres: scene
                .lights()
                .iter()
                .map(|l| l.atmosphere.clone())
                .collect(),
            terrain,
        }
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
        let shared = shared_resources(device, scene, settings)?;
        let passes = crate::passes::frame_passes(scene)
            .map(|entry| Ok((entry.name, (entry.gpu)(&shared, scene)?)))
            .collect::<Result<Vec<_>, RenderError>>()?;
        let spans = crate::passes::timestamp_spans(scene);
        let times = if settings.timestamps {
            PassTimes::new(device, queue, spans.clone())
        } else {
            None
        };
        Ok(Self {
            shared,
            passes,
            spans,
            prepared: false,
            times,
            built_for: BuiltFor::of(scene),
        })
    }

    /// Writes the frame's uniforms: each pass's, for this scene's camera and lights.
    ///
    /// Everything that depends on the view is written here, so one renderer draws any
    /// number of frames of its scene: a panorama's six faces are the scene turned by
    /// `PreparedScene::look_along` and prepared again (same size), each bit for bit the
    /// face a renderer built for it draws (`tests/panorama_gpu.rs`), and an animation's
    /// frames whose sun or moon moved are drawn by one renderer. A scene that runs other
    /// passes or steps than the one the renderer was built for, or whose lights'
    /// atmospheres or terrain differ from those it baked, is an error (build a new
    /// renderer for it).
    pub fn prepare(
        &mut self,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError> {
        let device = self.shared.device.clone();
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
        if (camera.width, camera.height) != (self.shared.width, self.shared.height) {
            return Err(RenderError::InvalidParameter {
                field: "output.width",
                value: format!("{}×{}", camera.width, camera.height),
                reason: "differs from the size the renderer was built for",
            });
        }
        let passes: Vec<_> = crate::passes::frame_passes(scene)
            .map(|entry| entry.name)
            .collect();
        let spans = crate::passes::timestamp_spans(scene);
        if passes != self.pass_names() || spans != self.spans {
            return Err(RenderError::InvalidParameter {
                field: "scene",
                value: format!("passes {passes:?}, steps {spans:?}"),
                reason: "differs from the scene the renderer was built for",
            });
        }
        if BuiltFor::of(scene) != self.built_for {
            return Err(RenderError::InvalidParameter {
                field: "scene",
                value: "other lights' atmospheres or another terrain".into(),
                reason: "differs from the scene the renderer was built for",
            });
        }
        for (_, pass) in &mut self.passes {
            pass.prepare(&mut self.shared, queue, scene)?;
        }
        self.prepared = true;
        Ok(())
    }

    /// Records the frame: each pass in order, then the timestamps' resolve.
    pub fn encode(&mut self, encoder: &mut wgpu::CommandEncoder) -> Result<(), RenderError> {
        if !self.prepared {
            return Err(RenderError::NotPrepared);
        }
        if let Some(times) = &self.times {
            times.begin_frame();
        }
        for (_, pass) in &mut self.passes {
            pass.encode(&self.shared, encoder, self.times.as_ref())?;
        }
        if let Some(times) = &self.times {
            times.resolve(encoder);
        }
        Ok(())
    }

    /// The names of the passes built, in the order `encode` records them.
    pub fn pass_names(&self) -> Vec<&'static str> {
        self.passes.iter().map(|(name, _)| *name).collect()
    }

    /// The frame's RGBA8 pixels (one `u32` each, R in the low byte; `COPY_SRC`).
    pub fn pixel_buffer(&self) -> &wgpu::Buffer {
        &self
            .pass::<crate::passes::display::gpu::DisplayPass>()
            .expect("every frame ends with the display pass")
            .pixels
    }

    /// The frame's HDR radiance × the scene's exposure (`rgba16float`: exposed, so a
    /// night's radiance stays inside f16's normal range; divide by
    /// `PreparedScene::present.exposure` for radiance).
    pub fn radiance_texture(&self) -> &wgpu::Texture {
        &self.shared.hdr
    }

    /// Tiles the terrain drew in the prepared frame.
    pub fn terrain_tiles(&self) -> u32 {
        self.pass::<crate::passes::terrain::gpu::TerrainPass>()
            .map_or(0, |terrain| terrain.tile_count())
    }

    /// GPU seconds per pass of the last submitted frame (after its submission), when
    /// timestamps were asked for and the device has them.
    pub fn pass_seconds(&self) -> Option<Result<Vec<(&'static str, f64)>, String>> {
        self.times.as_ref().map(|t| t.read(&self.shared.device))
    }

    /// The timestamp spans the last `encode` recorded, in order (empty without
    /// timestamps).
    pub fn recorded_spans(&self) -> Vec<&'static str> {
        self.times
            .as_ref()
            .map_or_else(Vec::new, PassTimes::recorded)
    }

    /// The built pass of type `P`, if the scene runs it.
    fn pass<P: GpuPass + 'static>(&self) -> Option<&P> {
        self.passes.iter().find_map(|(_, pass)| {
            let any: &dyn std::any::Any = pass.as_ref();
            any.downcast_ref::<P>()
        })
    }
}

/// The frame's targets and each light's atmosphere on the GPU.
fn shared_resources(
    device: &wgpu::Device,
    scene: &PreparedScene,
    settings: SceneRendererSettings,
) -> Result<GpuShared, RenderError> {
    let (width, height) = (scene.camera.width, scene.camera.height);
    let limit = device.limits().max_texture_dimension_2d;
    if width > limit || height > limit {
        return Err(RenderError::InvalidParameter {
            field: "output.width",
            value: format!("{width}×{height}"),
            reason: "beyond the device's largest texture side",
        });
    }
    let lights = scene.lights().len();
    if lights > super::frame::MAX_LIGHTS {
        return Err(RenderError::InvalidParameter {
            field: "lights",
            value: format!("{lights} lights"),
            reason: "the GPU renderer draws the sun and one light added to it (the CPU \
                     renderer draws any number)",
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
    // Each light's tables: the sun's, then one set per other light (the moon's on a
    // moonlit night).
    let mut tables: Vec<AtmosphereLuts> = luts.into_iter().collect();
    if !tables.is_empty() {
        for light in &scene.other_lights {
            tables.push(AtmosphereLuts::new(
                device,
                &light.atmosphere,
                &Default::default(),
            )?);
        }
    }
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
    // The cloud passes read the terrain's depth.
    let depth = target(
        DEPTH,
        wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
    );
    Ok(GpuShared {
        device: device.clone(),
        width,
        height,
        settings,
        hdr_view: hdr.create_view(&Default::default()),
        depth_view: depth.create_view(&Default::default()),
        hdr,
        tables,
        rung,
        rung_kind: scene.rung,
    })
}
