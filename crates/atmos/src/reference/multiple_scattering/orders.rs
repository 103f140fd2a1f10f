//! The orders of scattering: each order's scattering density `J_k` on the grid, and
//! its integral along a query's ray.

use super::super::transmittance_table::TransmittanceTable;
use super::super::{
    density_profile, extinction_from_densities, mean_transmittance_over_segment, single_scattering,
};
use super::quadrature::*;
use super::sky::*;
use crate::SkyQuery;

impl ReferenceSky {
    /// One order: J_k on the grid from L_{k−1} (marched from `source`) and G_{k−2}
    /// (`ground_irradiance`), and E_{k−1} on the sun-angle grid.
    pub(super) fn scattering_density_order(
        &self,
        source: &Source<'_>,
        transmittance: &TransmittanceTable,
        ground_irradiance: Option<&[[f64; 3]]>,
        spheres: &[DirectionSet],
    ) -> (Vec<PhaseWeighted>, Vec<[f64; 3]>) {
        let [n_r, n_mu, n_s, n_phi] = self.grid.sizes;
        let pairs: Vec<(usize, usize)> = (0..n_r)
            .flat_map(|i| (0..n_s).map(move |j| (i, j)))
            .collect();
        let threads = self.threads().min(pairs.len()).max(1);
        type PairResult = (usize, usize, Vec<PhaseWeighted>, [f64; 3]);
        let results: Vec<PairResult> = std::thread::scope(|scope| {
            let workers: Vec<_> = (0..threads)
                .map(|w| {
                    let pairs = &pairs;
                    scope.spawn(move || {
                        pairs
                            .iter()
                            .skip(w)
                            .step_by(threads)
                            .map(|&(i_r, i_s)| {
                                let (density, irradiance) = self.density_at(
                                    source,
                                    transmittance,
                                    ground_irradiance,
                                    &spheres[i_r],
                                    i_r,
                                    i_s,
                                );
                                (i_r, i_s, density, irradiance)
                            })
                            .collect::<Vec<_>>()
                    })
                })
                .collect();
            workers
                .into_iter()
                .flat_map(|w| w.join().expect("precomputation worker panicked"))
                .collect()
        });
        let mut density = vec![[0.0; 6]; self.grid.len()];
        let mut irradiance = vec![[0.0; 3]; n_s];
        for (i_r, i_s, values, e) in results {
            for i_mu in 0..n_mu {
                for i_phi in 0..n_phi {
                    density[self.grid.index([i_r, i_mu, i_s, i_phi])] =
                        values[i_mu * n_phi + i_phi];
                }
            }
            if i_r == 0 {
                irradiance[i_s] = e;
            }
        }
        (density, irradiance)
    }

    /// J_k per unit density ([`PhaseWeighted`]) for every view direction at grid radius
    /// `i_r` and sun angle `i_s`, and the order-(k−1) irradiance of the upper hemisphere
    /// there.
    pub(super) fn density_at(
        &self,
        source: &Source<'_>,
        transmittance: &TransmittanceTable,
        ground_irradiance: Option<&[[f64; 3]]>,
        sphere: &DirectionSet,
        i_r: usize,
        i_s: usize,
    ) -> (Vec<PhaseWeighted>, [f64; 3]) {
        let r = self.grid.radius(i_r);
        let sun_zenith = self.grid.angle(2, i_s);
        let (sin_s, cos_s) = sun_zenith.sin_cos();
        let incoming: Vec<[f64; 3]> = sphere
            .directions
            .iter()
            .map(|d| {
                let nu = d.sin_zenith * d.cos_azimuth * sin_s + d.cos_zenith * cos_s;
                self.march(
                    source,
                    transmittance,
                    ground_irradiance,
                    r,
                    d.cos_zenith,
                    cos_s,
                    nu,
                    self.settings.march_samples,
                )
            })
            .collect();
        // Upper-hemisphere irradiance on a horizontal surface (both mirrored halves).
        let mut irradiance = [0.0; 3];
        for (d, l) in sphere.directions.iter().zip(&incoming) {
            if d.cos_zenith > 0.0 {
                for k in 0..3 {
                    irradiance[k] += 2.0 * d.weight * d.cos_zenith * l[k];
                }
            }
        }
        let n_dirs = sphere.directions.len();
        let mut out = Vec::with_capacity(sphere.view_count);
        for v in 0..sphere.view_count {
            let (pr, pm) = (
                &sphere.rayleigh_weights[v * n_dirs..(v + 1) * n_dirs],
                &sphere.mie_weights[v * n_dirs..(v + 1) * n_dirs],
            );
            let mut sum_r = [0.0; 3];
            let mut sum_m = [0.0; 3];
            for ((l, wr), wm) in incoming.iter().zip(pr).zip(pm) {
                for k in 0..3 {
                    sum_r[k] += wr * l[k];
                    sum_m[k] += wm * l[k];
                }
            }
            out.push(std::array::from_fn(|k| {
                if k < 3 { sum_r[k] } else { sum_m[k - 3] }
            }));
        }
        (out, irradiance)
    }

    /// The scattering density `J = β_R ρ_R S_R + β_M ρ_M S_M` at (r, mu, mu_s, nu), with
    /// `S` interpolated in `table` and the densities exact at `r`.
    pub(super) fn source_at(
        &self,
        table: &[PhaseWeighted],
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
    ) -> [f64; 3] {
        let a = &self.atmosphere;
        let s = self.grid.interpolate(table, r, mu, mu_s, nu);
        let densities = density_profile(a, r - a.planet_radius);
        std::array::from_fn(|k| {
            a.rayleigh_scattering[k] * densities[0] * s[k]
                + a.mie_scattering[k] * densities[1] * s[k + 3]
        })
    }

    /// ∫ T·table dt along the query's segment (the multiple-scattering radiance).
    pub(super) fn march_source(&self, table: &[PhaseWeighted], query: &SkyQuery) -> [f64; 3] {
        let a = &self.atmosphere;
        let Some((r0, mu0, mu_s0, end, limit)) = view_segment(
            a,
            query.r(),
            query.mu(),
            query.mu_s(),
            query.nu(),
            query.max_distance(),
        ) else {
            return [0.0; 3];
        };
        let nu = query.nu();
        let mut depth = [0.0f64; 3];
        let mut radiance = [0.0; 3];
        for (t, dt) in ray_segments(r0, mu0, end, limit, self.settings.view_samples) {
            let r_t = (r0 * r0 + t * (2.0 * r0 * mu0 + t)).max(0.0).sqrt();
            let mu_t = ((r0 * mu0 + t) / r_t).clamp(-1.0, 1.0);
            let mu_s_t = ((r0 * mu_s0 + t * nu) / r_t).clamp(-1.0, 1.0);
            let densities = density_profile(a, r_t - a.planet_radius);
            let segment = extinction_from_densities(a, densities).map(|e| e * dt);
            let weight = mean_transmittance_over_segment(segment);
            let j = self.source_at(table, r_t, mu_t, mu_s_t, nu);
            for k in 0..3 {
                radiance[k] += (-depth[k]).exp() * j[k] * weight[k] * dt;
                depth[k] += segment[k];
            }
        }
        radiance
    }

    /// The query's radiance split by order: (single, all orders ≥ 2, the last order).
    pub fn evaluate_orders(&self, query: &SkyQuery) -> ([f64; 3], [f64; 3], [f64; 3]) {
        let a = &self.atmosphere;
        let single = single_scattering(
            a,
            query.r(),
            query.mu(),
            query.mu_s(),
            query.nu(),
            query.max_distance(),
            self.settings.view_samples,
            self.settings.light_samples,
        );
        (
            single.radiance,
            self.march_source(&self.source, query),
            self.march_source(&self.last_order_source, query),
        )
    }
}
