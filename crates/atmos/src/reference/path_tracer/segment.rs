//! Distance sampling on a ray segment: the majorant's free flight forced to end inside
//! the segment, piecewise-constant densities (a tabulated integrand, the majorant over
//! the sunlit part), and the sunlit parts themselves.

use glam::DVec3;

use super::medium::{Medium, Ray};

/// One piece of a segment between tracking shells: the majorant per channel and its
/// optical depth accumulated before the piece.
#[derive(Debug, Clone, Copy)]
pub(super) struct Track {
    pub start: f64,
    pub end: f64,
    pub majorant: [f64; 3],
    before: [f64; 3],
}

/// The tracking shells a segment crosses, for forced free flights: the density
/// `σ̄ e^{−τ̄(t)} / (1 − e^{−τ̄(L)})` of channel k's majorant, restricted to the segment
/// (exactly invertible: σ̄ is constant on each piece).
#[derive(Debug, Clone, Default)]
pub(super) struct Tracks {
    pub pieces: Vec<Track>,
    /// Majorant optical depth of the whole segment per channel.
    pub total: [f64; 3],
}

impl Tracks {
    pub fn new(medium: &Medium, ray: &Ray, length: f64) -> Self {
        let mut tracks = Self::default();
        let mut depth = [0.0; 3];
        medium.walk_tracking_shells(ray, length, |a, b, majorant| {
            tracks.pieces.push(Track {
                start: a,
                end: b,
                majorant,
                before: depth,
            });
            for k in 0..3 {
                depth[k] += majorant[k] * (b - a);
            }
            true
        });
        tracks.total = depth;
        tracks
    }

    fn piece_at(&self, t: f64) -> &Track {
        let i = self
            .pieces
            .partition_point(|p| p.start <= t)
            .saturating_sub(1);
        &self.pieces[i]
    }

    /// A forced free flight of channel `k` (requires `total[k] > 0`).
    pub fn sample(&self, k: usize, u: f64) -> f64 {
        // Inverse CDF: τ̄(t) = −ln(1 − u(1 − e^{−τ̄(L)})).
        let target = -(-u * -(-self.total[k]).exp_m1()).ln_1p();
        let i = self
            .pieces
            .partition_point(|p| p.before[k] <= target)
            .saturating_sub(1);
        let piece = &self.pieces[i];
        if piece.majorant[k] <= 0.0 {
            return piece.start;
        }
        (piece.start + (target - piece.before[k]) / piece.majorant[k]).clamp(piece.start, piece.end)
    }

    /// The density of [`Self::sample`] at `t`.
    pub fn pdf(&self, k: usize, t: f64) -> f64 {
        let piece = self.piece_at(t);
        let depth = piece.before[k] + piece.majorant[k] * (t - piece.start);
        piece.majorant[k] * (-depth).exp() / -(-self.total[k]).exp_m1()
    }
}

/// A normalised piecewise-constant density on a segment.
#[derive(Debug, Clone, Default)]
pub(super) struct PiecewiseDensity {
    /// (start, end, density, cumulative probability before the bin), by start.
    bins: Vec<(f64, f64, f64, f64)>,
}

impl PiecewiseDensity {
    /// From (start, end, height ≥ 0) in order; `None` if every height is 0.
    pub fn new(heights: impl IntoIterator<Item = (f64, f64, f64)>) -> Option<Self> {
        let mut bins = Vec::new();
        let mut before = 0.0;
        for (a, b, height) in heights {
            if height > 0.0 && b > a {
                bins.push((a, b, height, before));
                before += height * (b - a);
            }
        }
        if before <= 0.0 || !before.is_finite() {
            return None;
        }
        for bin in &mut bins {
            bin.2 /= before;
            bin.3 /= before;
        }
        Some(Self { bins })
    }

    pub fn sample(&self, u: f64) -> f64 {
        let i = self.bins.partition_point(|b| b.3 <= u).saturating_sub(1);
        let (a, b, density, before) = self.bins[i];
        (a + (u - before) / density).clamp(a, b)
    }

    pub fn pdf(&self, t: f64) -> f64 {
        let i = self.bins.partition_point(|b| b.0 <= t);
        match i.checked_sub(1).map(|i| self.bins[i]) {
            Some((_, end, density, _)) if t <= end => density,
            _ => 0.0,
        }
    }

    /// The majorant of channel `k` over the parts of the tracks in `intervals`.
    pub fn majorant_over(tracks: &Tracks, k: usize, intervals: &[(f64, f64)]) -> Option<Self> {
        Self::new(tracks.pieces.iter().flat_map(|piece| {
            intervals
                .iter()
                .map(move |&(a, b)| (a.max(piece.start), b.min(piece.end), piece.majorant[k]))
        }))
    }
}

/// The parts of `ray` over `[0, length]` outside the planet's shadow, in order (empty
/// when it is all in the shadow). A point of the air is in the shadow when its sun ray
/// meets the ground: behind the plane through the centre normal to `sun`, and within
/// `planet_radius` of the axis through the centre along `sun`. That set is convex, so
/// the ray crosses it once, leaving up to two sunlit intervals.
pub(super) fn sunlit_intervals(
    ray: &Ray,
    length: f64,
    sun: DVec3,
    planet_radius: f64,
) -> Vec<(f64, f64)> {
    let (o, v) = (ray.origin, ray.direction);
    let (o_axis, v_axis) = (o.dot(sun), v.dot(sun));
    let (o_across, v_across) = (o - o_axis * sun, v - v_axis * sun);
    // Inside the cylinder: a t² + 2 b t + c < 0.
    let (a, b, c) = (
        v_across.length_squared(),
        o_across.dot(v_across),
        o_across.length_squared() - planet_radius * planet_radius,
    );
    let (mut start, mut end) = if a <= f64::MIN_POSITIVE {
        if c < 0.0 {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (0.0, 0.0)
        }
    } else {
        let discriminant = b * b - a * c;
        if discriminant <= 0.0 {
            (0.0, 0.0)
        } else {
            let root = discriminant.sqrt();
            ((-b - root) / a, (-b + root) / a)
        }
    };
    // Behind the plane: o_axis + t v_axis < 0.
    if v_axis > 0.0 {
        end = end.min(-o_axis / v_axis);
    } else if v_axis < 0.0 {
        start = start.max(-o_axis / v_axis);
    } else if o_axis >= 0.0 {
        end = start;
    }
    let (start, end) = (start.clamp(0.0, length), end.clamp(0.0, length));
    if end <= start {
        return vec![(0.0, length)];
    }
    [(0.0, start), (end, length)]
        .into_iter()
        .filter(|(a, b)| b > a)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Atmosphere;

    #[test]
    fn sunlit_intervals_agree_with_the_shadow_test() {
        let earth = Atmosphere::earth();
        let medium = Medium::new(&earth);
        let sun = DVec3::new((-4f64).to_radians().cos(), 0.0, (-4f64).to_radians().sin());
        for (altitude, view) in [
            (0.0, DVec3::new(-0.98, 0.1, 0.17).normalize()),
            (0.0, DVec3::new(0.98, 0.1, 0.17).normalize()),
            (5e4, DVec3::new(-0.3, 0.9, -0.3).normalize()),
            (0.0, DVec3::Z),
        ] {
            let ray = Ray::new(DVec3::new(0.0, 0.0, earth.planet_radius + altitude), view);
            let (length, _) = ray.end(earth.planet_radius, earth.top_radius);
            let lit = sunlit_intervals(&ray, length, sun, earth.planet_radius);
            for i in 0..=1000 {
                let t = length * f64::from(i) / 1000.0;
                let shadowed = medium.sun_transmittance(ray.at(t), sun) == [0.0; 3];
                let in_lit = lit.iter().any(|&(a, b)| t > a + 1.0 && t < b - 1.0);
                let near_edge = lit
                    .iter()
                    .any(|&(a, b)| (t - a).abs() <= 1.0 || (t - b).abs() <= 1.0);
                assert!(
                    near_edge || in_lit != shadowed,
                    "view {view}: t {t} lit {lit:?}"
                );
            }
        }
    }

    #[test]
    fn densities_integrate_to_one_and_invert() {
        let medium = Medium::new(&Atmosphere::earth());
        let ray = Ray::new(
            DVec3::new(0.0, 0.0, medium.planet_radius + 500.0),
            DVec3::new(0.8, 0.0, 0.6),
        );
        let (length, _) = ray.end(medium.planet_radius, medium.top_radius);
        let tracks = Tracks::new(&medium, &ray, length);
        let piecewise = PiecewiseDensity::majorant_over(
            &tracks,
            2,
            &[(0.0, 0.3 * length), (0.5 * length, length)],
        )
        .unwrap();
        let n = 200_000;
        let (mut forced, mut table) = (0.0, 0.0);
        for i in 0..n {
            let t = length * (f64::from(i) + 0.5) / f64::from(n);
            forced += tracks.pdf(1, t) * length / f64::from(n);
            table += piecewise.pdf(t) * length / f64::from(n);
        }
        assert!(
            (forced - 1.0).abs() < 1e-4 && (table - 1.0).abs() < 1e-4,
            "{forced} {table}"
        );
        for u in [0.0, 0.1, 0.5, 0.9, 0.999_999] {
            let t = tracks.sample(1, u);
            assert!((0.0..=length).contains(&t));
            let t = piecewise.sample(u);
            assert!(piecewise.pdf(t) > 0.0, "u {u}: t {t}");
        }
    }
}
