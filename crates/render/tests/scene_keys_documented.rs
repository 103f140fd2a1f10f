//! `docs/scenes.md` documents every key the scene parser accepts, and no other.
//!
//! The parser's keys are not listed by hand here: each table's accepted fields come from
//! the parser itself. A probe document puts an unknown key in a table
//! (`[clouds.volume]` with `zz_probe = 0`); serde's `deny_unknown_fields` refuses it
//! with "unknown field `zz_probe`, expected one of `a`, `b`, …" — the same list the
//! scene errors' "did you mean" suggestions come from. A field that is itself a table
//! (or an array of tables, `[[clouds.layers]]`) is probed in turn, from the root down.
//!
//! The documented keys are the first column of the tables under "## Keys" in
//! `docs/scenes.md`: one row per key, written as its dotted path in backticks
//! (`` `clouds.volume.billboards.slices` ``; an array of tables is written without
//! brackets, `` `clouds.layers.kind` ``). The test fails naming every key documented
//! but not accepted, and every key accepted but not documented.

use std::collections::BTreeSet;

const PROBE: &str = "zz_probe";

/// What the parser says about a table path.
enum Probe {
    /// A table (or an array of tables) with these field names.
    Table(BTreeSet<String>),
    /// Not a table: a value.
    Value,
}

/// The parser's error for `zz_probe = 0` inside the table at `path`.
fn probe_error(path: &[String], array: bool) -> String {
    let header = if path.is_empty() {
        String::new()
    } else if array {
        format!("[[{}]]\n", path.join("."))
    } else {
        format!("[{}]\n", path.join("."))
    };
    let source = format!("{header}{PROBE} = 0\n");
    match render::scene::Scene::parse(&source, ".") {
        Ok(_) => panic!("the parser accepted an unknown key:\n{source}"),
        Err(error) => error.to_string(),
    }
}

/// The field names in serde's "unknown field `zz_probe`, expected one of `a`, `b`"
/// (or "expected `a`", or "there are no fields").
fn expected_fields(message: &str) -> Option<BTreeSet<String>> {
    let at = message.find(&format!("unknown field `{PROBE}`"))?;
    let rest = &message[at..];
    let rest = &rest[rest.find(',').map_or(rest.len(), |i| i + 1)..];
    let rest = rest.split(" (did you mean").next().unwrap_or(rest);
    Some(
        rest.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_owned)
            .collect(),
    )
}

fn probe(path: &[String]) -> Probe {
    for array in [false, true] {
        if let Some(fields) = expected_fields(&probe_error(path, array)) {
            return Probe::Table(fields);
        }
    }
    Probe::Value
}

/// Every key the parser accepts, as dotted paths of values (tables are walked into).
fn accepted_keys() -> BTreeSet<String> {
    let mut keys = BTreeSet::new();
    let mut stack: Vec<Vec<String>> = vec![Vec::new()];
    while let Some(path) = stack.pop() {
        match probe(&path) {
            Probe::Table(fields) => {
                assert!(
                    !fields.is_empty(),
                    "no fields found for `{}`",
                    path.join(".")
                );
                for field in fields {
                    let mut child = path.clone();
                    child.push(field);
                    stack.push(child);
                }
            }
            Probe::Value => {
                keys.insert(path.join("."));
            }
        }
    }
    keys
}

/// The keys in the first column of the tables under "## Keys" in `docs/scenes.md`.
fn documented_keys(text: &str) -> BTreeSet<String> {
    let start = text
        .find("\n## Keys\n")
        .expect("docs/scenes.md has a \"## Keys\" section");
    let section = &text[start + 1..];
    let end = section[3..].find("\n## ").map_or(section.len(), |i| i + 3);
    let mut keys = BTreeSet::new();
    for line in section[..end].lines() {
        let Some(first) = line.strip_prefix("| `") else {
            continue;
        };
        let key = first.split('`').next().unwrap();
        assert!(
            keys.insert(key.to_owned()),
            "docs/scenes.md documents `{key}` twice"
        );
    }
    keys
}

#[test]
fn the_documented_keys_are_the_parsers() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/scenes.md");
    let text = std::fs::read_to_string(path).unwrap();
    let documented = documented_keys(&text);
    let accepted = accepted_keys();
    assert!(accepted.len() > 50, "only {} keys found", accepted.len());
    let not_accepted: Vec<_> = documented.difference(&accepted).collect();
    let not_documented: Vec<_> = accepted.difference(&documented).collect();
    assert!(
        not_accepted.is_empty() && not_documented.is_empty(),
        "docs/scenes.md's keys and the parser's differ\n\
         documented but not accepted: {not_accepted:?}\n\
         accepted but not documented: {not_documented:?}"
    );
}

/// The check can fail: a key the parser refuses is found, and so is a table.
#[test]
fn the_probe_tells_tables_from_values() {
    let camera = vec!["camera".to_owned()];
    let Probe::Table(fields) = probe(&camera) else {
        panic!("`camera` is a table");
    };
    assert!(fields.contains("vertical_fov_deg"), "{fields:?}");
    let fov = vec!["camera".to_owned(), "vertical_fov_deg".to_owned()];
    assert!(matches!(probe(&fov), Probe::Value));
    let layers = vec!["clouds".to_owned(), "layers".to_owned()];
    assert!(matches!(probe(&layers), Probe::Table(f) if f.contains("base_m")));

    let documented =
        documented_keys("\n## Keys\n\n| `camera.fov` | x |\n| `a.b` | y |\n\n## Next\n| `c` |");
    assert_eq!(
        documented,
        BTreeSet::from(["camera.fov".into(), "a.b".into()])
    );
    assert!(!accepted_keys().contains("camera.fov"));
}

#[test]
#[ignore = "a tool, not a check: prints the parser's keys for docs/scenes.md \
           (cargo test -p render --test scene_keys_documented -- --ignored --nocapture)"]
fn print_the_parsers_keys() {
    for key in accepted_keys() {
        println!("{key}");
    }
}
