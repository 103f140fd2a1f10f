//! The `skyscape` binary never destroys what `-o` points at: a device, a FIFO and
//! standard output are written through, a symbolic link is followed (and kept), a
//! directory or a link to nothing is refused before the render starts, the format
//! comes from the extension, and Ctrl-C removes the `.partial` it was writing.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// An 8×8 scene on the closed form (milliseconds on the CPU).
const TINY: &str = "[camera]\nposition = [0.0, 2.0, 0.0]\nlook_direction = [0.0, 0.3, -1.0]\n\
                    [sun]\nelevation_deg = 30.0\nazimuth_deg = 180.0\n\
                    [atmosphere]\nrung = \"closed-form\"\n[output]\nwidth = 8\nheight = 8\n";

const PNG: &[u8] = b"\x89PNG\r\n\x1a\n";
const JPEG: &[u8] = b"\xff\xd8\xff";
const EXR: &[u8] = b"\x76\x2f\x31\x01";

/// A temporary folder holding the tiny scene as `tiny.toml`.
fn folder() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let scene = dir.path().join("tiny.toml");
    std::fs::write(&scene, TINY).expect("the scene is written");
    (dir, scene)
}

fn skyscape(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skyscape"))
        .current_dir(dir)
        .args(args)
        .stdin(Stdio::null())
        .output()
        .expect("the skyscape binary runs")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The folder's entries, sorted (to check nothing else was written).
fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

fn is_kind(path: &Path, check: fn(&std::fs::FileType) -> bool) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| check(&m.file_type()))
}

#[cfg(unix)]
#[test]
fn a_fifo_is_written_through_not_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let (dir, _) = folder();
    let fifo = dir.path().join("image.png");
    let made = Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo {fifo:?}");
    // The reader blocks until skyscape opens the FIFO for writing.
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read(fifo).expect("the FIFO is read"))
    };
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "image.png"],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let bytes = reader.join().unwrap();
    assert!(
        bytes.starts_with(PNG),
        "the reader got {} bytes",
        bytes.len()
    );
    assert!(is_kind(&fifo, |t| t.is_fifo()), "the FIFO is still a FIFO");
    assert_eq!(entries(dir.path()), ["image.png", "tiny.toml"]);
}

#[cfg(unix)]
#[test]
fn dev_null_and_a_device_node_are_written_through() {
    use std::os::unix::fs::FileTypeExt;
    let (dir, _) = folder();
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "/dev/null"],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(is_kind(Path::new("/dev/null"), |t| t.is_char_device()));
    // A device node of our own (the null device's numbers), where mknod is allowed.
    let node = dir.path().join("null.png");
    let made = Command::new("mknod")
        .arg(&node)
        .args(["c", "1", "3"])
        .stderr(Stdio::null())
        .status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("dev_null_and_a_device_node_are_written_through: mknod not allowed here");
        return;
    }
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "null.png"],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        is_kind(&node, |t| t.is_char_device()),
        "still a device node"
    );
}

#[cfg(unix)]
#[test]
fn a_full_device_is_an_error_and_stays_a_device() {
    use std::os::unix::fs::FileTypeExt;
    let (dir, _) = folder();
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "/dev/full"],
    );
    assert_eq!(output.status.code(), Some(1), "{}", stderr(&output));
    assert!(stderr(&output).contains("/dev/full"), "{}", stderr(&output));
    assert!(is_kind(Path::new("/dev/full"), |t| t.is_char_device()));
}

#[cfg(unix)]
#[test]
fn a_symlink_is_followed_and_kept() {
    let (dir, _) = folder();
    let real = dir.path().join("real.png");
    std::fs::write(&real, b"old").unwrap();
    std::os::unix::fs::symlink("real.png", dir.path().join("link.png")).unwrap();
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "link.png"],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let link = dir.path().join("link.png");
    assert!(is_kind(&link, |t| t.is_symlink()), "the link stays a link");
    assert!(std::fs::read(&real).unwrap().starts_with(PNG));
    assert_eq!(entries(dir.path()), ["link.png", "real.png", "tiny.toml"]);
}

#[cfg(unix)]
#[test]
fn a_dangling_symlink_is_refused() {
    let (dir, _) = folder();
    std::os::unix::fs::symlink("nowhere.png", dir.path().join("link.png")).unwrap();
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "link.png"],
    );
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(
        stderr(&output).contains("symbolic link"),
        "{}",
        stderr(&output)
    );
    assert_eq!(entries(dir.path()), ["link.png", "tiny.toml"]);
}

#[test]
fn a_directory_is_refused_before_the_render_starts() {
    let (dir, scene) = folder();
    std::fs::create_dir(dir.path().join("out.png")).unwrap();
    // A scene whose preparation fails: the output's error must come first.
    let broken = TINY.replace("[camera]\n", "[camera]\nnear = 10.0\nfar = 1.0\n");
    std::fs::write(&scene, broken).unwrap();
    let output = skyscape(
        dir.path(),
        &["render", "tiny.toml", "--cpu", "-o", "out.png"],
    );
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    let text = stderr(&output);
    assert!(text.contains("-o `out.png`: is a directory"), "{text}");
    assert!(!text.contains("camera.far"), "{text}");
    assert!(dir.path().join("out.png").is_dir());
    assert_eq!(entries(dir.path()), ["out.png", "tiny.toml"]);
}

#[test]
fn output_folder_errors_come_before_the_render() {
    let (dir, scene) = folder();
    let broken = TINY.replace("[camera]\n", "[camera]\nnear = 10.0\nfar = 1.0\n");
    std::fs::write(&scene, broken).unwrap();
    let read_only = dir.path().join("kept.png");
    std::fs::write(&read_only, b"keep").unwrap();
    let mut permissions = std::fs::metadata(&read_only).unwrap().permissions();
    permissions.set_readonly(true);
    std::fs::set_permissions(&read_only, permissions).unwrap();
    for (output, says) in [
        ("missing/out.png", "does not exist"),
        ("tiny.toml/out.png", "is not a folder"),
        ("kept.png", "is read-only"),
    ] {
        let run = skyscape(dir.path(), &["render", "tiny.toml", "--cpu", "-o", output]);
        assert_eq!(run.status.code(), Some(2), "{output}: {}", stderr(&run));
        assert!(stderr(&run).contains(says), "{output}: {}", stderr(&run));
    }
    assert_eq!(std::fs::read(&read_only).unwrap(), b"keep");
    assert_eq!(entries(dir.path()), ["kept.png", "tiny.toml"]);
}

#[test]
fn the_format_comes_from_the_extension_and_a_contradiction_is_refused() {
    let (dir, _) = folder();
    for (name, magic) in [
        ("a.png", PNG),
        ("b.jpg", JPEG),
        ("c.JPEG", JPEG),
        ("d.exr", EXR),
    ] {
        let output = skyscape(dir.path(), &["render", "tiny.toml", "--cpu", "-o", name]);
        assert_eq!(output.status.code(), Some(0), "{name}: {}", stderr(&output));
        let bytes = std::fs::read(dir.path().join(name)).unwrap();
        assert!(bytes.starts_with(magic), "{name}: {:02x?}", &bytes[..8]);
    }
    for args in [
        &["--format", "exr", "-o", "e.png"][..],
        &["--format", "png", "-o", "e.jpg"][..],
        &["-o", "e.tiff"][..],
    ] {
        let mut all = vec!["render", "tiny.toml", "--cpu"];
        all.extend_from_slice(args);
        let output = skyscape(dir.path(), &all);
        assert_eq!(
            output.status.code(),
            Some(2),
            "{args:?}: {}",
            stderr(&output)
        );
        assert!(
            stderr(&output).contains("-o"),
            "{args:?}: {}",
            stderr(&output)
        );
    }
    // An unknown extension with --format is that format.
    let output = skyscape(
        dir.path(),
        &[
            "render",
            "tiny.toml",
            "--cpu",
            "--format",
            "jpeg",
            "-o",
            "f.img",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        std::fs::read(dir.path().join("f.img"))
            .unwrap()
            .starts_with(JPEG)
    );
    assert_eq!(
        entries(dir.path()),
        ["a.png", "b.jpg", "c.JPEG", "d.exr", "f.img", "tiny.toml"]
    );
}

#[test]
fn a_dash_writes_standard_output() {
    let (dir, _) = folder();
    let output = skyscape(dir.path(), &["render", "tiny.toml", "--cpu", "-o", "-"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(output.stdout.starts_with(PNG));
    // What skyscape says goes to stderr then.
    assert!(stderr(&output).contains("wrote standard output"));
    assert_eq!(entries(dir.path()), ["tiny.toml"]);
}

#[cfg(unix)]
#[test]
fn ctrl_c_removes_the_partial_and_says_interrupted() {
    let (dir, _) = folder();
    // The reference rung's tables take seconds to build: time to interrupt it.
    let child = Command::new(env!("CARGO_BIN_EXE_skyscape"))
        .current_dir(dir.path())
        .args([
            "render",
            "tiny.toml",
            "--cpu",
            "--rung",
            "reference",
            "-o",
            "out.png",
        ])
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the skyscape binary runs");
    let partial = dir.path().join("out.png.partial");
    let start = std::time::Instant::now();
    while !partial.exists() {
        assert!(
            start.elapsed().as_secs() < 60,
            "no .partial within 60 s: {:?}",
            entries(dir.path())
        );
        std::thread::sleep(std::time::Duration::from_millis(10));
    }
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status();
    assert!(kill.is_ok_and(|s| s.success()));
    let output = child.wait_with_output().unwrap();
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(130), "{text}");
    assert!(text.contains("interrupted"), "{text}");
    assert_eq!(entries(dir.path()), ["tiny.toml"], "{text}");
}
