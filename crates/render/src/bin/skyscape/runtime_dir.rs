//! A valid `XDG_RUNTIME_DIR` for the GPU's loaders. Mesa's Vulkan window-system code
//! (through libwayland) prints "error: XDG_RUNTIME_DIR is invalid or not set in the
//! environment." on every instance it creates when the variable names no folder, on
//! runs that succeed. Setting a variable in a running process is `unsafe` (other
//! threads may read the environment), which this workspace forbids; so, before
//! anything else runs, skyscape re-executes itself (`exec`: the same process, no
//! child) with the variable naming a private folder of its own.

/// When `XDG_RUNTIME_DIR` names no folder: makes `$TMPDIR/skyscape-runtime-UID` (mode
/// 0700, owned by this user) and re-executes skyscape with it. Returns (doing nothing)
/// when the variable is valid, or when the folder cannot be made safely.
#[cfg(unix)]
pub(crate) fn ensure_runtime_dir() {
    use std::os::unix::fs::{DirBuilderExt, MetadataExt, PermissionsExt};
    use std::os::unix::process::CommandExt;
    if std::env::var_os("XDG_RUNTIME_DIR").is_some_and(|d| std::path::Path::new(&d).is_dir()) {
        return;
    }
    let Ok(uid) = std::fs::metadata("/proc/self").map(|m| m.uid()) else {
        return;
    };
    let folder = std::env::temp_dir().join(format!("skyscape-runtime-{uid}"));
    let _ = std::fs::DirBuilder::new().mode(0o700).create(&folder);
    // Only a folder of ours that no one else can enter (not a link planted by another).
    let safe = std::fs::symlink_metadata(&folder)
        .is_ok_and(|m| m.is_dir() && m.uid() == uid && m.permissions().mode() & 0o077 == 0);
    // The running binary itself, even if its file was replaced since it started.
    let program = match std::path::Path::new("/proc/self/exe") {
        own if own.exists() => own.to_owned(),
        _ => match std::env::current_exe() {
            Ok(path) => path,
            Err(_) => return,
        },
    };
    if safe {
        let mut args = std::env::args_os();
        let mut command = std::process::Command::new(program);
        if let Some(name) = args.next() {
            command.arg0(name);
        }
        // Returns only if the exec failed; then run on with the variable as it is.
        let _ = command.args(args).env("XDG_RUNTIME_DIR", &folder).exec();
    }
}

#[cfg(not(unix))]
pub(crate) fn ensure_runtime_dir() {}
