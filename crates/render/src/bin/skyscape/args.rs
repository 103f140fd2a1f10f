//! The `render` command's arguments.

use crate::*;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum Format {
    /// 8-bit sRGB, tone-mapped and dithered.
    Png,
    /// 8-bit sRGB as PNG's, lossy (quality 92), no alpha.
    #[value(alias = "jpg")]
    Jpeg,
    /// 32-bit float linear radiance (the unit of the sun's irradiance per sr).
    Exr,
}

impl Format {
    /// As `--format` spells it.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Jpeg => "jpeg",
            Format::Exr => "exr",
        }
    }

    /// The extension of the default output's name.
    pub(crate) fn extension(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Jpeg => "jpg",
            Format::Exr => "exr",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum ProjectionArg {
    Rectilinear,
    Cubemap,
    Equirectangular,
    Fisheye,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum DisplayTransformArg {
    /// Hue-preserving: the brightest channel follows a curve, the others keep their
    /// ratios to it, with a bounded path to white.
    Neutral,
    /// 1 − exp(−x) on each channel alone.
    PerChannel,
}

#[derive(Debug, Args, Default)]
pub(crate) struct RenderArgs {
    /// The scene: a .toml file or a shipped scene's name (`skyscape scenes`).
    pub(crate) scene: Option<String>,
    #[command(flatten)]
    pub(crate) output: OutputArgs,
    #[command(flatten)]
    pub(crate) overrides: SceneOverrides,
    #[command(flatten)]
    pub(crate) animation: AnimationArgs,
    /// Render on the CPU reference renderer even if a GPU adapter exists.
    #[arg(long)]
    pub(crate) cpu: bool,
    /// Render on the GPU and on the CPU and report how many pixels agree.
    #[arg(long, conflicts_with = "cpu")]
    pub(crate) compare: bool,
    /// Print the passes that run and their measured GPU cost.
    #[arg(long)]
    pub(crate) explain: bool,
    /// Restrict the adapter search to these backends (vulkan, gl, metal, dx12).
    #[arg(long)]
    pub(crate) backend: Option<String>,
    /// Where the atmosphere's precomputed tables are kept between runs (one file per
    /// atmosphere, written whole; a second run of a scene skips their bake).
    /// [$XDG_CACHE_HOME/skyscape, else ~/.cache/skyscape]
    #[arg(long, conflicts_with = "no_cache")]
    pub(crate) cache_dir: Option<PathBuf>,
    /// Keep nothing between runs (the tables are baked again each run).
    #[arg(long)]
    pub(crate) no_cache: bool,
}

impl RenderArgs {
    /// The preparation cache these arguments ask for.
    pub(crate) fn prepare_cache(&self) -> render::scene::PrepareCache {
        prepare_cache(self.no_cache, self.cache_dir.clone())
    }
}

/// The preparation cache `--no-cache` and `--cache-dir` ask for: in memory only, or
/// also in a folder (by default `$XDG_CACHE_HOME/skyscape`, else `~/.cache/skyscape`).
pub(crate) fn prepare_cache(
    no_cache: bool,
    cache_dir: Option<PathBuf>,
) -> render::scene::PrepareCache {
    let home_cache = || {
        let base = std::env::var_os("XDG_CACHE_HOME")
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
            .or_else(|| {
                std::env::var_os("HOME")
                    .filter(|v| !v.is_empty())
                    .map(|home| PathBuf::from(home).join(".cache"))
            })?;
        Some(base.join("skyscape"))
    };
    match (no_cache, cache_dir.or_else(home_cache)) {
        (false, Some(folder)) => render::scene::PrepareCache::in_folder(folder),
        _ => render::scene::PrepareCache::new(),
    }
}

/// Where and how the image is written.
#[derive(Debug, Args, Default)]
pub(crate) struct OutputArgs {
    /// Where to write the image: a file (replaced only when the image is complete), a
    /// device or FIFO (written through), or - (standard output). An animation's name
    /// holds `{frame}` (numbered 0000, 0001, …). [the scene's output.path, else
    /// target/skyscape/NAME.png]
    #[arg(short, long, allow_hyphen_values = true)]
    pub(crate) output: Option<PathBuf>,
    /// Output format [from the output's extension (.png, .jpg, .exr), else png].
    #[arg(long, value_enum)]
    pub(crate) format: Option<Format>,
    /// Create the output's folder if it does not exist (otherwise a missing folder is
    /// an error).
    #[arg(long)]
    pub(crate) mkdir: bool,
}

/// Values that override the scene file's.
#[derive(Debug, Args, Default)]
pub(crate) struct SceneOverrides {
    /// Image width, pixels (overrides the scene's).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) width: Option<i64>,
    /// Image height, pixels (overrides the scene's).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) height: Option<i64>,
    /// The output's projection (overrides the scene's): rectilinear, cubemap (a 6:1
    /// strip; width = 6 × height), equirectangular, fisheye.
    #[arg(long, value_enum)]
    pub(crate) projection: Option<ProjectionArg>,
    /// The atmosphere's rung (overrides the scene's): dome, closed-form,
    /// closed-form-vertex, single, precomputed, reference, reference-spectral.
    #[arg(long)]
    pub(crate) rung: Option<String>,
    /// The sun's elevation, degrees (overrides the scene's).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) sun_elevation_deg: Option<f64>,
    /// The sun's azimuth clockwise from north, degrees (overrides the scene's).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) sun_azimuth_deg: Option<f64>,
    /// Exposure before the display transform (overrides the scene's).
    #[arg(long, allow_hyphen_values = true)]
    pub(crate) exposure: Option<f32>,
    /// How exposed radiance becomes display values (overrides the scene's): neutral
    /// (hue-preserving) or per-channel (1 − exp(−x)).
    #[arg(long, value_enum)]
    pub(crate) display_transform: Option<DisplayTransformArg>,
}

/// Which frames of the scene's animation.
#[derive(Debug, Args, Default)]
pub(crate) struct AnimationArgs {
    /// The animation's length in frames (overrides the scene's `[animation] frames`;
    /// the scene must have `[animation]`).
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) frames: Option<i64>,
    /// Only frames a..b (half-open, within the animation's length), to split it
    /// across machines.
    #[arg(long, value_parser = parse_range, allow_hyphen_values = true)]
    pub(crate) frame_range: Option<(u32, u32)>,
}

pub(crate) fn parse_range(text: &str) -> Result<(u32, u32), String> {
    let (a, b) = text
        .split_once("..")
        .ok_or_else(|| format!("`{text}` is not a range a..b"))?;
    let parse = |s: &str| {
        s.parse::<u32>()
            .map_err(|_| format!("`{s}` in `{text}` is not a frame number (0, 1, 2, …)"))
    };
    let (a, b) = (parse(a)?, parse(b)?);
    if a >= b {
        return Err(format!("`{text}`: the range must not be empty (a < b)"));
    }
    Ok((a, b))
}
