//! The `skyscape` binary's command line: conflicting options are errors, not
//! self-comparisons.

use std::process::Command;

fn skyscape(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_skyscape"))
        .args(args)
        .output()
        .expect("the skyscape binary runs")
}

#[test]
fn compare_without_a_gpu_image_is_an_error() {
    // Each would compare the CPU image with itself and report 100 %.
    for args in [
        &["render", "--cpu", "--compare"][..],
        &["render", "--rung", "reference", "--compare"][..],
        &["render", "--rung", "reference-spectral", "--explain"][..],
    ] {
        let output = skyscape(args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        let flag = args[args.len() - 1];
        assert!(stderr.contains(flag), "{args:?}: {stderr}");
    }
}
