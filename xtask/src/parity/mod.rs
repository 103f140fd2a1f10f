//! `cargo xtask parity`: every WGSL function against its Rust f32 twin and f64 reference.

pub mod cases;
pub mod compare;
pub mod passes;

use cases::Case;
use compare::{SideStats, compare, inject_difference};
use passes::PassCase;
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
}

/// The result of one case.
#[derive(Debug)]
pub struct CaseReport {
    name: &'static str,
    inputs: usize,
    tolerance: String,
    why: &'static str,
    cpu: SideStats,
    gpu: Option<SideStats>,
    injected: bool,
}

impl CaseReport {
    fn passed(&self) -> bool {
        self.cpu.passed() && self.gpu.as_ref().is_none_or(SideStats::passed)
    }

    /// The side whose worst error/allowed ratio is larger.
    fn drift(&self) -> &'static str {
        match &self.gpu {
            None => "cpu (gpu skipped)",
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

/// Runs the selected cases; returns true when all passed.
pub fn run(options: &Options) -> Result<bool, String> {
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
    let gpu = match skyscape_harness::context() {
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
    };
    let mut reports = Vec::new();
    for case in &selected {
        let evaluated = case.evaluate_cpu()?;
        let tolerance = case.tolerance();
        let bounds = evaluated.bounds.as_deref();
        let mut cpu_values = evaluated.cpu.clone();
        let mut gpu_values = match gpu {
            Some(ctx) => Some(case.evaluate_gpu(ctx, &evaluated)?),
            None => None,
        };
        let injected = options
            .inject
            .as_ref()
            .is_some_and(|name| case.name().contains(name.as_str()));
        if injected {
            let index = evaluated.reference.len() / 2;
            let target = gpu_values.as_mut().unwrap_or(&mut cpu_values);
            inject_difference(target, &evaluated.reference, bounds, tolerance, index);
        }
        let cpu = compare(&cpu_values, &evaluated.reference, bounds, tolerance);
        let gpu = gpu_values
            .as_ref()
            .map(|values| compare(values, &evaluated.reference, bounds, tolerance));
        reports.push(CaseReport {
            name: case.name(),
            inputs: evaluated.inputs,
            tolerance: tolerance.describe(),
            why: tolerance.why,
            cpu,
            gpu,
            injected,
        });
    }
    print_table(&reports);
    let adapter = gpu.map(|g| skyscape_harness::describe_adapter(&g.info));
    write_json(&reports, adapter.as_deref()).map_err(|e| format!("writing report: {e}"))?;
    if let Some(path) = &options.markdown {
        write_markdown(path, &reports, adapter.as_deref())
            .map_err(|e| format!("writing {}: {e}", path.display()))?;
    }
    Ok(reports.iter().all(CaseReport::passed))
}

fn print_table(reports: &[CaseReport]) {
    println!(
        "{:<40} {:<4} {:>7} {:>10} {:>10} {:>8} {:>10} {:<30} {:<7} drift",
        "case",
        "side",
        "inputs",
        "max abs",
        "max rel",
        "max ulp",
        "p99 rel",
        "tolerance",
        "verdict"
    );
    for report in reports {
        let sides = [("cpu", Some(&report.cpu)), ("gpu", report.gpu.as_ref())];
        for (side, stats) in sides {
            let Some(stats) = stats else {
                println!("{:<40} {:<4} skipped (no GPU adapter)", report.name, side);
                continue;
            };
            println!(
                "{:<40} {:<4} {:>7} {:>10.3e} {:>10.3e} {:>8} {:>10.3e} {:<30} {:<7} {}",
                report.name,
                side,
                report.inputs,
                stats.max_abs,
                stats.max_rel,
                if stats.max_ulp == u64::MAX {
                    "NaN".to_string()
                } else {
                    stats.max_ulp.to_string()
                },
                stats.p99_rel,
                report.tolerance,
                if stats.passed() { "PASS" } else { "FAIL" },
                if side == "gpu" || report.gpu.is_none() {
                    report.drift()
                } else {
                    ""
                },
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

fn side_json(stats: &SideStats) -> String {
    format!(
        "{{\"elements\": {}, \"max_abs\": {}, \"max_rel\": {}, \"max_ulp\": {}, \"p99_rel\": {}, \
         \"worst_ratio\": {}, \"failures\": {}, \"passed\": {}}}",
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
        stats.passed()
    )
}

fn write_json(reports: &[CaseReport], adapter: Option<&str>) -> std::io::Result<()> {
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
             \"injected\": {}, \"passed\": {}, \"cpu\": {}, \"gpu\": {}}}",
            json_string(report.name),
            report.inputs,
            json_string(&report.tolerance),
            json_string(report.why),
            json_string(report.drift()),
            report.injected,
            report.passed(),
            side_json(&report.cpu),
            report.gpu.as_ref().map_or("null".into(), side_json),
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

fn write_markdown(
    path: &std::path::Path,
    reports: &[CaseReport],
    adapter: Option<&str>,
) -> std::io::Result<()> {
    let mut md = String::from(
        "# Parity: WGSL vs Rust f32 twin vs f64 reference\n\n\
         Generated by `cargo xtask parity --markdown docs/parity.md` (do not edit by hand).\n\n",
    );
    writeln!(
        md,
        "Adapter: {}\n\nAn element passes when |value − reference| ≤ abs + rel·|ref| + ulp·ULP(ref) \
         (+ the case's forward-error bound). Errors are against the f64 reference evaluated \
         on the same f32 inputs.\n",
        adapter.unwrap_or("none (GPU side skipped)")
    )
    .unwrap();
    md.push_str("| case | side | inputs | max abs | max rel | max ULP | p99 rel | tolerance | verdict | drift |\n");
    md.push_str("|---|---|---:|---:|---:|---:|---:|---|---|---|\n");
    for report in reports {
        for (side, stats) in [("cpu", Some(&report.cpu)), ("gpu", report.gpu.as_ref())] {
            match stats {
                Some(stats) => writeln!(
                    md,
                    "| `{}` | {side} | {} | {:.3e} | {:.3e} | {} | {:.3e} | {} | {} | {} |",
                    report.name,
                    report.inputs,
                    stats.max_abs,
                    stats.max_rel,
                    stats.max_ulp,
                    stats.p99_rel,
                    report.tolerance,
                    if stats.passed() { "PASS" } else { "FAIL" },
                    if side == "gpu" { report.drift() } else { "" },
                )
                .unwrap(),
                None => {
                    writeln!(md, "| `{}` | {side} | skipped | | | | | | | |", report.name).unwrap()
                }
            }
        }
    }
    md.push_str("\n## Why each tolerance\n\n");
    for report in reports {
        writeln!(md, "- `{}`: {}", report.name, report.why).unwrap();
    }
    std::fs::write(path, md)?;
    println!("markdown: {}", path.display());
    Ok(())
}

/// Comparator self-test without a GPU: for every case, the reference rounded to f32
/// passes, and an injected difference (and a NaN) fails. Returns the failures.
pub fn self_test() -> Vec<String> {
    let mut problems = Vec::new();
    for case in AnyCase::all() {
        let name = case.name();
        let tolerance = case.tolerance();
        let evaluated = match case.evaluate_cpu() {
            Ok(e) => e,
            Err(e) => {
                problems.push(format!("{name}: {e}"));
                continue;
            }
        };
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
    }
    problems
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
        for case in cases::all() {
            let n = (case.grid)().len();
            assert!(n >= 10_000, "{}: {n} inputs", case.name);
        }
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

    #[test]
    fn comparator_self_test_catches_injected_differences() {
        let problems = self_test();
        assert!(problems.is_empty(), "{problems:#?}");
    }

    #[test]
    fn cpu_sides_are_within_tolerance() {
        for case in AnyCase::all() {
            let e = case.evaluate_cpu().unwrap();
            let stats = compare(&e.cpu, &e.reference, e.bounds.as_deref(), case.tolerance());
            assert!(stats.passed(), "{}: {stats:?}", case.name());
        }
    }
}
