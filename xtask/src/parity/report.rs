//! What a parity run reports: one row per side of each case (a table on stdout,
//! `target/parity/report.json`, optionally Markdown), the one-line summary, and the
//! check of a committed Markdown table against a fresh run.

use super::audit::{Audit, LOOSENESS_LIMIT, ReferenceKind};
use super::compare::SideStats;
use std::fmt::Write as _;

/// The verdict of a CPU row whose reference is that CPU side itself.
pub const SELF_REFERENCED: &str = "reference = this side";

/// The result of one case.
#[derive(Debug)]
pub struct CaseReport {
    /// `crate::function` or the pass's name.
    pub name: &'static str,
    /// Inputs (grid rows, texels, cells) evaluated.
    pub inputs: usize,
    /// The tolerance in short form.
    pub tolerance: String,
    /// True when the tolerance allows no error at all (bit-exact cases).
    pub exact: bool,
    /// The tolerance's justification.
    pub why: &'static str,
    /// The case's audit declaration.
    pub audit: Audit,
    /// The f32 CPU twin against the reference.
    pub cpu: SideStats,
    /// The GPU against the reference (`None`: no adapter).
    pub gpu: Option<SideStats>,
    /// `--inject` perturbed this case.
    pub injected: bool,
}

/// A case's outcome over the rows that check something.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Every checked row is within tolerance.
    Passed,
    /// At least one checked row is out of tolerance.
    Failed,
    /// No row checks anything: the reference is the CPU side and there is no GPU row.
    Unchecked,
}

impl CaseReport {
    /// The CPU row compares the CPU side with itself.
    pub fn cpu_self_referenced(&self) -> bool {
        self.audit.reference == ReferenceKind::CpuSide
    }

    /// The rows that check something: the CPU row unless it is its own reference, and
    /// the GPU row when it ran.
    pub fn checked_rows(&self) -> impl Iterator<Item = &SideStats> {
        (!self.cpu_self_referenced())
            .then_some(&self.cpu)
            .into_iter()
            .chain(self.gpu.as_ref())
    }

    /// Passed, failed or unchecked (over the checked rows only).
    pub fn outcome(&self) -> Outcome {
        let mut rows = self.checked_rows().peekable();
        if rows.peek().is_none() {
            Outcome::Unchecked
        } else if rows.all(SideStats::passed) {
            Outcome::Passed
        } else {
            Outcome::Failed
        }
    }

    /// The verdict column of one row.
    pub fn row_verdict(&self, side: &str, stats: &SideStats) -> &'static str {
        if side == "cpu" && self.cpu_self_referenced() {
            SELF_REFERENCED
        } else if stats.passed() {
            "PASS"
        } else {
            "FAIL"
        }
    }

    /// How many times the tolerance exceeds the worst error of the checked rows
    /// (`allowed / error` at the element closest to failing; infinite when no checked
    /// row shows any error). `None` for exact tolerances (nothing to loosen) and for
    /// cases with no checked row.
    pub fn slack(&self) -> Option<f64> {
        if self.exact {
            return None;
        }
        let worst = self
            .checked_rows()
            .map(|s| s.worst_ratio)
            .reduce(f64::max)?;
        Some(if worst > 0.0 {
            1.0 / worst
        } else {
            f64::INFINITY
        })
    }

    /// The tightness audit: the tolerance is more than [`LOOSENESS_LIMIT`] times the
    /// worst observed error and the case does not say why. Only meaningful when every
    /// side ran (the CPU twin alone is often far more accurate than a GPU's built-ins).
    pub fn too_loose(&self) -> Option<String> {
        let slack = self.slack()?;
        (slack > LOOSENESS_LIMIT && self.audit.loose_because.is_none()).then(|| {
            format!(
                "{}: the tolerance is {} the worst error observed (limit {LOOSENESS_LIMIT}×): \
                 tighten it, or declare `Audit::…loose(\"why\")` in the case",
                self.name,
                format_slack(slack)
            )
        })
    }

    /// The side whose worst error/allowed ratio is larger.
    fn drift(&self) -> &'static str {
        match &self.gpu {
            None => "cpu (gpu skipped)",
            Some(_) if self.cpu_self_referenced() => "gpu vs cpu",
            Some(gpu) => match (self.cpu.passed(), gpu.passed()) {
                (false, false) => "both",
                (false, true) => "cpu",
                (true, false) => "gpu",
                (true, true) if gpu.worst_ratio == self.cpu.worst_ratio => {
                    if gpu.worst_ratio > 0.0 {
                        "equal (within tol)"
                    } else {
                        "none"
                    }
                }
                (true, true) if gpu.worst_ratio > self.cpu.worst_ratio => "gpu (within tol)",
                (true, true) => "cpu (within tol)",
            },
        }
    }

    fn sides(&self) -> [(&'static str, Option<&SideStats>); 2] {
        [("cpu", Some(&self.cpu)), ("gpu", self.gpu.as_ref())]
    }
}

/// `12×`, `∞×` (no error observed) or `—` (exact or unchecked).
pub fn format_slack(slack: f64) -> String {
    if slack.is_infinite() {
        "∞×".into()
    } else if slack >= 100.0 {
        format!("{slack:.0}×")
    } else {
        format!("{slack:.1}×")
    }
}

fn slack_cell(report: &CaseReport) -> String {
    report.slack().map_or("—".into(), format_slack)
}

fn ulp_cell(stats: &SideStats) -> String {
    if stats.max_ulp == u64::MAX {
        "NaN".into()
    } else {
        stats.max_ulp.to_string()
    }
}

/// The totals of a run, printed as its last line.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Summary {
    /// Cases run.
    pub cases: usize,
    /// Cases whose checked rows all passed.
    pub passed: usize,
    /// Cases with a checked row out of tolerance.
    pub failed: usize,
    /// Cases whose reference is their CPU side (that row is not counted as a check).
    pub self_referenced: usize,
    /// Cases with no checked row at all (self-referenced and no GPU row).
    pub unchecked: usize,
}

impl Summary {
    /// Counts the reports.
    pub fn of(reports: &[CaseReport]) -> Summary {
        let mut summary = Summary {
            cases: reports.len(),
            ..Summary::default()
        };
        for report in reports {
            match report.outcome() {
                Outcome::Passed => summary.passed += 1,
                Outcome::Failed => summary.failed += 1,
                Outcome::Unchecked => summary.unchecked += 1,
            }
            summary.self_referenced += usize::from(report.cpu_self_referenced());
        }
        summary
    }

    /// One line: `parity: 97 cases, 97 passed, 0 failed, 7 self-referenced (…)`.
    pub fn line(&self) -> String {
        let mut line = format!(
            "parity: {} cases, {} passed, {} failed, {} self-referenced \
             (CPU row = its reference, only the GPU row checks)",
            self.cases, self.passed, self.failed, self.self_referenced
        );
        if self.unchecked > 0 {
            write!(
                line,
                ", {} unchecked (self-referenced, no GPU row)",
                self.unchecked
            )
            .unwrap();
        }
        line
    }
}

/// The table on stdout, then each case's justification.
pub fn print_table(reports: &[CaseReport]) {
    println!(
        "{:<40} {:<4} {:>7} {:>10} {:>10} {:>8} {:>10} {:<30} {:<21} {:>7} drift",
        "case",
        "side",
        "inputs",
        "max abs",
        "max rel",
        "max ulp",
        "p99 rel",
        "tolerance",
        "verdict",
        "slack"
    );
    for report in reports {
        for (side, stats) in report.sides() {
            let Some(stats) = stats else {
                println!("{:<40} {:<4} skipped (no GPU adapter)", report.name, side);
                continue;
            };
            let last = side == "gpu" || report.gpu.is_none();
            println!(
                "{:<40} {:<4} {:>7} {:>10.3e} {:>10.3e} {:>8} {:>10.3e} {:<30} {:<21} {:>7} {}",
                report.name,
                side,
                report.inputs,
                stats.max_abs,
                stats.max_rel,
                ulp_cell(stats),
                stats.p99_rel,
                report.tolerance,
                report.row_verdict(side, stats),
                if last {
                    slack_cell(report)
                } else {
                    String::new()
                },
                if last { report.drift() } else { "" },
            );
            if !stats.passed() {
                println!(
                    "    {} element(s) over tolerance; worst at element {} ({}× allowed){}",
                    stats.failures,
                    stats.worst_index,
                    stats.worst_ratio,
                    if report.injected {
                        " [injected difference]"
                    } else {
                        ""
                    }
                );
            }
        }
    }
    for report in reports {
        println!("  {}: {}", report.name, report.why);
        if let Some(because) = report.audit.loose_because {
            println!("    loose tolerance: {because}");
        }
    }
}

fn json_string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            c if (c as u32) < 0x20 => write!(out, "\\u{:04x}", c as u32).unwrap(),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn json_number(x: f64) -> String {
    if x.is_finite() {
        format!("{x:e}")
    } else {
        "null".into()
    }
}

fn side_json(report: &CaseReport, side: &str, stats: &SideStats) -> String {
    format!(
        "{{\"elements\": {}, \"max_abs\": {}, \"max_rel\": {}, \"max_ulp\": {}, \"p99_rel\": {}, \
         \"worst_ratio\": {}, \"failures\": {}, \"passed\": {}, \"verdict\": {}}}",
        stats.elements,
        json_number(stats.max_abs),
        json_number(stats.max_rel),
        if stats.max_ulp == u64::MAX {
            "null".into()
        } else {
            stats.max_ulp.to_string()
        },
        json_number(stats.p99_rel),
        json_number(stats.worst_ratio),
        stats.failures,
        stats.passed(),
        json_string(report.row_verdict(side, stats)),
    )
}

/// Writes `target/parity/report.json`.
pub fn write_json(reports: &[CaseReport], adapter: Option<&str>) -> std::io::Result<()> {
    let dir = crate::workspace_root().join("target/parity");
    std::fs::create_dir_all(&dir)?;
    let mut json = String::from("{\n");
    writeln!(
        json,
        "  \"adapter\": {},",
        adapter.map_or("null".into(), json_string)
    )
    .unwrap();
    json.push_str("  \"cases\": [\n");
    for (i, report) in reports.iter().enumerate() {
        write!(
            json,
            "    {{\"name\": {}, \"inputs\": {}, \"tolerance\": {}, \"why\": {}, \"drift\": {}, \
             \"injected\": {}, \"reference\": {}, \"loose_because\": {}, \"slack\": {}, \
             \"outcome\": {}, \"cpu\": {}, \"gpu\": {}}}",
            json_string(report.name),
            report.inputs,
            json_string(&report.tolerance),
            json_string(report.why),
            json_string(report.drift()),
            report.injected,
            json_string(if report.cpu_self_referenced() {
                "cpu side"
            } else {
                "independent"
            }),
            report
                .audit
                .loose_because
                .map_or("null".into(), json_string),
            report.slack().map_or("null".into(), json_number),
            json_string(&format!("{:?}", report.outcome()).to_lowercase()),
            side_json(report, "cpu", &report.cpu),
            report
                .gpu
                .as_ref()
                .map_or("null".into(), |g| side_json(report, "gpu", g)),
        )
        .unwrap();
        json.push_str(if i + 1 < reports.len() { ",\n" } else { "\n" });
    }
    json.push_str("  ]\n}\n");
    let path = dir.join("report.json");
    std::fs::write(&path, json)?;
    println!("report: {}", path.display());
    Ok(())
}

/// The Markdown table (`docs/parity.md`).
pub fn markdown(reports: &[CaseReport], adapter: Option<&str>) -> String {
    let mut md = String::from(
        "# Parity: WGSL vs Rust f32 twin vs f64 reference\n\n\
         Generated by `cargo xtask parity --markdown docs/parity.md` (do not edit by hand; \
         CI runs `cargo xtask parity --check-markdown docs/parity.md` and fails when a case \
         name, side, input count, tolerance or verdict here differs from a fresh run — the \
         error columns, the slack and the drift depend on the adapter and are not compared).\n\n",
    );
    writeln!(
        md,
        "Adapter: {}\n\nAn element passes when |value − reference| ≤ abs + rel·|ref| + ulp·ULP(ref) \
         (+ the case's forward-error bound). Errors are against the case's reference evaluated \
         on the same f32 inputs: an f64 reference, pinned values or a second formulation of \
         the function — except in rows whose verdict is *{SELF_REFERENCED}*: there the \
         reference is that CPU side itself (a LUT bake with no f64 bake), so the row checks \
         nothing and is not counted as a pass; the GPU row of such a case measures GPU-vs-CPU \
         drift. *Slack* is how many times the tolerance exceeds the worst error of the \
         checked rows (`—`: an exact tolerance); above {LOOSENESS_LIMIT}× a case must say why \
         (listed below), or the run fails.\n",
        adapter.unwrap_or("none (GPU side skipped)")
    )
    .unwrap();
    md.push_str(
        "| case | side | inputs | max abs | max rel | max ULP | p99 rel | tolerance | verdict | slack | drift |\n",
    );
    md.push_str("|---|---|---:|---:|---:|---:|---:|---|---|---:|---|\n");
    for report in reports {
        for (side, stats) in report.sides() {
            match stats {
                Some(stats) => writeln!(
                    md,
                    "| `{}` | {side} | {} | {:.3e} | {:.3e} | {} | {:.3e} | {} | {} | {} | {} |",
                    report.name,
                    report.inputs,
                    stats.max_abs,
                    stats.max_rel,
                    ulp_cell(stats),
                    stats.p99_rel,
                    report.tolerance,
                    report.row_verdict(side, stats),
                    if side == "gpu" {
                        slack_cell(report)
                    } else {
                        String::new()
                    },
                    if side == "gpu" { report.drift() } else { "" },
                )
                .unwrap(),
                None => writeln!(
                    md,
                    "| `{}` | {side} | skipped | | | | | | | | |",
                    report.name
                )
                .unwrap(),
            }
        }
    }
    md.push_str("\n## Why each tolerance\n\n");
    for report in reports {
        writeln!(md, "- `{}`: {}", report.name, report.why).unwrap();
        if let Some(because) = report.audit.loose_because {
            writeln!(
                md,
                "  - loose tolerance ({}): {because}",
                slack_cell(report)
            )
            .unwrap();
        }
    }
    md
}

/// The columns of a Markdown table row that do not depend on the adapter:
/// case, side, inputs, tolerance, verdict.
fn stable_rows(markdown: &str) -> Vec<String> {
    markdown
        .lines()
        .filter(|line| line.starts_with("| `"))
        .map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            // ["", case, side, inputs, abs, rel, ulp, p99, tolerance, verdict, …]
            let cell = |i: usize| cells.get(i).copied().unwrap_or("");
            format!(
                "{} | {} | {} | {} | {}",
                cell(1),
                cell(2),
                cell(3),
                cell(8),
                cell(9)
            )
        })
        .collect()
}

/// Compares the stable columns of a committed table with a fresh one; returns each
/// difference (a removed row as `- …`, an added one as `+ …`).
pub fn stale_rows(committed: &str, fresh: &str) -> Vec<String> {
    let old = stable_rows(committed);
    let new = stable_rows(fresh);
    let mut differences: Vec<String> = old
        .iter()
        .filter(|row| !new.contains(row))
        .map(|row| format!("- {row}"))
        .collect();
    differences.extend(
        new.iter()
            .filter(|row| !old.contains(row))
            .map(|row| format!("+ {row}")),
    );
    if differences.is_empty() && old != new {
        differences.push("the rows are in a different order".into());
    }
    differences
}

#[cfg(test)]
mod tests {
    use super::*;

    const TABLE: &str = "| case | side |\n|---|---|\n\
        | `a::f` | cpu | 100 | 1e-7 | 1e-7 | 2 | 1e-7 | 4 ulp | PASS | | |\n\
        | `a::f` | gpu | 100 | 2e-7 | 2e-7 | 3 | 2e-7 | 4 ulp | PASS | 1.3× | gpu |\n";

    #[test]
    fn adapter_dependent_columns_are_not_compared() {
        let other_numbers = TABLE.replace("2e-7", "3e-7").replace("1.3×", "2.0×");
        assert!(stale_rows(TABLE, &other_numbers).is_empty());
    }

    #[test]
    fn names_inputs_tolerances_and_verdicts_are_compared() {
        for (from, to) in [
            ("`a::f` | gpu", "`a::g` | gpu"),
            ("| 100 | 2e-7", "| 101 | 2e-7"),
            ("4 ulp | PASS | 1.3×", "8 ulp | PASS | 1.3×"),
            ("PASS | 1.3×", "FAIL | 1.3×"),
        ] {
            let changed = TABLE.replace(from, to);
            assert_ne!(changed, TABLE);
            assert_eq!(stale_rows(TABLE, &changed).len(), 2, "{from} → {to}");
        }
        let fewer: String = TABLE.lines().take(3).map(|l| format!("{l}\n")).collect();
        assert_eq!(
            stale_rows(TABLE, &fewer),
            vec!["- `a::f` | gpu | 100 | 4 ulp | PASS"]
        );
    }
}
