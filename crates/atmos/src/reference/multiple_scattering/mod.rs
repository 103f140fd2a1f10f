//! Rung 4, the Reference: f64 single scattering computed per query at high sample
//! counts, plus multiple scattering by iterated orders (Bruneton & Neyret 2008,
//! Bruneton 2017's "scattering density"), including light the Lambertian ground
//! reflects and the air scatters again.
//!
//! Orders (k ≥ 2), with `L_k` the radiance of light scattered exactly k times and `E_m`
//! the ground irradiance of order m (`E_0` = direct sun):
//!
//! * `J_k(x, ω) = ∫_{4π} [L_{k−1}(x, ω') + G_{k−2}(x, ω')] (β_R ρ_R p_R(ω·ω') + β_M ρ_M p_M(ω·ω')) dω'`
//!   where `G_m` is the ground's radiance `α/π · E_m` times the transmittance to it, for
//!   directions ω' that meet the ground;
//! * `L_k(x, ω) = ∫ T(x, x_t) J_k(x_t, ω) dt` along the ray;
//! * `E_{k−1}(ground) = ∫_{2π} L_{k−1} cos θ' dω'`.
//!
//! `J_k` is tabulated on a 4D grid in (ρ/H, view zenith angle, sun zenith angle, view
//! azimuth relative to the sun), per unit density: the incoming radiance weighted by
//! each phase function, multiplied by the densities at the query point's own altitude
//! (see `PhaseWeighted`); the sun-angle rows crowd at the terminator (see
//! `SUN_CROWD_CENTRE`). For each grid point (r, sun angle) the incoming
//! radiance `L_{k−1} + G_{k−2}` is ray-marched over a fixed set of directions (half the
//! sphere: the field is symmetric about the sun's vertical plane), `E_{k−1}` follows at
//! the ground, and `J_k` for every view direction is a weighted sum with precomputed,
//! per-direction normalised phase weights (energy is conserved by construction). The
//! query adds `∫ T Σ_k J_k dt` along its own ray, marched at high resolution, to the
//! directly computed single scattering.

mod grid;
mod orders;
mod quadrature;
mod settings;
mod sky;

pub use settings::{MAX_SUN_ZENITH, ReferenceSettings};
pub use sky::ReferenceSky;
