//! WGSL module composition for skyscape.
//!
//! skyscape keeps every WGSL function exactly once (under `shaders/<crate>/`) and lets
//! other crates use it by import rather than by copy. The mechanism is a deliberately
//! small preprocessor with one directive:
//!
//! ```wgsl
//! #import atmos::phase
//! ```
//!
//! * A directive is a line whose first non-blank characters are `#import`, followed by
//!   one module name `crate::module`. Nothing else may follow on the line except a `//`
//!   comment.
//! * [`Composer::compose`] resolves imports depth first, emits each module **once**
//!   (before the first module that needs it) and then the root source. Cycles and
//!   unknown modules are errors naming the importing module.
//! * There is no textual `#define`/`#ifdef`: variants are WGSL `override` constants, so
//!   the composed text is always plain, valid WGSL and naga sees every branch.
//! * A forgotten composition step fails loudly: `#` is not a WGSL token, so naga
//!   rejects an uncomposed source.
//! * [`Composer::compose_module_bound`] binds an import to another module chosen by the
//!   Rust side: every `#import slot` then emits the bound module instead. The slot is a
//!   registered module itself (the default every module composes and validates with on
//!   its own), so one module written against an interface (e.g. cloudlight's march over
//!   `cloudlight::density_source`) serves every implementation without a copy.
//!
//! Why not naga_oil or WESL: both pin a naga version that trails wgpu's by a release or
//! more, and skyscape needs nothing beyond ordered, deduplicated inclusion. Name
//! clashes between modules are reported by naga itself when the composed source is
//! validated (see [`validate`], behind the `validate` feature).

#[cfg(feature = "build")]
pub mod build;
pub mod common;
pub mod dispatch;

use std::collections::{BTreeMap, HashSet};

/// The shared WGSL modules (`common::*`), canonical under `shaders/common/`.
pub const COMMON_MODULES: &[Module] = &[
    Module {
        name: "common::constants",
        source: include_str!("../shaders/constants.wgsl"),
    },
    Module {
        name: "common::hash",
        source: include_str!("../shaders/hash.wgsl"),
    },
    Module {
        name: "common::frames",
        source: include_str!("../shaders/frames.wgsl"),
    },
];

/// One named WGSL source file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Module {
    /// `crate::module`, e.g. `atmos::phase`.
    pub name: &'static str,
    /// The WGSL text, possibly with `#import` directives.
    pub source: &'static str,
}

/// Errors from registering or composing modules.
#[derive(Debug, Clone, thiserror::Error, PartialEq, Eq)]
pub enum ComposeError {
    /// A module name was registered twice with different sources.
    #[error("WGSL module `{name}` is registered twice with different sources")]
    DuplicateModule {
        /// The clashing name.
        name: String,
    },
    /// A module name does not have the `crate::module` form.
    #[error("WGSL module name `{name}` is not of the form `crate::module`")]
    BadModuleName {
        /// The offending name.
        name: String,
    },
    /// An `#import` names a module that was never registered.
    #[error("`{importer}` line {line}: `#import {module}` names an unknown module")]
    UnknownModule {
        /// The module (or root) containing the directive.
        importer: String,
        /// 1-based line number of the directive in `importer`.
        line: usize,
        /// The requested module.
        module: String,
    },
    /// A directive that is not `#import crate::module`.
    #[error(
        "`{importer}` line {line}: malformed directive `{text}` (expected `#import crate::module`)"
    )]
    MalformedDirective {
        /// The module (or root) containing the directive.
        importer: String,
        /// 1-based line number.
        line: usize,
        /// The text of the line.
        text: String,
    },
    /// Modules import each other in a cycle.
    #[error("WGSL import cycle: {}", chain.join(" -> "))]
    ImportCycle {
        /// The chain of module names, first and last equal.
        chain: Vec<String>,
    },
}

/// A set of registered modules that sources can import from.
#[derive(Debug, Clone, Default)]
pub struct Composer {
    modules: BTreeMap<&'static str, &'static str>,
}

/// What a line of WGSL is, as far as the composer cares.
enum Line<'a> {
    Import(&'a str),
    Malformed,
    Text,
}

fn classify(line: &str) -> Line<'_> {
    let trimmed = line.trim_start();
    let Some(rest) = trimmed.strip_prefix('#') else {
        return Line::Text;
    };
    let Some(rest) = rest.strip_prefix("import") else {
        return Line::Malformed;
    };
    let rest = match rest.find("//") {
        Some(comment) => &rest[..comment],
        None => rest,
    };
    let mut words = rest.split_whitespace();
    match (words.next(), words.next()) {
        (Some(name), None) if is_module_name(name) && rest.starts_with(char::is_whitespace) => {
            Line::Import(name)
        }
        _ => Line::Malformed,
    }
}

fn is_module_name(name: &str) -> bool {
    let mut parts = name.split("::");
    let ident = |s: &str| {
        !s.is_empty()
            && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !s.starts_with(|c: char| c.is_ascii_digit())
    };
    matches!((parts.next(), parts.next(), parts.next()), (Some(a), Some(b), None) if ident(a) && ident(b))
}

impl Composer {
    /// An empty composer; [`Composer::with_common`] is usually what you want.
    pub fn new() -> Self {
        Self::default()
    }

    /// A composer that already knows [`COMMON_MODULES`].
    pub fn with_common() -> Self {
        let mut composer = Self::new();
        composer
            .add_modules(COMMON_MODULES)
            .expect("common modules are well formed");
        composer
    }

    /// Registers modules. Registering the identical module twice is allowed (crates
    /// may each add their dependencies' modules); a different source under the same
    /// name is an error.
    pub fn add_modules(&mut self, modules: &[Module]) -> Result<&mut Self, ComposeError> {
        for module in modules {
            if !is_module_name(module.name) {
                return Err(ComposeError::BadModuleName {
                    name: module.name.to_owned(),
                });
            }
            match self.modules.get(module.name) {
                Some(existing) if *existing != module.source => {
                    return Err(ComposeError::DuplicateModule {
                        name: module.name.to_owned(),
                    });
                }
                _ => {
                    self.modules.insert(module.name, module.source);
                }
            }
        }
        Ok(self)
    }

    /// Names of all registered modules, sorted.
    pub fn module_names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.modules.keys().copied()
    }

    /// Composes the registered module `name` on its own (useful for validation).
    pub fn compose_module(&self, name: &str) -> Result<String, ComposeError> {
        let source = self
            .modules
            .get(name)
            .ok_or_else(|| ComposeError::UnknownModule {
                importer: "<caller>".into(),
                line: 0,
                module: name.to_owned(),
            })?;
        // The root is itself a module: importing itself is a cycle.
        self.compose_with_stack(name, source, vec![name.to_owned()], &[])
    }

    /// [`Composer::compose_module`] with imports bound to other modules: for each
    /// `(slot, module)` of `bindings`, every `#import slot` reached from `name` emits
    /// the registered `module` instead (once, also when `module` is imported directly).
    /// The slot is a registered module too: the default that every importer composes
    /// and validates with on its own (e.g. an interface written as its trivial case),
    /// so binding it chooses another implementation at composition time without a copy
    /// of the importers. A bound module that is not registered is
    /// [`ComposeError::UnknownModule`] naming the slot's importer and line.
    pub fn compose_module_bound(
        &self,
        name: &str,
        bindings: &[(&str, &str)],
    ) -> Result<String, ComposeError> {
        let source = self
            .modules
            .get(name)
            .ok_or_else(|| ComposeError::UnknownModule {
                importer: "<caller>".into(),
                line: 0,
                module: name.to_owned(),
            })?;
        self.compose_with_stack(name, source, vec![name.to_owned()], bindings)
    }

    /// Resolves the imports of `root_source` (named `root_name` in errors) and returns
    /// plain WGSL: each imported module once, dependencies first, then the root.
    ///
    /// `root_name` only labels errors: a free-standing root is not a module, so it may
    /// share a name with one it imports (e.g. a test kernel named after its function).
    pub fn compose(&self, root_name: &str, root_source: &str) -> Result<String, ComposeError> {
        self.compose_with_stack(root_name, root_source, Vec::new(), &[])
    }

    fn compose_with_stack(
        &self,
        root_name: &str,
        root_source: &str,
        mut stack: Vec<String>,
        bindings: &[(&str, &str)],
    ) -> Result<String, ComposeError> {
        let mut out = String::new();
        let mut emitted = HashSet::new();
        self.emit(
            root_name,
            root_source,
            bindings,
            &mut emitted,
            &mut stack,
            &mut out,
        )?;
        Ok(out)
    }

    fn emit(
        &self,
        name: &str,
        source: &str,
        bindings: &[(&str, &str)],
        emitted: &mut HashSet<String>,
        stack: &mut Vec<String>,
        out: &mut String,
    ) -> Result<(), ComposeError> {
        // Dependencies first, in directive order.
        for (index, line) in source.lines().enumerate() {
            match classify(line) {
                Line::Text => {}
                Line::Malformed => {
                    return Err(ComposeError::MalformedDirective {
                        importer: name.to_owned(),
                        line: index + 1,
                        text: line.trim().to_owned(),
                    });
                }
                Line::Import(imported) => {
                    let module = bindings
                        .iter()
                        .find(|(slot, _)| *slot == imported)
                        .map_or(imported, |&(_, bound)| bound);
                    if stack.iter().any(|s| s == module) {
                        let mut chain = stack.clone();
                        if chain.last().map(String::as_str) != Some(name) {
                            chain.push(name.to_owned());
                        }
                        chain.push(module.to_owned());
                        return Err(ComposeError::ImportCycle { chain });
                    }
                    if emitted.contains(module) {
                        continue;
                    }
                    let dependency =
                        self.modules
                            .get(module)
                            .ok_or_else(|| ComposeError::UnknownModule {
                                importer: name.to_owned(),
                                line: index + 1,
                                module: module.to_owned(),
                            })?;
                    stack.push(module.to_owned());
                    self.emit(module, dependency, bindings, emitted, stack, out)?;
                    stack.pop();
                    emitted.insert(module.to_owned());
                }
            }
        }
        // Then the body, with directives blanked (keeps line structure readable).
        out.push_str("// ---- begin ");
        out.push_str(name);
        out.push_str(" ----\n");
        for line in source.lines() {
            if matches!(classify(line), Line::Text) {
                out.push_str(line);
            }
            out.push('\n');
        }
        out.push_str("// ---- end ");
        out.push_str(name);
        out.push_str(" ----\n");
        Ok(())
    }
}

/// Errors from naga validation of a composed source.
#[cfg(feature = "validate")]
#[derive(Debug, thiserror::Error)]
pub enum ValidateError {
    /// The WGSL front end rejected the text.
    #[error("WGSL parse error in `{name}`:\n{message}")]
    Parse {
        /// Name given to [`validate`].
        name: String,
        /// naga's rendered diagnostic, with source excerpt.
        message: String,
    },
    /// The module parsed but failed validation.
    #[error("WGSL validation error in `{name}`:\n{message}")]
    Validation {
        /// Name given to [`validate`].
        name: String,
        /// naga's rendered diagnostic.
        message: String,
    },
}

/// Parses and validates composed WGSL with naga (the same front end wgpu uses), with
/// every capability enabled so that only real errors are reported.
#[cfg(feature = "validate")]
pub fn validate(name: &str, source: &str) -> Result<naga::Module, ValidateError> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| ValidateError::Parse {
        name: name.to_owned(),
        message: e.emit_to_string_with_path(source, name),
    })?;
    let mut validator = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    );
    validator
        .validate(&module)
        .map_err(|e| ValidateError::Validation {
            name: name.to_owned(),
            message: e.emit_to_string_with_path(source, name),
        })?;
    Ok(module)
}

/// Byte size (naga's `span`) of the struct `name` in a parsed module.
#[cfg(feature = "validate")]
pub fn struct_size(module: &naga::Module, name: &str) -> Option<u32> {
    struct_layout(module, name).map(|layout| layout.size)
}

/// The memory layout naga gives a WGSL struct: what a `#[repr(C)]` Rust twin of a
/// uniform or storage block must reproduce byte for byte.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StructLayout {
    /// The struct's name.
    pub name: String,
    /// Its byte size (naga's `span`, trailing padding included).
    pub size: u32,
    /// Its members in declaration order: name and byte offset.
    pub members: Vec<(String, u32)>,
}

/// The layout of the struct `name` in a parsed module (`None` when there is none).
#[cfg(feature = "validate")]
pub fn struct_layout(module: &naga::Module, name: &str) -> Option<StructLayout> {
    module.types.iter().find_map(|(_, ty)| match &ty.inner {
        naga::TypeInner::Struct { members, span } if ty.name.as_deref() == Some(name) => {
            Some(StructLayout {
                name: name.to_owned(),
                size: *span,
                members: members
                    .iter()
                    .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                    .collect(),
            })
        }
        _ => None,
    })
}

/// A `#[repr(C)]` Rust type's layout in the same form, written with [`rust_layout!`].
impl StructLayout {
    /// Compares a Rust twin's layout (`self`, from [`rust_layout!`]) with the WGSL
    /// struct's (`wgsl`): same size, and every WGSL member at the same offset as the
    /// Rust field of the same name. Padding (a name starting with `pad` or `_pad`) is
    /// exempt on both sides, since one side may spell it `_pad: [u32; 2]` and the other
    /// `_pad0, _pad1`; every other member must be on both sides.
    pub fn check_twin_of(&self, wgsl: &StructLayout) -> Result<(), String> {
        let mut problems = Vec::new();
        if self.size != wgsl.size {
            problems.push(format!(
                "size: Rust {} bytes, WGSL {} bytes",
                self.size, wgsl.size
            ));
        }
        let padding = |name: &str| name.starts_with("pad") || name.starts_with("_pad");
        for (member, offset) in wgsl.members.iter().filter(|(n, _)| !padding(n)) {
            match self.members.iter().find(|(n, _)| n == member) {
                None => problems.push(format!(
                    "`{member}` (WGSL offset {offset}) has no Rust field"
                )),
                Some((_, rust)) if rust != offset => problems.push(format!(
                    "`{member}`: Rust offset {rust}, WGSL offset {offset}"
                )),
                Some(_) => {}
            }
        }
        for (field, offset) in self.members.iter().filter(|(n, _)| !padding(n)) {
            if !wgsl.members.iter().any(|(n, _)| n == field) {
                problems.push(format!(
                    "Rust field `{field}` (offset {offset}) is not in the WGSL struct"
                ));
            }
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(format!(
                "`{}` and its Rust twin `{}` differ: {}",
                wgsl.name,
                self.name,
                problems.join("; ")
            ))
        }
    }
}

/// The [`StructLayout`] of a Rust struct from its size and `offset_of!` each field:
/// `rust_layout!(FrameCamera { position, width, right, ... })`. Every field must be
/// named: the macro destructures the struct without `..`, so a field added to the Rust
/// twin and not to its layout check is a compile error.
#[macro_export]
macro_rules! rust_layout {
    ($ty:path { $($field:ident),* $(,)? }) => {{
        let _every_field_is_named = |value: &$ty| {
            let $ty { $($field: _),* } = value;
        };
        $crate::StructLayout {
            name: ::std::string::String::from(stringify!($ty)),
            size: ::core::mem::size_of::<$ty>() as u32,
            members: ::std::vec![$(
                (::std::string::String::from(stringify!($field)),
                 ::core::mem::offset_of!($ty, $field) as u32)
            ),*],
        }
    }};
}

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

#[cfg(test)]
mod tests {
    use super::*;

    const A: Module = Module {
        name: "t::a",
        source: "fn a() -> f32 { return 1.0; }\n",
    };
    const B: Module = Module {
        name: "t::b",
        source: "#import t::a\nfn b() -> f32 { return a() + 1.0; }\n",
    };
    const C: Module = Module {
        name: "t::c",
        source: "#import t::a // shared\n#import t::b\nfn c() -> f32 { return a() + b(); }\n",
    };

    fn composer(modules: &[Module]) -> Composer {
        let mut c = Composer::new();
        c.add_modules(modules).unwrap();
        c
    }

    #[test]
    fn dependencies_come_first_and_once() {
        let c = composer(&[A, B, C]);
        let out = c
            .compose("root", "#import t::c\n#import t::b\nfn main_() {}\n")
            .unwrap();
        assert_eq!(out.matches("fn a()").count(), 1);
        assert_eq!(out.matches("fn b()").count(), 1);
        let (pa, pb, pc, pm) = (
            out.find("fn a()").unwrap(),
            out.find("fn b()").unwrap(),
            out.find("fn c()").unwrap(),
            out.find("fn main_()").unwrap(),
        );
        assert!(pa < pb && pb < pc && pc < pm, "{out}");
        assert!(!out.contains("#import"));
    }

    #[test]
    fn unknown_module_names_importer_and_line() {
        let c = composer(&[A]);
        let err = c.compose("root", "\n#import t::zzz\n").unwrap_err();
        assert_eq!(
            err,
            ComposeError::UnknownModule {
                importer: "root".into(),
                line: 2,
                module: "t::zzz".into()
            }
        );
    }

    #[test]
    fn cycles_are_reported_with_the_chain() {
        let x = Module {
            name: "t::x",
            source: "#import t::y\n",
        };
        let y = Module {
            name: "t::y",
            source: "#import t::x\n",
        };
        let err = composer(&[x, y])
            .compose("root", "#import t::x\n")
            .unwrap_err();
        assert_eq!(
            err,
            ComposeError::ImportCycle {
                chain: vec!["t::x".into(), "t::y".into(), "t::x".into()]
            }
        );
    }

    #[test]
    fn a_root_may_share_its_name_with_an_import_but_a_module_may_not_import_itself() {
        let c = composer(&[A]);
        assert!(c.compose("t::a", "#import t::a\nfn k() {}\n").is_ok());
        let selfish = Module {
            name: "t::s",
            source: "#import t::s\n",
        };
        assert_eq!(
            composer(&[selfish]).compose_module("t::s").unwrap_err(),
            ComposeError::ImportCycle {
                chain: vec!["t::s".into(), "t::s".into()]
            }
        );
    }

    #[test]
    fn a_bound_import_emits_the_bound_module_once_instead_of_the_slot() {
        let slot = Module {
            name: "t::field",
            source: "fn density() -> f32 { return 0.0; }\n",
        };
        let grid = Module {
            name: "t::grid",
            source: "#import t::a\nfn density() -> f32 { return a(); }\n",
        };
        let user = Module {
            name: "t::user",
            source: "#import t::field\nfn twice() -> f32 { return 2.0 * density(); }\n",
        };
        let root = Module {
            name: "t::root",
            source: "#import t::grid\n#import t::user\n#import t::field\nfn main_() {}\n",
        };
        let c = composer(&[A, slot, grid, user, root]);
        // Unbound, the slot is an ordinary module: the default each module validates with.
        let plain = c.compose_module("t::user").unwrap();
        assert!(plain.contains("return 0.0"), "{plain}");
        assert_eq!(plain, c.compose_module_bound("t::user", &[]).unwrap());
        // Bound, every import of the slot emits the bound module, once, dependencies first.
        let out = c
            .compose_module_bound("t::root", &[("t::field", "t::grid")])
            .unwrap();
        assert!(!out.contains("return 0.0"), "{out}");
        assert!(!out.contains("begin t::field"), "{out}");
        assert_eq!(out.matches("fn density()").count(), 1, "{out}");
        let (pa, pg, pu, pm) = (
            out.find("fn a()").unwrap(),
            out.find("return a()").unwrap(),
            out.find("fn twice()").unwrap(),
            out.find("fn main_()").unwrap(),
        );
        assert!(pa < pg && pg < pu && pu < pm, "{out}");
        // Binding a module to an unregistered one names the slot's importer and line.
        assert_eq!(
            c.compose_module_bound("t::user", &[("t::field", "t::none")])
                .unwrap_err(),
            ComposeError::UnknownModule {
                importer: "t::user".into(),
                line: 1,
                module: "t::none".into()
            }
        );
        // A binding that leads back to an importer is a cycle.
        assert!(matches!(
            c.compose_module_bound("t::user", &[("t::field", "t::user")]),
            Err(ComposeError::ImportCycle { .. })
        ));
    }

    #[test]
    fn malformed_directives_are_rejected() {
        let c = composer(&[A]);
        for bad in [
            "#include t::a",
            "#import",
            "#import t::a t::b",
            "#import a",
            "#importt::a",
        ] {
            assert!(
                matches!(
                    c.compose("root", bad),
                    Err(ComposeError::MalformedDirective { .. })
                ),
                "{bad}"
            );
        }
    }

    #[test]
    fn duplicate_registration_rules() {
        let mut c = composer(&[A]);
        assert!(
            c.add_modules(&[A]).is_ok(),
            "identical re-registration is fine"
        );
        let other = Module {
            name: "t::a",
            source: "fn a2() {}",
        };
        assert!(matches!(
            c.add_modules(&[other]),
            Err(ComposeError::DuplicateModule { .. })
        ));
        assert!(matches!(
            Composer::new().add_modules(&[Module {
                name: "nocrate",
                source: ""
            }]),
            Err(ComposeError::BadModuleName { .. })
        ));
    }

    #[cfg(feature = "validate")]
    #[test]
    fn common_modules_validate_and_uncomposed_source_fails() {
        let c = Composer::with_common();
        for name in c.module_names() {
            let src = c.compose_module(name).unwrap();
            validate(name, &src).unwrap();
        }
        // Forgetting to compose must not go unnoticed.
        assert!(validate("raw", "#import common::constants\n").is_err());
    }

    #[cfg(feature = "validate")]
    #[test]
    fn struct_layouts_are_checked_member_by_member() {
        #[repr(C)]
        #[allow(dead_code)]
        struct Twin {
            direction: [f32; 3],
            scale: f32,
            count: u32,
            _pad: [u32; 3],
        }
        #[repr(C)]
        #[allow(dead_code)]
        struct Shifted {
            direction: [f32; 3],
            count: u32,
            scale: f32,
            _pad: [u32; 3],
        }
        #[repr(C)]
        #[allow(dead_code)]
        struct Short {
            direction: [f32; 3],
            scale: f32,
            count: u32,
        }
        let module = validate(
            "layout",
            "struct Block { direction: vec3<f32>, scale: f32, count: u32 }\n\
             @group(0) @binding(0) var<uniform> block: Block;\n",
        )
        .unwrap();
        let wgsl = struct_layout(&module, "Block").unwrap();
        assert_eq!(wgsl.size, 32, "{wgsl:?}");
        assert_eq!(
            wgsl.members,
            [
                ("direction".to_owned(), 0),
                ("scale".to_owned(), 12),
                ("count".to_owned(), 16)
            ]
        );
        assert_eq!(struct_size(&module, "Block"), Some(32));
        assert!(struct_layout(&module, "Missing").is_none());
        rust_layout!(Twin {
            direction,
            scale,
            count,
            _pad
        })
        .check_twin_of(&wgsl)
        .unwrap();
        // Swapped fields of equal size: the size agrees, the offsets do not.
        let swapped = rust_layout!(Shifted {
            direction,
            count,
            scale,
            _pad
        })
        .check_twin_of(&wgsl);
        assert!(
            swapped
                .as_ref()
                .is_err_and(|e| e.contains("`scale`: Rust offset 16, WGSL offset 12")),
            "{swapped:?}"
        );
        let short = rust_layout!(Short {
            direction,
            scale,
            count
        })
        .check_twin_of(&wgsl);
        assert!(
            short
                .as_ref()
                .is_err_and(|e| e.contains("size: Rust 20 bytes, WGSL 32 bytes")),
            "{short:?}"
        );
    }
}
