//! The `render` and `explain` commands.

use crate::*;

/// The CPU's stages (wall time) and the frame's passes with their GPU time.
pub(crate) fn print_passes(scene: &PreparedScene, rendered: &Rendered, stages: &Stages) {
    print_stages(stages);
    println!(
        "the frame's passes, in order ({}); a step's time is the GPU's work between its \
         timestamps, measured on the device: it leaves out the CPU preparation above, \
         command recording, submission, waiting for the GPU and reading the image back, \
         and on a software adapter (lavapipe) it is CPU time too:",
        rendered.device
    );
    print_plan(scene, Some(&rendered.pass_seconds));
}

/// The CPU's stages and their wall time (the preparation builds the tables the CPU
/// renderer reads; the GPU renderer builds its own in its first passes).
pub(crate) fn print_stages(stages: &Stages) {
    let total: f64 = stages.finished.iter().map(|(_, s)| s).sum();
    println!("the CPU's stages (wall time, {total:.3} s in all):");
    for (name, seconds) in &stages.finished {
        println!("      {name:<30} {:>10.3} ms", seconds * 1e3);
    }
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

/// Whether the GPU scene renderer draws `rung` (the reference rungs have no GPU passes).
fn gpu_draws(rung: render::scene::Rung) -> bool {
    use render::scene::Rung;
    matches!(
        rung,
        Rung::Precomputed | Rung::Dome | Rung::ClosedForm | Rung::ClosedFormVertex | Rung::Single
    )
}

pub(crate) fn render_command(args: RenderArgs) -> Result<(), Failure> {
    let backends = backends(args.backend.as_deref())?;
    let (mut scene, name) = load_scene(args.scene.as_deref())?;
    apply_overrides(&mut scene, &args)?;
    let rung = scene.file.atmosphere.rung;
    if (args.compare || args.explain) && !gpu_draws(rung) {
        // The reference rungs have no GPU passes: comparing would set the CPU image
        // against itself.
        return Err(Failure::Input(format!(
            "{} needs a GPU image, and rung `{}` renders on the CPU reference renderer only \
             (the GPU scene renderer draws the dome, closed-form, closed-form-vertex, single \
             and precomputed rungs)",
            if args.compare {
                "--compare"
            } else {
                "--explain"
            },
            rung.name()
        )));
    }
    let frames = frames(&mut scene, &args)?;
    let destination = Destination::new(&args, &scene, &name, frames.sequence)?;
    // Every frame's output is checked before the first frame's work starts.
    let scene_file = args
        .scene
        .as_deref()
        .and_then(|s| std::fs::canonicalize(s).ok());
    let mut targets = Vec::with_capacity(frames.range.len());
    for frame in frames.range.clone() {
        let path = destination.path(frame);
        let target = target(&path, destination.mkdir, &destination.label)?;
        if let (Target::Replace(file), Some(scene_file)) = (&target, &scene_file)
            && std::fs::canonicalize(file).is_ok_and(|f| f == *scene_file)
        {
            return Err(Failure::Input(format!(
                "{} `{}`: is the scene file itself",
                destination.label,
                path.display()
            )));
        }
        targets.push((frame, target));
    }
    let to_stdout = targets.iter().any(|(_, t)| *t == Target::Stdout);
    // With the image on standard output, what skyscape says goes to stderr.
    let say = |text: String| {
        if to_stdout {
            eprintln!("{text}");
        } else {
            println!("{text}");
        }
    };
    for warning in scene.warnings() {
        eprintln!("skyscape: warning: {warning}");
    }
    let cpu = args.cpu || !gpu_draws(rung);
    if !args.cpu && !gpu_draws(rung) {
        eprintln!(
            "skyscape: note: rung `{}` has no GPU passes: it renders on the CPU reference \
             renderer",
            rung.name()
        );
    }
    let format = destination.format;
    let bar = (frames.range.len() > 1)
        .then(|| indicatif::ProgressBar::new(frames.range.len() as u64).with_message("frames"));
    // An animation's frames share what did not change between them (the atmosphere's
    // tables, the terrain).
    let cache = args.prepare_cache();
    // And the device and scene renderer, while a frame's scene needs no new one.
    let mut session = GpuSession::new(backends, args.explain);
    for (frame, target) in targets {
        // The `.partial` exists from here: a failure or Ctrl-C removes it.
        let reserved = Reserved::new(target.clone(), &destination.label)?;
        let mut frame_scene = scene.clone();
        if let Some(animation) = &scene.file.animation {
            animation.apply(&mut frame_scene.file, frame);
        }
        let start = std::time::Instant::now();
        let projected =
            frame_scene.file.output.projection != render::projection::Projection::Rectilinear;
        let label = if frames.sequence {
            format!("{name} frame {frame}")
        } else {
            name.clone()
        };
        let mut stages = Stages::new(label.clone());
        let mut prepared = prepare(
            &frame_scene,
            &label,
            !(cpu || args.compare || projected),
            &cache,
            &mut stages,
        )?;
        stages.begin("drawing");
        let gpu = if cpu || projected {
            None
        } else {
            match session.render(&prepared, format == Format::Exr) {
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
                    eprintln!(
                        "skyscape: note: no GPU image ({reason}); rendering on the CPU \
                         reference renderer"
                    );
                    None
                }
            }
        };
        let rendered = match gpu {
            Some(rendered) => rendered,
            None if projected => {
                let on = match (cpu, args.compare) {
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
        let output = &frame_scene.file.output;
        stages.begin("writing");
        let bytes = encode(format, (output.width, output.height), &rendered)?;
        reserved.write(&bytes)?;
        stages.finish();
        if let Some(bar) = &bar {
            bar.inc(1);
        }
        say(format!(
            "rendered {name}{} ({}×{} {:?}, {}) on {} in {:.2} s\nwrote {}",
            if frames.sequence {
                format!(" frame {frame}")
            } else {
                String::new()
            },
            output.width,
            output.height,
            output.projection,
            prepared.sky_model.label(),
            rendered.device,
            start.elapsed().as_secs_f64(),
            match &target {
                Target::Stdout => "standard output".to_owned(),
                Target::Through(path) | Target::Replace(path) => path.display().to_string(),
            }
        ));
        if args.explain {
            print_passes(&prepared, &rendered, &stages);
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
                (Ok(close), Ok(identical)) => say(format!(
                    "--compare: {:.4} % of pixels within 2 LSB of the CPU reference renderer, \
                     {:.4} % identical",
                    100.0 * close,
                    100.0 * identical
                )),
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
    let mut stages = Stages::new(label.clone());
    let prepared = prepare(
        &scene,
        &label,
        false,
        &render::scene::PrepareCache::new(),
        &mut stages,
    )?;
    stages.finish();
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
        Ok(rendered) => print_passes(&prepared, &rendered, &stages),
        Err(reason) => {
            print_stages(&stages);
            println!(
                "no GPU passes ({reason}): the CPU reference renderer would run the frame's \
                 passes, in order:"
            );
            print_plan(&prepared, None);
        }
    }
    Ok(())
}
