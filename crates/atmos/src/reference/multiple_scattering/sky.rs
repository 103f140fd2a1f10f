//! [`ReferenceSky`]: the precomputation of the orders and the queries.

use std::f64::consts::PI;

use super::super::transmittance_table::TransmittanceTable;
use super::super::{
    cornette_shanks_phase, density_profile, extinction_from_densities, lowest_point_distance,
    mean_transmittance_over_segment, ray_sample_distance, ray_sphere_intersect, rayleigh_phase,
    single_scattering,
};
use super::grid::*;
use super::quadrature::*;
use super::settings::*;
use crate::{AtmosError, Atmosphere, SkyModel, SkyQuery, SkySample};

/// The precomputed Reference sky.
#[derive(Debug, Clone)]
pub struct ReferenceSky {
    pub(super) atmosphere: Atmosphere,
    pub(super) settings: ReferenceSettings,
    pub(super) grid: SourceGrid,
    /// Σ_{k=2}^{N} J_k per unit density: the incoming radiance weighted by the
    /// Rayleigh phase (entries 0–2) and by the Mie phase (3–5); see [`PhaseWeighted`].
    pub(super) source: Vec<PhaseWeighted>,
    /// J_N alone, to show the last order is negligible.
    pub(super) last_order_source: Vec<PhaseWeighted>,
    pub(super) precompute_seconds: f64,
}

/// The tabulated source of one grid point and view direction: the incoming radiance
/// integrated against the Rayleigh phase function (per channel, entries 0–2) and
/// against the Mie phase function (3–5). The scattering density is
/// `J = β_R ρ_R(h) S_R + β_M ρ_M(h) S_M` with the densities at the query point's own
/// altitude ([`ReferenceSky::source_at`]): interpolating `J` itself between the radius
/// rows interpolated the exponential densities linearly (the Mie density, scale
/// height 1.2 km, by up to +44 % between the rows at 1.8 and 4 km).
pub(super) type PhaseWeighted = [f64; 6];

/// Where the source comes from when marching an incoming ray during precomputation.
pub(super) enum Source<'a> {
    /// Single scattering of direct sunlight (order 1).
    Sun(&'a TransmittanceTable),
    /// A tabulated scattering source of order ≥ 2.
    Table(&'a [PhaseWeighted]),
}

/// The view segment in the inside frame: (r0, mu0, mu_s0, length), `None` when empty.
/// Mirrors the geometry of `single_scattering` (re-based at the top for outside viewers).
pub(super) fn view_segment(
    atmosphere: &Atmosphere,
    r: f64,
    mu: f64,
    mu_s: f64,
    nu: f64,
    max_distance: f64,
) -> Option<(f64, f64, f64, f64, f64)> {
    let (planet, top) = (atmosphere.planet_radius, atmosphere.top_radius);
    let (r0, mu0, mu_s0, max_distance) = if r <= top {
        (r.max(planet), mu, mu_s, max_distance)
    } else {
        let hit = ray_sphere_intersect(r, mu, top);
        if mu >= 0.0 || hit[0] < 0.0 {
            return None;
        }
        let b = r * mu;
        let c = (r - top) * (r + top);
        let mu_entry = -(b * b - c).max(0.0).sqrt() / top;
        let mu_s_entry = ((r * mu_s + hit[0] * nu) / top).clamp(-1.0, 1.0);
        (top, mu_entry, mu_s_entry, max_distance - hit[0])
    };
    let ground = ray_sphere_intersect(r0, mu0, planet);
    let top_hit = ray_sphere_intersect(r0, mu0, top);
    let mut end = top_hit[1].max(0.0);
    if mu0 < 0.0 && ground[0] >= 0.0 {
        end = ground[0];
    }
    let limit = end.min(max_distance.max(0.0));
    (end > 0.0 || mu0 < 0.0 && ground[0] >= 0.0).then_some((r0, mu0, mu_s0, end, limit))
}

/// (sample distance, segment length) of the rung-2 layout (`ray_sample_distance`) over
/// a ray of length `end`, cut at `limit`.
pub(super) fn ray_segments(
    r0: f64,
    mu0: f64,
    end: f64,
    limit: f64,
    samples: u32,
) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(samples as usize);
    if end <= 0.0 {
        return out;
    }
    let n = f64::from(samples.max(1));
    let t_split = lowest_point_distance(r0, mu0, end);
    let mut t_start = 0.0;
    for i in 0..samples.max(1) {
        if t_start >= limit {
            break;
        }
        let t_end = ray_sample_distance(f64::from(i + 1) / n, t_split, end);
        out.push((
            ray_sample_distance((f64::from(i) + 0.5) / n, t_split, end),
            t_end.min(limit) - t_start,
        ));
        t_start = t_end;
    }
    out
}

impl ReferenceSky {
    /// Validates and precomputes the multiple-scattering source table.
    pub fn new(atmosphere: &Atmosphere, settings: ReferenceSettings) -> Result<Self, AtmosError> {
        atmosphere.validate()?;
        settings.validate()?;
        let start = std::time::Instant::now();
        let grid = SourceGrid {
            sizes: [
                settings.radius_size,
                settings.view_zenith_size,
                settings.sun_zenith_size,
                settings.azimuth_size,
            ],
            planet_radius: atmosphere.planet_radius,
            top_radius: atmosphere.top_radius,
        };
        let transmittance = TransmittanceTable::new(atmosphere, 128, 256, 500);
        let mut sky = Self {
            atmosphere: atmosphere.clone(),
            settings,
            grid,
            source: vec![[0.0; 6]; grid.len()],
            last_order_source: Vec::new(),
            precompute_seconds: 0.0,
        };
        let spheres: Vec<DirectionSet> = (0..grid.sizes[0])
            .map(|i_r| DirectionSet::new(&settings, atmosphere, &grid, grid.radius(i_r)))
            .collect();
        // E_{k−2}: ground irradiance of the order before last, on the sun-angle grid
        // (`None`: E_0, the direct sun, computed exactly).
        let mut ground_irradiance: Option<Vec<[f64; 3]>> = None;
        let mut previous: Option<Vec<PhaseWeighted>> = None;
        for _order in 2..=settings.scattering_orders {
            let source = match &previous {
                None => Source::Sun(&transmittance),
                Some(table) => Source::Table(table),
            };
            let (density, irradiance) = sky.scattering_density_order(
                &source,
                &transmittance,
                ground_irradiance.as_deref(),
                &spheres,
            );
            for (sum, j) in sky.source.iter_mut().zip(&density) {
                for k in 0..6 {
                    sum[k] += j[k];
                }
            }
            ground_irradiance = Some(irradiance);
            previous = Some(density);
        }
        sky.last_order_source = previous.unwrap_or_default();
        sky.precompute_seconds = start.elapsed().as_secs_f64();
        Ok(sky)
    }

    /// Wall-clock seconds the precomputation took.
    pub fn precompute_seconds(&self) -> f64 {
        self.precompute_seconds
    }

    /// The settings.
    pub fn settings(&self) -> ReferenceSettings {
        self.settings
    }

    pub(super) fn threads(&self) -> usize {
        if self.settings.threads > 0 {
            self.settings.threads
        } else {
            std::thread::available_parallelism().map_or(1, |n| n.get())
        }
    }

    /// Direct sun irradiance on the ground at sun cosine `mu_s` (E_0).
    pub(super) fn direct_ground_irradiance(
        &self,
        transmittance: &TransmittanceTable,
        mu_s: f64,
    ) -> [f64; 3] {
        if mu_s <= 0.0 {
            return [0.0; 3];
        }
        let t = transmittance.lookup(self.atmosphere.planet_radius, mu_s);
        std::array::from_fn(|k| t[k] * mu_s * self.atmosphere.sun_irradiance[k])
    }

    /// E_m at sun cosine `mu_s` from its table on the sun-angle grid (linear in the
    /// grid's coordinate).
    pub(super) fn tabulated_ground_irradiance(&self, table: &[[f64; 3]], mu_s: f64) -> [f64; 3] {
        let angle = mu_s.clamp(-1.0, 1.0).acos();
        if angle > MAX_SUN_ZENITH {
            return [0.0; 3];
        }
        let n = table.len();
        let x = sun_zenith_coordinate(angle) * (n - 1) as f64;
        let i = (x.floor() as usize).min(n - 2);
        let f = x - i as f64;
        std::array::from_fn(|k| (1.0 - f) * table[i][k] + f * table[i + 1][k])
    }

    /// Radiance arriving at (r, mu) from the ray ahead: ∫ T·source dt plus, if the ray
    /// meets the ground, the ground's reflected radiance α/π·E times the transmittance.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn march(
        &self,
        source: &Source<'_>,
        transmittance: &TransmittanceTable,
        ground_irradiance: Option<&[[f64; 3]]>,
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
        samples: u32,
    ) -> [f64; 3] {
        let a = &self.atmosphere;
        let Some((r0, mu0, mu_s0, end, _)) = view_segment(a, r, mu, mu_s, nu, f64::INFINITY) else {
            return [0.0; 3];
        };
        let (rayleigh, mie) = (rayleigh_phase(nu), cornette_shanks_phase(nu, a.mie_g));
        let mut depth = [0.0f64; 3];
        let mut radiance = [0.0; 3];
        for (t, dt) in ray_segments(r0, mu0, end, end, samples) {
            let r_t = (r0 * r0 + t * (2.0 * r0 * mu0 + t)).max(0.0).sqrt();
            let altitude = r_t - a.planet_radius;
            let mu_t = ((r0 * mu0 + t) / r_t).clamp(-1.0, 1.0);
            let mu_s_t = ((r0 * mu_s0 + t * nu) / r_t).clamp(-1.0, 1.0);
            let densities = density_profile(a, altitude);
            let segment = extinction_from_densities(a, densities).map(|e| e * dt);
            let weight = mean_transmittance_over_segment(segment);
            let j = match source {
                Source::Sun(table) => {
                    let ground = ray_sphere_intersect(r_t, mu_s_t, a.planet_radius);
                    if mu_s_t < 0.0 && ground[1] > 0.0 {
                        [0.0; 3]
                    } else {
                        let sun = table.lookup(r_t, mu_s_t);
                        std::array::from_fn(|k| {
                            a.sun_irradiance[k]
                                * sun[k]
                                * (a.rayleigh_scattering[k] * densities[0] * rayleigh
                                    + a.mie_scattering[k] * densities[1] * mie)
                        })
                    }
                }
                Source::Table(table) => self.source_at(table, r_t, mu_t, mu_s_t, nu),
            };
            for k in 0..3 {
                radiance[k] += (-depth[k]).exp() * j[k] * weight[k] * dt;
                depth[k] += segment[k];
            }
        }
        let hits_ground = mu0 < 0.0 && ray_sphere_intersect(r0, mu0, a.planet_radius)[0] >= 0.0;
        if hits_ground {
            let mu_s_ground = ((r0 * mu_s0 + end * nu) / a.planet_radius).clamp(-1.0, 1.0);
            let irradiance = match ground_irradiance {
                None => self.direct_ground_irradiance(transmittance, mu_s_ground),
                Some(table) => self.tabulated_ground_irradiance(table, mu_s_ground),
            };
            for k in 0..3 {
                radiance[k] += (-depth[k]).exp() * a.ground_albedo[k] / PI * irradiance[k];
            }
        }
        radiance
    }
}

impl SkyModel for ReferenceSky {
    fn label(&self) -> String {
        let s = &self.settings;
        format!(
            "reference ({} orders, {}/{} samples, J {}x{}x{}x{})",
            s.scattering_orders,
            s.view_samples,
            s.light_samples,
            s.radius_size,
            s.view_zenith_size,
            s.sun_zenith_size,
            s.azimuth_size
        )
    }

    fn evaluate(&self, query: &SkyQuery) -> SkySample {
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
        let multiple = self.march_source(&self.source, query);
        SkySample {
            radiance: std::array::from_fn(|k| single.radiance[k] + multiple[k]),
            transmittance: single.transmittance,
        }
    }
}
