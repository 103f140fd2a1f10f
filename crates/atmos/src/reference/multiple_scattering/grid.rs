//! The 4D grid of the scattering-density table and its sun-angle rows.

use std::f64::consts::PI;

use super::settings::*;

/// Where the sun-angle rows crowd: the terminator seen from the air (the planet's
/// shadow reaches a point at altitude h at a sun zenith angle of 90° + its horizon's dip,
/// 3.2° at 10 km, 10° at 100 km), where the source falls by orders of magnitude over a
/// few degrees. Rows uniform in angle (5.2° apart) interpolated that fall linearly,
/// several times too bright in the shadow.
pub(super) const SUN_CROWD_CENTRE: f64 = 97.0 * PI / 180.0;
/// Width (rad) of the crowding.
pub(super) const SUN_CROWD_WIDTH: f64 = 8.0 * PI / 180.0;
/// Row density at the centre, relative to far from it: 1 + this.
pub(super) const SUN_CROWD_STRENGTH: f64 = 4.0;

/// The unnormalised sun-angle coordinate: ∫ 1 + A/(1 + ((θ − θ₀)/w)²) dθ.
pub(super) fn sun_zenith_mass(theta: f64) -> f64 {
    let w = SUN_CROWD_WIDTH;
    theta
        + SUN_CROWD_STRENGTH
            * w
            * (((theta - SUN_CROWD_CENTRE) / w).atan() - (-SUN_CROWD_CENTRE / w).atan())
}

/// The sun-angle axis' coordinate in [0, 1] of a sun zenith angle in [0, `MAX_SUN_ZENITH`].
pub(super) fn sun_zenith_coordinate(theta: f64) -> f64 {
    sun_zenith_mass(theta) / sun_zenith_mass(MAX_SUN_ZENITH)
}

/// The sun zenith angle of a coordinate in [0, 1] (the inverse, by bisection).
pub(super) fn sun_zenith_from_coordinate(x: f64) -> f64 {
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
pub(super) struct SourceGrid {
    pub(super) sizes: [usize; 4],
    pub(super) planet_radius: f64,
    pub(super) top_radius: f64,
}

impl SourceGrid {
    pub(super) fn horizon_length(&self) -> f64 {
        ((self.top_radius - self.planet_radius) * (self.top_radius + self.planet_radius)).sqrt()
    }

    pub(super) fn len(&self) -> usize {
        self.sizes.iter().product()
    }

    pub(super) fn index(&self, i: [usize; 4]) -> usize {
        ((i[0] * self.sizes[1] + i[1]) * self.sizes[2] + i[2]) * self.sizes[3] + i[3]
    }

    /// Radius of grid row `i`: ρ = H·i/(n − 1) puts half the rows below 25 km.
    pub(super) fn radius(&self, i: usize) -> f64 {
        let rho = self.horizon_length() * i as f64 / (self.sizes[0] - 1) as f64;
        (rho * rho + self.planet_radius * self.planet_radius).sqrt()
    }

    pub(super) fn angle(&self, axis: usize, i: usize) -> f64 {
        let x = i as f64 / (self.sizes[axis] - 1) as f64;
        if axis == 2 {
            sun_zenith_from_coordinate(x)
        } else {
            PI * x
        }
    }

    /// Continuous grid coordinates of (r, mu, mu_s, nu); `None` beyond the sun limit.
    pub(super) fn coordinates(&self, r: f64, mu: f64, mu_s: f64, nu: f64) -> Option<[f64; 4]> {
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
    pub(super) fn interpolate<const N: usize>(
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
