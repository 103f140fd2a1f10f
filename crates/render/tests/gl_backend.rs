//! The GL backend cannot compile some of skyscape's pipelines (naga's GLSL output has
//! no `textureLoad` from depth textures, which the cloud passes use). The scene
//! renderer returns that as an error naming the pipeline and the adapter (error
//! scopes, `render::gpu::validation`), and the `skyscape` binary falls back to the
//! CPU reference renderer, or exits 1 where a GPU image is required: never a panic.
//!
//! Runs only where a GL adapter exists (Mesa's llvmpipe on CI machines); otherwise it
//! says so on stderr and passes.

use std::process::{Command, Output};

fn skyscape(args: &[&str]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_skyscape"));
    command.args(args).env("RUST_BACKTRACE", "0");
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        // EGL without a display wants one; any writable folder does.
        command.env("XDG_RUNTIME_DIR", std::env::temp_dir());
    }
    command.output().expect("the skyscape binary runs")
}

/// Whether `skyscape adapters --backend gl` lists a GL adapter (its lines read
/// `Gl <type> <name> (<driver>)`).
fn gl_adapter() -> bool {
    let output = skyscape(&["adapters", "--backend", "gl"]);
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .any(|line| line.starts_with("Gl "))
}

fn assert_no_panic(what: &str, output: &Output) -> String {
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_ne!(output.status.code(), Some(101), "{what} panicked: {stderr}");
    assert!(!stderr.contains("panicked"), "{what} panicked: {stderr}");
    stderr
}

#[test]
fn a_pipeline_gl_cannot_compile_is_an_error_not_a_panic() {
    if !gl_adapter() {
        eprintln!("skipped: no GL adapter (skyscape adapters --backend gl lists none)");
        return;
    }
    let out = std::env::temp_dir().join(format!("skyscape-gl-{}.png", std::process::id()));
    let out_arg = out.to_str().expect("a UTF-8 temporary path");
    let size = ["--width", "16", "--height", "9"];

    // The default render falls back to the CPU reference renderer and says why.
    let mut args = vec!["render", "stratocumulus", "--backend", "gl", "-o", out_arg];
    args.extend(size);
    let output = skyscape(&args);
    let stderr = assert_no_panic("render on gl", &output);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    for expected in [
        "SceneRenderer::new",
        "(gl)",
        "'render shell clouds'",
        "rendering on the CPU reference renderer",
    ] {
        assert!(stderr.contains(expected), "no `{expected}` in: {stderr}");
    }
    assert!(
        String::from_utf8_lossy(&output.stdout).contains("on the CPU reference renderer"),
        "{}",
        String::from_utf8_lossy(&output.stdout)
    );
    assert!(out.exists(), "no image at {}", out.display());
    let _ = std::fs::remove_file(&out);

    // --explain needs a GPU image: a runtime failure (exit 1) naming the backend.
    let mut args = vec!["render", "stratocumulus", "--backend", "gl", "--explain"];
    args.extend(["-o", out_arg]);
    args.extend(size);
    let output = skyscape(&args);
    let stderr = assert_no_panic("render --explain on gl", &output);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    for expected in [
        "--explain needs a GPU image",
        "(gl)",
        "'render shell clouds'",
    ] {
        assert!(stderr.contains(expected), "no `{expected}` in: {stderr}");
    }
    let _ = std::fs::remove_file(&out);
}
