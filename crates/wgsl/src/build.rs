//! Build-time composition and validation of a crate's WGSL (feature `build`).
//!
//! Every crate that ships WGSL calls [`check_crate_shaders`] from its `build.rs`, with
//! `skyscape-wgsl` (feature `build`) as a build-dependency, so a broken shader fails
//! `cargo build`, not only a test:
//!
//! ```no_run
//! // `fn main` of the build.rs of `atmos` (Cargo.toml: `links = "skyscape-wgsl-atmos"`)
//! if let Err(error) = skyscape_wgsl::build::check_crate_shaders("atmos") {
//!     eprintln!("{error}");
//!     std::process::exit(1);
//! }
//! ```
//!
//! How a build script finds WGSL it imports from other crates:
//!
//! * A crate's modules are the files `shaders/*.wgsl` beside its `Cargo.toml` (the
//!   folder the crate embeds with `include_str!`, so it is in the packaged crate too);
//!   `shaders/<stem>.wgsl` is the module `<prefix>::<stem>`.
//! * `common::*` comes from this crate ([`crate::COMMON_MODULES`]).
//! * Another crate's modules come from its build script: each WGSL crate declares a
//!   `links` key and prints `cargo::metadata=wgsl_dir_<prefix>=<folder>` for its own
//!   folder **and for every folder it received**, so the list is transitive. Cargo
//!   hands that metadata to the build scripts of direct dependents as
//!   `DEP_<LINKS>_WGSL_DIR_<PREFIX>`, which [`check_crate_shaders`] reads. No relative
//!   path between crates is assumed: it works in the workspace, in a packaged crate
//!   and from a registry.
//!
//! Only the crate's own modules are validated (each composed with its imports);
//! imported modules were validated by their own crate's build. The common modules are
//! validated by every WGSL crate's build, since `skyscape-wgsl` cannot build-depend on
//! itself.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

use crate::{COMMON_MODULES, ComposeError, Composer, Module, ValidateError};

/// The metadata key prefix: `cargo::metadata=wgsl_dir_<prefix>=<folder>`.
const METADATA_KEY: &str = "wgsl_dir_";
/// The same key as it appears in a dependent's environment (`DEP_<LINKS>_WGSL_DIR_<PREFIX>`).
const ENV_KEY: &str = "_WGSL_DIR_";

/// Errors from [`check_crate_shaders`] and [`load_modules`].
#[derive(Debug, thiserror::Error)]
pub enum BuildError {
    /// A variable cargo sets for build scripts is missing.
    #[error("environment variable `{name}` is not set (call this from a build script)")]
    MissingEnv {
        /// The variable.
        name: &'static str,
    },
    /// A module prefix is not a lowercase WGSL-style identifier.
    #[error(
        "WGSL module prefix `{prefix}` must be lowercase ASCII letters, digits and `_`, not starting with a digit"
    )]
    BadPrefix {
        /// The prefix.
        prefix: String,
    },
    /// A folder of WGSL could not be listed.
    #[error("cannot list the WGSL folder {}: {source}", path.display())]
    ReadDir {
        /// The folder.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A WGSL file could not be read.
    #[error("cannot read the WGSL file {}: {source}", path.display())]
    ReadFile {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The module list could not be written into `OUT_DIR`.
    #[error("cannot write the WGSL module list {}: {source}", path.display())]
    WriteFile {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A file name does not make a module name.
    #[error("WGSL file {} does not name a module (`<identifier>.wgsl`)", path.display())]
    BadFileName {
        /// The file.
        path: PathBuf,
    },
    /// A `DEP_*_WGSL_DIR_*` value is not valid UTF-8 or names no folder.
    #[error("`{variable}` = {value:?} does not name a WGSL folder")]
    BadDependencyDir {
        /// The environment variable.
        variable: String,
        /// Its value.
        value: OsString,
    },
    /// Two dependencies export different folders under one prefix.
    #[error("WGSL prefix `{prefix}` is exported from two folders: {} and {}", first.display(), second.display())]
    ConflictingDirs {
        /// The prefix.
        prefix: String,
        /// The folder seen first.
        first: PathBuf,
        /// The other folder.
        second: PathBuf,
    },
    /// Composition failed (unknown import, cycle, malformed directive).
    #[error(transparent)]
    Compose(#[from] ComposeError),
    /// naga rejected a composed module.
    #[error(transparent)]
    Validate(#[from] ValidateError),
}

/// What [`check_crate_shaders`] did.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckReport {
    /// The crate's own modules, each composed and validated.
    pub validated: Vec<String>,
    /// Every WGSL folder by prefix: the crate's own and those received from dependencies.
    pub dirs: BTreeMap<String, PathBuf>,
}

fn check_prefix(prefix: &str) -> Result<(), BuildError> {
    let ok = !prefix.is_empty()
        && prefix
            .chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
        && !prefix.starts_with(|c: char| c.is_ascii_digit());
    if ok {
        Ok(())
    } else {
        Err(BuildError::BadPrefix {
            prefix: prefix.to_owned(),
        })
    }
}

/// The `*.wgsl` files of `dir`, sorted by name (other files are ignored).
pub fn wgsl_files(dir: &Path) -> Result<Vec<PathBuf>, BuildError> {
    let read_dir = |source| BuildError::ReadDir {
        path: dir.to_owned(),
        source,
    };
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).map_err(read_dir)? {
        let path = entry.map_err(read_dir)?.path();
        if path.extension().is_some_and(|e| e == "wgsl") {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

/// The module names of a folder: `shaders/<stem>.wgsl` is `<prefix>::<stem>`, sorted.
///
/// Crates test that their `WGSL_MODULES` list names exactly these, so the list a
/// program composes at run time is the one validated at build time.
pub fn module_names(prefix: &str, dir: &Path) -> Result<Vec<String>, BuildError> {
    check_prefix(prefix)?;
    wgsl_files(dir)?
        .iter()
        .map(|path| module_name(prefix, path))
        .collect()
}

fn module_name(prefix: &str, path: &Path) -> Result<String, BuildError> {
    let name = path
        .file_stem()
        .and_then(|s| s.to_str())
        .map(|stem| format!("{prefix}::{stem}"))
        .filter(|name| crate::is_module_name(name))
        .ok_or_else(|| BuildError::BadFileName {
            path: path.to_owned(),
        })?;
    Ok(name)
}

/// Reads every `*.wgsl` file of `dir` as the module `<prefix>::<stem>`.
///
/// Meant for build scripts: [`Module`] holds `&'static str`, so the names and texts
/// are leaked (a build script is a short-lived process that reads a few dozen files).
pub fn load_modules(prefix: &str, dir: &Path) -> Result<Vec<Module>, BuildError> {
    check_prefix(prefix)?;
    wgsl_files(dir)?
        .into_iter()
        .map(|path| {
            let name = module_name(prefix, &path)?;
            let source = std::fs::read_to_string(&path).map_err(|source| BuildError::ReadFile {
                path: path.clone(),
                source,
            })?;
            Ok(Module {
                name: Box::leak(name.into_boxed_str()),
                source: Box::leak(source.into_boxed_str()),
            })
        })
        .collect()
}

/// The WGSL folders exported by dependencies, read from `DEP_*_WGSL_DIR_*` variables.
fn dependency_dirs(
    vars: impl Iterator<Item = (OsString, OsString)>,
) -> Result<BTreeMap<String, PathBuf>, BuildError> {
    let mut dirs = BTreeMap::new();
    for (key, value) in vars {
        let Some(key) = key.to_str() else { continue };
        if !key.starts_with("DEP_") {
            continue;
        }
        let Some(at) = key.rfind(ENV_KEY) else {
            continue;
        };
        let prefix = key[at + ENV_KEY.len()..].to_ascii_lowercase();
        check_prefix(&prefix)?;
        let dir = PathBuf::from(&value);
        if !dir.is_dir() {
            return Err(BuildError::BadDependencyDir {
                variable: key.to_owned(),
                value,
            });
        }
        insert_dir(&mut dirs, prefix, dir)?;
    }
    Ok(dirs)
}

fn insert_dir(
    dirs: &mut BTreeMap<String, PathBuf>,
    prefix: String,
    dir: PathBuf,
) -> Result<(), BuildError> {
    // Compare canonical paths: the same folder may be reached through a symlink.
    let canonical = dir.canonicalize().unwrap_or_else(|_| dir.clone());
    match dirs.get(&prefix) {
        Some(first) if *first != canonical => Err(BuildError::ConflictingDirs {
            prefix,
            first: first.clone(),
            second: canonical,
        }),
        _ => {
            dirs.insert(prefix, canonical);
            Ok(())
        }
    }
}

/// Composes and validates every module of the crate whose build script calls it, and
/// exports its WGSL folders to dependents' build scripts (see the module docs).
///
/// `prefix` is the crate's module prefix (`atmos` for `atmos::phase`). Prints the
/// `cargo::rerun-if-changed` lines for every file it reads and the
/// `cargo::metadata` lines for dependents; the crate needs a `links` key in its
/// `Cargo.toml` for cargo to pass the metadata on.
pub fn check_crate_shaders(prefix: &str) -> Result<CheckReport, BuildError> {
    check_prefix(prefix)?;
    let manifest_dir = std::env::var_os("CARGO_MANIFEST_DIR")
        .ok_or(BuildError::MissingEnv {
            name: "CARGO_MANIFEST_DIR",
        })
        .map(PathBuf::from)?;
    let own_dir = manifest_dir.join("shaders");
    let mut dirs = dependency_dirs(std::env::vars_os())?;
    insert_dir(&mut dirs, prefix.to_owned(), own_dir.clone())?;
    let report = check_dirs(prefix, &dirs)?;
    // Rerun when a file is edited, added or removed; `shaders` may be a symlink, so
    // name the canonical folders and each file.
    for dir in dirs.values() {
        println!("cargo::rerun-if-changed={}", dir.display());
        for file in wgsl_files(dir)? {
            println!("cargo::rerun-if-changed={}", file.display());
        }
    }
    for (exported, dir) in &dirs {
        println!("cargo::metadata={METADATA_KEY}{exported}={}", dir.display());
    }
    let out_dir = std::env::var_os("OUT_DIR")
        .ok_or(BuildError::MissingEnv { name: "OUT_DIR" })
        .map(PathBuf::from)?;
    let list = out_dir.join(MODULE_LIST);
    std::fs::write(&list, module_list(prefix, &own_dir)?).map_err(|source| {
        BuildError::WriteFile {
            path: list.clone(),
            source,
        }
    })?;
    Ok(report)
}

/// The file [`check_crate_shaders`] writes into `OUT_DIR`: the crate's modules as a Rust
/// expression of type `&[Module]`, every file of its folder embedded with
/// `include_str!`, so the list a program composes is the folder the build validated.
/// A crate defines its list with
/// `pub const WGSL_MODULES: &[skyscape_wgsl::Module] = include!(concat!(env!("OUT_DIR"), "/wgsl_modules.rs"));`.
pub const MODULE_LIST: &str = "wgsl_modules.rs";

/// The text of [`MODULE_LIST`] for the folder `dir` of the crate `prefix`.
pub fn module_list(prefix: &str, dir: &Path) -> Result<String, BuildError> {
    check_prefix(prefix)?;
    let mut text = String::from("&[\n");
    for path in wgsl_files(dir)? {
        let name = module_name(prefix, &path)?;
        let path = path.canonicalize().map_err(|source| BuildError::ReadFile {
            path: path.clone(),
            source,
        })?;
        let path = path
            .to_str()
            .ok_or_else(|| BuildError::BadFileName { path: path.clone() })?;
        text.push_str(&format!(
            "    skyscape_wgsl::Module {{ name: {name:?}, source: include_str!({path:?}) }},\n"
        ));
    }
    text.push(']');
    Ok(text)
}

/// The work of [`check_crate_shaders`] without the environment: validates the modules
/// of `dirs[prefix]`, composed with every module of `dirs` and the common modules.
pub fn check_dirs(
    prefix: &str,
    dirs: &BTreeMap<String, PathBuf>,
) -> Result<CheckReport, BuildError> {
    let mut composer = Composer::new();
    composer.add_modules(COMMON_MODULES)?;
    let mut own = Vec::new();
    for (module_prefix, dir) in dirs {
        let modules = load_modules(module_prefix, dir)?;
        composer.add_modules(&modules)?;
        if module_prefix == prefix {
            own = modules;
        }
    }
    let mut validated = Vec::new();
    for module in COMMON_MODULES.iter().chain(&own) {
        let source = composer.compose_module(module.name)?;
        crate::validate(module.name, &source)?;
        if module.name.starts_with(prefix) && module.name[prefix.len()..].starts_with("::") {
            validated.push(module.name.to_owned());
        }
    }
    Ok(CheckReport {
        validated,
        dirs: dirs.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scratch folder under the system's temporary directory, removed on drop.
    struct Scratch(PathBuf);

    impl Scratch {
        fn new(name: &str) -> Self {
            let dir = std::env::temp_dir()
                .join(format!("skyscape-wgsl-build-{name}-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            Self(dir)
        }

        fn write(&self, file: &str, text: &str) -> &Self {
            std::fs::write(self.0.join(file), text).unwrap();
            self
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    fn dirs(entries: &[(&str, &Scratch)]) -> BTreeMap<String, PathBuf> {
        entries
            .iter()
            .map(|(p, s)| (p.to_string(), s.0.clone()))
            .collect()
    }

    #[test]
    fn a_crate_validates_its_own_modules_with_imports_from_a_dependency() {
        let lower = Scratch::new("lower");
        lower.write("shape.wgsl", "fn area(r: f32) -> f32 { return r * r; }\n");
        let upper = Scratch::new("upper");
        upper
            .write(
                "light.wgsl",
                "#import lower::shape\n#import common::constants\nfn lit(r: f32) -> f32 { return area(r) * PI; }\n",
            )
            .write("notes.txt", "not WGSL");
        let report = check_dirs("upper", &dirs(&[("lower", &lower), ("upper", &upper)])).unwrap();
        assert_eq!(report.validated, ["upper::light"]);
    }

    #[test]
    fn a_broken_shader_fails_with_naga_s_message_naming_the_module() {
        let own = Scratch::new("broken");
        own.write("bad.wgsl", "fn f() -> f32 { return 1u; }\n");
        let error = check_dirs("own", &dirs(&[("own", &own)])).unwrap_err();
        let text = error.to_string();
        assert!(matches!(error, BuildError::Validate(_)), "{text}");
        assert!(text.contains("own::bad"), "{text}");
    }

    #[test]
    fn an_import_of_a_crate_not_exported_is_an_unknown_module() {
        let own = Scratch::new("orphan");
        own.write("a.wgsl", "#import elsewhere::thing\nfn a() {}\n");
        assert!(matches!(
            check_dirs("own", &dirs(&[("own", &own)])),
            Err(BuildError::Compose(ComposeError::UnknownModule { .. }))
        ));
    }

    #[test]
    fn dependency_folders_are_read_from_dep_variables() {
        let lower = Scratch::new("dep");
        let var = |k: &str, v: &Path| (OsString::from(k), v.as_os_str().to_owned());
        let found = dependency_dirs(
            [
                var("DEP_SKYSCAPE_WGSL_LOWER_WGSL_DIR_LOWER", &lower.0),
                var("DEP_SKYSCAPE_WGSL_MID_WGSL_DIR_LOWER", &lower.0),
                var("DEP_Z_OTHER", Path::new("/nonexistent")),
                var("PATH", Path::new("/bin")),
            ]
            .into_iter(),
        )
        .unwrap();
        assert_eq!(found.len(), 1);
        assert_eq!(found["lower"], lower.0.canonicalize().unwrap());

        let other = Scratch::new("dep-other");
        assert!(matches!(
            dependency_dirs(
                [
                    var("DEP_A_WGSL_DIR_LOWER", &lower.0),
                    var("DEP_B_WGSL_DIR_LOWER", &other.0),
                ]
                .into_iter()
            ),
            Err(BuildError::ConflictingDirs { .. })
        ));
        assert!(matches!(
            dependency_dirs([var("DEP_A_WGSL_DIR_LOWER", Path::new("/nonexistent"))].into_iter()),
            Err(BuildError::BadDependencyDir { .. })
        ));
    }

    #[test]
    fn the_module_list_embeds_every_file_of_the_folder() {
        let dir = Scratch::new("list");
        dir.write("b.wgsl", "fn b() {}\n")
            .write("a.wgsl", "fn a() {}\n")
            .write("notes.txt", "not wgsl");
        let list = module_list("own", &dir.0).unwrap();
        let a = list.find("\"own::a\"").unwrap();
        let b = list.find("\"own::b\"").unwrap();
        assert!(a < b, "{list}");
        assert_eq!(list.matches("include_str!").count(), 2, "{list}");
        assert!(!list.contains("notes"), "{list}");
    }

    #[test]
    fn module_names_follow_file_stems_and_reject_bad_ones() {
        let own = Scratch::new("names");
        own.write("b.wgsl", "").write("a.wgsl", "");
        assert_eq!(module_names("own", &own.0).unwrap(), ["own::a", "own::b"]);
        own.write("bad-name.wgsl", "");
        assert!(matches!(
            module_names("own", &own.0),
            Err(BuildError::BadFileName { .. })
        ));
        assert!(matches!(
            module_names("Own", &own.0),
            Err(BuildError::BadPrefix { .. })
        ));
    }
}
