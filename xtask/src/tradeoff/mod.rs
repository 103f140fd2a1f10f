//! `cargo xtask tradeoff <subsystem>`: what each quality setting costs and how wrong it
//! is against the subsystem's reference, written to `docs/tradeoffs/<subsystem>.md`
//! (table + error-vs-cost plot, `docs/tradeoffs/<subsystem>.svg`) and the raw rows to
//! `target/tradeoff/<subsystem>.json`.

pub mod plot;

mod atmos;
mod cloudlight;
mod sky_dome;
mod terrain;

use std::process::ExitCode;

const USAGE: &str = "usage: cargo xtask tradeoff <atmos|terrain|sky-dome|cloudlight> [--quick] [--backend BACKENDS]";

/// Options shared by every subsystem.
#[derive(Debug, Default, Clone)]
pub struct Options {
    /// Smaller problem sizes (for CI smoke runs); the docs are written from full runs.
    pub quick: bool,
}

/// Entry point for `cargo xtask tradeoff …`.
pub fn run(args: &[String]) -> ExitCode {
    let Some(subsystem) = args.first() else {
        eprintln!("{USAGE}");
        return ExitCode::FAILURE;
    };
    let mut options = Options::default();
    let mut iter = args[1..].iter();
    while let Some(arg) = iter.next() {
        match arg.as_str() {
            "--quick" => options.quick = true,
            "--backend" => {
                let Some(v) = iter.next() else {
                    eprintln!("--backend needs a value");
                    return ExitCode::FAILURE;
                };
                let backends = wgpu::Backends::from_comma_list(v);
                if backends.is_empty() {
                    eprintln!("--backend `{v}` names no known backend");
                    return ExitCode::FAILURE;
                }
                if let Err(e) = skyscape_harness::select_backends(backends) {
                    eprintln!("{e}");
                    return ExitCode::FAILURE;
                }
            }
            other => {
                eprintln!("unknown option `{other}`\n{USAGE}");
                return ExitCode::FAILURE;
            }
        }
    }
    let result = match subsystem.as_str() {
        "atmos" => atmos::run(&options),
        "terrain" => terrain::run(&options),
        "sky-dome" => sky_dome::run(&options),
        "cloudlight" => cloudlight::run(&options),
        other => Err(format!("unknown subsystem `{other}`\n{USAGE}")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("tradeoff: {message}");
            ExitCode::FAILURE
        }
    }
}

/// A criterion benchmark name from a label: lower-case ASCII words joined by `_`, at
/// most 64 characters (criterion keeps no more of a benchmark's directory name).
pub fn slug(label: &str) -> String {
    label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '_'
            }
        })
        .collect::<String>()
        .split('_')
        .filter(|s| !s.is_empty())
        .collect::<Vec<_>>()
        .join("_")
        .chars()
        .take(64)
        .collect()
}

/// Writes `contents` to `path` (relative to the workspace root), creating folders.
pub fn write_output(relative: &str, contents: &str) -> Result<std::path::PathBuf, String> {
    let path = crate::workspace_root().join(relative);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(|e| format!("{}: {e}", parent.display()))?;
    }
    std::fs::write(&path, contents).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

/// Times `f` by repeating it until at least `min_seconds` have passed (at least once);
/// returns seconds per call. For whole bakes the tradeoff reports; per-function CPU
/// costs come from criterion (`cargo bench`), named in each report.
pub fn time_per_call(min_seconds: f64, mut f: impl FnMut()) -> f64 {
    let start = std::time::Instant::now();
    let mut calls = 0u64;
    loop {
        f();
        calls += 1;
        let elapsed = start.elapsed().as_secs_f64();
        if elapsed >= min_seconds {
            return elapsed / calls as f64;
        }
    }
}
