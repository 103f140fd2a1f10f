//! The stages of a frame's work (the preparation's steps, the drawing, the writing)
//! with their wall time: on a terminal an indicatif spinner naming the current stage,
//! with a line per finished stage above it; otherwise one line per finished stage on
//! stderr. Stages that did nothing (under a millisecond) get no line.

use std::io::IsTerminal;
use std::time::Instant;

#[derive(Debug)]
pub(crate) struct Stages {
    label: String,
    bar: Option<indicatif::ProgressBar>,
    current: Option<(&'static str, Instant)>,
    /// Each finished stage and its wall time, seconds.
    pub(crate) finished: Vec<(&'static str, f64)>,
}

impl Stages {
    /// Stages of the work called `label` (the scene's name, the frame).
    pub(crate) fn new(label: String) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new_spinner();
            bar.set_style(
                indicatif::ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
            );
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
            bar
        });
        Self {
            label,
            bar,
            current: None,
            finished: Vec::new(),
        }
    }

    /// Ends the current stage (if any) and begins `name`.
    pub(crate) fn begin(&mut self, name: &'static str) {
        self.end_current();
        if let Some(bar) = &self.bar {
            bar.set_message(format!("{}: {name}", self.label));
            bar.reset_elapsed();
        }
        self.current = Some((name, Instant::now()));
    }

    fn end_current(&mut self) {
        let Some((name, start)) = self.current.take() else {
            return;
        };
        let seconds = start.elapsed().as_secs_f64();
        self.finished.push((name, seconds));
        if seconds < 1e-3 {
            return;
        }
        let line = format!("skyscape: {}: {name} {seconds:.2} s", self.label);
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprintln!("{line}"),
        }
    }

    /// Ends the last stage and clears the spinner.
    pub(crate) fn finish(&mut self) {
        self.end_current();
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

impl Drop for Stages {
    fn drop(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
