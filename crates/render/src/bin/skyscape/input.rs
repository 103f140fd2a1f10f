//! The scene named on the command line, the flags' overrides, and where frames go.

use crate::*;

/// The scene named on the command line (a file, or a shipped scene) and its name.
pub(crate) fn load_scene(name: Option<&str>) -> Result<(Scene, String), Failure> {
    let name = name.unwrap_or("default");
    let path = Path::new(name);
    if path.extension().is_some() || path.exists() {
        let scene =
            Scene::open(path).map_err(|e| Failure::Input(format!("{}: {e}", path.display())))?;
        let stem = path
            .file_stem()
            .map_or_else(|| "scene".to_owned(), |s| s.to_string_lossy().into_owned());
        return Ok((scene, stem));
    }
    let shipped = shipped(name).ok_or_else(|| {
        let names: Vec<&str> = SHIPPED.iter().map(|s| s.name).collect();
        Failure::Input(format!(
            "scene `{name}`: no such file, and not a shipped scene ({})",
            names.join(", ")
        ))
    })?;
    let scene = Scene::parse(shipped.source, ".")
        .map_err(|e| Failure::Input(format!("shipped scene {name}: {e}")))?;
    Ok((scene, name.to_owned()))
}

/// Applies the command line's overrides to the scene's values, each recorded as the
/// flag's ([`Scene::set_by_flag`]) so that an error about it names the flag.
pub(crate) fn apply_overrides(scene: &mut Scene, args: &RenderArgs) -> Result<(), Failure> {
    let side = |flag: &str, value: i64| {
        u32::try_from(value)
            .ok()
            .filter(|&v| (1..=render::scene::prepare::MAX_OUTPUT_SIDE).contains(&v))
            .ok_or_else(|| {
                Failure::Input(format!(
                    "{flag} {value}: must be in 1..={} pixels",
                    render::scene::prepare::MAX_OUTPUT_SIDE
                ))
            })
    };
    if let Some(width) = args.overrides.width {
        scene.file.output.width = side("--width", width)?;
        scene.set_by_flag(&["output", "width"], "--width");
    }
    if let Some(height) = args.overrides.height {
        scene.file.output.height = side("--height", height)?;
        scene.set_by_flag(&["output", "height"], "--height");
    }
    if let Some(projection) = args.overrides.projection {
        use render::projection::Projection;
        scene.file.output.projection = match projection {
            ProjectionArg::Rectilinear => Projection::Rectilinear,
            ProjectionArg::Cubemap => Projection::Cubemap,
            ProjectionArg::Equirectangular => Projection::Equirectangular,
            ProjectionArg::Fisheye => Projection::Fisheye,
        };
        scene.set_by_flag(&["output", "projection"], "--projection");
    }
    if let Some(exposure) = args.overrides.exposure {
        scene.file.output.exposure = exposure;
        scene.set_by_flag(&["output", "exposure"], "--exposure");
    }
    if let Some(transform) = args.overrides.display_transform {
        use render::tonemap::DisplayTransform;
        scene.file.output.display_transform = match transform {
            DisplayTransformArg::Neutral => DisplayTransform::Neutral,
            DisplayTransformArg::PerChannel => DisplayTransform::PerChannel,
        };
        scene.set_by_flag(&["output", "display_transform"], "--display-transform");
    }
    // An explicit sun replaces the scene's [time] (then no sky objects are placed).
    let current = scene
        .file
        .sun
        .map(|sun| (sun.elevation_deg, sun.azimuth_deg));
    let (elevation, azimuth) = (
        args.overrides.sun_elevation_deg,
        args.overrides.sun_azimuth_deg,
    );
    let explicit = match (elevation, azimuth, current) {
        (None, None, _) => None,
        (Some(e), Some(a), _) => Some((e, a)),
        (Some(e), None, Some((_, a))) => Some((e, a)),
        (None, Some(a), Some((e, _))) => Some((e, a)),
        (Some(_), None, None) | (None, Some(_), None) => {
            return Err(Failure::Input(
                "--sun-elevation-deg/--sun-azimuth-deg: the scene places the sun by [time]; \
                 give both to replace it with an explicit sun"
                    .into(),
            ));
        }
    };
    if let Some((elevation_deg, azimuth_deg)) = explicit {
        let file = &mut scene.file;
        file.sun = Some(render::scene::SunSection {
            elevation_deg,
            azimuth_deg,
        });
        file.time = None;
        file.sky_objects = None;
        if let Some(animation) = &mut file.animation {
            // [time]'s motion has nothing left to move.
            animation.seconds_per_frame = 0.0;
        }
    }
    if elevation.is_some() {
        scene.set_by_flag(&["sun", "elevation_deg"], "--sun-elevation-deg");
    }
    if azimuth.is_some() {
        scene.set_by_flag(&["sun", "azimuth_deg"], "--sun-azimuth-deg");
    }
    if let Some(rung) = &args.overrides.rung {
        scene.file.atmosphere.rung = render::scene::Rung::from_name(rung).ok_or_else(|| {
            let names: Vec<&str> = render::scene::Rung::ALL.iter().map(|r| r.name()).collect();
            Failure::Input(format!("--rung `{rung}`: not one of {}", names.join(", ")))
        })?;
        scene.set_by_flag(&["atmosphere", "rung"], "--rung");
    }
    Ok(())
}

/// The frames to draw: a still (`sequence` false, frame 0), or frames `range` of the
/// scene's `[animation]`.
#[derive(Debug, Clone)]
pub(crate) struct Frames {
    pub(crate) sequence: bool,
    pub(crate) range: std::ops::Range<u32>,
}

/// The animation rule: `--frames` and `--frame-range` need the scene's `[animation]`;
/// `--frames` replaces its length; `--frame-range` lies within it; the whole range is
/// checked ([`Scene::check_animation`]) before the first frame.
pub(crate) fn frames(scene: &mut Scene, args: &RenderArgs) -> Result<Frames, Failure> {
    let animation = &args.animation;
    let Some(section) = scene.file.animation.as_mut() else {
        let flag = match (animation.frames, animation.frame_range) {
            (Some(n), _) => format!("--frames {n}"),
            (None, Some((a, b))) => format!("--frame-range {a}..{b}"),
            (None, None) => {
                return Ok(Frames {
                    sequence: false,
                    range: 0..1,
                });
            }
        };
        return Err(Failure::Input(format!(
            "{flag}: the scene has no [animation], so every frame would be the same image \
             (add an [animation] table: docs/scenes.md)"
        )));
    };
    if let Some(n) = animation.frames {
        section.frames = u32::try_from(n)
            .ok()
            .filter(|&n| (1..=render::scene::MAX_FRAMES).contains(&n))
            .ok_or_else(|| {
                Failure::Input(format!(
                    "--frames {n}: must be in 1..={}",
                    render::scene::MAX_FRAMES
                ))
            })?;
        scene.set_by_flag(&["animation", "frames"], "--frames");
    }
    let total = scene.file.animation.as_ref().map_or(1, |a| a.frames);
    let range = match animation.frame_range {
        Some((a, b)) => {
            if (1..=render::scene::MAX_FRAMES).contains(&total) && b > total {
                return Err(Failure::Input(format!(
                    "--frame-range {a}..{b}: the animation has {total} frames (0..{total}, {})",
                    match scene.location(&["animation", "frames"]) {
                        Some(l) if l.origin == render::scene::Origin::Key =>
                            format!("animation.frames on line {}", l.line),
                        _ => "--frames".to_owned(),
                    }
                )));
            }
            a..b
        }
        None => 0..total,
    };
    scene
        .check_animation(range.clone())
        .map_err(|e| Failure::Input(e.to_string()))?;
    Ok(Frames {
        sequence: true,
        range,
    })
}

/// `for_gpu`: only the GPU renderer will draw it (`Scene::prepare_for_gpu`: the shell
/// deck's shadow maps are left to the GPU to bake). Each step is a stage of `stages`;
/// what `cache` kept from an earlier frame is taken, not built again.
pub(crate) fn prepare(
    scene: &Scene,
    label: &str,
    for_gpu: bool,
    cache: &render::scene::PrepareCache,
    stages: &mut Stages,
) -> Result<PreparedScene, Failure> {
    scene
        .prepare_in_stages(for_gpu, cache, &mut |name| stages.begin(name))
        .map_err(|e| Failure::Input(format!("{label}: {e}")))
}

/// Where the frames go: a path (`{frame}` numbering an animation's frames), the
/// words that name its source in errors, whether a missing folder is created, and the
/// format.
#[derive(Debug, Clone)]
pub(crate) struct Destination {
    pattern: PathBuf,
    pub(crate) label: String,
    pub(crate) mkdir: bool,
    pub(crate) format: Format,
}

/// The placeholder of the frame number in an animation's output name.
const FRAME: &str = "{frame}";

impl Destination {
    /// `-o`, else the scene's `[output] path` (relative to the scene file's folder),
    /// else target/skyscape/NAME.EXT (NAME_{frame}.EXT for an animation; its folder
    /// created). An animation's name must hold `{frame}`, a still's must not.
    pub(crate) fn new(
        args: &RenderArgs,
        scene: &Scene,
        name: &str,
        sequence: bool,
    ) -> Result<Self, Failure> {
        let flag = args.output.format;
        let (pattern, label, mkdir, format) = if let Some(path) = &args.output.output {
            let format = format_for(Some(path), flag, "-o")?;
            (path.clone(), "-o".to_owned(), args.output.mkdir, format)
        } else if let Some(path) = &scene.file.output.path {
            let label = match scene.location(&["output", "path"]) {
                Some(l) => format!("line {}: `output.path`", l.line),
                None => "`output.path`".to_owned(),
            };
            let format = format_for(Some(path), flag, &label)?;
            (scene.resolve(path), label, args.output.mkdir, format)
        } else {
            let format = format_for(None, flag, "")?;
            let numbered = if sequence { "_{frame}" } else { "" };
            let path = format!("target/skyscape/{name}{numbered}.{}", format.extension());
            (
                PathBuf::from(path),
                "the default output".to_owned(),
                true,
                format,
            )
        };
        let text = pattern.to_string_lossy();
        match (sequence, text.contains(FRAME)) {
            (true, false) => Err(Failure::Input(format!(
                "{label} `{text}`: the scene is an animation: its name needs `{FRAME}` where \
                 the frame number goes (e.g. frames/{name}_{FRAME}.{})",
                format.extension()
            ))),
            (false, true) => Err(Failure::Input(format!(
                "{label} `{text}`: `{FRAME}` numbers an animation's frames, and the scene has \
                 no [animation]"
            ))),
            _ => Ok(Self {
                pattern,
                label,
                mkdir,
                format,
            }),
        }
    }

    /// The path of `frame` (`{frame}` replaced by its 4-digit number).
    pub(crate) fn path(&self, frame: u32) -> PathBuf {
        let text = self.pattern.to_string_lossy();
        if text.contains(FRAME) {
            PathBuf::from(text.replace(FRAME, &format!("{frame:04}")))
        } else {
            self.pattern.clone()
        }
    }
}
