//! Star names by Hipparcos number, embedded as `data/star_names.csv`: the IAU Working
//! Group on Star Names' approved names (one per star) for the stars of the
//! magnitude-8 catalogue, and the other names star-catalog's `names.json` gives some
//! of them (Agena, Rigil Kent, Groombridge 1830, …), which lookups accept too.

use crate::error::{CelestialError, Result};

const DATA: &str = include_str!("../../data/star_names.csv");

/// Whose name it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum NameKind {
    /// The IAU's approved proper name.
    Iau,
    /// Another name in use.
    Other,
}

/// One row of the table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct StarName {
    pub hip: usize,
    pub name: &'static str,
    pub kind: NameKind,
}

/// Every row of the embedded table.
pub(crate) fn star_names() -> Result<Vec<StarName>> {
    let corrupt = |offset: usize| CelestialError::CorruptData {
        field: "star_names.csv",
        offset,
    };
    let mut rows = Vec::new();
    let mut offset = 0;
    for line in DATA.lines() {
        let here = offset;
        offset += line.len() + 1;
        if line.starts_with('#') || line == "hip,name,kind" || line.is_empty() {
            continue;
        }
        let mut fields = line.split(',');
        let (Some(hip), Some(name), Some(kind), None) =
            (fields.next(), fields.next(), fields.next(), fields.next())
        else {
            return Err(corrupt(here));
        };
        let kind = match kind {
            "iau" => NameKind::Iau,
            "other" => NameKind::Other,
            _ => return Err(corrupt(here)),
        };
        let hip = hip.parse().map_err(|_| corrupt(here))?;
        rows.push(StarName { hip, name, kind });
    }
    Ok(rows)
}

/// A Hipparcos number written as `32349`, `HIP 32349` or `hip32349`.
pub(crate) fn parse_hipparcos_number(text: &str) -> Option<usize> {
    let text = text.trim();
    let digits = match text.get(..3) {
        Some(prefix) if prefix.eq_ignore_ascii_case("hip") => text[3..].trim_start(),
        _ => text,
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    digits.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_parses_and_names_each_star_once_by_the_iau() {
        let rows = star_names().unwrap();
        let iau: Vec<_> = rows.iter().filter(|r| r.kind == NameKind::Iau).collect();
        assert!(iau.len() > 300, "{}", iau.len());
        let mut hips: Vec<_> = iau.iter().map(|r| r.hip).collect();
        hips.sort_unstable();
        hips.dedup();
        assert_eq!(hips.len(), iau.len(), "one IAU name per star");
        let named = |hip| iau.iter().find(|r| r.hip == hip).unwrap().name;
        assert_eq!(named(71_683), "Rigil Kentaurus");
        assert_eq!(named(71_681), "Toliman");
        assert_eq!(named(32_349), "Sirius");
    }

    #[test]
    fn hipparcos_numbers() {
        assert_eq!(parse_hipparcos_number("32349"), Some(32_349));
        assert_eq!(parse_hipparcos_number(" HIP 32349 "), Some(32_349));
        assert_eq!(parse_hipparcos_number("hip32349"), Some(32_349));
        assert_eq!(parse_hipparcos_number("HIP"), None);
        assert_eq!(parse_hipparcos_number("Sirius"), None);
        assert_eq!(parse_hipparcos_number("-5"), None);
        assert_eq!(parse_hipparcos_number("Hipparchus"), None);
    }
}
