//! skyscape's developer tasks: `cargo xtask <command>`.
//!
//! * `parity [--filter NAME] [--backend vulkan|gl|…] [--inject CASE] [--markdown PATH]
//!   [--check-markdown PATH] [--self-test]` — every WGSL function against its Rust twin
//!   and f64 reference, each case's CPU sides evaluated once for the comparison, the
//!   comparator self-test and the tightness audit; table on stdout,
//!   `target/parity/report.json`, progress on stderr, a one-line summary last; exits
//!   non-zero when a case fails, a comparator lets an injected difference through, a
//!   tolerance is looser than the audit allows or the checked Markdown table is stale.
//!   `--self-test` evaluates the CPU sides only (no GPU).
//! * `tradeoff <atmos|terrain|sky-dome|cloudlight> [--quick] [--backend …]` — speed against
//!   accuracy for each quality setting of a subsystem, measured; writes
//!   `docs/tradeoffs/<subsystem>.md` (`sky-dome`: SGSky's 12-sided dome against the
//!   per-pixel sky, `sky_dome.md`).
//! * `gallery` — every shipped scene rendered by the CPU reference renderer into
//!   `docs/gallery/NAME.png`, and `docs/gallery.md` listing them.

mod gallery;
mod parity;
mod tradeoff;

use std::path::PathBuf;
use std::process::ExitCode;

/// The workspace root (xtask lives one level below it).
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask is inside the workspace")
        .to_path_buf()
}

const USAGE: &str = "usage: cargo xtask parity [--filter NAME] [--backend BACKENDS] [--inject CASE]
                          [--markdown PATH] [--check-markdown PATH] [--self-test]
       cargo xtask tradeoff <atmos|terrain|sky-dome|cloudlight> [--quick] [--backend BACKENDS]
       cargo xtask gallery";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args.first().map(String::as_str) {
        Some("parity") => run_parity(&args[1..]),
        Some("tradeoff") => tradeoff::run(&args[1..]),
        Some("gallery") => gallery::run(&args[1..]),
        Some("-h" | "--help") | None => {
            println!("{USAGE}");
            ExitCode::SUCCESS
        }
        Some(other) => {
            eprintln!("unknown command `{other}`\n{USAGE}");
            ExitCode::FAILURE
        }
    }
}

fn run_parity(args: &[String]) -> ExitCode {
    let mut options = parity::Options::default();
    let mut iter = args.iter();
    while let Some(arg) = iter.next() {
        let mut value = |flag: &str| {
            iter.next()
                .cloned()
                .ok_or_else(|| format!("{flag} needs a value"))
        };
        let result = match arg.as_str() {
            "--filter" => value("--filter").map(|v| options.filter = Some(v)),
            "--inject" => value("--inject").map(|v| options.inject = Some(v)),
            "--markdown" => value("--markdown").map(|v| options.markdown = Some(v.into())),
            "--check-markdown" => {
                value("--check-markdown").map(|v| options.check_markdown = Some(v.into()))
            }
            "--backend" => value("--backend").and_then(|v| {
                let backends = wgpu::Backends::from_comma_list(&v);
                if backends.is_empty() {
                    Err(format!("--backend `{v}` names no known backend"))
                } else {
                    skyscape_harness::select_backends(backends).map_err(|e| e.to_string())
                }
            }),
            "--self-test" => {
                options.cpu_only = true;
                Ok(())
            }
            other => Err(format!("unknown option `{other}`\n{USAGE}")),
        };
        if let Err(message) = result {
            eprintln!("{message}");
            return ExitCode::FAILURE;
        }
    }
    match parity::run(&options) {
        Ok(findings) if findings.clean() => ExitCode::SUCCESS,
        Ok(_) => {
            eprintln!("parity: FAILED (see the lines above the summary)");
            ExitCode::FAILURE
        }
        Err(message) => {
            eprintln!("parity: {message}");
            ExitCode::FAILURE
        }
    }
}
