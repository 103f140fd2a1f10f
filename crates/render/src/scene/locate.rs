//! Finding a key in the scene text: the line and column of a field that another
//! crate rejected after parsing, and the dotted key under a toml error's span.

use toml::de::{DeTable, DeValue};

/// Where a value came from: its place in the scene text (1-based), or the flag that
/// supplied it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// Line, from 1 (the key's, or its table's for [`Origin::Section`]; 0 when a flag
    /// supplied a key the file does not have).
    pub line: usize,
    /// Column in characters, from 1 (0 as `line`).
    pub column: usize,
    /// What `line` and `column` point at.
    pub origin: Origin,
}

/// What a [`Location`] points at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Origin {
    /// The key's value, as typed in the file.
    Key,
    /// The table or array element holding the key, which the file does not give: the
    /// value is the default.
    Section,
    /// A command-line flag (`--width`) replaced the file's value.
    Flag(&'static str),
}

impl Location {
    /// The line and column of byte `offset` in `source`.
    pub fn of_offset(source: &str, offset: usize) -> Self {
        let offset = offset.min(source.len());
        let mut end = offset.min(source.len());
        while !source.is_char_boundary(end) {
            end -= 1;
        }
        let before = &source[..end];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        Self {
            line,
            column: before[line_start..].chars().count() + 1,
            origin: Origin::Key,
        }
    }
}

/// Where the value of the key at `path` (`["camera", "near"]`; an array's element by
/// its index, `["clouds", "layers", "0", "coverage"]`) is written; for a key the file
/// does not give, the innermost table or element that holds it ([`Origin::Section`]).
pub(crate) fn locate(source: &str, path: &[&str]) -> Option<Location> {
    let document = DeTable::parse(source).ok()?;
    let mut value: Option<&DeValue<'_>> = None;
    let mut table = document.get_ref();
    let mut found: Option<Location> = None;
    for key in path {
        let next = match value {
            None => table
                .iter()
                .find(|(k, _)| k.get_ref() == key)
                .map(|(_, v)| v),
            Some(DeValue::Table(inner)) => {
                table = inner;
                table
                    .iter()
                    .find(|(k, _)| k.get_ref() == key)
                    .map(|(_, v)| v)
            }
            Some(DeValue::Array(items)) => key.parse::<usize>().ok().and_then(|i| items.get(i)),
            Some(_) => None,
        };
        let Some(next) = next else {
            return found.map(|l| Location {
                origin: Origin::Section,
                ..l
            });
        };
        found = Some(Location::of_offset(source, next.span().start));
        value = Some(next.get_ref());
    }
    found
}

/// The dotted key whose key or value covers `span` (`atmosphere.rung`), searching
/// the document's tables; `None` for a span outside every key (a syntax error).
pub(crate) fn dotted_key_at(source: &str, span: std::ops::Range<usize>) -> Option<String> {
    let (document, _) = DeTable::parse_recoverable(source);
    let mut path = Vec::new();
    find(document.get_ref(), &span, &mut path).then(|| path.join("."))
}

fn find(table: &DeTable<'_>, span: &std::ops::Range<usize>, path: &mut Vec<String>) -> bool {
    let covers =
        |s: std::ops::Range<usize>| s.start <= span.start && span.end <= s.end.max(s.start + 1);
    for (key, value) in table.iter() {
        path.push(key.get_ref().to_string());
        // A `[section]`'s value span need not cover its keys: search inside first.
        if let DeValue::Table(inner) = value.get_ref()
            && find(inner, span, path)
        {
            return true;
        }
        // A `[[table]]` array: each table by its index (`clouds.layers.0.coverage`).
        if let DeValue::Array(items) = value.get_ref() {
            for (index, item) in items.iter().enumerate() {
                if let DeValue::Table(inner) = item.get_ref() {
                    path.push(index.to_string());
                    if find(inner, span, path) {
                        return true;
                    }
                    path.pop();
                }
            }
        }
        if covers(key.span()) || covers(value.span()) {
            return true;
        }
        path.pop();
    }
    false
}
