//! Composes and validates this crate's WGSL (`shaders/*.wgsl`) with naga at build
//! time, so a broken shader fails `cargo build`; exports the WGSL folders to the build
//! scripts of dependent crates (see `skyscape_wgsl::build` and `docs/architecture.md`).
//! In the workspace it also fingerprints `atmos`' sources, which name the preparation
//! cache's table files (`scene::cache`): tables baked by other code are never read back.

use std::path::Path;

fn main() {
    if let Err(error) = skyscape_wgsl::build::check_crate_shaders("render") {
        eprintln!("{error}");
        std::process::exit(1);
    }
    let atmos = Path::new(env!("CARGO_MANIFEST_DIR")).join("../atmos/src");
    if atmos.is_dir() {
        println!("cargo:rerun-if-changed={}", atmos.display());
        let mut hash = 0xcbf2_9ce4_8422_2325u64;
        fingerprint(&atmos, &mut hash);
        println!("cargo:rustc-env=SKYSCAPE_ATMOS_SOURCE_HASH={hash:016x}");
    }
}

/// FNV-1a over every file's path and bytes below `folder`, in sorted order.
fn fingerprint(folder: &Path, hash: &mut u64) {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return;
    };
    let mut paths: Vec<_> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for path in paths {
        if path.is_dir() {
            fingerprint(&path, hash);
        } else if let Ok(bytes) = std::fs::read(&path) {
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            for byte in name.unwrap_or_default().bytes().chain(bytes) {
                *hash = (*hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01b3);
            }
        }
    }
}
