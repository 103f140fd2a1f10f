//! Composes and validates this crate's WGSL (`shaders/*.wgsl`) with naga at build
//! time, so a broken shader fails `cargo build`; exports the WGSL folders to the build
//! scripts of dependent crates (see `skyscape_wgsl::build` and `docs/architecture.md`).

fn main() {
    if let Err(error) = skyscape_wgsl::build::check_crate_shaders("cloudlight") {
        eprintln!("{error}");
        std::process::exit(1);
    }
}
