//! Time to picture: how long a user waits for `skyscape render` — the process started,
//! the scene read and checked, prepared, drawn, read back and written — on the GPU
//! adapter wgpu finds and on the CPU reference renderer (`--cpu`), with an empty
//! preparation cache and then a warm one, and what an animation's later frames cost
//! against its first (the sun moving: one process, one cache, one renderer). Runs the
//! `skyscape` binary this bench was built with and writes `docs/time-to-picture.md`.
//!
//! `cargo bench -p render --bench picture` (960×540: the shipped scenes' size);
//! `SKYSCAPE_PICTURE_SCENES=default,stratocumulus`, `SKYSCAPE_PICTURE_RUNS=3` (runs per
//! figure, the median reported), `SKYSCAPE_PICTURE_FRAMES=6` (the animation's length) and
//! `SKYSCAPE_PICTURE_REPORT=path.md` change what is measured and where it is written. On
//! a CPU adapter (lavapipe) the GPU runs are CPU time too, and the report says so.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

const BINARY: &str = env!("CARGO_BIN_EXE_skyscape");

fn env_or(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_owned())
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(f64::NAN)
}

/// One run of the binary: its wall time (s, from spawn to exit), what it printed
/// (stdout, then stderr), and its "rendered … on DEVICE in T s" lines.
struct Run {
    wall: f64,
    output: String,
    device: String,
}

impl Run {
    /// The seconds of its stage lines (`skyscape: LABEL: STAGE T s`) before drawing:
    /// the preparation (stages under 10 ms are not printed).
    fn preparation(&self) -> f64 {
        self.output
            .lines()
            .filter(|line| line.starts_with("skyscape: ") && line.ends_with(" s"))
            .filter(|line| !line.contains(": drawing ") && !line.contains(": writing "))
            .filter_map(|line| line.rsplit(' ').nth(1)?.parse::<f64>().ok())
            .sum()
    }

    /// Each frame's time from its "rendered … frame K … in T s" line, in order.
    fn frame_seconds(&self) -> Vec<f64> {
        self.output
            .lines()
            .filter(|line| line.starts_with("rendered ") && line.contains(" frame "))
            .filter_map(|line| line.rsplit(" in ").next()?.strip_suffix(" s")?.parse().ok())
            .collect()
    }
}

fn run(args: &[&str]) -> Result<Run, String> {
    let start = Instant::now();
    let output = Command::new(BINARY)
        .args(args)
        .output()
        .map_err(|e| format!("{BINARY}: {e}"))?;
    let wall = start.elapsed().as_secs_f64();
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    if !output.status.success() {
        return Err(format!("skyscape {}: {stderr}", args.join(" ")));
    }
    let report = format!("{stdout}{stderr}");
    let device = report
        .lines()
        .filter(|line| line.starts_with("rendered "))
        .map(str::to_owned)
        .collect::<Vec<_>>()
        .join("\n");
    Ok(Run {
        wall,
        output: report,
        device,
    })
}

/// The device a run drew on: the text between " on " and " in " of its report.
fn device_of(run: &Run) -> String {
    let line = run.device.lines().next().unwrap_or_default();
    let after = line.split_once(") on ").map_or(line, |(_, rest)| rest);
    after
        .rsplit_once(" in ")
        .map_or(after, |(device, _)| device)
        .to_owned()
}

/// Median wall time and preparation of `runs` runs of `args`, each with a cache folder
/// made by `folder()` (empty: a cold cache; shared: warm after the first).
fn measure(
    args: &[&str],
    runs: usize,
    folder: &dyn Fn() -> PathBuf,
) -> Result<(f64, f64, String), String> {
    let mut walls = Vec::new();
    let mut preparations = Vec::new();
    let mut device = String::new();
    for _ in 0..runs {
        let cache = folder();
        let cache = cache.to_string_lossy().into_owned();
        let mut all: Vec<&str> = args.to_vec();
        all.extend(["--cache-dir", cache.as_str()]);
        let r = run(&all)?;
        walls.push(r.wall);
        preparations.push(r.preparation());
        device = device_of(&r);
    }
    Ok((median(walls), median(preparations), device))
}

/// A scene's rows: what ran, its median wall time and preparation (s), and the device
/// its binary reported.
struct SceneFigures {
    name: String,
    rows: Vec<(String, f64, f64, String)>,
}

fn main() {
    let scenes = env_or("SKYSCAPE_PICTURE_SCENES", "default,stratocumulus");
    let runs: usize = env_or("SKYSCAPE_PICTURE_RUNS", "3")
        .parse()
        .unwrap_or(3)
        .max(1);
    let frames: usize = env_or("SKYSCAPE_PICTURE_FRAMES", "6")
        .parse()
        .unwrap_or(6)
        .max(2);
    let work = tempfile::tempdir().expect("a temporary folder");
    let out = work.path().join("picture.png");
    let out = out.to_string_lossy().into_owned();
    let warm = work.path().join("warm-cache");
    // A new, empty cache folder per cold run.
    let cold_runs = std::cell::Cell::new(0);
    let cold = || {
        cold_runs.set(cold_runs.get() + 1);
        work.path().join(format!("cold-cache-{}", cold_runs.get()))
    };
    let mut figures = Vec::new();
    let mut gpu_device = String::new();
    for name in scenes.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let base = ["render", name, "-o", out.as_str()];
        let with_cpu = ["render", name, "--cpu", "-o", out.as_str()];
        let warm_folder = || warm.clone();
        // Fill the warm cache once.
        let measured = (|| -> Result<SceneFigures, String> {
            run(&[&base[..], &["--cache-dir", &warm.to_string_lossy()]].concat())?;
            let mut rows = Vec::new();
            let (wall, prep, device) = measure(&base, runs, &cold)?;
            rows.push(("GPU, empty cache".to_owned(), wall, prep, device.clone()));
            gpu_device = device;
            let (wall, prep, device) = measure(&base, runs, &warm_folder)?;
            rows.push(("GPU, warm cache".to_owned(), wall, prep, device));
            let (wall, prep, device) = measure(&with_cpu, runs, &cold)?;
            rows.push(("`--cpu`, empty cache".to_owned(), wall, prep, device));
            let (wall, prep, device) = measure(&with_cpu, runs, &warm_folder)?;
            rows.push(("`--cpu`, warm cache".to_owned(), wall, prep, device));
            Ok(SceneFigures {
                name: name.to_owned(),
                rows,
            })
        })();
        match measured {
            Ok(f) => figures.push(f),
            Err(e) => eprintln!("picture bench: {name}: {e}"),
        }
    }
    let animation = animation(work.path(), &warm, frames);
    let report = write_report(&figures, animation, &gpu_device, runs, frames);
    print!("{report}");
    let path = env_or(
        "SKYSCAPE_PICTURE_REPORT",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/time-to-picture.md"),
    );
    match std::fs::write(&path, &report) {
        Ok(()) => eprintln!("picture bench: wrote {path}"),
        Err(e) => eprintln!("picture bench: cannot write {path}: {e}"),
    }
}

/// The default scene with the sun moving (`[animation]`, 5 minutes of time per frame)
/// at each of [`ANIMATION_SIZES`]: each frame's seconds on the GPU and on the CPU
/// reference renderer.
fn animation(work: &Path, cache: &Path, frames: usize) -> Result<Vec<AnimationRun>, String> {
    ANIMATION_SIZES
        .iter()
        .map(|&size| Ok((size, animation_at(work, cache, frames, size)?)))
        .collect()
}

/// An animation's size and its frames' seconds on the GPU and on the CPU.
type AnimationRun = ([u32; 2], [Vec<f64>; 2]);

/// The animation's sizes: the scene's own, where drawing dominates a frame, and a
/// small one, where preparation does.
const ANIMATION_SIZES: [[u32; 2]; 2] = [[960, 540], [160, 90]];

fn animation_at(
    work: &Path,
    cache: &Path,
    frames: usize,
    size: [u32; 2],
) -> Result<[Vec<f64>; 2], String> {
    let scene = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenes/default.toml"
    ))
    .map_err(|e| e.to_string())?;
    let file = work.join("sun_moving.toml");
    std::fs::write(
        &file,
        format!("{scene}\n[animation]\nframes = {frames}\nseconds_per_frame = 300.0\n"),
    )
    .map_err(|e| e.to_string())?;
    let file = file.to_string_lossy().into_owned();
    let pattern = work
        .join("frame_{frame}.png")
        .to_string_lossy()
        .into_owned();
    let cache = cache.to_string_lossy().into_owned();
    let (width, height) = (size[0].to_string(), size[1].to_string());
    let mut out = [Vec::new(), Vec::new()];
    for (k, cpu) in [false, true].into_iter().enumerate() {
        let mut args = vec!["render", file.as_str(), "-o", pattern.as_str()];
        args.extend(["--cache-dir", cache.as_str()]);
        args.extend(["--width", width.as_str(), "--height", height.as_str()]);
        if cpu {
            args.push("--cpu");
        }
        out[k] = run(&args)?.frame_seconds();
        if out[k].len() != frames {
            return Err(format!("{} frame lines, expected {frames}", out[k].len()));
        }
    }
    Ok(out)
}

fn write_report(
    figures: &[SceneFigures],
    animation: Result<Vec<AnimationRun>, String>,
    gpu_device: &str,
    runs: usize,
    frames: usize,
) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "# Time to picture\n");
    let _ = writeln!(
        out,
        "Generated by `cargo bench -p render --bench picture` ({runs} runs per figure, the \
         median; {frames} animation frames); do not edit by hand.\n"
    );
    let cpu_adapter = gpu_device.contains("CPU adapter");
    let _ = writeln!(
        out,
        "GPU runs drew on {gpu_device}.{} The CPU reference renderer (`--cpu`) uses every \
         core of this machine ({} threads).\n",
        if cpu_adapter {
            " **That is a CPU adapter (a software rasteriser): its times are CPU time on this \
             machine, not a GPU's.**"
        } else {
            ""
        },
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    let _ = writeln!(
        out,
        "Each figure is the wall time of `skyscape render SCENE` at the scene's own size \
         (960×540): the process started, the scene checked, prepared, drawn, read back and \
         the PNG written. An empty cache is a new `--cache-dir` folder (the atmosphere's \
         static tables baked); a warm one holds them from an earlier run. Preparation is \
         the sum of the stages the binary reports before drawing.\n"
    );
    for f in figures {
        let _ = writeln!(out, "## {}\n", f.name);
        let _ = writeln!(
            out,
            "| run | picture (s) | of which preparation (s) |\n|---|---:|---:|"
        );
        for (label, wall, prep, device) in &f.rows {
            // A GPU run on a machine without an adapter falls back to the CPU renderer.
            let fell_back = label.starts_with("GPU") && device.contains("CPU reference renderer");
            let note = if fell_back {
                " (no adapter: drawn by the CPU reference renderer)"
            } else {
                ""
            };
            let _ = writeln!(out, "| {label}{note} | {wall:.2} | {prep:.2} |");
        }
        let _ = writeln!(out);
    }
    let _ = writeln!(
        out,
        "## An animation: the default scene with the sun moving\n"
    );
    match animation {
        Ok(sizes) => {
            let _ = writeln!(
                out,
                "`[animation]` with 5 minutes per frame, one process with a warm cache: the \
                 frames share the preparation cache and, on the GPU, the renderer. Each \
                 frame's time is the binary's own \"rendered … in T s\" (from its \
                 preparation to its file written; the process start and the device are \
                 frame 1's).\n"
            );
            let _ = writeln!(
                out,
                "| size | renderer | frame 1 (s) | frames 2…{frames}, mean (s) | later / first |\n|---|---|---:|---:|---:|"
            );
            for ([width, height], [gpu, cpu]) in sizes {
                for (label, seconds) in [("GPU", gpu), ("`--cpu`", cpu)] {
                    let first = seconds[0];
                    let later = seconds[1..].iter().sum::<f64>() / (seconds.len() - 1) as f64;
                    let _ = writeln!(
                        out,
                        "| {width}×{height} | {label} | {first:.2} | {later:.2} | {:.0} % |",
                        100.0 * later / first
                    );
                }
            }
        }
        Err(e) => {
            let _ = writeln!(out, "Not measured: {e}");
        }
    }
    out
}
