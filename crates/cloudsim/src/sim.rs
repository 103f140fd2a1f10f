//! [`Simulation`]: the fast CPU implementation with its ping-pong buffers, step
//! counter and the `cld` history the density smoothing needs.

use std::collections::VecDeque;

use crate::{Error, Model, PackedState, density, packed};

/// A running automaton on the CPU (bit-packed, multi-threaded).
#[derive(Debug, Clone)]
pub struct Simulation {
    model: Model,
    state: PackedState,
    scratch: PackedState,
    step: u32,
    threads: usize,
    history: VecDeque<Vec<u32>>,
}

impl Simulation {
    /// An all-empty grid at step 0, using all available cores.
    pub fn new(model: Model) -> Result<Self, Error> {
        let state = PackedState::empty(model.size())?;
        Self::with_state(model, state, 0)
    }

    /// Starts from `state` at step `step` (the next step draws with counter `step`).
    pub fn with_state(model: Model, state: PackedState, step: u32) -> Result<Self, Error> {
        state.check()?;
        if state.size() != model.size() {
            return Err(Error::SizeMismatch {
                what: "state",
                got: state.size().cells(),
                expected: model.size().cells(),
            });
        }
        let scratch = PackedState::empty(model.size())?;
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let history = VecDeque::from([state.cld.clone()]);
        Ok(Self {
            model,
            state,
            scratch,
            step,
            threads,
            history,
        })
    }

    /// Sets the worker thread count (the result does not depend on it).
    pub fn set_threads(&mut self, threads: usize) -> Result<(), Error> {
        if threads == 0 {
            return Err(Error::ZeroThreads);
        }
        self.threads = threads;
        Ok(())
    }

    /// Worker thread count.
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Runs `steps` steps.
    pub fn advance(&mut self, steps: u32) -> Result<(), Error> {
        let keep = self.model.smoothing().radius_steps as usize + 1;
        for _ in 0..steps {
            packed::step(
                &self.model,
                &mut self.state,
                &mut self.scratch,
                self.step,
                self.threads,
            )?;
            self.step = self.step.wrapping_add(1);
            let mut newest = if self.history.len() >= keep {
                self.history.pop_back().unwrap_or_default()
            } else {
                Vec::new()
            };
            newest.clear();
            newest.extend_from_slice(&self.state.cld);
            self.history.push_front(newest);
        }
        Ok(())
    }

    /// The current state.
    pub fn state(&self) -> &PackedState {
        &self.state
    }

    /// The counter of the next step.
    pub fn step_index(&self) -> u32 {
        self.step
    }

    /// The model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The smoothed density of the current state and its recent history (see
    /// [`density::density`]).
    pub fn density(&self) -> Result<Vec<f32>, Error> {
        let history: Vec<&[u32]> = self.history.iter().map(Vec::as_slice).collect();
        density::density(&self.model, &history)
    }

    /// [`Simulation::density`] in f64 (see [`density::density_f64`]).
    pub fn density_f64(&self) -> Result<Vec<f64>, Error> {
        let history: Vec<&[u32]> = self.history.iter().map(Vec::as_slice).collect();
        density::density_f64(&self.model, &history)
    }
}
