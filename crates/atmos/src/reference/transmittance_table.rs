//! A fine f64 table of transmittance from a point to the top of the atmosphere, used by
//! the Reference's precomputation to light table points by the sun (a light march per
//! sample would cost ~100× more). Parameterisation of Bruneton 2017 (§ "Transmittance"):
//! `x_r = ρ/H` and `x_mu = (d − d_min)/(d_max − d_min)`, with `ρ = √(r² − R²)`,
//! `H = √(R_top² − R²)` and `d` the distance to the top, which spends the texels where
//! transmittance changes (near the horizon) and keeps them off the straight-up rays.

use super::{extinction_from_densities, optical_lengths};
use crate::Atmosphere;

/// Transmittance to the top sampled on a regular grid in (x_r, x_mu): the optical depth
/// is stored and interpolated bilinearly, then exponentiated (interpolating the
/// transmittance itself overestimated it where it falls steeply, on the grazing sun
/// paths of twilight). The caller handles the planet's shadow (rays meeting the ground).
#[derive(Debug, Clone)]
pub struct TransmittanceTable {
    radius_size: usize,
    mu_size: usize,
    planet_radius: f64,
    top_radius: f64,
    values: Vec<[f64; 3]>,
}

impl TransmittanceTable {
    /// Integrates each texel's optical depth with `samples` midpoint samples.
    pub fn new(atmosphere: &Atmosphere, radius_size: usize, mu_size: usize, samples: u32) -> Self {
        let mut table = Self {
            radius_size: radius_size.max(2),
            mu_size: mu_size.max(2),
            planet_radius: atmosphere.planet_radius,
            top_radius: atmosphere.top_radius,
            values: Vec::new(),
        };
        let mut values = Vec::with_capacity(table.radius_size * table.mu_size);
        for i in 0..table.radius_size {
            for j in 0..table.mu_size {
                let x_r = i as f64 / (table.radius_size - 1) as f64;
                let x_mu = j as f64 / (table.mu_size - 1) as f64;
                let (r, mu, length) = table.ray(x_r, x_mu);
                let lengths = optical_lengths(atmosphere, r, mu, length, samples);
                let depth = extinction_from_densities(atmosphere, lengths);
                values.push(depth);
            }
        }
        table.values = values;
        table
    }

    fn horizon_length(&self) -> f64 {
        ((self.top_radius - self.planet_radius) * (self.top_radius + self.planet_radius)).sqrt()
    }

    /// (r, mu, distance to the top) of a texel coordinate.
    fn ray(&self, x_r: f64, x_mu: f64) -> (f64, f64, f64) {
        let h = self.horizon_length();
        let rho = h * x_r;
        let r = (rho * rho + self.planet_radius * self.planet_radius).sqrt();
        let d_min = self.top_radius - r;
        let d_max = rho + h;
        let d = d_min + x_mu * (d_max - d_min);
        let mu = if d <= 0.0 {
            1.0
        } else {
            ((h * h - rho * rho - d * d) / (2.0 * r * d)).clamp(-1.0, 1.0)
        };
        (r, mu, d)
    }

    /// Transmittance from (r, mu) to the top of the atmosphere (ignoring the ground).
    pub fn lookup(&self, r: f64, mu: f64) -> [f64; 3] {
        let h = self.horizon_length();
        let r = r.clamp(self.planet_radius, self.top_radius);
        let rho = ((r - self.planet_radius) * (r + self.planet_radius))
            .max(0.0)
            .sqrt();
        let discriminant = r * r * (mu * mu - 1.0) + self.top_radius * self.top_radius;
        let d = (-r * mu + discriminant.max(0.0).sqrt()).max(0.0);
        let d_min = self.top_radius - r;
        let d_max = rho + h;
        let x_mu = if d_max > d_min {
            ((d - d_min) / (d_max - d_min)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let x_r = (rho / h).clamp(0.0, 1.0);
        let fi = x_r * (self.radius_size - 1) as f64;
        let fj = x_mu * (self.mu_size - 1) as f64;
        let i0 = (fi.floor() as usize).min(self.radius_size - 2);
        let j0 = (fj.floor() as usize).min(self.mu_size - 2);
        let (a, b) = (fi - i0 as f64, fj - j0 as f64);
        let at = |i: usize, j: usize| self.values[i * self.mu_size + j];
        let (v00, v01, v10, v11) = (
            at(i0, j0),
            at(i0, j0 + 1),
            at(i0 + 1, j0),
            at(i0 + 1, j0 + 1),
        );
        std::array::from_fn(|k| {
            let depth = (1.0 - a) * ((1.0 - b) * v00[k] + b * v01[k])
                + a * ((1.0 - b) * v10[k] + b * v11[k]);
            (-depth).exp()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::light_path_transmittance;

    #[test]
    fn table_matches_direct_integration() {
        let earth = Atmosphere::earth();
        // The Reference's size; the horizontal rays (mu = 0) are the steepest texels.
        let table = TransmittanceTable::new(&earth, 128, 256, 500);
        for altitude in [0.0, 500.0, 5_000.0, 40_000.0, 99_000.0] {
            for mu in [1.0, 0.5, 0.1, 0.0, -0.05] {
                let r = earth.planet_radius + altitude;
                let direct = light_path_transmittance(&earth, altitude, mu, 2000);
                if direct[0] == 0.0 {
                    continue;
                }
                let got = table.lookup(r, mu);
                for k in 0..3 {
                    assert!(
                        (got[k] - direct[k]).abs() < 5e-3 * direct[k] + 1e-5,
                        "h {altitude} mu {mu}: {got:?} vs {direct:?}"
                    );
                }
            }
        }
    }

    /// The grazing sun paths of twilight, where the transmittance falls by orders of
    /// magnitude over a few texels: interpolating the optical depth keeps the relative
    /// error at 2.5 % (interpolating the transmittance itself would give 24 %; `cargo test -p atmos --lib grazing_rays_keep --
    /// --nocapture`).
    #[test]
    fn grazing_rays_keep_a_small_relative_error() {
        let earth = Atmosphere::earth();
        let table = TransmittanceTable::new(&earth, 128, 256, 500);
        let mut worst: f64 = 0.0;
        for altitude in [2_000.0, 10_000.0, 20_000.0, 40_000.0] {
            let r = earth.planet_radius + altitude;
            let horizon = -(1.0 - (earth.planet_radius / r).powi(2)).sqrt();
            for offset in [3e-5, 1e-4, 3e-4, 1e-3, 3e-3] {
                let mu = horizon + offset;
                let direct = light_path_transmittance(&earth, altitude, mu, 20_000);
                let got = table.lookup(r, mu);
                for k in 0..3 {
                    if direct[k] > 1e-30 {
                        worst = worst.max((got[k] / direct[k] - 1.0).abs());
                    }
                }
            }
        }
        eprintln!("grazing rays: worst relative error {worst:.2e}");
        assert!(worst < 0.04, "worst relative error {worst}");
    }
}
