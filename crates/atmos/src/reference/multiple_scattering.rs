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

use std::f64::consts::PI;

use super::transmittance_table::TransmittanceTable;
use super::{
    cornette_shanks_phase, density_profile, extinction_from_densities, lowest_point_distance,
    mean_transmittance_over_segment, ray_sample_distance, ray_sphere_intersect, rayleigh_phase,
    single_scattering,
};
use crate::{AtmosError, Atmosphere, SkyModel, SkyQuery, SkySample};

/// Resolutions and sample counts of the Reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReferenceSettings {
    /// Total scattering orders, single scattering included (≥ 4).
    pub scattering_orders: u32,
    /// Query: samples along the view segment (single scattering and the
    /// multiple-scattering source alike).
    pub view_samples: u32,
    /// Query: samples along each light path of single scattering.
    pub light_samples: u32,
    /// Source table: radius (ρ/H) samples.
    pub radius_size: usize,
    /// Source table: view zenith angle samples over [0, π].
    pub view_zenith_size: usize,
    /// Source table: sun zenith angle samples over [0, [`MAX_SUN_ZENITH`]].
    pub sun_zenith_size: usize,
    /// Source table: view azimuth (relative to the sun) samples over [0, π].
    pub azimuth_size: usize,
    /// Sphere of incoming directions: zenith cells over [0, π].
    pub sphere_zenith_size: usize,
    /// Sphere of incoming directions: azimuth cells over [0, π] (mirrored to 2π).
    pub sphere_azimuth_size: usize,
    /// Samples per incoming-direction ray march during precomputation.
    pub march_samples: u32,
    /// Worker threads for the precomputation (0: all available).
    pub threads: usize,
}

/// Sun zenith angles beyond this (120°) see no light scattered from the sunlit side:
/// at the top of the atmosphere the planet's shadow starts at 100.2°, so a point at
/// 120° is > 2,000 km into the night. The source table stops here (and is 0 beyond).
pub const MAX_SUN_ZENITH: f64 = 2.0 * PI / 3.0;

impl Default for ReferenceSettings {
    /// See [`ReferenceSettings::DEFAULT_JUSTIFICATION`].
    fn default() -> Self {
        Self {
            scattering_orders: 7,
            view_samples: 256,
            light_samples: 64,
            radius_size: 16,
            view_zenith_size: 32,
            sun_zenith_size: 24,
            azimuth_size: 12,
            sphere_zenith_size: 24,
            sphere_azimuth_size: 24,
            march_samples: 32,
            threads: 0,
        }
    }
}

impl ReferenceSettings {
    /// Why the defaults: measured by `crates/atmos/tests/reference.rs`
    /// (`reference_convergence`, release only) and reported in the atmos README.
    pub const DEFAULT_JUSTIFICATION: &'static str = "7 orders: the 7th contributes at most \
        0.035 % of the luminance at sun elevations ≥ 5° (orders ≥ 2 are 25 % on average); \
        256 view / 64 light samples per query (doubling both: 0.002 % mean change); a \
        16×32×24×12 source table (doubling every axis: 0.28 %) from 24×24 half-sphere \
        incoming directions marched with 32 samples (doubling all three: 0.46 %; both \
        measured before the path-tracer fixes of issue 13.2); against the path tracer \
        (1,320 views, 4,096 samples each) day mean 0.31 %, max 1.34 %, twilight mean \
        2.0 %; about 40 s of precomputation on 2 busy cores";

    /// Small tables for tests in debug builds (a second, not a minute).
    pub fn low() -> Self {
        Self {
            scattering_orders: 4,
            view_samples: 64,
            light_samples: 16,
            radius_size: 8,
            view_zenith_size: 16,
            sun_zenith_size: 12,
            azimuth_size: 6,
            sphere_zenith_size: 12,
            sphere_azimuth_size: 8,
            march_samples: 24,
            threads: 0,
        }
    }

    /// Checks every count (the error names the field).
    pub fn validate(&self) -> Result<(), AtmosError> {
        let checks: [(&str, usize, usize, usize); 11] = [
            ("scattering_orders", self.scattering_orders as usize, 4, 64),
            ("view_samples", self.view_samples as usize, 1, 1 << 16),
            ("light_samples", self.light_samples as usize, 1, 1 << 16),
            ("radius_size", self.radius_size, 2, 1024),
            ("view_zenith_size", self.view_zenith_size, 2, 4096),
            ("sun_zenith_size", self.sun_zenith_size, 2, 4096),
            ("azimuth_size", self.azimuth_size, 2, 4096),
            ("sphere_zenith_size", self.sphere_zenith_size, 2, 4096),
            ("sphere_azimuth_size", self.sphere_azimuth_size, 1, 4096),
            ("march_samples", self.march_samples as usize, 1, 1 << 16),
            ("threads", self.threads, 0, 1024),
        ];
        for (field, value, min, max) in checks {
            if value < min || value > max {
                return Err(AtmosError::InvalidSetting {
                    setting: "reference settings",
                    field: field.to_owned(),
                    value: value as f64,
                    reason: "outside the accepted range (see ReferenceSettings::validate)",
                });
            }
        }
        Ok(())
    }
}

/// Where the sun-angle rows crowd: the terminator seen from the air (the planet's
/// shadow reaches a point at altitude h at a sun zenith angle of 90° + its horizon's dip,
/// 3.2° at 10 km, 10° at 100 km), where the source falls by orders of magnitude over a
/// few degrees. Rows uniform in angle (5.2° apart) interpolated that fall linearly,
/// several times too bright in the shadow.
const SUN_CROWD_CENTRE: f64 = 97.0 * PI / 180.0;
/// Width (rad) of the crowding.
const SUN_CROWD_WIDTH: f64 = 8.0 * PI / 180.0;
/// Row density at the centre, relative to far from it: 1 + this.
const SUN_CROWD_STRENGTH: f64 = 4.0;

/// The unnormalised sun-angle coordinate: ∫ 1 + A/(1 + ((θ − θ₀)/w)²) dθ.
fn sun_zenith_mass(theta: f64) -> f64 {
    let w = SUN_CROWD_WIDTH;
    theta
        + SUN_CROWD_STRENGTH
            * w
            * (((theta - SUN_CROWD_CENTRE) / w).atan() - (-SUN_CROWD_CENTRE / w).atan())
}

/// The sun-angle axis' coordinate in [0, 1] of a sun zenith angle in [0, `MAX_SUN_ZENITH`].
fn sun_zenith_coordinate(theta: f64) -> f64 {
    sun_zenith_mass(theta) / sun_zenith_mass(MAX_SUN_ZENITH)
}

/// The sun zenith angle of a coordinate in [0, 1] (the inverse, by bisection).
fn sun_zenith_from_coordinate(x: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, MAX_SUN_ZENITH);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if sun_zenith_coordinate(mid) < x {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The 4D grid of the scattering-density table.
#[derive(Debug, Clone, Copy)]
struct SourceGrid {
    sizes: [usize; 4],
    planet_radius: f64,
    top_radius: f64,
}

impl SourceGrid {
    fn horizon_length(&self) -> f64 {
        ((self.top_radius - self.planet_radius) * (self.top_radius + self.planet_radius)).sqrt()
    }

    fn len(&self) -> usize {
        self.sizes.iter().product()
    }

    fn index(&self, i: [usize; 4]) -> usize {
        ((i[0] * self.sizes[1] + i[1]) * self.sizes[2] + i[2]) * self.sizes[3] + i[3]
    }

    /// Radius of grid row `i`: ρ = H·i/(n − 1) puts half the rows below 25 km.
    fn radius(&self, i: usize) -> f64 {
        let rho = self.horizon_length() * i as f64 / (self.sizes[0] - 1) as f64;
        (rho * rho + self.planet_radius * self.planet_radius).sqrt()
    }

    fn angle(&self, axis: usize, i: usize) -> f64 {
        let x = i as f64 / (self.sizes[axis] - 1) as f64;
        if axis == 2 {
            sun_zenith_from_coordinate(x)
        } else {
            PI * x
        }
    }

    /// Continuous grid coordinates of (r, mu, mu_s, nu); `None` beyond the sun limit.
    fn coordinates(&self, r: f64, mu: f64, mu_s: f64, nu: f64) -> Option<[f64; 4]> {
        let mu = mu.clamp(-1.0, 1.0);
        let mu_s = mu_s.clamp(-1.0, 1.0);
        let sun_zenith = mu_s.acos();
        if sun_zenith > MAX_SUN_ZENITH {
            return None;
        }
        let rho = ((r - self.planet_radius) * (r + self.planet_radius))
            .max(0.0)
            .sqrt();
        let x_r = (rho / self.horizon_length()).clamp(0.0, 1.0);
        let sines = ((1.0 - mu * mu) * (1.0 - mu_s * mu_s)).max(0.0).sqrt();
        let cos_azimuth = if sines > 1e-12 {
            ((nu - mu * mu_s) / sines).clamp(-1.0, 1.0)
        } else {
            1.0
        };
        let n = |axis: usize| (self.sizes[axis] - 1) as f64;
        Some([
            x_r * n(0),
            mu.acos() / PI * n(1),
            sun_zenith_coordinate(sun_zenith) * n(2),
            cos_azimuth.acos() / PI * n(3),
        ])
    }

    /// Interpolation of `table` at (r, mu, mu_s, nu): trilinear in (r, mu, nu) on the
    /// two sun-angle rows around `mu_s`, then between them linearly while both rows have
    /// the sun above the horizon, geometrically from the pair that straddles it on
    /// (where both values are positive). Past the
    /// horizon the source falls by orders of magnitude from row to row, close to
    /// exponentially, and a linear blend is several times too bright in the shadow; in
    /// daylight it is smooth and concave, and a geometric blend reads it 0.6 % low.
    fn interpolate<const N: usize>(
        &self,
        table: &[[f64; N]],
        r: f64,
        mu: f64,
        mu_s: f64,
        nu: f64,
    ) -> [f64; N] {
        let Some(x) = self.coordinates(r, mu, mu_s, nu) else {
            return [0.0; N];
        };
        let mut base = [0usize; 4];
        let mut frac = [0.0f64; 4];
        for a in 0..4 {
            let b = (x[a].floor() as usize).min(self.sizes[a] - 2);
            base[a] = b;
            frac[a] = (x[a] - b as f64).clamp(0.0, 1.0);
        }
        let mut rows = [[0.0; N]; 2];
        for corner in 0..16usize {
            let mut weight = 1.0;
            let mut idx = [0usize; 4];
            for a in 0..4 {
                let bit = (corner >> a) & 1;
                idx[a] = base[a] + bit;
                if a != 2 {
                    weight *= if bit == 1 { frac[a] } else { 1.0 - frac[a] };
                }
            }
            if weight == 0.0 {
                continue;
            }
            let v = table[self.index(idx)];
            let row = &mut rows[(corner >> 2) & 1];
            for k in 0..N {
                row[k] += weight * v[k];
            }
        }
        let f = frac[2];
        let horizon_row = sun_zenith_coordinate(0.5 * PI) * (self.sizes[2] - 1) as f64;
        let beyond_horizon = (base[2] + 1) as f64 >= horizon_row;
        std::array::from_fn(|k| {
            let (a, b) = (rows[0][k], rows[1][k]);
            if f == 0.0 {
                a
            } else if f == 1.0 {
                b
            } else if beyond_horizon && a > 0.0 && b > 0.0 {
                a.powf(1.0 - f) * b.powf(f)
            } else {
                (1.0 - f) * a + f * b
            }
        })
    }
}

/// The precomputed Reference sky.
#[derive(Debug, Clone)]
pub struct ReferenceSky {
    atmosphere: Atmosphere,
    settings: ReferenceSettings,
    grid: SourceGrid,
    /// Σ_{k=2}^{N} J_k per unit density: the incoming radiance weighted by the
    /// Rayleigh phase (entries 0–2) and by the Mie phase (3–5); see [`PhaseWeighted`].
    source: Vec<PhaseWeighted>,
    /// J_N alone, to show the last order is negligible.
    last_order_source: Vec<PhaseWeighted>,
    precompute_seconds: f64,
}

/// The tabulated source of one grid point and view direction: the incoming radiance
/// integrated against the Rayleigh phase function (per channel, entries 0–2) and
/// against the Mie phase function (3–5). The scattering density is
/// `J = β_R ρ_R(h) S_R + β_M ρ_M(h) S_M` with the densities at the query point's own
/// altitude ([`ReferenceSky::source_at`]): interpolating `J` itself between the radius
/// rows interpolated the exponential densities linearly (the Mie density, scale
/// height 1.2 km, by up to +44 % between the rows at 1.8 and 4 km).
type PhaseWeighted = [f64; 6];

/// Where the source comes from when marching an incoming ray during precomputation.
enum Source<'a> {
    /// Single scattering of direct sunlight (order 1).
    Sun(&'a TransmittanceTable),
    /// A tabulated scattering source of order ≥ 2.
    Table(&'a [PhaseWeighted]),
}

/// The view segment in the inside frame: (r0, mu0, mu_s0, length), `None` when empty.
/// Mirrors the geometry of `single_scattering` (re-based at the top for outside viewers).
fn view_segment(
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
fn ray_segments(r0: f64, mu0: f64, end: f64, limit: f64, samples: u32) -> Vec<(f64, f64)> {
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

    fn threads(&self) -> usize {
        if self.settings.threads > 0 {
            self.settings.threads
        } else {
            std::thread::available_parallelism().map_or(1, |n| n.get())
        }
    }

    /// Direct sun irradiance on the ground at sun cosine `mu_s` (E_0).
    fn direct_ground_irradiance(&self, transmittance: &TransmittanceTable, mu_s: f64) -> [f64; 3] {
        if mu_s <= 0.0 {
            return [0.0; 3];
        }
        let t = transmittance.lookup(self.atmosphere.planet_radius, mu_s);
        std::array::from_fn(|k| t[k] * mu_s * self.atmosphere.sun_irradiance[k])
    }

    /// E_m at sun cosine `mu_s` from its table on the sun-angle grid (linear in the
    /// grid's coordinate).
    fn tabulated_ground_irradiance(&self, table: &[[f64; 3]], mu_s: f64) -> [f64; 3] {
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
    fn march(
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

    /// One order: J_k on the grid from L_{k−1} (marched from `source`) and G_{k−2}
    /// (`ground_irradiance`), and E_{k−1} on the sun-angle grid.
    fn scattering_density_order(
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
    fn density_at(
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
    fn source_at(&self, table: &[PhaseWeighted], r: f64, mu: f64, mu_s: f64, nu: f64) -> [f64; 3] {
        let a = &self.atmosphere;
        let s = self.grid.interpolate(table, r, mu, mu_s, nu);
        let densities = density_profile(a, r - a.planet_radius);
        std::array::from_fn(|k| {
            a.rayleigh_scattering[k] * densities[0] * s[k]
                + a.mie_scattering[k] * densities[1] * s[k + 3]
        })
    }

    /// ∫ T·table dt along the query's segment (the multiple-scattering radiance).
    fn march_source(&self, table: &[PhaseWeighted], query: &SkyQuery) -> [f64; 3] {
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

/// One incoming direction of the quadrature (azimuth in [0, π]; its mirror image has
/// the same radiance and weight).
#[derive(Debug, Clone, Copy)]
struct Direction {
    cos_zenith: f64,
    sin_zenith: f64,
    cos_azimuth: f64,
    /// Solid angle of one of the two mirrored cells (sr).
    weight: f64,
}

/// The incoming-direction quadrature and, for every table view direction, the phase
/// weights of each incoming direction (mirror pair summed), normalised so each view's
/// weights integrate the phase function to exactly 1.
struct DirectionSet {
    directions: Vec<Direction>,
    view_count: usize,
    rayleigh_weights: Vec<f64>,
    mie_weights: Vec<f64>,
}

/// The zenith angles and solid-angle widths (per unit azimuth) of the incoming
/// directions at radius `r`: the cells split at the horizon of `r` (the zenith angle
/// `θ_h` beyond which rays meet the ground), half over the sky and half over the ground,
/// each crowding quadratically towards it, where the incoming radiance peaks (the
/// longest paths) and steps (sky to ground). Uniform cells over [0, π] straddled the
/// horizon of every altitude above the ground and sampled its peak coarsely.
fn zenith_cells(count: usize, planet_radius: f64, r: f64) -> Vec<(f64, f64)> {
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
    fn new(
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
