//! The incoming-direction quadrature and its normalised phase weights.

use std::f64::consts::PI;

use super::super::{cornette_shanks_phase, rayleigh_phase};
use super::grid::*;
use super::settings::*;
use crate::Atmosphere;

/// One incoming direction of the quadrature (azimuth in [0, π]; its mirror image has
/// the same radiance and weight).
#[derive(Debug, Clone, Copy)]
pub(super) struct Direction {
    pub(super) cos_zenith: f64,
    pub(super) sin_zenith: f64,
    pub(super) cos_azimuth: f64,
    /// Solid angle of one of the two mirrored cells (sr).
    pub(super) weight: f64,
}

/// The incoming-direction quadrature and, for every table view direction, the phase
/// weights of each incoming direction (mirror pair summed), normalised so each view's
/// weights integrate the phase function to exactly 1.
pub(super) struct DirectionSet {
    pub(super) directions: Vec<Direction>,
    pub(super) view_count: usize,
    pub(super) rayleigh_weights: Vec<f64>,
    pub(super) mie_weights: Vec<f64>,
}

/// The zenith angles and solid-angle widths (per unit azimuth) of the incoming
/// directions at radius `r`: the cells split at the horizon of `r` (the zenith angle
/// `θ_h` beyond which rays meet the ground), half over the sky and half over the ground,
/// each crowding quadratically towards it, where the incoming radiance peaks (the
/// longest paths) and steps (sky to ground). Uniform cells over [0, π] straddled the
/// horizon of every altitude above the ground and sampled its peak coarsely.
pub(super) fn zenith_cells(count: usize, planet_radius: f64, r: f64) -> Vec<(f64, f64)> {
    let horizon = PI
        - (planet_radius / r.max(planet_radius))
            .clamp(-1.0, 1.0)
            .asin();
    let sky = count / 2;
    let ground = count - sky;
    let mut cells = Vec::with_capacity(count);
    // Sky: θ = θ_h (1 − (1 − u)²), u ∈ [0, 1], midpoints in u.
    for i in 0..sky {
        let u = (i as f64 + 0.5) / sky as f64;
        let theta = horizon * (1.0 - (1.0 - u) * (1.0 - u));
        let width = horizon * 2.0 * (1.0 - u) / sky as f64;
        cells.push((theta, theta.sin() * width));
    }
    // Ground: θ = θ_h + (π − θ_h) u².
    for i in 0..ground {
        let u = (i as f64 + 0.5) / ground as f64;
        let theta = horizon + (PI - horizon) * u * u;
        let width = (PI - horizon) * 2.0 * u / ground as f64;
        cells.push((theta, theta.sin() * width));
    }
    cells
}

impl DirectionSet {
    pub(super) fn new(
        settings: &ReferenceSettings,
        atmosphere: &Atmosphere,
        grid: &SourceGrid,
        r: f64,
    ) -> Self {
        let g = atmosphere.mie_g;
        let (n_theta, n_phi) = (settings.sphere_zenith_size, settings.sphere_azimuth_size);
        let d_phi = PI / n_phi as f64;
        let mut directions = Vec::with_capacity(n_theta * n_phi);
        let mut azimuths = Vec::with_capacity(n_theta * n_phi);
        for (theta, zenith_weight) in zenith_cells(n_theta, atmosphere.planet_radius, r) {
            for b in 0..n_phi {
                let phi = (b as f64 + 0.5) * d_phi;
                directions.push(Direction {
                    cos_zenith: theta.cos(),
                    sin_zenith: theta.sin(),
                    cos_azimuth: phi.cos(),
                    weight: zenith_weight * d_phi,
                });
                azimuths.push(phi);
            }
        }
        let [_, n_mu, _, n_view_phi] = grid.sizes;
        let view_count = n_mu * n_view_phi;
        let mut rayleigh_weights = Vec::with_capacity(view_count * directions.len());
        let mut mie_weights = Vec::with_capacity(view_count * directions.len());
        for i_mu in 0..n_mu {
            let (sin_v, cos_v) = grid.angle(1, i_mu).sin_cos();
            for i_phi in 0..n_view_phi {
                let phi_v = grid.angle(3, i_phi);
                let start = rayleigh_weights.len();
                let (mut norm_r, mut norm_m) = (0.0, 0.0);
                for (d, &phi) in directions.iter().zip(&azimuths) {
                    let mut wr = 0.0;
                    let mut wm = 0.0;
                    for mirrored in [phi, -phi] {
                        let c = (sin_v * d.sin_zenith * (phi_v - mirrored).cos()
                            + cos_v * d.cos_zenith)
                            .clamp(-1.0, 1.0);
                        wr += d.weight * rayleigh_phase(c);
                        wm += d.weight * cornette_shanks_phase(c, g);
                    }
                    norm_r += wr;
                    norm_m += wm;
                    rayleigh_weights.push(wr);
                    mie_weights.push(wm);
                }
                for w in &mut rayleigh_weights[start..] {
                    *w /= norm_r;
                }
                for w in &mut mie_weights[start..] {
                    *w /= norm_m;
                }
            }
        }
        Self {
            directions,
            view_count,
            rayleigh_weights,
            mie_weights,
        }
    }
}
