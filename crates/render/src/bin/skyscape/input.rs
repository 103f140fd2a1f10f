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

/// Applies the command line's overrides to the scene's values.
pub(crate) fn apply_overrides(scene: &mut Scene, args: &RenderArgs) -> Result<(), Failure> {
    let file = &mut scene.file;
    if let Some(width) = args.overrides.width {
        file.output.width = width;
    }
    if let Some(height) = args.overrides.height {
        file.output.height = height;
    }
    if let Some(projection) = args.overrides.projection {
        use render::projection::Projection;
        file.output.projection = match projection {
            ProjectionArg::Rectilinear => Projection::Rectilinear,
            ProjectionArg::Cubemap => Projection::Cubemap,
            ProjectionArg::Equirectangular => Projection::Equirectangular,
            ProjectionArg::Fisheye => Projection::Fisheye,
        };
    }
    if let Some(exposure) = args.overrides.exposure {
        file.output.exposure = exposure;
    }
    // An explicit sun replaces the scene's [time] (then no sky objects are placed).
    let current = file.sun.map(|sun| (sun.elevation_deg, sun.azimuth_deg));
    let explicit = match (
        args.overrides.sun_elevation_deg,
        args.overrides.sun_azimuth_deg,
        current,
    ) {
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
    if let Some((elevation, azimuth)) = explicit {
        file.sun = Some(render::scene::SunSection {
            elevation_deg: elevation,
            azimuth_deg: azimuth,
        });
        file.time = None;
        file.sky_objects = None;
    }
    if let Some(rung) = &args.overrides.rung {
        file.atmosphere.rung = render::scene::Rung::from_name(rung).ok_or_else(|| {
            Failure::Input(format!(
                "--rung `{rung}`: not one of closed-form, closed-form-vertex, single, \
                 precomputed, reference, reference-spectral"
            ))
        })?;
    }
    Ok(())
}

/// `for_gpu`: only the GPU renderer will draw it (`Scene::prepare_for_gpu`: the shell
/// deck's shadow maps are left to the GPU to bake).
pub(crate) fn prepare(scene: &Scene, label: &str, for_gpu: bool) -> Result<PreparedScene, Failure> {
    let spinner = indicatif::ProgressBar::new_spinner().with_message(format!(
        "preparing {label}: atmosphere tables, terrain, horizon maps"
    ));
    spinner.enable_steady_tick(std::time::Duration::from_millis(120));
    let prepared = if for_gpu {
        scene.prepare_for_gpu()
    } else {
        scene.prepare()
    }
    .map_err(|e| Failure::Input(format!("{label}: {e}")));
    spinner.finish_and_clear();
    prepared
}

/// Where a frame goes: the given path, else the scene's, else target/skyscape/NAME;
/// numbered when the animation has several frames.
pub(crate) fn output_path(
    args: &RenderArgs,
    scene: &Scene,
    name: &str,
    format: Format,
    frame: Option<u32>,
) -> Result<PathBuf, Failure> {
    let extension = match format {
        Format::Png => "png",
        Format::Exr => "exr",
    };
    let (path, default) = match args
        .output
        .output
        .clone()
        .or_else(|| scene.file.output.path.clone())
    {
        Some(path) => (path, false),
        None => (
            PathBuf::from(format!("target/skyscape/{name}.{extension}")),
            true,
        ),
    };
    let path = match frame {
        Some(frame) => {
            let stem = path
                .file_stem()
                .map_or_else(|| name.into(), |s| s.to_string_lossy().into_owned());
            path.with_file_name(format!("{stem}_{frame:04}.{extension}"))
        }
        None => path,
    };
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty())
        && !parent.is_dir()
    {
        if default || args.output.mkdir {
            std::fs::create_dir_all(parent)
                .map_err(|e| Failure::Runtime(format!("creating {}: {e}", parent.display())))?;
        } else {
            return Err(Failure::Input(format!(
                "output `{}`: the folder {} does not exist (create it, or pass --mkdir)",
                path.display(),
                parent.display()
            )));
        }
    }
    Ok(path)
}

pub(crate) fn write(
    path: &Path,
    (width, height): (u32, u32),
    format: Format,
    rendered: &Rendered,
) -> Result<(), Failure> {
    let result = match format {
        Format::Png => render::cpu_renderer::write_png(
            path,
            &render::cpu_renderer::Frame {
                width,
                height,
                pixels: rendered.pixels.clone(),
            },
        ),
        Format::Exr => {
            let radiance = rendered.radiance.as_deref().unwrap_or_default();
            render::cpu_renderer::write_exr(path, width, height, radiance)
        }
    };
    result.map_err(|e| Failure::Input(format!("writing {}: {e}", path.display())))
}
