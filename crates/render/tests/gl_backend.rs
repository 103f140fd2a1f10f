//! The GL backend gives no GPU image: atmos refuses to bake the precomputed rung's
//! tables there (wgpu's GL backend writes one slice of a 3-D storage texture), and the
//! rungs without tables use pipelines GL cannot compile (naga's GLSL output has no
//! `textureLoad` from depth textures). The scene renderer returns either as an error
//! (the second caught by error scopes, `render::gpu::validation`, naming the pipeline
//! and the adapter), and the `skyscape` binary falls back to the CPU reference
//! renderer, or exits 1 where a GPU image is required: never a panic, never a wrong
//! image.
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

    // The precomputed rung (the scene's): atmos refuses to bake its tables on GL, whose
    // 3-D storage writes reach one slice only (a wrong image otherwise), and the render
    // falls back to the CPU reference renderer.
    let mut args = vec!["render", "stratocumulus", "--backend", "gl", "-o", out_arg];
    args.extend(size);
    let output = skyscape(&args);
    let stderr = assert_no_panic("render on gl", &output);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    for expected in [
        "the gl backend cannot bake the LUTs",
        "rendering on the CPU reference renderer",
    ] {
        assert!(stderr.contains(expected), "no `{expected}` in: {stderr}");
    }
    assert!(out.exists(), "no image at {}", out.display());
    let _ = std::fs::remove_file(&out);

    // The closed form has no tables: a pipeline GL cannot compile (textureLoad from a
    // depth texture) is caught by the error scopes, named, and the render falls back.
    let mut args = vec!["render", "stratocumulus", "--backend", "gl", "-o", out_arg];
    args.extend(["--rung", "closed-form"]);
    args.extend(size);
    let output = skyscape(&args);
    let stderr = assert_no_panic("render --rung closed-form on gl", &output);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    for expected in [
        "RungPasses::new",
        "(gl)",
        "the device rejected it",
        "textureLoad",
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
    args.extend(["--rung", "closed-form", "-o", out_arg]);
    args.extend(size);
    let output = skyscape(&args);
    let stderr = assert_no_panic("render --explain on gl", &output);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    for expected in [
        "--explain needs a GPU image",
        "(gl)",
        "the device rejected it",
    ] {
        assert!(stderr.contains(expected), "no `{expected}` in: {stderr}");
    }
    let _ = std::fs::remove_file(&out);
}
