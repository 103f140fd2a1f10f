//! The `skyscape` binary's rules beyond refusing bad input: an animation writes one
//! numbered file per frame of its range, `[output] path` is relative to the scene
//! file, what is valid but almost certainly not meant gets one warning line, and a
//! run that succeeds prints no line that says "error".

use std::path::Path;
use std::process::{Command, Output, Stdio};

/// An 8×8 scene on the closed form (milliseconds on the CPU).
const TINY: &str = "[camera]\nposition = [0.0, 2.0, 0.0]\nlook_direction = [0.0, 0.3, -1.0]\n\
                    [sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n\
                    [atmosphere]\nrung = \"closed-form\"\n[output]\nwidth = 8\nheight = 8\n";

fn skyscape(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skyscape"))
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("the skyscape binary runs")
}

fn text(output: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn an_animation_writes_its_range_as_numbered_files() {
    let dir = tempfile::tempdir().unwrap();
    let scene = format!("{TINY}[animation]\nframes = 12\nsun_elevation_deg_per_frame = 2.0\n");
    std::fs::write(dir.path().join("anim.toml"), scene).unwrap();
    std::fs::create_dir(dir.path().join("frames")).unwrap();
    let run = skyscape(
        dir.path(),
        &[
            "render",
            "anim.toml",
            "--cpu",
            "--frame-range",
            "10..12",
            "-o",
            "frames/sun_{frame}.png",
        ],
    );
    assert_eq!(run.status.code(), Some(0), "{}", text(&run));
    assert_eq!(
        files(&dir.path().join("frames")),
        ["sun_0010.png", "sun_0011.png"]
    );
    // --frames sets the length: 14 frames reach 30° + 13 × 2° = 56°.
    let run = skyscape(
        dir.path(),
        &[
            "render",
            "anim.toml",
            "--cpu",
            "--frames",
            "14",
            "--frame-range",
            "13..14",
            "-o",
            "frames/sun_{frame}.png",
        ],
    );
    assert_eq!(run.status.code(), Some(0), "{}", text(&run));
    assert!(dir.path().join("frames/sun_0013.png").is_file());
}

#[test]
fn the_output_path_of_a_scene_is_relative_to_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let scenes = dir.path().join("scenes");
    std::fs::create_dir(&scenes).unwrap();
    let scene = TINY.replace("[output]\n", "[output]\npath = \"beside.png\"\n");
    std::fs::write(scenes.join("tiny.toml"), scene).unwrap();
    let run = skyscape(dir.path(), &["render", "scenes/tiny.toml", "--cpu"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run));
    assert!(scenes.join("beside.png").is_file(), "{:?}", files(&scenes));
    assert!(!dir.path().join("beside.png").exists());
}

#[test]
fn valid_but_unlikely_values_get_one_warning_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tiny.toml"), TINY).unwrap();
    let far = TINY.replace("[0.0, 2.0, 0.0]", "[0.0, 1e9, 0.0]");
    std::fs::write(dir.path().join("far.toml"), far).unwrap();
    for (args, says) in [
        (
            &[
                "tiny.toml",
                "--sun-elevation-deg",
                "-30",
                "--sun-azimuth-deg",
                "180",
            ][..],
            "--sun-elevation-deg: `sun.elevation_deg` = -30°",
        ),
        (&["far.toml"][..], "line 2, column 12: `camera.position`"),
    ] {
        let mut all = vec!["render", "--cpu", "-o", "out.png"];
        all.extend_from_slice(args);
        let run = skyscape(dir.path(), &all);
        assert_eq!(run.status.code(), Some(0), "{args:?}: {}", text(&run));
        let stderr = String::from_utf8_lossy(&run.stderr);
        let warnings: Vec<&str> = stderr.lines().filter(|l| l.contains("warning")).collect();
        assert_eq!(warnings.len(), 1, "{args:?}: {stderr}");
        assert!(warnings[0].contains(says), "{args:?}: {stderr}");
    }
}

#[test]
fn a_successful_run_prints_no_error_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tiny.toml"), TINY).unwrap();
    // No XDG_RUNTIME_DIR (Mesa's loader then complains), and the GPU if there is one;
    // and the reference rung, which has no GPU passes, without --cpu.
    for args in [
        &["render", "tiny.toml", "-o", "a.png"][..],
        &["render", "tiny.toml", "--rung", "reference", "-o", "b.png"][..],
    ] {
        let run = Command::new(env!("CARGO_BIN_EXE_skyscape"))
            .current_dir(dir.path())
            .args(args)
            .env_remove("XDG_RUNTIME_DIR")
            .stdin(Stdio::null())
            .output()
            .unwrap();
        let all = text(&run);
        assert_eq!(run.status.code(), Some(0), "{args:?}: {all}");
        let lines: Vec<&str> = all
            .lines()
            .filter(|l| l.to_lowercase().contains("error"))
            .collect();
        assert!(lines.is_empty(), "{args:?}: {lines:?}");
    }
}

#[test]
fn stages_are_reported_and_explain_says_what_its_times_measure() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tiny.toml"), TINY).unwrap();
    // Not a terminal: a line per finished stage (over a millisecond) on stderr.
    let run = skyscape(
        dir.path(),
        &[
            "render",
            "tiny.toml",
            "--cpu",
            "--width",
            "96",
            "--height",
            "96",
            "-o",
            "a.png",
        ],
    );
    assert_eq!(run.status.code(), Some(0), "{}", text(&run));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("skyscape: tiny: drawing ") && l.ends_with(" s")),
        "{stderr}"
    );
    let run = skyscape(dir.path(), &["explain", "tiny.toml"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run));
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("the CPU's stages (wall time"), "{stdout}");
    assert!(stdout.contains("atmosphere tables"), "{stdout}");
    let gpu = stdout.contains("the GPU's work between its timestamps")
        && stdout.contains("leaves out the CPU preparation");
    let cpu = stdout.contains("no GPU passes");
    assert!(gpu || cpu, "{stdout}");
}
