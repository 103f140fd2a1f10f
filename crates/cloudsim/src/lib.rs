//! Dobashi et al. 2000's cellular automaton for cloud growth, three ways with one
//! result.
//!
//! A grid `nx × ny × nz` (z up) holds three booleans per cell: humidity `hum`,
//! activation `act` and cloud `cld`. Each step reads only the previous state:
//!
//! ```text
//! hum' = hum ∧ ¬act      cld' = cld ∨ act      act' = ¬act ∧ hum ∧ f_act
//! f_act = OR of act over x±1, y±1, x±2, y±2, z+1, z−1, z−2
//! ```
//!
//! then applies three stochastic terms, each with its own draw per cell: extinction
//! `cld' ∧= ¬(rnd < p_ext)`, humidity supply `hum' ∨= (rnd < p_hum)`, activation
//! `act' ∨= (rnd < p_act)`; clouds vanish where the ellipsoid mask is 0; finally each
//! slice moves with its wind. Probabilities come from ellipsoids ([`Model`]).
//!
//! * [`naive`]: one bool per cell, the reference;
//! * [`packed`] / [`Simulation`]: 32 cells per `u32`, multi-threaded;
//! * `gpu` (feature `gpu`): WGSL compute on the same packed layout, and the density
//!   volume (`gpu::GpuDensity`).
//!
//! Draws are counter based ([`rng`]), so all three agree bit for bit for the same seed,
//! whatever the thread count. [`density()`] turns the `cld` history into a smooth
//! `f32` volume.
//!
//! [`prelude`] holds the types a typical program needs; [`twins`] the draw helpers that
//! only `cargo xtask parity` calls on their own.

mod error;
mod model;
mod sim;
mod state;

pub mod density;
#[cfg(feature = "gpu")]
pub mod gpu;
pub mod naive;
pub mod packed;
pub mod regions;
pub mod rng;

pub use density::density;
pub use error::Error;
pub use model::{
    Boundary, Config, Ellipsoid, GridSize, MASK_LEVEL_MAX, MAX_CELLS, MAX_DIMENSION,
    MAX_SMOOTHING_RADIUS_CELLS, MAX_SMOOTHING_RADIUS_STEPS, MAX_WIND, Model, Probabilities,
    Smoothing,
};
pub use sim::Simulation;
pub use state::{NaiveState, PackedState};

/// The crates whose types appear in this crate's public API, re-exported so that a
/// dependent names the very versions this crate was built with (no pinning by hand):
/// `skyscape_wgsl` (the WGSL `Composer` and `Module`), and with
/// feature `gpu` `wgpu` (devices, queues, encoders).
pub use skyscape_wgsl;
#[cfg(feature = "gpu")]
pub use wgpu;

/// The types a typical program needs: `use cloudsim::prelude::*;`.
///
/// ```
/// use cloudsim::prelude::*;
/// let mut config = Config::new(GridSize::new(32, 16, 8));
/// config.seed = 7;
/// config.probabilities = Probabilities { activation: 0.01, ..Probabilities::default() };
/// let mut sim = Simulation::new(Model::new(config)?)?;
/// sim.advance(20)?;
/// let volume = sim.density()?; // f32 per cell, x fastest
/// assert_eq!(volume.len(), 32 * 16 * 8);
/// assert!(volume.iter().all(|d| (0.0..=1.0).contains(d)));
/// # Ok::<(), Error>(())
/// ```
pub mod prelude {
    pub use crate::{
        Boundary, Config, Ellipsoid, Error, GridSize, Model, NaiveState, PackedState,
        Probabilities, Simulation, Smoothing, density,
    };
}

/// Rust twins of the WGSL draw helpers that only `cargo xtask parity` calls on their
/// own (each compared bit for bit with its WGSL twin and with an independent
/// re-derivation).
///
/// The simulation composes them ([`rng::uniform16`] for the naive reference, a
/// 16-word batch of [`below_lane_thresholds`](twins::below_lane_thresholds) for the
/// packed one), so a program does not need them. They stay defined in [`rng`], which
/// mirrors `shaders/cloudsim/rng.wgsl` function for function, and are hidden there.
pub mod twins {
    #[doc(inline)]
    pub use crate::rng::{below_lane_thresholds, plane_bits};
}

/// The crate's WGSL modules, canonical under `shaders/cloudsim/`.
pub const WGSL_MODULES: &[skyscape_wgsl::Module] =
    include!(concat!(env!("OUT_DIR"), "/wgsl_modules.rs"));

/// The README's examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;

#[cfg(test)]
mod tests {
    #[test]
    fn every_wgsl_module_composes_and_validates() {
        let mut composer = skyscape_wgsl::Composer::with_common();
        composer.add_modules(super::WGSL_MODULES).unwrap();
        for module in super::WGSL_MODULES {
            let source = composer.compose_module(module.name).unwrap();
            skyscape_wgsl::validate(module.name, &source).unwrap_or_else(|e| panic!("{e}"));
        }
        // the module names follow the `cloudsim::<file_stem>` convention (sorted)
        let names: Vec<_> = super::WGSL_MODULES.iter().map(|m| m.name).collect();
        assert_eq!(
            names,
            ["cloudsim::density", "cloudsim::rng", "cloudsim::step"]
        );
    }

    #[cfg(feature = "gpu")]
    #[test]
    fn composed_step_shader_has_both_entry_points() {
        let source = super::gpu::compose_shader().unwrap();
        let module = skyscape_wgsl::validate("cloudsim::step", &source).unwrap();
        let entries: Vec<_> = module
            .entry_points
            .iter()
            .map(|e| e.name.as_str())
            .collect();
        assert_eq!(entries, ["step_main", "wind_main"]);
        let source = super::gpu::density::compose_density_shader().unwrap();
        let module = skyscape_wgsl::validate("cloudsim::density", &source).unwrap();
        assert_eq!(module.entry_points[0].name, "density_main");
    }
}
