//! The `render` and `explain` commands.

use crate::*;

pub(crate) fn print_passes(scene: &PreparedScene, rendered: &Rendered) {
    println!(
        "the frame's passes, in order ({}; a step's time is its GPU timestamps' span):",
        rendered.device
    );
    print_plan(scene, Some(&rendered.pass_seconds));
}

/// The frame's passes in order (`render::passes::FRAME`), each with its steps: run
/// (with its GPU time when `seconds` has it) or skipped, and why.
pub(crate) fn print_plan(scene: &PreparedScene, seconds: Option<&[(&'static str, f64)]>) {
    for (index, entry) in render::passes::FRAME.iter().enumerate() {
        let runs = (entry.runs)(scene);
        println!(
            "{:>2}. {}{}",
            index + 1,
            entry.name,
            if runs { "" } else { " (not in this scene)" }
        );
        for line in (entry.plan)(scene) {
            let pass = line.label;
            match line.status {
                Ok(what) => {
                    let time = match seconds {
                        None => "(CPU)".to_owned(),
                        Some(seconds) => seconds
                            .iter()
                            .find(|(label, _)| *label == pass)
                            .map_or_else(
                                || {
                                    if line.timed {
                                        "(no timestamps)".to_owned()
                                    } else {
                                        "(in its pass)".to_owned()
                                    }
                                },
                                |(_, s)| format!("{:.3} ms", s * 1e3),
                            ),
                    };
                    println!("      run   {pass:<26} {time:<15} {what}");
                }
                Err(why) => println!("      skip  {pass:<26} {:<15} {why}", "—"),
            }
        }
    }
}

pub(crate) fn render_command(args: RenderArgs) -> Result<(), Failure> {
    let backends = backends(args.backend.as_deref())?;
    let (mut scene, name) = load_scene(args.scene.as_deref())?;
    apply_overrides(&mut scene, &args)?;
    let format = args.output.format.unwrap_or_else(|| {
        match args
            .output
            .output
            .as_ref()
            .and_then(|p| p.extension())
            .and_then(|e| e.to_str())
        {
            Some("exr") => Format::Exr,
            _ => Format::Png,
        }
    });
    if (args.compare || args.explain)
        && !matches!(
            scene.file.atmosphere.rung,
            render::scene::Rung::Precomputed
                | render::scene::Rung::ClosedForm
                | render::scene::Rung::ClosedFormVertex
                | render::scene::Rung::Single
        )
    {
        // The reference rungs have no GPU passes: comparing would set the CPU image
        // against itself.
        return Err(Failure::Input(format!(
            "{} needs a GPU image, and rung `{}` renders on the CPU reference renderer only \
             (the GPU scene renderer draws the closed-form, closed-form-vertex, single and \
             precomputed rungs)",
            if args.compare {
                "--compare"
            } else {
                "--explain"
            },
            scene.file.atmosphere.rung.name()
        )));
    }
    let animation = scene.file.animation;
    let frames = args
        .animation
        .frames
        .or(animation.map(|a| a.frames))
        .unwrap_or(1);
    if frames == 0 {
        return Err(Failure::Input("--frames 0: must be ≥ 1".into()));
    }
    let range = args.animation.frame_range.unwrap_or((0, frames));
    if range.1 > frames {
        return Err(Failure::Input(format!(
            "--frame-range {}..{}: the animation has {frames} frames",
            range.0, range.1
        )));
    }
    let bar = (range.1 - range.0 > 1)
        .then(|| indicatif::ProgressBar::new(u64::from(range.1 - range.0)).with_message("frames"));
    for frame in range.0..range.1 {
        let mut frame_scene = scene.clone();
        if let Some(animation) = animation {
            animation.apply(&mut frame_scene.file, frame);
        }
        let start = std::time::Instant::now();
        let projected =
            frame_scene.file.output.projection != render::projection::Projection::Rectilinear;
        let mut prepared = prepare(
            &frame_scene,
            &name,
            !(args.cpu || args.compare || projected),
        )?;
        let gpu = if args.cpu || projected {
            None
        } else {
            match render_gpu(&prepared, backends, format == Format::Exr, args.explain) {
                Ok(rendered) => Some(rendered),
                Err(reason) if args.compare || args.explain => {
                    return Err(Failure::Runtime(format!(
                        "{} needs a GPU image: {reason}",
                        if args.compare {
                            "--compare"
                        } else {
                            "--explain"
                        }
                    )));
                }
                Err(reason) => {
                    eprintln!("skyscape: {reason}; rendering on the CPU reference renderer");
                    None
                }
            }
        };
        let rendered = match gpu {
            Some(rendered) => rendered,
            None if projected => {
                let on = match (args.cpu, args.compare) {
                    (true, _) => FacesOn::Cpu,
                    (false, true) => FacesOn::Gpu,
                    (false, false) => FacesOn::GpuOrCpu,
                };
                render_projected(&frame_scene, &mut prepared, backends, on)?
            }
            None => {
                // A GPU failure falls back here: bake what was left to the GPU.
                prepared.bake_shell_shadow_on_cpu();
                render_cpu(&prepared).map_err(Failure::Runtime)?
            }
        };
        let numbered = (frames > 1).then_some(frame);
        let path = output_path(&args, &frame_scene, &name, format, numbered)?;
        let size = (
            frame_scene.file.output.width,
            frame_scene.file.output.height,
        );
        write(&path, size, format, &rendered)?;
        if let Some(bar) = &bar {
            bar.inc(1);
        }
        println!(
            "rendered {name}{} ({}×{} {:?}, {}) on {} in {:.2} s\nwrote {}",
            numbered.map_or_else(String::new, |f| format!(" frame {f}")),
            frame_scene.file.output.width,
            frame_scene.file.output.height,
            frame_scene.file.output.projection,
            prepared.sky_model.label(),
            rendered.device,
            start.elapsed().as_secs_f64(),
            path.display()
        );
        if args.explain {
            print_passes(&prepared, &rendered);
        }
        if args.compare {
            // A projection against the CPU's six faces resampled the same way, not
            // against the scene camera's rectilinear view.
            let cpu = if projected {
                render_projected(&frame_scene, &mut prepared, backends, FacesOn::Cpu)?
            } else {
                render_cpu(&prepared).map_err(Failure::Runtime)?
            };
            let within =
                |lsb| render::tonemap::fraction_within_lsb(&rendered.pixels, &cpu.pixels, lsb);
            match (within(2), within(0)) {
                (Ok(close), Ok(identical)) => println!(
                    "--compare: {:.4} % of pixels within 2 LSB of the CPU reference renderer, \
                     {:.4} % identical",
                    100.0 * close,
                    100.0 * identical
                ),
                (Err(e), _) | (_, Err(e)) => return Err(Failure::Runtime(e.to_string())),
            }
        }
    }
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    Ok(())
}

pub(crate) fn explain_command(name: &str, backend: Option<&str>) -> Result<(), Failure> {
    let backends = backends(backend)?;
    let (scene, label) = load_scene(Some(name))?;
    let prepared = prepare(&scene, &label, false)?;
    println!(
        "{label}: {}×{}, {}, terrain {}",
        prepared.camera.width,
        prepared.camera.height,
        prepared.sky_model.label(),
        prepared.terrain.as_ref().map_or_else(
            || "none".to_owned(),
            |t| format!(
                "{}×{} texels",
                t.heightfield.width(),
                t.heightfield.height()
            )
        )
    );
    match render_gpu(&prepared, backends, false, true) {
        Ok(rendered) => print_passes(&prepared, &rendered),
        Err(reason) => {
            println!(
                "no GPU passes ({reason}): the CPU reference renderer would run the frame's \
                 passes, in order:"
            );
            print_plan(&prepared, None);
        }
    }
    Ok(())
}
