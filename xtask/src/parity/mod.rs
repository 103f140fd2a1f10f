//! `cargo xtask parity`: every WGSL function against its Rust f32 twin and f64 reference.

pub mod audit;
pub mod cases;
pub mod compare;
pub mod passes;
pub mod report;

use audit::{Audit, ReferenceKind};
use cases::Case;
use compare::{Tolerance, compare, inject_difference};
use passes::PassCase;
use report::CaseReport;
use std::fmt::Write as _;

/// Options from the command line.
#[derive(Debug, Default)]
pub struct Options {
    /// Only cases whose name contains this.
    pub filter: Option<String>,
    /// Perturb this case's GPU result (or CPU result without a GPU) to prove the
    /// comparator catches it.
    pub inject: Option<String>,
    /// Also write the table as Markdown to this path (e.g. `docs/parity.md`).
    pub markdown: Option<std::path::PathBuf>,
    /// Compare this committed Markdown table with the run (case names, sides, inputs,
    /// tolerances, verdicts); a difference fails the run.
    pub check_markdown: Option<std::path::PathBuf>,
    /// Evaluate the CPU sides only (comparator self-test and CPU rows), no GPU.
    pub cpu_only: bool,
}

/// Builds the compute kernel that evaluates a case's WGSL over the input buffer.
pub fn kernel_source(case: &Case, count: usize) -> String {
    let (n_in, n_out) = case.arity;
    let mut src = String::new();
    for import in case.imports {
        writeln!(src, "#import {import}").unwrap();
    }
    writeln!(
        src,
        "@group(0) @binding(0) var<storage, read> parity_inputs: array<f32>;\n\
         @group(0) @binding(1) var<storage, read_write> parity_outputs: array<f32>;\n\
         @compute @workgroup_size(64)\n\
         fn parity_main(@builtin(global_invocation_id) gid: vec3<u32>, \
         @builtin(num_workgroups) groups: vec3<u32>) {{\n    \
         let i = gid.x + gid.y * groups.x * 64u;\n    \
         if i >= {count}u {{ return; }}"
    )
    .unwrap();
    for k in 0..n_in {
        writeln!(src, "    let x{k} = parity_inputs[i * {n_in}u + {k}u];").unwrap();
    }
    for k in 0..n_out {
        writeln!(src, "    var y{k}: f32 = 0.0;").unwrap();
    }
    writeln!(src, "    {}", case.wgsl).unwrap();
    for k in 0..n_out {
        writeln!(src, "    parity_outputs[i * {n_out}u + {k}u] = y{k};").unwrap();
    }
    src.push_str("}\n");
    src
}

/// The composer with every crate's WGSL modules.
pub fn composer() -> skyscape_wgsl::Composer {
    let mut composer = render::composer();
    composer
        .add_modules(terrain::WGSL_MODULES)
        .expect("terrain WGSL modules register")
        .add_modules(cloudlight::WGSL_MODULES)
        .expect("cloudlight WGSL modules register")
        .add_modules(cloudsim::WGSL_MODULES)
        .expect("cloudsim WGSL modules register")
        .add_modules(celestial::WGSL_MODULES)
        .expect("celestial WGSL modules register");
    composer
}

struct Evaluated {
    inputs: usize,
    inputs32: Vec<f32>,
    reference: Vec<f64>,
    bounds: Option<Vec<f64>>,
    cpu: Vec<f32>,
}

fn evaluate_cpu(case: &Case) -> Evaluated {
    let grid = (case.grid)();
    let (n_in, n_out) = case.arity;
    let mut inputs32 = Vec::with_capacity(grid.len() * n_in);
    let mut reference = Vec::with_capacity(grid.len() * n_out);
    let mut cpu = Vec::with_capacity(grid.len() * n_out);
    let mut bounds = case
        .tolerance
        .bound
        .map(|_| Vec::with_capacity(grid.len() * n_out));
    for row in &grid {
        assert_eq!(row.len(), n_in, "{}: grid row arity", case.name);
        let x32: Vec<f32> = row.iter().map(|&x| x as f32).collect();
        // The reference sees exactly the inputs the f32 sides see.
        let x64: Vec<f64> = x32.iter().map(|&x| f64::from(x)).collect();
        inputs32.extend_from_slice(&x32);
        let r = (case.reference)(&x64);
        let c = (case.cpu)(&x32);
        assert_eq!(
            (r.len(), c.len()),
            (n_out, n_out),
            "{}: output arity",
            case.name
        );
        reference.extend(r);
        cpu.extend(c);
        if let (Some(b), Some(f)) = (bounds.as_mut(), case.tolerance.bound) {
            b.extend(f(&x64));
        }
    }
    Evaluated {
        inputs: grid.len(),
        inputs32,
        reference,
        bounds,
        cpu,
    }
}

fn evaluate_gpu(
    gpu: &skyscape_harness::GpuContext,
    case: &Case,
    inputs32: &[f32],
) -> Result<Vec<f32>, String> {
    let count = inputs32.len() / case.arity.0;
    let composed = composer()
        .compose(case.name, &kernel_source(case, count))
        .map_err(|e| e.to_string())?;
    let bytes = skyscape_harness::run_compute(
        gpu,
        &skyscape_harness::ComputeJob {
            label: case.name,
            source: &composed,
            entry: "parity_main",
            constants: &[],
            inputs: &[bytemuck::cast_slice(inputs32)],
            output_bytes: (count * case.arity.1 * 4) as u64,
            workgroups: skyscape_harness::workgroups_1d(count as u32, 64),
        },
    )
    .map_err(|e| e.to_string())?;
    Ok(bytemuck::cast_slice(&bytes).to_vec())
}

/// A function case or a pass case.
enum AnyCase {
    Function(Case),
    Pass(PassCase),
}

impl AnyCase {
    fn all() -> Vec<AnyCase> {
        let functions = cases::all().into_iter().map(AnyCase::Function);
        functions
            .chain(passes::all().into_iter().map(AnyCase::Pass))
            .collect()
    }

    fn name(&self) -> &'static str {
        match self {
            AnyCase::Function(c) => c.name,
            AnyCase::Pass(p) => p.name,
        }
    }

    fn tolerance(&self) -> &compare::Tolerance {
        match self {
            AnyCase::Function(c) => &c.tolerance,
            AnyCase::Pass(p) => &p.tolerance,
        }
    }

    fn audit(&self) -> Audit {
        match self {
            AnyCase::Function(c) => c.audit,
            AnyCase::Pass(p) => p.audit,
        }
    }

    fn evaluate_cpu(&self) -> Result<Evaluated, String> {
        match self {
            AnyCase::Function(c) => Ok(evaluate_cpu(c)),
            AnyCase::Pass(p) => {
                let cpu = (p.cpu)()?;
                if cpu.cpu.len() != cpu.reference.len() {
                    return Err(format!("{}: CPU and reference lengths differ", p.name));
                }
                Ok(Evaluated {
                    inputs: cpu.inputs,
                    inputs32: Vec::new(),
                    reference: cpu.reference,
                    bounds: cpu.bounds,
                    cpu: cpu.cpu,
                })
            }
        }
    }

    fn evaluate_gpu(
        &self,
        gpu: &skyscape_harness::GpuContext,
        evaluated: &Evaluated,
    ) -> Result<Vec<f32>, String> {
        let values = match self {
            AnyCase::Function(c) => evaluate_gpu(gpu, c, &evaluated.inputs32)?,
            AnyCase::Pass(p) => (p.gpu)(gpu)?,
        };
        if values.len() != evaluated.reference.len() {
            return Err(format!(
                "{}: GPU returned {} values, reference has {}",
                self.name(),
                values.len(),
                evaluated.reference.len()
            ));
        }
        Ok(values)
    }
}

/// The comparator self-test of one case, on its own CPU evaluation (no GPU needed):
/// the reference rounded to f32 passes, and an injected difference (4× the allowed
/// error) and a NaN fail at the first, middle and last element. Returns the problems.
fn comparator_self_test(name: &str, evaluated: &Evaluated, tolerance: &Tolerance) -> Vec<String> {
    let mut problems = Vec::new();
    let bounds = evaluated.bounds.as_deref();
    let exact: Vec<f32> = evaluated.reference.iter().map(|&r| r as f32).collect();
    if !compare(&exact, &evaluated.reference, bounds, tolerance).passed() {
        problems.push(format!("{name}: the reference itself fails"));
    }
    for index in [
        0,
        evaluated.reference.len() / 2,
        evaluated.reference.len() - 1,
    ] {
        let mut perturbed = exact.clone();
        inject_difference(
            &mut perturbed,
            &evaluated.reference,
            bounds,
            tolerance,
            index,
        );
        if compare(&perturbed, &evaluated.reference, bounds, tolerance).passed() {
            problems.push(format!("{name}: injected difference at {index} passed"));
        }
        let mut nan = exact.clone();
        nan[index] = f32::NAN;
        if compare(&nan, &evaluated.reference, bounds, tolerance).passed() {
            problems.push(format!("{name}: NaN at {index} passed"));
        }
    }
    problems
}

/// What a run found beyond the table.
#[derive(Debug, Default)]
pub struct Findings {
    /// The totals (the last line printed).
    pub summary: report::Summary,
    /// Comparators that let an injected difference or a NaN through.
    pub self_test_problems: Vec<String>,
    /// Tolerances looser than the audit allows (only with every side run).
    pub loose_tolerances: Vec<String>,
    /// Differences between the committed Markdown table and this run.
    pub stale_rows: Vec<String>,
}

impl Findings {
    /// True when nothing failed.
    pub fn clean(&self) -> bool {
        self.summary.failed == 0
            && self.self_test_problems.is_empty()
            && self.loose_tolerances.is_empty()
            && self.stale_rows.is_empty()
    }
}

/// Runs the selected cases: each case's CPU sides are evaluated once and serve the
/// comparison, the comparator self-test and (with a GPU) the GPU comparison and the
/// tightness audit; then the table, the JSON and Markdown reports and the check of a
/// committed table. Progress goes to stderr.
pub fn run(options: &Options) -> Result<Findings, String> {
    let selected: Vec<AnyCase> = AnyCase::all()
        .into_iter()
        .filter(|c| {
            options
                .filter
                .as_ref()
                .is_none_or(|f| c.name().contains(f.as_str()))
        })
        .collect();
    if selected.is_empty() {
        return Err(format!("no parity case matches {:?}", options.filter));
    }
    if let Some(inject) = &options.inject
        && !selected.iter().any(|c| c.name().contains(inject.as_str()))
    {
        return Err(format!("--inject {inject}: no selected case has that name"));
    }
    if options.check_markdown.is_some() && (options.filter.is_some() || options.inject.is_some()) {
        return Err(
            "--check-markdown compares the whole table: not with --filter or --inject".into(),
        );
    }
    let gpu = if options.cpu_only {
        println!("CPU sides only (--self-test): no GPU row, no tightness audit");
        None
    } else {
        match skyscape_harness::context() {
            Ok(ctx) => {
                println!("adapter: {}", skyscape_harness::describe_adapter(&ctx.info));
                Some(ctx)
            }
            Err(e) if skyscape_harness::gpu_required() => {
                return Err(format!(
                    "{}=1 but no GPU is usable: {e}",
                    skyscape_harness::REQUIRE_GPU_ENV
                ));
            }
            Err(e) => {
                println!("SKIPPED GPU side of every case: {e}");
                None
            }
        }
    };
    let mut findings = Findings::default();
    let mut reports = Vec::new();
    let started = std::time::Instant::now();
    for (number, case) in selected.iter().enumerate() {
        let case_started = std::time::Instant::now();
        eprint!("[{:>3}/{}] {:<60}", number + 1, selected.len(), case.name());
        let evaluated = case.evaluate_cpu()?;
        let cpu_seconds = case_started.elapsed().as_secs_f64();
        let tolerance = case.tolerance();
        findings.self_test_problems.extend(comparator_self_test(
            case.name(),
            &evaluated,
            tolerance,
        ));
        let bounds = evaluated.bounds.as_deref();
        let mut cpu_values = evaluated.cpu.clone();
        let mut gpu_values = match gpu {
            Some(ctx) => Some(case.evaluate_gpu(ctx, &evaluated)?),
            None => None,
        };
        eprintln!(
            " cpu {cpu_seconds:>5.1} s, gpu {:>5.1} s",
            case_started.elapsed().as_secs_f64() - cpu_seconds
        );
        let injected = options
            .inject
            .as_ref()
            .is_some_and(|name| case.name().contains(name.as_str()));
        if injected {
            let index = evaluated.reference.len() / 2;
            let target = match gpu_values.as_mut() {
                Some(values) => values,
                None if case.audit().reference == ReferenceKind::CpuSide => {
                    return Err(format!(
                        "--inject {}: its CPU row is its own reference and there is no GPU \
                         row to perturb",
                        case.name()
                    ));
                }
                None => &mut cpu_values,
            };
            inject_difference(target, &evaluated.reference, bounds, tolerance, index);
        }
        let cpu = compare(&cpu_values, &evaluated.reference, bounds, tolerance);
        let gpu = gpu_values
            .as_ref()
            .map(|values| compare(values, &evaluated.reference, bounds, tolerance));
        if std::env::var_os("SKYSCAPE_PARITY_FAILURES").is_some() {
            for (side, values) in [("cpu", Some(&cpu_values)), ("gpu", gpu_values.as_ref())] {
                if let Some(values) = values {
                    dump_failures(case.name(), side, values, &evaluated, tolerance);
                }
            }
        }
        reports.push(CaseReport {
            name: case.name(),
            inputs: evaluated.inputs,
            tolerance: tolerance.describe(),
            exact: tolerance.abs == 0.0
                && tolerance.rel == 0.0
                && tolerance.ulp == 0.0
                && tolerance.bound.is_none(),
            why: tolerance.why,
            audit: case.audit(),
            cpu,
            gpu,
            injected,
        });
    }
    eprintln!(
        "parity: {} cases evaluated in {:.1} s",
        selected.len(),
        started.elapsed().as_secs_f64()
    );
    report::print_table(&reports);
    let adapter = gpu.map(|g| skyscape_harness::describe_adapter(&g.info));
    report::write_json(&reports, adapter.as_deref()).map_err(|e| format!("writing report: {e}"))?;
    let markdown = report::markdown(&reports, adapter.as_deref());
    if let Some(path) = &options.check_markdown {
        let committed = std::fs::read_to_string(path)
            .map_err(|e| format!("reading {}: {e}", path.display()))?;
        findings.stale_rows = report::stale_rows(&committed, &markdown);
    }
    if let Some(path) = &options.markdown {
        std::fs::write(path, &markdown).map_err(|e| format!("writing {}: {e}", path.display()))?;
        println!("markdown: {}", path.display());
    }
    // The tolerances are written for the GPU's built-ins: without the GPU rows the CPU
    // twin alone would call most of them loose.
    if gpu.is_some() && options.inject.is_none() {
        findings.loose_tolerances = reports.iter().filter_map(CaseReport::too_loose).collect();
    }
    findings.summary = report::Summary::of(&reports);
    for problem in &findings.self_test_problems {
        println!("self-test: {problem}");
    }
    if findings.self_test_problems.is_empty() {
        println!(
            "self-test: every comparator passes its reference and rejects an injected \
             difference and a NaN"
        );
    }
    for problem in &findings.loose_tolerances {
        println!("tightness: {problem}");
    }
    if gpu.is_none() {
        println!("tightness: not audited (needs the GPU rows)");
    } else if findings.loose_tolerances.is_empty() && options.inject.is_none() {
        println!(
            "tightness: every tolerance is within {}× of the worst error observed, or says why",
            audit::LOOSENESS_LIMIT
        );
    }
    if let Some(path) = &options.check_markdown {
        for row in &findings.stale_rows {
            println!("stale {}: {row}", path.display());
        }
        if findings.stale_rows.is_empty() {
            println!(
                "{}: case names, inputs, tolerances and verdicts match this run",
                path.display()
            );
        } else {
            println!(
                "{} is stale: regenerate it with `cargo xtask parity --markdown {}`",
                path.display(),
                path.display()
            );
        }
    }
    println!("{}", findings.summary.line());
    Ok(findings)
}

/// With `SKYSCAPE_PARITY_FAILURES` set: the first 16 failing elements of a side
/// (row inputs as f32, value, reference, allowed error) appended to
/// `target/parity/failures.txt`, to find what a device run disagreed on.
fn dump_failures(
    name: &str,
    side: &str,
    values: &[f32],
    evaluated: &Evaluated,
    tolerance: &Tolerance,
) {
    let outputs_per_row = evaluated.reference.len() / evaluated.inputs.max(1);
    let inputs_per_row = evaluated.inputs32.len() / evaluated.inputs.max(1);
    let mut text = String::new();
    let mut shown = 0;
    for (i, (&value, &expected)) in values.iter().zip(&evaluated.reference).enumerate() {
        let bound = evaluated.bounds.as_ref().map(|b| b[i]);
        let allowed = tolerance.allowed(expected, bound);
        let error = (f64::from(value) - expected).abs();
        if error <= allowed && !value.is_nan() {
            continue;
        }
        if shown == 16 {
            break;
        }
        shown += 1;
        let row = i / outputs_per_row.max(1);
        let inputs = evaluated
            .inputs32
            .get(row * inputs_per_row..(row + 1) * inputs_per_row)
            .unwrap_or(&[]);
        let _ = writeln!(
            text,
            "{name} {side} element {i} (row {row}, output {}): inputs {inputs:?} value {value:e} \
             reference {expected:e} allowed {allowed:e}",
            i % outputs_per_row.max(1)
        );
    }
    if text.is_empty() {
        return;
    }
    let path = std::path::Path::new("target/parity/failures.txt");
    let _ = std::fs::create_dir_all("target/parity");
    if let Ok(mut file) = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
    {
        let _ = std::io::Write::write_all(&mut file, text.as_bytes());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_has_enough_inputs_and_distinct_names() {
        let all = AnyCase::all();
        let mut names: Vec<_> = all.iter().map(AnyCase::name).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all.len());
        let short: Vec<String> = cases::all()
            .iter()
            .map(|case| (case.name, (case.grid)().len()))
            .filter(|&(_, n)| n < 10_000)
            .map(|(name, n)| format!("{name}: {n} inputs"))
            .collect();
        assert!(short.is_empty(), "cases under 10,000 inputs: {short:?}");
    }

    #[test]
    fn every_kernel_composes_and_validates() {
        let composer = composer();
        for case in cases::all() {
            let src = composer
                .compose(case.name, &kernel_source(&case, 10))
                .unwrap();
            skyscape_wgsl::validate(case.name, &src).unwrap();
        }
    }

    // Every case's comparator self-test and CPU rows run in `cargo xtask parity` (CI), on
    // the one evaluation of its CPU sides; the tests here check the machinery on small
    // synthetic data instead of evaluating every case again.

    fn evaluated(reference: Vec<f64>) -> Evaluated {
        Evaluated {
            inputs: reference.len(),
            inputs32: Vec::new(),
            cpu: reference.iter().map(|&r| r as f32).collect(),
            reference,
            bounds: None,
        }
    }

    const FOUR_ULP: Tolerance = Tolerance {
        abs: 0.0,
        rel: 0.0,
        ulp: 4.0,
        bound: None,
        why: "test",
    };

    #[test]
    fn comparator_self_test_passes_a_sound_comparator() {
        let e = evaluated((1..100).map(|i| f64::from(i).sqrt()).collect());
        assert!(comparator_self_test("t", &e, &FOUR_ULP).is_empty());
    }

    #[test]
    fn comparator_self_test_reports_a_tolerance_its_own_reference_fails() {
        // √i is not an f32: an exact tolerance rejects the reference rounded to f32.
        let e = evaluated((2..100).map(|i| f64::from(i).sqrt()).collect());
        let exact = Tolerance {
            ulp: 0.0,
            ..FOUR_ULP
        };
        let problems = comparator_self_test("t", &e, &exact);
        assert_eq!(problems, vec!["t: the reference itself fails".to_string()]);
    }

    fn case_report(audit: Audit, cpu_ratio: f64, gpu: Option<f64>) -> CaseReport {
        let stats = |ratio: f64| compare::SideStats {
            elements: 10,
            worst_ratio: ratio,
            failures: usize::from(ratio > 1.0),
            ..Default::default()
        };
        CaseReport {
            name: "t",
            inputs: 10,
            tolerance: "4 ulp".into(),
            exact: false,
            why: "test",
            audit,
            cpu: stats(cpu_ratio),
            gpu: gpu.map(stats),
            injected: false,
        }
    }

    #[test]
    fn a_self_referenced_cpu_row_is_not_a_pass() {
        let no_gpu = case_report(Audit::CPU_IS_REFERENCE, 0.0, None);
        assert_eq!(no_gpu.outcome(), report::Outcome::Unchecked);
        assert_eq!(
            no_gpu.row_verdict("cpu", &no_gpu.cpu),
            report::SELF_REFERENCED
        );
        let gpu_fails = case_report(Audit::CPU_IS_REFERENCE, 0.0, Some(2.0));
        assert_eq!(gpu_fails.outcome(), report::Outcome::Failed);
        let summary = report::Summary::of(&[
            no_gpu,
            gpu_fails,
            case_report(Audit::INDEPENDENT, 0.5, Some(0.5)),
        ]);
        assert_eq!(
            summary,
            report::Summary {
                cases: 3,
                passed: 1,
                failed: 1,
                self_referenced: 2,
                unchecked: 1,
            }
        );
    }

    #[test]
    fn tightness_audit_uses_the_checked_rows() {
        let limit = audit::LOOSENESS_LIMIT;
        // The GPU row is within the limit: tight enough, however exact the CPU twin.
        assert!(
            case_report(Audit::INDEPENDENT, 0.0, Some(2.0 / limit))
                .too_loose()
                .is_none()
        );
        assert!(
            case_report(Audit::INDEPENDENT, 0.1 / limit, Some(0.5 / limit))
                .too_loose()
                .is_some()
        );
        // A self-referenced CPU row (error 0) does not count; a declared reason does.
        assert!(
            case_report(Audit::CPU_IS_REFERENCE, 0.0, Some(0.5))
                .too_loose()
                .is_none()
        );
        assert!(
            case_report(Audit::INDEPENDENT.loose("test"), 0.0, Some(0.0))
                .too_loose()
                .is_none()
        );
    }
}
