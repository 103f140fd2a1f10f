//! The code cites published sources and says what it does now, never its history
//! (`docs/architecture.md`, "Comments"). This test reads every `*.rs` file under
//! `crates/`, `tests/` and `xtask/` and every `*.wgsl` file under `shaders/`, and fails
//! naming `file:line` for each
//!
//! * reference to an unpublished design document by number (`seed` followed by a
//!   three-digit number, in code, strings or comments): cite the source in
//!   `docs/references.md` instead;
//! * reference to a task by number (`issue` followed by a number, or an ordinal such as
//!   the twelfth written as digits and `th`), in code, strings or comments;
//! * ISO calendar date (`YYYY-MM` or `YYYY-MM-DD`, years 2000–2099) in a comment,
//!   unless it is part of an instant the code computes with: the date followed by
//!   `T` and a time (RFC 3339, `2003-10-17T12:30:30-07:00`), or by a space, an optional
//!   `~` and `HH:MM` with a time scale (`UTC`, `UT`, `TT`) after it. Dated history
//!   ("measured on ...") has no such time; a scene's instant names one.

use std::path::{Path, PathBuf};

use regex::Regex;

/// One finding: where, and which rule.
#[derive(Debug, PartialEq)]
struct Finding {
    line: usize,
    rule: &'static str,
    text: String,
}

struct Rules {
    design_document: Regex,
    task_number: Regex,
    ordinal: Regex,
    date: Regex,
    instant_tail: Regex,
}

impl Rules {
    fn new() -> Self {
        // The patterns are assembled so that this file does not match them itself.
        let seed = format!(r"(?i){}[\s_-]*0\d\d(\D|$)", "seed");
        let issue = format!(r"(?i)\b{}\s*#?\d+", "issue");
        Rules {
            design_document: Regex::new(&seed).unwrap(),
            task_number: Regex::new(&issue).unwrap(),
            ordinal: Regex::new(r"\b1\dth\b").unwrap(),
            date: Regex::new(r"\b20\d\d-[01]\d(-[0-3]\d)?").unwrap(),
            instant_tail: Regex::new(r"^(T\d\d:\d\d| ~?\d\d:\d\d(:\d\d)? (UTC|UT|TT)\b)").unwrap(),
        }
    }

    /// The findings in one file's text (`wgsl` and Rust share `//` comments).
    fn check(&self, text: &str) -> Vec<Finding> {
        let mut out = Vec::new();
        for (index, line) in text.lines().enumerate() {
            let mut found = |rule: &'static str| {
                out.push(Finding {
                    line: index + 1,
                    rule,
                    text: line.trim().to_owned(),
                })
            };
            if self.design_document.is_match(line) {
                found("a design document by number: cite docs/references.md");
            }
            if self.task_number.is_match(line) || self.ordinal.is_match(line) {
                found("a task by number: say what the code does now");
            }
            if let Some(comment) = comment(line) {
                let dated = self
                    .date
                    .find_iter(comment)
                    .any(|date| !self.instant_tail.is_match(&comment[date.end()..]));
                if dated {
                    found("a date in a comment: no history in code");
                }
            }
        }
        out
    }
}

/// The comment on a line: from the first `//` that is not part of a URL (`://`).
fn comment(line: &str) -> Option<&str> {
    let mut from = 0;
    while let Some(at) = line[from..].find("//") {
        let at = from + at;
        if at > 0 && line.as_bytes()[at - 1] == b':' {
            from = at + 2;
            continue;
        }
        return Some(&line[at..]);
    }
    None
}

/// Every file with extension `ext` under `dir`, skipping build outputs.
fn files(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy();
        if path.is_symlink() || name == "target" || name.starts_with('.') {
            continue;
        }
        if path.is_dir() {
            files(&path, ext, out);
        } else if path.extension().is_some_and(|e| e == ext) {
            out.push(path);
        }
    }
}

#[test]
fn code_cites_sources_and_carries_no_history() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let mut paths = Vec::new();
    for dir in ["crates", "tests", "xtask"] {
        files(&root.join(dir), "rs", &mut paths);
    }
    files(&root.join("shaders"), "wgsl", &mut paths);
    paths.sort();
    assert!(paths.len() > 100, "only {} source files found", paths.len());

    let rules = Rules::new();
    let mut report = String::new();
    for path in &paths {
        let relative = path.strip_prefix(root).unwrap().display().to_string();
        if rules.design_document.is_match(&relative) {
            report += &format!("{relative}: a design document by number in a file name\n");
        }
        let text = std::fs::read_to_string(path).unwrap();
        for finding in rules.check(&text) {
            report += &format!(
                "{relative}:{}: {}\n    {}\n",
                finding.line, finding.rule, finding.text
            );
        }
    }
    assert!(
        report.is_empty(),
        "history or unpublished references in code:\n{report}"
    );
}

/// The check can fail: each rule finds its pattern, and the exemptions are exact.
#[test]
fn each_rule_finds_its_pattern() {
    let rules = Rules::new();
    let lines = |text: &str| -> Vec<usize> { rules.check(text).iter().map(|f| f.line).collect() };
    let seed = ["// after ", "seed", " 002's automaton"].concat();
    let task = ["// the ", "issue", " 14 goal"].concat();
    let ordinal = ["// since the ", "14", "th"].concat();
    let string = ["let s = \"", "Seed", " 004 layers\";"].concat();
    let name = ["fn ", "seed", "_000_observations() {"].concat();
    let text = [seed.as_str(), &task, &ordinal, &string, &name].join("\n");
    assert_eq!(lines(&text), [1, 2, 3, 4, 5]);

    // Dates: history in a comment fails; an instant the code uses does not; a date in
    // code (a string the parser is tested on) is not a comment. The dates are joined at
    // run time so that this file's own lines do not match.
    let day = ["2026", "-03-02"].concat();
    let month = ["2026", "-03"].concat();
    let history = [
        format!("// measured {day} on the 2-core machine"),
        format!("// ({month}) slower"),
        format!("/// {day}, the new moon"),
        format!("// {day} 21:00 without a time scale"),
    ];
    for line in &history {
        assert_eq!(lines(line), [1], "{line}");
    }
    let instants = [
        format!("/// J2000.0 is {day}T12:00 TT"),
        format!("//! RFC 3339 (`{day}T12:30:30-07:00`)"),
        format!("/// The shipped night ({day} 21:00 UTC, 46.5° N)"),
        format!("// the sun near the zenith: {day} ~12:07 UTC"),
        format!("let t = Instant::parse(\"{day}T21:00:00Z\");"),
        format!("let url = \"https://example.org/{month}\"; // a link"),
    ];
    for line in &instants {
        assert_eq!(lines(line), Vec::<usize>::new(), "{line}");
    }
}
