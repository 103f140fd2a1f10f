//! `render`'s modules form no import cycle: every module's code names only modules
//! below it. The check resolves each `crate::`, `super::`, `self::` and `use` path in a
//! module's non-test code to the module that defines the item (following `pub use`
//! re-exports), and looks for a cycle in the resulting graph. A module re-exporting its
//! own descendants' items (a facade, e.g. `scene` re-exporting `scene::prepare`'s types)
//! does not depend on them; a method call through a type is not a path and is not seen.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use regex::Regex;

/// A crate's modules: name (`a::b`, `""` for the root) → non-test source.
fn modules(src: &Path) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                if path.file_name().unwrap() != "bin" {
                    stack.push(path);
                }
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let relative = path.strip_prefix(src).unwrap().with_extension("");
            let mut parts: Vec<String> = relative
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if parts.last().is_some_and(|p| p == "mod") {
                parts.pop();
            }
            if parts == ["lib"] {
                parts.clear();
            }
            let text = std::fs::read_to_string(&path).unwrap();
            out.insert(parts.join("::"), code(&text));
        }
    }
    out
}

/// The source without its test module (always last in skyscape's files) and comments.
fn code(text: &str) -> String {
    let text = text.find("#[cfg(test)]\nmod ").map_or(text, |i| &text[..i]);
    let comment = Regex::new(r"//[^\n]*").unwrap();
    comment.replace_all(text, "").into_owned()
}

/// `a::{b, c::{d, e}}` → `a::b`, `a::c::d`, `a::c::e`.
fn expand_use(body: &str) -> Vec<String> {
    let body = body.trim();
    let Some(open) = body.find('{') else {
        return vec![body.to_owned()];
    };
    let (prefix, inner) = (&body[..open], &body[open + 1..body.len() - 1]);
    let mut parts = Vec::new();
    let (mut depth, mut current) = (0, String::new());
    for c in inner.chars() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            _ => {}
        }
        if c == ',' && depth == 0 {
            parts.push(std::mem::take(&mut current));
        } else {
            current.push(c);
        }
    }
    parts.push(current);
    parts
        .iter()
        .map(|p| p.trim())
        .filter(|p| !p.is_empty())
        .flat_map(|p| {
            expand_use(p)
                .into_iter()
                .map(move |e| format!("{prefix}{e}"))
        })
        .collect()
}

struct Graph {
    modules: BTreeMap<String, String>,
    /// Items each module defines.
    items: BTreeMap<String, BTreeSet<String>>,
    /// Each module's imports: (name bound, absolute path, public).
    uses: BTreeMap<String, Vec<(String, Vec<String>, bool)>>,
}

impl Graph {
    fn new(src: &Path) -> Self {
        let modules = modules(src);
        let item = Regex::new(
            r"\b(?:fn|struct|enum|const|static|type|trait|union|macro_rules!)\s+([A-Za-z_][A-Za-z0-9_]*)",
        )
        .unwrap();
        let items = modules
            .iter()
            .map(|(m, s)| {
                let names = item.captures_iter(s).map(|c| c[1].to_owned()).collect();
                (m.clone(), names)
            })
            .collect();
        let mut graph = Self {
            modules,
            items,
            uses: BTreeMap::new(),
        };
        let use_statement = Regex::new(r"(pub(?:\([a-z]+\))?\s+)?use\s+([^;]+);").unwrap();
        let mut uses = BTreeMap::new();
        for (m, s) in &graph.modules {
            let mut list = Vec::new();
            for c in use_statement.captures_iter(s) {
                for full in expand_use(&c[2]) {
                    let (path, alias) = match full.split_once(" as ") {
                        Some((p, a)) => (p.trim().to_owned(), Some(a.trim().to_owned())),
                        None => (full.trim().to_owned(), None),
                    };
                    if let Some(absolute) = graph.absolute(m, &path) {
                        let name = alias.unwrap_or_else(|| absolute.last().cloned().unwrap());
                        list.push((name, absolute, c.get(1).is_some()));
                    }
                }
            }
            uses.insert(m.clone(), list);
        }
        graph.uses = uses;
        graph
    }

    /// A path as seen from module `m`, from the crate root; `None` for another crate's.
    fn absolute(&self, m: &str, path: &str) -> Option<Vec<String>> {
        let segments: Vec<String> = path.split("::").map(str::to_owned).collect();
        let mut base: Vec<String> = if m.is_empty() {
            Vec::new()
        } else {
            m.split("::").map(str::to_owned).collect()
        };
        match segments[0].as_str() {
            "crate" => Some(segments[1..].to_vec()),
            "self" => Some([base, segments[1..].to_vec()].concat()),
            "super" => {
                let mut rest = &segments[..];
                while rest.first().is_some_and(|s| s == "super") {
                    base.pop();
                    rest = &rest[1..];
                }
                Some([base, rest.to_vec()].concat())
            }
            first => {
                let child = [base.clone(), vec![first.to_owned()]].concat().join("::");
                self.modules
                    .contains_key(&child)
                    .then(|| [base, segments].concat())
            }
        }
    }

    /// The module defining the item at `path` (or the module itself).
    fn resolve(&self, path: &[String], depth: usize) -> Option<String> {
        if depth > 20 {
            return None;
        }
        for k in (0..=path.len()).rev() {
            let module = path[..k].join("::");
            if !self.modules.contains_key(&module) {
                continue;
            }
            let rest = &path[k..];
            let Some(name) = rest.first() else {
                return Some(module);
            };
            if name == "*" || self.items[&module].contains(name) {
                return Some(module);
            }
            for (bound, target, _) in &self.uses[&module] {
                if bound == name {
                    return self.resolve(&[target.clone(), rest[1..].to_vec()].concat(), depth + 1);
                }
                if bound == "*" {
                    let glob = [target[..target.len() - 1].to_vec(), rest.to_vec()].concat();
                    if let Some(found) = self.resolve(&glob, depth + 1)
                        && found != module
                    {
                        return Some(found);
                    }
                }
            }
            return Some(module);
        }
        None
    }

    /// Each module's dependencies.
    fn edges(&self) -> BTreeMap<String, BTreeSet<String>> {
        let path =
            Regex::new(r"(?:^|[^A-Za-z0-9_:])((?:crate|super|self)(?:::[A-Za-z_][A-Za-z0-9_]*)+)")
                .unwrap();
        let use_statement = Regex::new(r"(pub(?:\([a-z]+\))?\s+)?use\s+[^;]+;").unwrap();
        let mut edges = BTreeMap::new();
        for (m, source) in &self.modules {
            let mut paths = Vec::new();
            for (_, target, public) in &self.uses[m] {
                let facade = *public
                    && self
                        .resolve(target, 0)
                        .is_some_and(|t| m.is_empty() || t.starts_with(&format!("{m}::")));
                if !facade {
                    paths.push(target.clone());
                }
            }
            let body = use_statement.replace_all(source, "");
            for c in path.captures_iter(&body) {
                if let Some(absolute) = self.absolute(m, &c[1]) {
                    paths.push(absolute);
                }
            }
            let targets = paths
                .iter()
                .filter_map(|p| self.resolve(p, 0))
                .filter(|t| t != m)
                .collect();
            edges.insert(m.clone(), targets);
        }
        edges
    }
}

/// The strongly connected components of more than one module (Tarjan).
fn cycles(edges: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        edges: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(state: &mut State<'a>, v: &'a str) {
        let i = state.index.len();
        state.index.insert(v, i);
        state.low.insert(v, i);
        state.stack.push(v);
        state.on_stack.insert(v);
        for w in &state.edges[v] {
            let w = w.as_str();
            if !state.index.contains_key(w) {
                visit(state, w);
                let low = state.low[v].min(state.low[w]);
                state.low.insert(v, low);
            } else if state.on_stack.contains(w) {
                let low = state.low[v].min(state.index[w]);
                state.low.insert(v, low);
            }
        }
        if state.low[v] == state.index[v] {
            let mut component = Vec::new();
            while let Some(w) = state.stack.pop() {
                state.on_stack.remove(w);
                component.push(w.to_owned());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                state.out.push(component);
            }
        }
    }
    let mut state = State {
        edges,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on_stack: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in edges.keys() {
        if !state.index.contains_key(v.as_str()) {
            visit(&mut state, v);
        }
    }
    state.out
}

fn crate_src(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../crates")
        .join(name)
        .join("src")
}

#[test]
fn render_has_no_import_cycle() {
    let graph = Graph::new(&crate_src("render"));
    let edges = graph.edges();
    assert!(edges.len() > 40, "render's modules were found");
    assert!(
        edges["passes::terrain::gpu"].contains("gpu::frame"),
        "paths resolve to the defining module"
    );
    let found = cycles(&edges);
    assert!(found.is_empty(), "import cycles in render: {found:?}");
}

/// The check finds a cycle where there is one.
#[test]
fn a_cycle_is_found() {
    let mut edges = Graph::new(&crate_src("render")).edges();
    edges.get_mut("scene").unwrap().insert("passes".into());
    assert!(!cycles(&edges).is_empty());
}
