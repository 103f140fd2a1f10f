//! `rust-version` in the root `Cargo.toml` is true for the dependencies: no locked
//! package declares a newer minimum compiler than the workspace does.
//!
//! The other half of the check is clippy's `incompatible_msrv` lint (warn by default,
//! an error under CI's `-D warnings`), which reads `rust-version` and flags any std
//! API stabilised after it. Language features are not checked by either: only a build
//! with that toolchain (`cargo +1.88 check --workspace`) would.

use std::process::Command;

/// `"1.88"` or `"1.88.0"` as `(1, 88, 0)`.
fn version(text: &str) -> (u32, u32, u32) {
    let mut parts = text.split('.').map(|p| p.parse::<u32>().unwrap());
    (
        parts.next().unwrap(),
        parts.next().unwrap_or(0),
        parts.next().unwrap_or(0),
    )
}

/// The host's target triple, from `rustc -vV`.
fn host_triple() -> String {
    let output = Command::new(std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into()))
        .arg("-vV")
        .output()
        .expect("rustc -vV runs");
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .find_map(|line| line.strip_prefix("host: "))
        .expect("rustc -vV names the host")
        .to_owned()
}

#[test]
fn no_dependency_needs_a_newer_compiler_than_rust_version() {
    // Offline, only the host's packages are on disk (a build fetches no other
    // platform's), so the metadata is filtered to the host.
    let output = Command::new(env!("CARGO"))
        .args(["metadata", "--format-version", "1", "--offline", "--locked"])
        .args(["--filter-platform", &host_triple()])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo metadata runs");
    assert!(
        output.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let packages = metadata["packages"].as_array().unwrap();
    let ours = version(env!("CARGO_PKG_RUST_VERSION"));
    let mut newest = ((0, 0, 0), String::new());
    for package in packages {
        let Some(required) = package["rust_version"].as_str() else {
            continue;
        };
        let name = format!("{} {}", package["name"], package["version"]);
        if package["source"].is_null() {
            // A workspace member: all inherit the workspace's rust-version.
            assert_eq!(version(required), ours, "{name}");
        } else if version(required) > newest.0 {
            newest = (version(required), name);
        }
    }
    assert!(
        newest.0 <= ours,
        "{} needs Rust {:?}, but the workspace's rust-version is {:?}",
        newest.1,
        newest.0,
        ours
    );
    eprintln!(
        "rust-version {ours:?}; the most demanding dependency is {} ({:?})",
        newest.1, newest.0
    );
}
