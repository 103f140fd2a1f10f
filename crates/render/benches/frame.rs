//! What a frame of every shipped scene costs on the adapter wgpu finds: the CPU
//! preparation's stages (first frame, and a frame that reuses the first's products:
//! `PrepareCache`), then per GPU pass the time between its timestamps (median of
//! several frames drawn by one renderer), and the frame's wall time from `prepare` to
//! the finished submission. Writes the table to `docs/performance.md`.
//!
//! `cargo bench -p render --bench frame` (1920×1080, every shipped scene, 5 frames);
//! `SKYSCAPE_BENCH_SIZE=1280x720`, `SKYSCAPE_BENCH_SCENES=default,orbit`,
//! `SKYSCAPE_BENCH_FRAMES=3` and `SKYSCAPE_BENCH_REPORT=path.md` change what is
//! measured and where it is written. On a CPU adapter (lavapipe) every time is CPU time,
//! and the report says so.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::time::Instant;

use render::gpu::{SceneRenderer, SceneRendererSettings};
use render::scene::{PrepareCache, Scene};

/// One scene's measurements.
struct Measured {
    name: &'static str,
    stages: Vec<(&'static str, f64)>,
    cached_prepare: f64,
    passes: Vec<(&'static str, f64)>,
    frame: f64,
}

fn env_or(name: &str, default: &str) -> String {
    std::env::var(name).unwrap_or_else(|_| default.to_owned())
}

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied().unwrap_or(f64::NAN)
}

fn measure(
    gpu: &skyscape_harness::GpuContext,
    name: &'static str,
    size: [u32; 2],
    frames: usize,
) -> Result<Measured, String> {
    let path = format!("{}/../../scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let mut scene = Scene::open(&path).map_err(|e| e.to_string())?;
    scene.file.output.width = size[0];
    scene.file.output.height = size[1];
    let cache = PrepareCache::new();
    let mut stages: Vec<(&'static str, f64)> = Vec::new();
    let mut current: Option<(&'static str, Instant)> = None;
    let prepared = scene
        .prepare_in_stages(true, &cache, &mut |stage| {
            if let Some((name, started)) = current.take() {
                stages.push((name, started.elapsed().as_secs_f64()));
            }
            current = Some((stage, Instant::now()));
        })
        .map_err(|e| e.to_string())?;
    if let Some((name, started)) = current.take() {
        stages.push((name, started.elapsed().as_secs_f64()));
    }
    let started = Instant::now();
    scene
        .prepare_for_gpu_cached(&cache)
        .map_err(|e| e.to_string())?;
    let cached_prepare = started.elapsed().as_secs_f64();
    let settings = SceneRendererSettings {
        timestamps: true,
        ..Default::default()
    };
    let mut renderer = SceneRenderer::new(&gpu.device, &gpu.queue, &prepared, settings)
        .map_err(|e| e.to_string())?;
    let mut per_pass: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    let mut order: Vec<&'static str> = Vec::new();
    let mut walls = Vec::new();
    // One frame to warm up (the static tables' bake, pipeline compilation), then the
    // measured ones.
    for frame in 0..=frames {
        let started = Instant::now();
        renderer
            .prepare(&gpu.queue, &prepared)
            .map_err(|e| e.to_string())?;
        let mut encoder = gpu.device.create_command_encoder(&Default::default());
        renderer.encode(&mut encoder).map_err(|e| e.to_string())?;
        gpu.queue.submit([encoder.finish()]);
        gpu.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| e.to_string())?;
        let wall = started.elapsed().as_secs_f64();
        let passes = renderer.pass_seconds().unwrap_or(Ok(Vec::new()))?;
        if frame == 0 {
            continue;
        }
        walls.push(wall);
        for (pass, seconds) in passes {
            if !order.contains(&pass) {
                order.push(pass);
            }
            per_pass.entry(pass).or_default().push(seconds);
        }
    }
    Ok(Measured {
        name,
        stages,
        cached_prepare,
        passes: order
            .into_iter()
            .map(|pass| (pass, median(per_pass.remove(pass).unwrap_or_default())))
            .collect(),
        frame: median(walls),
    })
}

fn main() {
    // `cargo bench` passes `--bench`; this harness takes no arguments of its own.
    let size_text = env_or("SKYSCAPE_BENCH_SIZE", "1920x1080");
    let size: Vec<u32> = size_text
        .split('x')
        .filter_map(|s| s.parse().ok())
        .collect();
    let [width, height] = size[..] else {
        eprintln!("SKYSCAPE_BENCH_SIZE={size_text}: expected WIDTHxHEIGHT, e.g. 1920x1080");
        std::process::exit(2);
    };
    let frames: usize = match env_or("SKYSCAPE_BENCH_FRAMES", "5").parse() {
        Ok(n) if n >= 1 => n,
        _ => {
            eprintln!("SKYSCAPE_BENCH_FRAMES: expected a whole number ≥ 1");
            std::process::exit(2);
        }
    };
    let wanted = env_or("SKYSCAPE_BENCH_SCENES", "");
    let scenes: Vec<&'static str> = render::scene::shipped::SHIPPED
        .iter()
        .map(|s| s.name)
        .filter(|name| wanted.is_empty() || wanted.split(',').any(|w| w == *name))
        .collect();
    let Some(gpu) = skyscape_harness::gpu_or_skip("render frame bench") else {
        return;
    };
    let mut measured = Vec::new();
    for name in scenes {
        eprintln!("frame bench: {name} {width}×{height} …");
        match measure(gpu, name, [width, height], frames) {
            Ok(m) => measured.push(m),
            Err(e) => eprintln!("frame bench: {name}: {e}"),
        }
    }
    let report = report(gpu, [width, height], frames, &measured);
    let path = env_or(
        "SKYSCAPE_BENCH_REPORT",
        concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/performance.md"),
    );
    match std::fs::write(&path, &report) {
        Ok(()) => eprintln!("frame bench: wrote {path}"),
        Err(e) => eprintln!("frame bench: cannot write {path}: {e}"),
    }
    print!("{report}");
}

fn report(
    gpu: &skyscape_harness::GpuContext,
    [width, height]: [u32; 2],
    frames: usize,
    measured: &[Measured],
) -> String {
    let info = &gpu.info;
    let cpu_adapter = info.device_type == wgpu::DeviceType::Cpu;
    let mut out = String::new();
    let _ = writeln!(out, "# Frame cost per shipped scene\n");
    let _ = writeln!(
        out,
        "Generated by `cargo bench -p render --bench frame` (with `SKYSCAPE_BENCH_SIZE={width}x{height}`, \
         `SKYSCAPE_BENCH_FRAMES={frames}`); do not edit by hand.\n"
    );
    let _ = writeln!(
        out,
        "Adapter: {}.{}\n",
        skyscape_harness::describe_adapter(info),
        if cpu_adapter {
            " **A CPU adapter (a software rasteriser): every time below is CPU time on \
             this machine, not a GPU's.**"
        } else {
            ""
        }
    );
    let _ = writeln!(
        out,
        "Per scene at {width}×{height}: the CPU preparation's stages on the first frame \
         (wall time, s), the preparation of a later frame that reuses the first's \
         products (`PrepareCache`: the atmosphere's tables, the terrain, the star \
         catalogue), each GPU pass's time between its timestamps (median of {frames} \
         frames drawn by one renderer after a warm-up frame; the GPU's work only), and \
         the frame's wall time from `SceneRenderer::prepare` to the submission's end.\n"
    );
    for m in measured {
        let _ = writeln!(out, "## {}\n", m.name);
        let stages: Vec<String> = m
            .stages
            .iter()
            .map(|(stage, s)| format!("{stage} {s:.3}"))
            .collect();
        let first: f64 = m.stages.iter().map(|(_, s)| s).sum();
        let _ = writeln!(
            out,
            "Preparation: first frame {first:.3} s ({}); a later frame {:.3} s.\n",
            stages.join(", "),
            m.cached_prepare
        );
        let _ = writeln!(out, "| pass (GPU timestamps) | ms |\n|---|---:|");
        let mut sum = 0.0;
        for (pass, seconds) in &m.passes {
            sum += seconds;
            let _ = writeln!(out, "| {pass} | {:.3} |", seconds * 1e3);
        }
        let _ = writeln!(out, "| **all passes** | **{:.3}** |", sum * 1e3);
        let _ = writeln!(
            out,
            "| frame wall time (prepare → submission done) | {:.3} |\n",
            m.frame * 1e3
        );
        if m.frame > 2.0 * sum {
            let _ = writeln!(
                out,
                "The timestamps bracket {:.0} % of the frame's wall time: the rest is work \
                 they do not bracket{}, or the CPU's `prepare`.\n",
                100.0 * sum / m.frame,
                if cpu_adapter {
                    " (a CPU adapter runs compute passes when the submission is waited on)"
                } else {
                    ""
                }
            );
        }
    }
    out
}
