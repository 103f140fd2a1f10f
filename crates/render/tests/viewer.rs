//! `skyscape view` under a window system (Xvfb when no display is set) with a script
//! that turns and moves the camera and moves the clock, then takes a screenshot. The
//! screenshot (read back from the window's surface) agrees with `skyscape render` of
//! the same camera and time on the same adapter within the renderer's GPU-vs-CPU bound
//! (`common::Agreement`, as `scene_gpu`; the two are the same passes, so in practice
//! identical), has no bias against the CPU reference renderer's picture (whose terrain
//! silhouettes differ pixel by pixel from rasterised triangles this close), and does
//! not agree with the render of a camera turned 2° further: the comparison can fail.

mod common;

use std::path::{Path, PathBuf};
use std::process::{Child, Command};

use common::Agreement;

const SKYSCAPE: &str = env!("CARGO_BIN_EXE_skyscape");
const SIZE: (u32, u32) = (240, 135);

/// An X server this test started (stopped when dropped).
struct Xvfb(Child);

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The display to open the window on: the session's, else an Xvfb started here; None
/// (skip, or fail under `SKYSCAPE_REQUIRE_GPU=1`) when neither exists.
fn display() -> Option<(String, Option<Xvfb>)> {
    if let Ok(display) = std::env::var("DISPLAY")
        && !display.is_empty()
    {
        return Some((display, None));
    }
    for number in 90..110 {
        let name = format!(":{number}");
        if display_in_use(number) {
            continue;
        }
        let socket = format!("/tmp/.X11-unix/X{number}");
        let spawned = std::time::SystemTime::now();
        let child = Command::new("Xvfb")
            .args([
                name.as_str(),
                "-screen",
                "0",
                "640x480x24",
                "-nolisten",
                "tcp",
            ])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .ok()?;
        let server = Xvfb(child);
        for _ in 0..100 {
            // Ready once this server has made its socket: one left by a server killed
            // earlier is older than the spawn.
            let fresh = std::fs::metadata(&socket)
                .and_then(|m| m.modified())
                .is_ok_and(|made| made >= spawned);
            if fresh {
                return Some((name, Some(server)));
            }
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        return None;
    }
    None
}

/// Whether display `:number` has a running server: its lock file names a live process.
/// A socket without one was left by a server that was killed; a new server replaces it.
fn display_in_use(number: u32) -> bool {
    let Ok(lock) = std::fs::read_to_string(format!("/tmp/.X{number}-lock")) else {
        return false;
    };
    match lock.trim().parse::<u32>() {
        Ok(pid) if Path::new("/proc/self").exists() => Path::new(&format!("/proc/{pid}")).exists(),
        _ => true,
    }
}

/// The default scene's camera after the script's `turn 20 -3` and `move 300 100 50`,
/// worked out here from the scene file (x east, y up, z south; azimuth clockwise from
/// north), not by the viewer's code: where it starts, its view and its travel.
fn expected_pose(extra_turn_deg: f64) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let position = [-2000.0, 3300.0, 14500.0];
    let look_at = [0.0, 1900.0, 0.0];
    let f: Vec<f64> = (0..3).map(|i| look_at[i] - position[i]).collect();
    let length = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
    let azimuth = f[0].atan2(-f[2]) + (20.0 + extra_turn_deg).to_radians();
    let elevation = (f[1] / length).asin() - 3f64.to_radians();
    let forward = [
        azimuth.sin() * elevation.cos(),
        elevation.sin(),
        -azimuth.cos() * elevation.cos(),
    ];
    let right = [azimuth.cos(), 0.0, azimuth.sin()];
    let travel = [
        300.0 * forward[0] + 100.0 * right[0],
        300.0 * forward[1] + 100.0 * right[1] + 50.0,
        300.0 * forward[2] + 100.0 * right[2],
    ];
    (position, forward, travel)
}

/// `skyscape render` (`--cpu` when `cpu`) of the default scene from `pose`, 1800 s
/// later: frame 1 of an animation whose camera travels the viewer's move, so that the
/// cloud layers keep their place on the ground as they do in the viewer (their texture
/// offset is the camera's travel from the scene's start).
fn render(
    folder: &Path,
    name: &str,
    (position, forward, travel): ([f64; 3], [f64; 3], [f64; 3]),
    cpu: bool,
) -> Vec<u32> {
    let source = render::scene::shipped::shipped("default").unwrap().source;
    let look_at: Vec<f64> = (0..3).map(|a| position[a] + 1000.0 * forward[a]).collect();
    let camera = format!(
        "[camera]\nposition = {position:?}\nlook_at = {look_at:?}\n\
         vertical_fov_deg = 50.0\nnear = 1.0\nfar = 120000.0\n\n\
         [animation]\nframes = 2\ncamera_m_per_frame = {travel:?}\n"
    );
    let start = source.find("[camera]").unwrap();
    let end = source.find("[time]").unwrap();
    let scene = format!(
        "{}{camera}\n{}",
        &source[..start],
        source[end..].replace(
            "longitude_deg = 8.0",
            "longitude_deg = 8.0\noffset_s = 1800.0"
        )
    );
    let path = folder.join(format!("{name}.toml"));
    std::fs::write(&path, scene).unwrap();
    let image = folder.join(format!("{name}-{{frame}}.png"));
    let output = Command::new(SKYSCAPE)
        .arg("render")
        .arg(&path)
        .args(cpu.then_some("--cpu"))
        .args(["--frame-range", "1..2", "--no-cache", "--width"])
        .arg(SIZE.0.to_string())
        .arg("--height")
        .arg(SIZE.1.to_string())
        .arg("-o")
        .arg(&image)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    pixels(&folder.join(format!("{name}-0001.png")))
}

fn pixels(path: &Path) -> Vec<u32> {
    let image = image::open(path).unwrap().to_rgba8();
    assert_eq!(image.dimensions(), SIZE, "{}", path.display());
    image
        .pixels()
        .map(|p| u32::from_le_bytes([p[0], p[1], p[2], 255]))
        .collect()
}

#[test]
fn a_scripted_flight_shows_what_skyscape_render_draws() {
    let Some((display, _server)) = display() else {
        assert!(
            !skyscape_harness::gpu_required(),
            "SKYSCAPE_REQUIRE_GPU=1 but neither DISPLAY nor Xvfb is available"
        );
        eprintln!("SKIPPED render::viewer: no DISPLAY and no Xvfb (install xvfb)");
        return;
    };
    let folder = tempfile::tempdir().unwrap();
    let shot: PathBuf = folder.path().join("shot");
    let script = folder.path().join("flight.txt");
    std::fs::write(
        &script,
        format!(
            "0 turn 20 -3\n0 move 300 100 50\n1 time 1800\n2 screenshot {}\n3 quit\n",
            shot.display()
        ),
    )
    .unwrap();
    let output = Command::new(SKYSCAPE)
        .args(["view", "default", "--scale", "1", "--no-cache", "--size"])
        .arg(format!("{}x{}", SIZE.0, SIZE.1))
        .arg("--script")
        .arg(&script)
        .env("DISPLAY", &display)
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    if !output.status.success() && stderr.contains("no GPU adapter") {
        assert!(!skyscape_harness::gpu_required(), "{stderr}");
        eprintln!("SKIPPED render::viewer: {stderr}");
        return;
    }
    assert!(output.status.success(), "skyscape view failed: {stderr}");
    assert!(shot.with_extension("exr").is_file(), "{stderr}");
    let viewer = pixels(&shot.with_extension("png"));

    let expected = render(folder.path(), "expected", expected_pose(0.0), false);
    let agreement = Agreement::of(&viewer, &expected, SIZE.0 as usize);
    let differing = viewer.iter().zip(&expected).filter(|(a, b)| a != b).count();
    eprintln!(
        "viewer against skyscape render: {agreement}; {differing} of {} pixels differ",
        viewer.len()
    );
    assert!(agreement.close(), "{}", agreement.fractions());
    assert!(agreement.unbiased(1.0), "{}", agreement.biases());

    let reference = render(folder.path(), "reference", expected_pose(0.0), true);
    let physics = Agreement::of(&viewer, &reference, SIZE.0 as usize);
    eprintln!("viewer against skyscape render --cpu: {physics}");
    assert!(physics.unbiased(1.0), "{}", physics.biases());

    // Another camera's picture fails the comparison.
    let turned = render(folder.path(), "turned", expected_pose(2.0), false);
    let other = Agreement::of(&viewer, &turned, SIZE.0 as usize);
    eprintln!("viewer against a camera turned 2° further: {other}");
    assert!(!(other.close() && other.unbiased(1.0)), "{other}");
}

#[test]
fn bad_flags_are_named_before_any_window_opens() {
    let folder = tempfile::tempdir().unwrap();
    let bad_script = folder.path().join("bad.txt");
    std::fs::write(&bad_script, "0 turn 10\n").unwrap();
    let a_file = folder.path().join("a_file");
    std::fs::write(&a_file, "").unwrap();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (vec!["--size".into(), "0x5".into()], "--size `0x5`"),
        (
            vec!["--scale".into(), "2".into()],
            "--scale 2: must be in (0, 1]",
        ),
        (vec!["--scale".into(), "NaN".into()], "--scale NaN"),
        (
            vec!["--script".into(), bad_script.display().to_string()],
            "line 1: `turn` takes 2 numbers, got `10`",
        ),
        (
            vec!["--script".into(), "no/such/script.txt".into()],
            "--script `no/such/script.txt`",
        ),
        (
            vec![
                "--record".into(),
                "2".into(),
                "--out".into(),
                a_file.display().to_string(),
            ],
            "not a folder",
        ),
        (
            vec!["--record".into(), "0".into(), "--out".into(), "x".into()],
            "--record 0",
        ),
        (vec!["no_such_scene".into()], "scene `no_such_scene`"),
        (
            vec!["--backend".into(), "glide".into()],
            "`glide` is not a backend",
        ),
    ];
    for (args, expected) in cases {
        let output = Command::new(SKYSCAPE)
            .arg("view")
            .args(&args)
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    assert_eq!(
        std::fs::read_dir(folder.path()).unwrap().count(),
        2,
        "no file written"
    );
    // No window system: a message, not a panic.
    let output = Command::new(SKYSCAPE)
        .arg("view")
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .env_remove("WAYLAND_SOCKET")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("needs a display"), "{stderr}");
}
