//! f64 references for every f32 twin in this crate: the same names, arguments and
//! algorithms, evaluated in double precision. `cargo xtask parity` measures both the
//! f32 twin and the WGSL against these, so the reported error is floating-point error
//! (the discretisation, where there is one, is shared and is measured separately
//! against analytic results in the unit tests).
//!
//! Where the f64 reference is the same formula as its f32 twin, the formula is written
//! once, generic over [`crate::real::Real`], and re-exported here at f64 (phase
//! functions, geometry, densities, optical depth, transmittance, closed form, single
//! scattering). What stays separate is independent on purpose: `one_minus_exp_neg`
//! (`expm1` against the twin's series) and the multiple-scattering
//! [`ReferenceSky`] and [`PathTracedSky`] (other algorithms, converged).

// The phase functions are written once, generic over `Real`; at f64 they are the
// references of their f32 twins.
pub use crate::phase::{
    cornette_shanks_legendre_moments, cornette_shanks_phase, henyey_greenstein_phase,
    phase_denominator_base, rayleigh_phase,
};

pub use crate::geometry::{altitude_along_ray, ray_sphere_intersect};

pub use crate::closed_form::{closed_form_extinction, closed_form_inscatter};
pub use crate::optical_depth::optical_length_exponential;
pub use crate::transmittance::transmittance_from_optical_depth;

/// 1 − exp(−x) exactly rounded in f64 (via `exp_m1`): an independent formulation of
/// the f32 twin's Horner series ([`crate::transmittance::one_minus_exp_neg`]).
pub fn one_minus_exp_neg(x: f64) -> f64 {
    <f64 as crate::real::Real>::one_minus_exp_neg(x)
}

#[doc(inline)]
pub use crate::atmosphere::{exponential_density, extinction_at_altitude, tent_density};

#[doc(inline)]
pub use crate::single_scattering::{
    density_profile, extinction_from_densities, light_path_transmittance, lowest_point_distance,
    mean_transmittance_over_segment, optical_lengths, ray_sample_distance, single_scattering,
    single_scattering_inside,
};

pub mod multiple_scattering;
mod transmittance_table;
pub use multiple_scattering::{ReferenceSettings, ReferenceSky};
pub mod path_tracer;
pub use path_tracer::{FreePaths, PathTracedSample, PathTracedSky, PathTracerSettings};
pub mod spectral;
pub use spectral::SpectralReferenceSky;
pub use transmittance_table::TransmittanceTable;
