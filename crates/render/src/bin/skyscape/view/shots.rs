//! The viewer's screenshots (`F12`, a script's `screenshot`) and recordings
//! (`--record N --out DIR`): a PNG of what the window shows and an OpenEXR of the
//! radiance behind it, written beside each other under names that replace nothing.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::window_gpu::Shot;
use crate::{Format, Rendered, encode};

/// Writes `shot` as `stem.png` and `stem.exr`; either file existing already is an
/// error (nothing is replaced). Returns the PNG's path.
pub(crate) fn write_pair(stem: &Path, shot: &Shot) -> Result<PathBuf, String> {
    let png = stem.with_extension("png");
    let exr = stem.with_extension("exr");
    for path in [&png, &exr] {
        if path.exists() {
            return Err(format!(
                "screenshot `{}`: exists already (skyscape view replaces no file)",
                path.display()
            ));
        }
    }
    write_new(&png, &encoded(Format::Png, shot)?)?;
    write_new(&exr, &encoded(Format::Exr, shot)?)?;
    Ok(png)
}

/// Writes `shot` as the first `skyscape-NNNN.png`/`.exr` pair in `folder` whose names
/// are both free. Returns the PNG's path.
pub(crate) fn write_numbered(folder: &Path, shot: &Shot) -> Result<PathBuf, String> {
    for number in 0..100_000 {
        let stem = folder.join(format!("skyscape-{number:04}"));
        if !stem.with_extension("png").exists() && !stem.with_extension("exr").exists() {
            return write_pair(&stem, shot);
        }
    }
    Err(format!(
        "screenshots: {} holds skyscape-0000 … skyscape-99999 already",
        folder.display()
    ))
}

/// Writes frame `index` of a recording into `folder` as `frame-NNNN.png`.
pub(crate) fn write_frame(folder: &Path, index: u32, shot: &Shot) -> Result<PathBuf, String> {
    let path = folder.join(format!("frame-{index:04}.png"));
    write_new(&path, &encoded(Format::Png, shot)?)?;
    Ok(path)
}

/// Checks `--out DIR` before any frame: a folder (created if missing) holding none of
/// the `count` frames' names.
pub(crate) fn check_record_folder(folder: &Path, count: u32) -> Result<(), String> {
    if folder.exists() && !folder.is_dir() {
        return Err(format!("--out `{}`: not a folder", folder.display()));
    }
    std::fs::create_dir_all(folder)
        .map_err(|e| format!("--out `{}`: cannot create it: {e}", folder.display()))?;
    for index in 0..count {
        let path = folder.join(format!("frame-{index:04}.png"));
        if path.exists() {
            return Err(format!(
                "--out `{}`: holds {} already (skyscape view replaces no file)",
                folder.display(),
                path.display()
            ));
        }
    }
    Ok(())
}

fn encoded(format: Format, shot: &Shot) -> Result<Vec<u8>, String> {
    // The EXR holds the renderer's radiance, at the render size.
    let size = match format {
        Format::Exr => shot.radiance_size,
        _ => shot.size,
    };
    let rendered = Rendered {
        pixels: shot.pixels.clone(),
        radiance: Some(shot.radiance.clone()),
        device: String::new(),
        pass_seconds: Vec::new(),
    };
    encode(format, size, &rendered).map_err(|failure| match failure {
        crate::Failure::Input(m) | crate::Failure::Runtime(m) => m,
    })
}

/// Creates `path` (never replacing a file) and writes `bytes` into it.
fn write_new(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(path)
        .map_err(|e| format!("`{}`: {e}", path.display()))?;
    file.write_all(bytes)
        .map_err(|e| format!("writing `{}`: {e}", path.display()))
}
