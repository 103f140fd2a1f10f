//! One sample of a query: the first scattering points on the view segment, next-event
//! estimation toward the sun, and the continued paths of orders ≥ 2 (see the parent
//! module's documentation for the estimator).

use std::f64::consts::PI;

use glam::DVec3;

use super::medium::{Densities, Flight, Medium, Ray};
use super::sampling::{
    Random, direction_around, sample_cornette_shanks_cosine, sample_cosine_hemisphere,
    sample_rayleigh_cosine,
};
use super::segment::{PiecewiseDensity, Tracks, sunlit_intervals};
use super::{FreePaths, PathTracerSettings};
use crate::SkyQuery;
use crate::ladder::LUMINANCE_WEIGHTS;
use crate::reference::{cornette_shanks_phase, rayleigh_phase};

/// Steps of the single-scattering table's uniform grid (at ≥ 256 samples).
const TABLE_GRID: usize = 64;

/// Per-sample values: single, multiple, total, each as R, G, B, luminance.
pub(super) type Values = [f64; 12];

/// A way to draw the first scattering point on the view segment.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Strategy {
    /// Forced free flight in channel k's majorant.
    Majorant(usize),
    /// From the single-scattering table.
    Tabulated,
}

/// The query's view segment and what sampling it needs, shared by all its samples.
#[derive(Debug, Clone)]
pub(super) struct ViewSegment {
    ray: Ray,
    /// Length of the segment (m); 0 when empty.
    pub length: f64,
    sun: DVec3,
    /// Rayleigh and Cornette–Shanks phase values toward the viewer (cos = ν).
    phase: [f64; 2],
    tracks: Tracks,
    /// Quadrature pieces (start, density lengths before it).
    pieces: Vec<(f64, [f64; 3])>,
    strategies: Vec<Strategy>,
    /// A piecewise-constant density shaped like the single-scattering integrand
    /// `T·Σβp·T_sun` (each channel normalised to a unit integral, then averaged),
    /// tabulated once per query: bins between the majorant shells and on a 64-step
    /// grid (fewer below 256 samples), each as high as the largest of the integrand at its ends and middle (so a
    /// bin the shadow's edge crosses is not missed). The majorant strategies keep the
    /// mixture positive wherever the air scatters, so the table needs no accuracy for
    /// the estimate to be unbiased.
    table: Option<PiecewiseDensity>,
}

/// One first scattering point of a sample.
#[derive(Debug, Clone, Copy)]
struct FirstPoint {
    position: DVec3,
    densities: Densities,
    /// T·σ_s/Σpdf per channel: the weight of continuing from here.
    weight: [f64; 3],
}

/// What the next event of a continued path is.
enum Event {
    /// Scattering in the air at `position`, the path weight multiplied by `weight`.
    Air {
        position: DVec3,
        densities: Densities,
        weight: f64,
    },
    /// The ground at `position`, the path weight multiplied by `weight`.
    Ground { position: DVec3, weight: f64 },
    /// The path leaves the atmosphere.
    Escape,
}

/// The estimator: the medium and the settings.
#[derive(Debug, Clone, Copy)]
pub(super) struct Estimator<'a> {
    pub medium: &'a Medium,
    pub settings: &'a PathTracerSettings,
}

fn luminance(v: [f64; 3]) -> f64 {
    v.iter().zip(LUMINANCE_WEIGHTS).map(|(c, w)| c * w).sum()
}

impl Estimator<'_> {
    /// The view segment inside the atmosphere (re-based at the top for a viewer above
    /// it, raised to the ground for one below it), `None` when the ray misses the
    /// atmosphere: the geometry of the Reference's single scattering.
    pub fn view_segment(&self, query: &SkyQuery) -> Option<ViewSegment> {
        let m = self.medium;
        let (position, view) = (query.position(), query.view());
        let r = position.length();
        let (origin, budget) = if r <= m.top_radius {
            let origin = if r < m.planet_radius {
                position * (m.planet_radius / r)
            } else {
                position
            };
            (origin, query.max_distance())
        } else {
            let b = position.dot(view);
            let c = (r - m.top_radius) * (r + m.top_radius);
            let discriminant = b * b - c;
            if b >= 0.0 || discriminant < 0.0 {
                return None;
            }
            let entry = c / (-b + discriminant.sqrt());
            (position + entry * view, query.max_distance() - entry)
        };
        let ray = Ray::new(origin, view);
        let (end, _) = ray.end(m.planet_radius, m.top_radius);
        let length = end.min(budget.max(0.0));
        let nu = query.nu();
        let mut segment = ViewSegment {
            ray,
            length,
            sun: query.sun(),
            phase: [rayleigh_phase(nu), cornette_shanks_phase(nu, m.mie_g)],
            tracks: Tracks::default(),
            pieces: Vec::new(),
            strategies: Vec::new(),
            table: None,
        };
        if length <= 0.0 {
            return Some(segment);
        }
        segment.tracks = Tracks::new(m, &ray, length);
        let mut lengths = [0.0; 3];
        for (a, b) in m.quadrature_pieces(&ray, length) {
            segment.pieces.push((a, lengths));
            m.gauss_piece(&ray, a, b, &mut lengths);
        }
        segment.strategies = (0..3)
            .filter(|&k| segment.tracks.total[k] > 0.0)
            .map(Strategy::Majorant)
            .collect();
        segment.table = self.single_scattering_table(&segment);
        if segment.table.is_some() {
            segment.strategies.push(Strategy::Tabulated);
        }
        Some(segment)
    }

    /// Optical depth per channel from the segment's start to `t`.
    pub fn optical_depth_to(&self, segment: &ViewSegment, t: f64) -> [f64; 3] {
        let i = segment
            .pieces
            .partition_point(|p| p.0 <= t)
            .saturating_sub(1);
        let Some(&(start, mut lengths)) = segment.pieces.get(i) else {
            return [0.0; 3];
        };
        self.medium
            .gauss_piece(&segment.ray, start, t, &mut lengths);
        self.medium.extinction(lengths)
    }

    /// Sun radiance scattered at a point per unit scattering path, channel `k`:
    /// `E·T_sun·(β_R ρ_R p_R + β_M ρ_M p_M)` (divided by σ_s: the normalised phase
    /// mixture).
    fn sun_in_scattering(
        &self,
        k: usize,
        densities: Densities,
        phase: [f64; 2],
        sun_transmittance: [f64; 3],
    ) -> f64 {
        let m = self.medium;
        m.sun_irradiance[k]
            * sun_transmittance[k]
            * (m.rayleigh_scattering[k] * densities[0] * phase[0]
                + m.mie_scattering[k] * densities[1] * phase[1])
    }

    /// The single-scattering integrand per channel at distance `t` on the segment.
    fn single_scattering_integrand(&self, segment: &ViewSegment, t: f64) -> [f64; 3] {
        let m = self.medium;
        let densities = m.densities_at_radius(segment.ray.radius_at(t));
        let depth = self.optical_depth_to(segment, t);
        let sun_transmittance = m.sun_transmittance(segment.ray.at(t), segment.sun);
        std::array::from_fn(|k| {
            (-depth[k]).exp()
                * self.sun_in_scattering(k, densities, segment.phase, sun_transmittance)
        })
    }

    /// See [`ViewSegment::table`]; `None` when no part of the segment scatters sunlight.
    fn single_scattering_table(&self, segment: &ViewSegment) -> Option<PiecewiseDensity> {
        let length = segment.length;
        // Two sun transmittances per bin: for a few samples (the energy test's
        // thousands of 2-sample queries) the table shrinks to stay a fraction of their
        // cost; from 256 samples on it has every shell edge and the full grid.
        let grid = (self.settings.samples as usize / 4).clamp(4, TABLE_GRID);
        let shell_edges = if self.settings.samples >= 256 {
            segment.tracks.pieces.as_slice()
        } else {
            &[]
        };
        let mut edges: Vec<f64> = shell_edges
            .iter()
            .map(|t| t.start)
            .chain((0..=grid).map(|i| length * i as f64 / grid as f64))
            .collect();
        edges.sort_by(f64::total_cmp);
        edges.dedup_by(|a, b| *a - *b <= 1e-6 * length);
        let values: Vec<[f64; 3]> = edges
            .iter()
            .map(|&t| self.single_scattering_integrand(segment, t))
            .collect();
        let mut bins = Vec::with_capacity(edges.len());
        let mut totals = [0.0; 3];
        for (i, pair) in edges.windows(2).enumerate() {
            let middle = self.single_scattering_integrand(segment, 0.5 * (pair[0] + pair[1]));
            let height: [f64; 3] =
                std::array::from_fn(|k| values[i][k].max(values[i + 1][k]).max(middle[k]));
            for k in 0..3 {
                totals[k] += height[k] * (pair[1] - pair[0]);
            }
            bins.push((pair[0], pair[1], height));
        }
        let lit: Vec<usize> = (0..3).filter(|&k| totals[k] > 0.0).collect();
        if lit.is_empty() {
            return None;
        }
        PiecewiseDensity::new(
            bins.into_iter()
                .map(|(a, b, h)| (a, b, lit.iter().map(|&k| h[k] / totals[k]).sum())),
        )
    }

    fn sample_distance(segment: &ViewSegment, strategy: Strategy, u: f64) -> f64 {
        match strategy {
            Strategy::Majorant(k) => segment.tracks.sample(k, u),
            Strategy::Tabulated => segment.table.as_ref().map_or(0.0, |t| t.sample(u)),
        }
    }

    fn distance_pdf(segment: &ViewSegment, strategy: Strategy, t: f64) -> f64 {
        match strategy {
            Strategy::Majorant(k) => segment.tracks.pdf(k, t),
            Strategy::Tabulated => segment.table.as_ref().map_or(0.0, |table| table.pdf(t)),
        }
    }

    /// A direction from channel `k`'s phase mixture at `densities`, about `axis`.
    fn sample_phase(
        &self,
        k: usize,
        densities: Densities,
        axis: DVec3,
        random: &mut Random,
    ) -> DVec3 {
        let m = self.medium;
        let rayleigh = m.rayleigh_scattering[k] * densities[0];
        let mie = m.mie_scattering[k] * densities[1];
        let cos_theta = if random.uniform() * (rayleigh + mie) < rayleigh {
            sample_rayleigh_cosine(random.uniform())
        } else {
            sample_cornette_shanks_cosine(m.mie_g, random)
        };
        direction_around(axis, cos_theta, 2.0 * PI * random.uniform())
    }

    /// The next event of channel `k` along `ray`, by analog delta tracking.
    fn tracked_event(&self, k: usize, ray: &Ray, random: &mut Random) -> Event {
        let m = self.medium;
        match m.free_flight(ray, k, || random.uniform()) {
            Flight::Escaped => Event::Escape,
            Flight::Collision { t, densities } => Event::Air {
                position: ray.at(t),
                densities,
                weight: m.scattering(densities)[k] / m.extinction(densities)[k],
            },
            Flight::Ground { t } => Event::Ground {
                position: ray.at(t),
                weight: 1.0,
            },
        }
    }

    /// The next event of channel `k` along `ray`, forced: the ground (if the ray meets
    /// it and the albedo is not 0) with probability `q` ≈ its share `α T̄/(α T̄ + 1 − T̄)`,
    /// weight `T(L)/q`; else a scattering point from the forced free flight of the
    /// majorant, mixed half and half with the majorant over the sunlit part when the
    /// segment is partly in the planet's shadow (the light of a shadowed point comes
    /// from there), weight `T σ_s/((1 − q) pdf)`. Transmittances by quadrature.
    fn forced_event(&self, k: usize, ray: &Ray, sun: DVec3, random: &mut Random) -> Event {
        let m = self.medium;
        let (end, ground) = ray.end(m.planet_radius, m.top_radius);
        let tracks = Tracks::new(m, ray, end);
        let majorant_depth = tracks.total[k];
        let albedo = m.ground_albedo[k];
        let ground_probability = if !ground || albedo <= 0.0 {
            0.0
        } else if majorant_depth <= 0.0 {
            1.0
        } else {
            let through = (-majorant_depth).exp();
            (albedo * through / (albedo * through + 1.0 - through)).clamp(0.02, 0.98)
        };
        if ground_probability > 0.0 && random.uniform() < ground_probability {
            let depth = m.extinction(m.density_lengths(ray, 0.0, end))[k];
            return Event::Ground {
                position: ray.at(end),
                weight: (-depth).exp() / ground_probability,
            };
        }
        if majorant_depth <= 0.0 {
            return Event::Escape;
        }
        let sunlit = sunlit_intervals(ray, end, sun, m.planet_radius);
        let partly_shadowed = sunlit.first().is_none_or(|&(a, b)| a > 0.0 || b < end);
        let sunlit_density = if partly_shadowed && !sunlit.is_empty() {
            PiecewiseDensity::majorant_over(&tracks, k, &sunlit)
        } else {
            None
        };
        let t = match &sunlit_density {
            Some(density) if random.uniform() < 0.5 => density.sample(random.uniform()),
            _ => tracks.sample(k, random.uniform()),
        };
        let pdf = match &sunlit_density {
            Some(density) => 0.5 * (density.pdf(t) + tracks.pdf(k, t)),
            None => tracks.pdf(k, t),
        };
        let densities = m.densities_at_radius(ray.radius_at(t));
        let depth = m.extinction(m.density_lengths(ray, 0.0, t))[k];
        let weight =
            (-depth).exp() * m.scattering(densities)[k] / ((1.0 - ground_probability) * pdf);
        if weight > 0.0 && weight.is_finite() {
            Event::Air {
                position: ray.at(t),
                densities,
                weight,
            }
        } else {
            Event::Escape
        }
    }

    /// Orders ≥ 2 in channel `k` from a first scattering point (`incoming`: the view
    /// direction), per unit weight of that point.
    fn continued_path(
        &self,
        k: usize,
        first: &FirstPoint,
        incoming: DVec3,
        sun: DVec3,
        random: &mut Random,
    ) -> f64 {
        let m = self.medium;
        let max_order = self.settings.max_order.unwrap_or(u32::MAX);
        let mut order = 1u32;
        let mut throughput = 1.0f64;
        let mut sum = 0.0;
        let mut direction = self.sample_phase(k, first.densities, incoming, random);
        let mut position = first.position;
        loop {
            let ray = Ray::new(position, direction);
            let event = match self.settings.free_paths {
                FreePaths::Forced => self.forced_event(k, &ray, sun, random),
                FreePaths::DeltaTracking => self.tracked_event(k, &ray, random),
            };
            order += 1;
            match event {
                Event::Escape => return sum,
                Event::Air {
                    position: at,
                    densities,
                    weight,
                } => {
                    position = at;
                    throughput *= weight;
                    let cos_theta = sun.dot(direction);
                    let phase = [
                        rayleigh_phase(cos_theta),
                        cornette_shanks_phase(cos_theta, m.mie_g),
                    ];
                    let sun_transmittance = m.sun_transmittance(position, sun);
                    sum += throughput
                        * self.sun_in_scattering(k, densities, phase, sun_transmittance)
                        / m.scattering(densities)[k];
                    if order >= max_order || !roulette(&mut throughput, order, random) {
                        return sum;
                    }
                    direction = self.sample_phase(k, densities, direction, random);
                }
                Event::Ground {
                    position: at,
                    weight,
                } => {
                    let normal = at.normalize();
                    position = normal * m.planet_radius;
                    throughput *= weight;
                    let albedo = m.ground_albedo[k];
                    let cos_sun = normal.dot(sun);
                    if cos_sun > 0.0 {
                        sum += throughput * albedo / PI
                            * cos_sun
                            * m.sun_transmittance(position, sun)[k]
                            * m.sun_irradiance[k];
                    }
                    throughput *= albedo;
                    if order >= max_order
                        || throughput <= 0.0
                        || !roulette(&mut throughput, order, random)
                    {
                        return sum;
                    }
                    direction = sample_cosine_hemisphere(normal, random);
                }
            }
        }
    }

    /// One sample of a non-empty segment.
    pub fn sample(&self, segment: &ViewSegment, random: &mut Random) -> Values {
        let m = self.medium;
        let mut single = [0.0; 3];
        let mut first_points = [None::<FirstPoint>; 4];
        let mut distances = [0.0; 4];
        for (distance, &strategy) in distances.iter_mut().zip(&segment.strategies) {
            *distance = Self::sample_distance(segment, strategy, random.uniform());
        }
        for (slot, &t) in first_points
            .iter_mut()
            .zip(&distances)
            .take(segment.strategies.len())
        {
            let pdf: f64 = segment
                .strategies
                .iter()
                .map(|&s| Self::distance_pdf(segment, s, t))
                .sum();
            if pdf <= 0.0 || !pdf.is_finite() {
                continue;
            }
            let position = segment.ray.at(t);
            let densities = m.densities_at_radius(segment.ray.radius_at(t));
            let scattering = m.scattering(densities);
            let depth = self.optical_depth_to(segment, t);
            let transmittance_over_pdf = depth.map(|tau| (-tau).exp() / pdf);
            let sun_transmittance = m.sun_transmittance(position, segment.sun);
            for (k, value) in single.iter_mut().enumerate() {
                *value += transmittance_over_pdf[k]
                    * self.sun_in_scattering(k, densities, segment.phase, sun_transmittance);
            }
            *slot = Some(FirstPoint {
                position,
                densities,
                weight: std::array::from_fn(|k| transmittance_over_pdf[k] * scattering[k]),
            });
        }
        let mut multiple = [0.0; 3];
        if self.settings.max_order != Some(1) {
            for (k, value) in multiple.iter_mut().enumerate() {
                let total: f64 = first_points.iter().flatten().map(|p| p.weight[k]).sum();
                if total <= 0.0 {
                    continue;
                }
                // One point continues, chosen in proportion to its weight; the path then
                // carries the total weight (unbiased for the sum over the points).
                let mut pick = random.uniform() * total;
                let chosen = first_points
                    .iter()
                    .flatten()
                    .find(|p| {
                        pick -= p.weight[k];
                        pick < 0.0
                    })
                    .or_else(|| first_points.iter().flatten().rfind(|p| p.weight[k] > 0.0));
                if let Some(first) = chosen {
                    *value = total
                        * self.continued_path(k, first, segment.ray.direction, segment.sun, random);
                }
            }
        }
        let total: [f64; 3] = std::array::from_fn(|k| single[k] + multiple[k]);
        [
            single[0],
            single[1],
            single[2],
            luminance(single),
            multiple[0],
            multiple[1],
            multiple[2],
            luminance(multiple),
            total[0],
            total[1],
            total[2],
            luminance(total),
        ]
    }
}

/// Russian roulette on a path weight: survive with probability min(weight, 1) (from
/// order 64 on at most 1/2, so a conservative atmosphere over a white ground ends too),
/// the weight divided by it. Returns whether the path goes on.
fn roulette(throughput: &mut f64, order: u32, random: &mut Random) -> bool {
    let cap = if order < 64 { 1.0 } else { 0.5 };
    let survival = throughput.min(cap);
    if random.uniform() >= survival {
        return false;
    }
    *throughput /= survival;
    true
}
