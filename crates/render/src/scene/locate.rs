//! Finding a key in the scene text: the line and column of a field that another
//! crate rejected after parsing, and the dotted key under a toml error's span.

use toml::de::{DeTable, DeValue};

/// A place in the scene text (1-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Location {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
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
        }
    }
}

/// Where the value of the key at `path` (`["camera", "near"]`) is written.
pub(crate) fn locate(source: &str, path: &[&str]) -> Option<Location> {
    let document = DeTable::parse(source).ok()?;
    let mut table = document.get_ref();
    let (last, parents) = path.split_last()?;
    for key in parents {
        let (_, value) = table.iter().find(|(k, _)| k.get_ref() == key)?;
        match value.get_ref() {
            DeValue::Table(inner) => table = inner,
            _ => return None,
        }
    }
    let (_, value) = table.iter().find(|(k, _)| k.get_ref() == last)?;
    Some(Location::of_offset(source, value.span().start))
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
        if covers(key.span()) || covers(value.span()) {
            return true;
        }
        path.pop();
    }
    false
}
