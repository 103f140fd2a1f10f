//! Where an image goes, checked before the render starts, and how it is written.
//!
//! The rules (`docs/scenes.md`, "Output"):
//! - `-` is standard output (refused when it is a terminal);
//! - a device or a FIFO is opened and written through, never replaced;
//! - a regular file, or a name that does not exist yet, is written to `NAME.partial`
//!   beside it and renamed over it once complete; the `.partial` is created before
//!   the render (proving the folder exists and is writable) and removed on failure,
//!   Ctrl-C or SIGTERM;
//! - a symbolic link is followed: what it points to is written by the rules above (the
//!   link stays); a link to nothing is an error;
//! - a directory, a socket or anything else is refused.
//!
//! The format comes from the extension (`.png`, `.jpg`/`.jpeg`, `.exr`) or `--format`;
//! both given and disagreeing is an error, as is an unknown extension without
//! `--format`.

use std::io::Write;
use std::sync::Mutex;

use crate::*;

/// What `-o` (or the scene's path) names, classified.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Target {
    /// `-`: standard output.
    Stdout,
    /// A device or a FIFO: opened for writing, never replaced.
    Through(PathBuf),
    /// A regular file, or one to create: `NAME.partial` beside it, renamed over it.
    Replace(PathBuf),
}

/// A file extension's format, `None` for none or an unknown one.
fn extension_format(path: &Path) -> Option<Result<Format, String>> {
    let extension = path.extension()?.to_string_lossy().to_ascii_lowercase();
    Some(match extension.as_str() {
        "png" => Ok(Format::Png),
        "jpg" | "jpeg" => Ok(Format::Jpeg),
        "exr" => Ok(Format::Exr),
        _ => Err(extension),
    })
}

/// The format of `path` (from its extension) and `--format`: an unknown extension
/// needs `--format`, and the two must agree. `path` `None`: the default path, named
/// after the format.
pub(crate) fn format_for(
    path: Option<&Path>,
    flag: Option<Format>,
    label: &str,
) -> Result<Format, Failure> {
    let shown = |p: &Path| p.display().to_string();
    match (path.and_then(extension_format), flag) {
        (None, flag) => Ok(flag.unwrap_or(Format::Png)),
        (Some(Ok(from_name)), None) => Ok(from_name),
        (Some(Ok(from_name)), Some(flag)) if from_name == flag => Ok(flag),
        (Some(Ok(from_name)), Some(flag)) => Err(Failure::Input(format!(
            "--format {} contradicts {label} `{}` (a .{} name): give one, or make them agree",
            flag.name(),
            path.map(shown).unwrap_or_default(),
            from_name.extension()
        ))),
        (Some(Err(_)), Some(flag)) => Ok(flag),
        (Some(Err(extension)), None) => Err(Failure::Input(format!(
            "{label} `{}`: `.{extension}` is not an image format skyscape writes (.png, .jpg, \
             .exr): rename it, or give --format",
            path.map(shown).unwrap_or_default()
        ))),
    }
}

/// Classifies what `path` names, before any work: `mkdir` creates a missing folder
/// (else a missing folder is an error). `flag` names where the path came from.
pub(crate) fn target(path: &Path, mkdir: bool, flag: &str) -> Result<Target, Failure> {
    if path.as_os_str() == "-" {
        use std::io::IsTerminal;
        if std::io::stdout().is_terminal() {
            return Err(Failure::Input(format!(
                "{flag} -: standard output is a terminal; redirect it (> image.png) or name a file"
            )));
        }
        return Ok(Target::Stdout);
    }
    let refuse = |what: &str| {
        Failure::Input(format!(
            "{flag} `{}`: {what}; skyscape writes only a regular file (replaced when the image \
             is complete), a device, a FIFO or - (standard output)",
            path.display()
        ))
    };
    let meta = match std::fs::symlink_metadata(path) {
        Ok(meta) => meta,
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory
            ) =>
        {
            return new_file(path, mkdir, flag).map(|()| Target::Replace(path.to_owned()));
        }
        Err(e) => return Err(refuse(&format!("cannot be examined ({e})"))),
    };
    let (real, meta) = if meta.file_type().is_symlink() {
        // Followed: the link stays, what it points to is written.
        let real = std::fs::canonicalize(path).map_err(|e| {
            refuse(&format!(
                "a symbolic link to {}, which cannot be followed ({e})",
                std::fs::read_link(path)
                    .map(|t| format!("`{}`", t.display()))
                    .unwrap_or_else(|_| "nothing".into())
            ))
        })?;
        let meta = std::fs::metadata(&real).map_err(|e| refuse(&e.to_string()))?;
        (real, meta)
    } else {
        (path.to_owned(), meta)
    };
    let kind = meta.file_type();
    if kind.is_file() {
        if meta.permissions().readonly() {
            return Err(refuse("is read-only"));
        }
        return Ok(Target::Replace(real));
    }
    if kind.is_dir() {
        return Err(refuse("is a directory"));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() || kind.is_char_device() || kind.is_block_device() {
            return Ok(Target::Through(real));
        }
        if kind.is_socket() {
            return Err(refuse("is a socket"));
        }
    }
    Err(refuse("is not a regular file"))
}

/// A file to create: its folder must exist (or be created with `mkdir`).
fn new_file(path: &Path, mkdir: bool, flag: &str) -> Result<(), Failure> {
    let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) else {
        return Ok(());
    };
    match std::fs::metadata(parent) {
        Ok(meta) if meta.is_dir() => Ok(()),
        Ok(_) => Err(Failure::Input(format!(
            "{flag} `{}`: {} is not a folder",
            path.display(),
            parent.display()
        ))),
        Err(_) if mkdir => std::fs::create_dir_all(parent).map_err(|e| {
            Failure::Input(format!(
                "{flag} `{}`: creating the folder {}: {e}",
                path.display(),
                parent.display()
            ))
        }),
        Err(_) => Err(Failure::Input(format!(
            "{flag} `{}`: the folder {} does not exist (create it, or pass --mkdir)",
            path.display(),
            parent.display()
        ))),
    }
}

/// The `.partial` file a Ctrl-C or SIGTERM removes (at most one at a time).
static PARTIAL: Mutex<Option<PathBuf>> = Mutex::new(None);

/// On Ctrl-C or SIGTERM: removes the `.partial` being written, says "interrupted" and
/// exits with 130.
pub(crate) fn handle_interrupts() {
    // A second handler cannot be installed; the first one stays (not an error to report).
    let _ = ctrlc::set_handler(|| {
        if let Some(partial) = PARTIAL.lock().ok().and_then(|mut p| p.take()) {
            let _ = std::fs::remove_file(partial);
        }
        eprintln!("skyscape: interrupted");
        std::process::exit(130);
    });
}

/// An output ready to be written: for a file, its `.partial` already created (so the
/// folder is known writable before the render); dropped without [`Reserved::write`],
/// the `.partial` is removed.
#[derive(Debug)]
pub(crate) struct Reserved {
    target: Target,
    partial: Option<(PathBuf, std::fs::File)>,
}

impl Reserved {
    /// Creates `NAME.partial` for a file target (a stale regular one is replaced; any
    /// other kind of `NAME.partial` is an error).
    pub(crate) fn new(target: Target, flag: &str) -> Result<Self, Failure> {
        let Target::Replace(path) = &target else {
            return Ok(Self {
                target,
                partial: None,
            });
        };
        let mut name = path.as_os_str().to_owned();
        name.push(".partial");
        let partial = PathBuf::from(name);
        if let Ok(meta) = std::fs::symlink_metadata(&partial) {
            if !meta.is_file() {
                return Err(Failure::Input(format!(
                    "{flag} `{}`: `{}` exists and is not a file (skyscape writes the image \
                     there first)",
                    path.display(),
                    partial.display()
                )));
            }
            let _ = std::fs::remove_file(&partial);
        }
        // `create_new` does not follow a link planted in the meantime.
        let file = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&partial)
            .map_err(|e| {
                Failure::Input(format!(
                    "{flag} `{}`: cannot write in its folder ({e})",
                    path.display()
                ))
            })?;
        if let Ok(mut registered) = PARTIAL.lock() {
            *registered = Some(partial.clone());
        }
        Ok(Self {
            target,
            partial: Some((partial, file)),
        })
    }

    /// Writes the encoded image: through to stdout, a device or a FIFO, or into the
    /// `.partial` and renamed over the file.
    pub(crate) fn write(mut self, bytes: &[u8]) -> Result<(), Failure> {
        let failed = |path: &Path, e: std::io::Error| {
            Failure::Runtime(format!("writing {}: {e}", path.display()))
        };
        match (&self.target, self.partial.take()) {
            (Target::Stdout, _) => {
                let mut stdout = std::io::stdout().lock();
                stdout
                    .write_all(bytes)
                    .and_then(|()| stdout.flush())
                    .map_err(|e| failed(Path::new("standard output"), e))
            }
            (Target::Through(path), _) => std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .and_then(|mut file| file.write_all(bytes).and_then(|()| file.flush()))
                .map_err(|e| failed(path, e)),
            (Target::Replace(path), Some((partial, mut file))) => {
                let result = file
                    .write_all(bytes)
                    .and_then(|()| file.sync_all())
                    .and_then(|()| std::fs::rename(&partial, path));
                drop(file);
                unregister(&partial);
                result.map_err(|e| {
                    let _ = std::fs::remove_file(&partial);
                    failed(path, e)
                })
            }
            (Target::Replace(path), None) => Err(Failure::Runtime(format!(
                "writing {}: no .partial was reserved",
                path.display()
            ))),
        }
    }
}

impl Drop for Reserved {
    fn drop(&mut self) {
        if let Some((partial, file)) = self.partial.take() {
            drop(file);
            let _ = std::fs::remove_file(&partial);
            unregister(&partial);
        }
    }
}

fn unregister(partial: &Path) {
    if let Ok(mut registered) = PARTIAL.lock()
        && registered.as_deref() == Some(partial)
    {
        *registered = None;
    }
}

/// The rendered frame encoded in `format`: PNG (RGBA8), JPEG (RGB8, quality 92) or
/// OpenEXR (32-bit float linear radiance).
pub(crate) fn encode(
    format: Format,
    (width, height): (u32, u32),
    rendered: &Rendered,
) -> Result<Vec<u8>, Failure> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    let mismatch = || Failure::Runtime(format!("encoding: the image is not {width}×{height}"));
    let result = match format {
        Format::Png | Format::Jpeg => {
            let rgba: Vec<u8> = rendered
                .pixels
                .iter()
                .flat_map(|p| p.to_le_bytes())
                .collect();
            let image = image::RgbaImage::from_raw(width, height, rgba).ok_or_else(mismatch)?;
            if format == Format::Png {
                image.write_to(&mut bytes, image::ImageFormat::Png)
            } else {
                let rgb = image::DynamicImage::ImageRgba8(image).to_rgb8();
                rgb.write_with_encoder(image::codecs::jpeg::JpegEncoder::new_with_quality(
                    &mut bytes, 92,
                ))
            }
        }
        Format::Exr => {
            let radiance = rendered.radiance.as_deref().unwrap_or_default();
            let floats: Vec<f32> = radiance.iter().flatten().copied().collect();
            let image = image::Rgb32FImage::from_raw(width, height, floats).ok_or_else(mismatch)?;
            image.write_to(&mut bytes, image::ImageFormat::OpenExr)
        }
    };
    result.map_err(|e| Failure::Runtime(format!("encoding the {}: {e}", format.name())))?;
    Ok(bytes.into_inner())
}
