//! The frame as one ordered list of passes, [`FRAME`].
//!
//! Everything that is written per pass derives from this list:
//!
//! * the GPU's [`SceneRenderer`](crate::gpu::SceneRenderer) builds, prepares and records
//!   the passes a scene runs, in this order, into the caller's encoder;
//! * the CPU reference renderer ([`crate::cpu_renderer`]) composites each pass's twin in
//!   the same order;
//! * `skyscape explain` prints each pass's [`PlanLine`]s (what runs and why, what is
//!   skipped and why), and the GPU's timestamp spans are the plan's timed lines.
//!
//! A pass is one folder here: its plan (`mod.rs`), its CPU twin and its GPU pass
//! (`gpu.rs`). Adding one is that folder and one entry in [`FRAME`]; the test
//! `frame_list` fails when the GPU's passes, the CPU's, the timestamps recorded and the
//! plan disagree for any shipped scene.

pub mod billboards;
pub mod cloud_layers;
pub mod display;
pub mod marched_clouds;
pub mod sky;
pub mod sky_objects;
pub mod tables;
pub mod terrain;

use crate::RenderError;
use crate::scene::prepare::PreparedScene;

/// One line of a pass's plan: a step of the pass, run (`Ok`, what it does) or skipped
/// (`Err`, why).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanLine {
    /// The step's name; for a timed step, its GPU timestamp span.
    pub label: &'static str,
    /// What the step does, or why the scene skips it.
    pub status: Result<String, String>,
    /// Whether the GPU times the step (a span of its own) when it runs.
    pub timed: bool,
}

impl PlanLine {
    /// A timed step.
    pub fn timed(label: &'static str, status: Result<String, String>) -> Self {
        Self {
            label,
            status,
            timed: true,
        }
    }

    /// A step without a span of its own (a property of another step's pass).
    pub fn untimed(label: &'static str, status: Result<String, String>) -> Self {
        Self {
            label,
            status,
            timed: false,
        }
    }
}

/// One entry of the frame: a pass, whether a scene runs it, its plan, its CPU twin and
/// (feature `gpu`) how to build its GPU pass.
pub struct PassEntry {
    /// The pass's name (`skyscape explain`'s heading).
    pub name: &'static str,
    /// Whether `scene` runs the pass.
    pub runs: fn(&PreparedScene) -> bool,
    /// The pass's steps for `scene`, each run or skipped with the reason.
    pub plan: fn(&PreparedScene) -> Vec<PlanLine>,
    /// The CPU twin: composites the pass into the CPU renderer's frame.
    pub(crate) cpu: fn(&mut crate::cpu_frame::CpuFrame<'_>) -> Result<(), RenderError>,
    /// Builds the GPU pass (only for a scene that runs it).
    #[cfg(feature = "gpu")]
    pub(crate) gpu: BuildGpuPass,
}

/// Builds a pass's GPU resources for a scene that runs it.
#[cfg(feature = "gpu")]
pub(crate) type BuildGpuPass = fn(
    &crate::gpu::frame::GpuShared,
    &PreparedScene,
) -> Result<Box<dyn crate::gpu::frame::GpuPass>, RenderError>;

impl std::fmt::Debug for PassEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PassEntry")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

/// The frame's passes, in the order both renderers run them.
pub const FRAME: [PassEntry; 8] = [
    tables::ENTRY,
    sky::ENTRY,
    terrain::ENTRY,
    sky_objects::ENTRY,
    cloud_layers::ENTRY,
    marched_clouds::ENTRY,
    billboards::ENTRY,
    display::ENTRY,
];

/// The entries of [`FRAME`] that `scene` runs, in order.
pub fn frame_passes(scene: &PreparedScene) -> impl Iterator<Item = &'static PassEntry> + '_ {
    FRAME.iter().filter(|entry| (entry.runs)(scene))
}

/// Every pass's plan for `scene`, in frame order (a pass the scene does not run has
/// every line skipped).
pub fn plan(scene: &PreparedScene) -> Vec<PlanLine> {
    FRAME
        .iter()
        .flat_map(|entry| {
            let runs = (entry.runs)(scene);
            (entry.plan)(scene).into_iter().inspect(move |line| {
                debug_assert!(
                    runs || line.status.is_err(),
                    "{}: `{}` runs in a pass the scene skips",
                    entry.name,
                    line.label
                );
            })
        })
        .collect()
}

/// The GPU's timestamp spans for `scene`: the plan's timed steps that run, in order.
pub fn timestamp_spans(scene: &PreparedScene) -> Vec<&'static str> {
    plan(scene)
        .into_iter()
        .filter(|line| line.timed && line.status.is_ok())
        .map(|line| line.label)
        .collect()
}

/// What `skyscape explain` prints: each step with what it does or why it is skipped.
pub fn planned_passes(scene: &PreparedScene) -> Vec<(&'static str, Result<String, String>)> {
    plan(scene)
        .into_iter()
        .map(|line| (line.label, line.status))
        .collect()
}

/// The sky model's name for plan text: "the closed form", "single scattering", or
/// `None` for a rung drawn through atmos' tables.
pub(crate) fn rung_model(scene: &PreparedScene) -> Option<&'static str> {
    scene.rung.gpu_model()
}

/// A light after the sun lights the scene (the moon on a moonlit night: the sun down,
/// the moon up).
pub(crate) fn moonlit(scene: &PreparedScene) -> bool {
    !scene.other_lights.is_empty()
}
