//! What the GPU passes of a frame share: the render targets, the atmosphere of each
//! light (atmos' tables, or a rung's own passes), and the interface every pass of
//! [`crate::passes::FRAME`] implements on the GPU.

use atmos::gpu::AtmosphereLuts;

use super::cloud_air::CloudAir;
use super::timer::PassTimes;
use crate::RenderError;
use crate::scene::prepare::PreparedScene;

/// The HDR target's format: radiance × the scene's exposure.
pub(crate) const HDR: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// The depth target's format (reverse z: near 1, infinitely far 0).
pub(crate) const DEPTH: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// The most lights the GPU renderer draws: the sun and one light added to it (the moon
/// on a moonlit night). The passes keep their lights as lists, but the WGSL that adds
/// the lights in one shader (the marched clouds' composite, the rungs' terrain air, the
/// billboards' rung air) binds two; a scene with more is refused when the renderer is
/// built (`SceneRenderer::new`), naming the count. The CPU renderer has no such bound.
pub const MAX_LIGHTS: usize = 2;

/// Quality choices of the GPU renderer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneRendererSettings {
    /// The terrain's largest projected geometric error (pixels): smaller draws more
    /// tiles.
    pub terrain_error_px: f64,
    /// Record GPU timestamps per pass (when the device has `TIMESTAMP_QUERY`).
    pub timestamps: bool,
    /// Amortise the marched clouds over frames (`cloudlight::gpu::TemporalMarch`: a
    /// quarter of the cloud pixels marched each frame, the others reprojected from the
    /// last frame; a still camera's image is the full march's after four frames). For a
    /// renderer that draws a sequence of frames from a moving camera (`skyscape view`);
    /// off by default, so that every frame is the full march.
    pub temporal_clouds: bool,
}

impl Default for SceneRendererSettings {
    fn default() -> Self {
        Self {
            terrain_error_px: crate::aerial_vertex::TERRAIN_ERROR_PX,
            timestamps: false,
            temporal_clouds: false,
        }
    }
}

/// The resources the frame's passes share: the device, the targets and each light's
/// atmosphere on the GPU.
#[derive(Debug)]
pub(crate) struct GpuShared {
    pub(crate) device: wgpu::Device,
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) settings: SceneRendererSettings,
    /// Radiance × exposure (`rgba16float`).
    pub(crate) hdr: wgpu::Texture,
    pub(crate) hdr_view: wgpu::TextureView,
    pub(crate) depth_view: wgpu::TextureView,
    /// The precomputed rung's tables per light of the frame, the sun's first (on a
    /// moonlit night the moon's after it); empty for a rung without tables.
    pub(crate) tables: Vec<AtmosphereLuts>,
    /// The sky, terrain and air passes of a rung without tables (both lights).
    pub(crate) rung: Option<super::rungs::RungPasses>,
    /// The scene's rung.
    pub(crate) rung_kind: crate::scene::Rung,
}

impl GpuShared {
    /// The sun's tables (the precomputed rung).
    pub(crate) fn sun_tables(&self) -> Option<&AtmosphereLuts> {
        self.tables.first()
    }

    /// A marched cloud's air for each of the scene's lights (the sun first): the
    /// precomputed rung's tables or the passes of a rung without tables
    /// (`super::cloud_air`); an error naming the rung when there are neither (the
    /// reference rungs).
    pub(crate) fn cloud_airs(&self) -> Result<Vec<CloudAir<'_>>, RenderError> {
        let airs: Vec<CloudAir<'_>> = match &self.rung {
            _ if !self.tables.is_empty() => self.tables.iter().map(CloudAir::Tables).collect(),
            Some(rung) => (0..rung.light_count())
                .filter_map(|index| rung.cloud_air(index))
                .collect(),
            None => Vec::new(),
        };
        if airs.is_empty() {
            return Err(super::rung_kind::volume_needs_tables(self.rung_kind));
        }
        Ok(airs)
    }
}

/// A pass of the frame on the GPU: built by its [`crate::passes::PassEntry`] for a
/// scene that runs it.
pub(crate) trait GpuPass: std::any::Any + std::fmt::Debug + Send + Sync {
    /// Writes the frame's uniforms and (re)binds what changed (`shared` is mutable for
    /// the tables pass, which prepares each light's atmosphere).
    fn prepare(
        &mut self,
        shared: &mut GpuShared,
        queue: &wgpu::Queue,
        scene: &PreparedScene,
    ) -> Result<(), RenderError>;

    /// Records the pass into the caller's encoder, each step timed under its plan line's
    /// label.
    fn encode(
        &mut self,
        shared: &GpuShared,
        encoder: &mut wgpu::CommandEncoder,
        times: Option<&PassTimes>,
    ) -> Result<(), RenderError>;
}

/// The error of a scene prepared on a renderer built for another: `field` given
/// (`built` false) or absent (`built` true).
pub(crate) fn differs(field: &'static str, built: bool) -> RenderError {
    RenderError::InvalidParameter {
        field,
        value: if built { "absent" } else { "given" }.into(),
        reason: "differs from the scene the renderer was built for",
    }
}
