//! `skyscape view`: the scene in a window, drawn every frame by the same passes as
//! `skyscape render` (`render::gpu::SceneRenderer`), flown through with the mouse and
//! keys while the sun moves; choices switch live and only what they change is
//! prepared again (on a thread of its own, with one `PrepareCache` for the run).
//! Controls and measurements: `docs/viewer.md`.

mod app;
mod camera;
mod overlay;
mod script;
mod shots;
mod state;
mod window_gpu;
mod worker;

use std::path::PathBuf;

use clap::Args;

use crate::{Failure, backends, load_scene};

/// `skyscape view`'s arguments.
#[derive(Debug, Args)]
pub(crate) struct ViewArgs {
    /// The scene: a .toml file or a shipped scene's name. [default: default]
    pub(crate) scene: Option<String>,
    /// Restrict the adapter search to these backends (vulkan, gl, metal, dx12).
    #[arg(long)]
    pub(crate) backend: Option<String>,
    /// The window's size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1280x720")]
    pub(crate) size: String,
    /// Draw the scene at this fraction of the window's pixels, in (0, 1] [1 on a GPU,
    /// 0.5 on a CPU adapter].
    #[arg(long)]
    pub(crate) scale: Option<f64>,
    /// Present as fast as the GPU draws instead of at the display's refresh.
    #[arg(long)]
    pub(crate) no_vsync: bool,
    /// Start with the overlay hidden (F1 shows it).
    #[arg(long)]
    pub(crate) no_overlay: bool,
    /// A file of timed actions to run (camera moves, time, rung, screenshots, quit):
    /// see docs/viewer.md.
    #[arg(long)]
    pub(crate) script: Option<PathBuf>,
    /// Write the first N frames as PNGs into --out, then quit (after the script, if
    /// one runs).
    #[arg(long, requires = "out", value_name = "N")]
    pub(crate) record: Option<u32>,
    /// The folder --record writes frame-0000.png, … into (created if missing; no file
    /// in it is replaced).
    #[arg(long, requires = "record", value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// At exit, write the median GPU time per pass and the median frame time over the
    /// frames drawn (Markdown, replaced when complete): the figures of
    /// docs/viewer-timings.md.
    #[arg(long, value_name = "FILE")]
    pub(crate) timings: Option<PathBuf>,
    /// Where F12 writes its screenshots. [the current folder]
    #[arg(long, value_name = "DIR")]
    pub(crate) screenshot_dir: Option<PathBuf>,
    /// Where the atmosphere's precomputed tables are kept between runs.
    /// [$XDG_CACHE_HOME/skyscape, else ~/.cache/skyscape]
    #[arg(long, conflicts_with = "no_cache")]
    pub(crate) cache_dir: Option<PathBuf>,
    /// Keep nothing between runs.
    #[arg(long)]
    pub(crate) no_cache: bool,
}

/// The checked arguments.
#[derive(Debug, Clone)]
pub(crate) struct ViewOptions {
    pub(crate) scene: Option<String>,
    pub(crate) scene_label: String,
    pub(crate) backends: wgpu::Backends,
    pub(crate) size: (u32, u32),
    pub(crate) scale: Option<f64>,
    pub(crate) no_vsync: bool,
    pub(crate) no_overlay: bool,
    pub(crate) script: Option<script::Script>,
    pub(crate) record: Option<u32>,
    pub(crate) out: Option<PathBuf>,
    pub(crate) screenshot_folder: PathBuf,
    pub(crate) timings: Option<PathBuf>,
}

/// The scene named on the command line (for `F5`, read again).
pub(crate) fn load(scene: &Option<String>) -> Result<render::scene::Scene, String> {
    load_scene(scene.as_deref())
        .map(|(scene, _)| scene)
        .map_err(|failure| match failure {
            Failure::Input(m) | Failure::Runtime(m) => m,
        })
}

/// `WIDTHxHEIGHT`, each side in 1..=16384.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let bad = || format!("--size `{text}`: give WIDTHxHEIGHT, each 1 to 16384 pixels (1280x720)");
    let (width, height) = text.split_once(['x', '×']).ok_or_else(bad)?;
    let side = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=16_384).contains(v))
            .ok_or_else(bad)
    };
    Ok((side(width)?, side(height)?))
}

/// Every argument checked before the window opens.
fn options(args: &ViewArgs) -> Result<ViewOptions, Failure> {
    let backends = backends(args.backend.as_deref())?;
    let size = parse_size(&args.size).map_err(Failure::Input)?;
    if let Some(scale) = args.scale
        && !(scale > 0.0 && scale <= 1.0)
    {
        return Err(Failure::Input(format!(
            "--scale {scale}: must be in (0, 1]"
        )));
    }
    let script = match &args.script {
        Some(path) => Some(script::Script::open(path).map_err(Failure::Input)?),
        None => None,
    };
    if let (Some(count), Some(folder)) = (args.record, &args.out) {
        if count == 0 {
            return Err(Failure::Input(
                "--record 0: record at least one frame".into(),
            ));
        }
        shots::check_record_folder(folder, count).map_err(Failure::Input)?;
    }
    if let Some(path) = &args.timings
        && path.is_dir()
    {
        return Err(Failure::Input(format!(
            "--timings `{}`: is a folder, give a file",
            path.display()
        )));
    }
    let screenshot_folder = args
        .screenshot_dir
        .clone()
        .unwrap_or_else(|| PathBuf::from("."));
    if !screenshot_folder.is_dir() {
        return Err(Failure::Input(format!(
            "--screenshot-dir `{}`: not a folder",
            screenshot_folder.display()
        )));
    }
    Ok(ViewOptions {
        scene: args.scene.clone(),
        scene_label: args.scene.clone().unwrap_or_else(|| "default".into()),
        backends,
        size,
        scale: args.scale,
        no_vsync: args.no_vsync,
        no_overlay: args.no_overlay,
        script,
        record: args.record,
        out: args.out.clone(),
        screenshot_folder,
        timings: args.timings.clone(),
    })
}

pub(crate) fn view_command(args: ViewArgs) -> Result<(), Failure> {
    let options = options(&args)?;
    let (scene, _) = load_scene(args.scene.as_deref())?;
    // The first preparation runs on the preparation thread while the window shows its
    // stages; a scene that cannot be prepared ends the viewer with the error naming
    // its field.
    let cache = crate::prepare_cache(args.no_cache, args.cache_dir.clone());
    let event_loop = winit::event_loop::EventLoop::new().map_err(|e| {
        Failure::Runtime(format!(
            "no window system ({e}): skyscape view needs a display (DISPLAY or \
             WAYLAND_DISPLAY; on a headless machine, xvfb-run)"
        ))
    })?;
    let state = state::ViewState::new(scene, options.scale.unwrap_or(1.0));
    let preparer = worker::Preparer::start(cache);
    let mut app = app::App::new(options, state, preparer);
    event_loop
        .run_app(&mut app)
        .map_err(|e| Failure::Runtime(format!("the window's event loop: {e}")))?;
    if let Some(path) = &app.options_timings() {
        app.write_timings(path).map_err(Failure::Runtime)?;
    }
    match app.failure.take() {
        Some(failure) => Err(failure),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::parse_size;

    #[test]
    fn sizes_parse_or_name_the_flag() {
        assert_eq!(parse_size("1280x720"), Ok((1280, 720)));
        assert_eq!(parse_size("64×32"), Ok((64, 32)));
        for bad in ["1280", "0x10", "axb", "20000x10"] {
            assert!(parse_size(bad).unwrap_err().starts_with("--size"), "{bad}");
        }
    }
}
