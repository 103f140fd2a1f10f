//! The f64 reference: what every lighting method of the crate is measured against. It
//! approximates nothing that it can compute.
//!
//! * [`optical_depth`] / [`transmittance`]: exact optical depth through a [`CloudVolume`]'s
//!   trilinear density along a ray. Why exact: between consecutive crossings of the planes
//!   through cell centres and the volume's faces, the (clamped) trilinear density is a
//!   product of at most three affine functions of the ray parameter, i.e. a cubic in `t`,
//!   and Simpson's rule integrates cubics exactly. So the integral is a sum of Simpson
//!   pieces with no discretisation error.
//! * [`ReferenceField`]: a [`DensityField<f64>`] the reference can light: its optical depth
//!   (exact for a [`CloudVolume`]; for any other field an adaptive Simpson march with a
//!   convergence test, its reached error reported in an [`Integral`]), an upper bound of its
//!   density (the path tracer's majorant) and where its density changes formula along a ray.
//! * [`single_scattering`](mod@single_scattering): radiance along a view ray lit once by a
//!   directional [`Sun`] with a [`Phase`] function, the transmittance toward the sun
//!   computed exactly at every quadrature point, the view quadrature adaptive with its
//!   reached tolerance reported.
//! * [`path_tracer`](mod@path_tracer): every scattering order by an unbiased Monte Carlo
//!   path tracer (delta tracking, phase sampling, next-event estimation toward the sun),
//!   mean and standard error.
//!
//! Conventions: `Sun::to_sun` points from the cloud toward the sun; a view ray's direction
//! points away from the camera; the phase function's cosine is `dot(view, to_sun)` (1 when
//! looking straight into the sun: forward scattering). No ground, black background.

use crate::{CloudVolume, DensityField};

pub mod path_tracer;
pub mod single_scattering;

/// Bad ray for the reference, naming the field and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReferenceError {
    /// A component of the ray is not finite, the direction is zero, or the length is negative/NaN.
    #[error("{field} = {value}: {requirement}")]
    BadRay {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
    /// A lighting or sampling parameter is out of its domain.
    #[error("{field} = {value}: {requirement}")]
    BadParameter {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
    /// A field's density exceeded its own [`ReferenceField::density_bound`], so delta
    /// tracking's majorant was not one and the estimate would be biased.
    #[error(
        "density = {density} exceeds density_bound = {bound}: the majorant must bound the field"
    )]
    MajorantExceeded {
        /// The density met.
        density: f64,
        /// The bound the field claimed.
        bound: f64,
    },
}

fn bad(field: &'static str, value: f64, requirement: &'static str) -> ReferenceError {
    ReferenceError::BadRay {
        field,
        value,
        requirement,
    }
}

/// Every `t > 0` where the volume's piecewise-cubic density along `start + t·d` may change
/// formula: crossings of the planes through cell centres and of the faces (unsorted).
fn volume_breaks(volume: &CloudVolume, start: [f64; 3], d: [f64; 3]) -> Vec<f64> {
    let (origin, voxel, dims) = (volume.origin(), volume.voxel_size(), volume.dims());
    let mut breaks = Vec::new();
    for axis in 0..3 {
        if d[axis] == 0.0 {
            continue;
        }
        let n = dims[axis];
        let planes = (0..n).map(|k| k as f64 + 0.5).chain([0.0, n as f64]);
        for u in planes {
            let t = (origin[axis] + u * voxel - start[axis]) / d[axis];
            if t > 0.0 && t.is_finite() {
                breaks.push(t);
            }
        }
    }
    breaks
}

/// Optical depth `∫ σ_t ρ(start + t·d̂) dt` for `t ∈ [0, length]` (metres, `d̂` = normalised
/// `direction`); `length = ∞` integrates to where the ray leaves the volume.
pub fn optical_depth(
    volume: &CloudVolume,
    start: [f64; 3],
    direction: [f64; 3],
    length: f64,
) -> Result<f64, ReferenceError> {
    for (field, value) in ["start.x", "start.y", "start.z"].into_iter().zip(start) {
        if !value.is_finite() {
            return Err(bad(field, value, "must be finite (metres)"));
        }
    }
    for (field, value) in ["direction.x", "direction.y", "direction.z"]
        .into_iter()
        .zip(direction)
    {
        if !value.is_finite() {
            return Err(bad(field, value, "must be finite"));
        }
    }
    let norm = direction.iter().map(|c| c * c).sum::<f64>().sqrt();
    if norm == 0.0 {
        return Err(bad("direction", norm, "must be non-zero"));
    }
    if length.is_nan() || length < 0.0 {
        return Err(bad("length", length, "must be ≥ 0 (metres; ∞ allowed)"));
    }
    let d = direction.map(|c| c / norm);
    let (origin, voxel, dims) = (volume.origin(), volume.voxel_size(), volume.dims());

    let mut breaks = volume_breaks(volume, start, d);
    let end = if length.is_finite() {
        length
    } else {
        breaks.iter().copied().fold(0.0, f64::max)
    };
    breaks.retain(|&t| t < end);
    breaks.push(0.0);
    breaks.push(end);
    breaks.sort_by(f64::total_cmp);

    let point = |t: f64| [0, 1, 2].map(|a| start[a] + t * d[a]);
    let inside = |p: [f64; 3]| {
        (0..3).all(|a| {
            let u = (p[a] - origin[a]) / voxel;
            u >= 0.0 && u <= dims[a] as f64
        })
    };
    let mut integral = 0.0;
    for piece in breaks.windows(2) {
        let (t0, t1) = (piece[0], piece[1]);
        let mid = 0.5 * (t0 + t1);
        // A piece lies wholly inside or outside (faces are breaks); outside contributes 0,
        // and its end points must not borrow the face value from inside.
        if t1 <= t0 || !inside(point(mid)) {
            continue;
        }
        let f0 = volume.density_at(point(t0));
        let fm = volume.density_at(point(mid));
        let f1 = volume.density_at(point(t1));
        integral += (t1 - t0) / 6.0 * (f0 + 4.0 * fm + f1);
    }
    Ok(volume.extinction_per_density() * integral)
}

/// Transmittance `exp(−optical_depth)` along the ray; see [`optical_depth`].
pub fn transmittance(
    volume: &CloudVolume,
    start: [f64; 3],
    direction: [f64; 3],
    length: f64,
) -> Result<f64, ReferenceError> {
    optical_depth(volume, start, direction, length).map(|tau| (-tau).exp())
}

/// A converged integral: its value, the estimate of its remaining error (absolute, same
/// unit), and how many integrand evaluations it took. `converged` is false where the
/// adaptive rule hit its depth limit before meeting the tolerance; `error_estimate` still
/// says how far it got.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Integral {
    /// The integral.
    pub value: f64,
    /// Estimated absolute error (0 for an exact rule).
    pub error_estimate: f64,
    /// Integrand evaluations.
    pub evaluations: usize,
    /// Whether every piece met its tolerance.
    pub converged: bool,
}

impl Integral {
    /// An exact value.
    pub fn exact(value: f64) -> Self {
        Self {
            value,
            error_estimate: 0.0,
            evaluations: 0,
            converged: true,
        }
    }

    fn add(&mut self, other: Integral) {
        self.value += other.value;
        self.error_estimate += other.error_estimate;
        self.evaluations += other.evaluations;
        self.converged &= other.converged;
    }
}

/// Integrand evaluations one default [`ReferenceField::reference_optical_depth`] may spend.
pub const OPTICAL_DEPTH_BUDGET: usize = 1 << 20;

/// Deepest bisection of the adaptive Simpson rule (2⁻⁴⁰ of a piece).
const MAX_DEPTH: u32 = 40;

/// Adaptive Simpson quadrature of `f` over `[a, b]`, split first into `panels` equal
/// pieces, each bisected until Richardson's estimate `|S₂ − S₁|/15` is within its share of
/// the absolute `tolerance` (the returned value includes the Richardson correction).
/// `budget` counts the evaluations left: once spent, pieces are accepted as they are and
/// the result says it did not converge (no input can make the rule run forever).
pub fn adaptive_simpson(
    f: &mut impl FnMut(f64) -> f64,
    a: f64,
    b: f64,
    tolerance: f64,
    panels: usize,
    budget: &mut usize,
) -> Integral {
    let mut total = Integral::exact(0.0);
    if b <= a {
        return total;
    }
    let panels = panels.max(1);
    let width = (b - a) / panels as f64;
    for k in 0..panels {
        let (x0, x1) = (
            a + k as f64 * width,
            if k + 1 == panels {
                b
            } else {
                a + (k + 1) as f64 * width
            },
        );
        let xm = 0.5 * (x0 + x1);
        let (f0, fm, f1) = (f(x0), f(xm), f(x1));
        *budget = budget.saturating_sub(3);
        let whole = (x1 - x0) / 6.0 * (f0 + 4.0 * fm + f1);
        let mut piece = Integral {
            value: 0.0,
            error_estimate: 0.0,
            evaluations: 3,
            converged: true,
        };
        // Explicit stack: (x0, x1, f0, fm, f1, whole, tolerance, depth).
        let mut stack = vec![(x0, x1, f0, fm, f1, whole, tolerance / panels as f64, 0u32)];
        while let Some((x0, x1, f0, fm, f1, whole, tol, depth)) = stack.pop() {
            let xm = 0.5 * (x0 + x1);
            let (xl, xr) = (0.5 * (x0 + xm), 0.5 * (xm + x1));
            if *budget < 2 {
                piece.value += whole;
                piece.error_estimate += tol.max(f64::MIN_POSITIVE);
                piece.converged = false;
                continue;
            }
            let (fl, fr) = (f(xl), f(xr));
            *budget -= 2;
            piece.evaluations += 2;
            let left = (xm - x0) / 6.0 * (f0 + 4.0 * fl + fm);
            let right = (x1 - xm) / 6.0 * (fm + 4.0 * fr + f1);
            let delta = left + right - whole;
            let error = delta.abs() / 15.0;
            if error <= tol || depth >= MAX_DEPTH || !(xl > x0 && xr < x1) {
                piece.value += left + right + delta / 15.0;
                piece.error_estimate += error;
                piece.converged &= error <= tol;
            } else {
                stack.push((xm, x1, fm, fr, f1, right, 0.5 * tol, depth + 1));
                stack.push((x0, xm, f0, fl, fm, left, 0.5 * tol, depth + 1));
            }
        }
        total.add(piece);
    }
    total
}

/// Panels of at most `max_panel` covering `length` (at least 1; capped at 2²⁰).
pub(crate) fn initial_panels(length: f64, max_panel: f64) -> usize {
    let n = (length / max_panel).ceil();
    if n.is_finite() && n >= 1.0 {
        n.min(f64::from(1u32 << 20)) as usize
    } else {
        1
    }
}

/// The procedural shell: its density is dimensionless in [0, 1] (the shell's module
/// documentation), so 1 bounds it; the first panels are no longer than the finest noise
/// lattice spacing, `min(shape_period/128, detail_period/32)`.
impl ReferenceField for crate::CloudShell {
    fn density_bound(&self) -> f64 {
        1.0
    }

    fn max_panel_length(&self) -> f64 {
        let s = self.settings();
        (s.shape_period / 128.0).min(s.detail_period / 32.0)
    }
}

/// A directional sun: the unit direction toward it and its irradiance (RGB, on a surface
/// facing it, W/m² per channel or any unit: radiances come out in it per steradian).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sun {
    to_sun: [f64; 3],
    irradiance: [f64; 3],
}

impl Sun {
    /// A sun toward `to_sun` (normalised here; finite, non-zero) with `irradiance`
    /// (finite, ≥ 0 per channel).
    pub fn new(to_sun: [f64; 3], irradiance: [f64; 3]) -> Result<Self, ReferenceError> {
        let to_sun = unit(to_sun, ["to_sun.x", "to_sun.y", "to_sun.z"], "to_sun")?;
        for (field, value) in ["irradiance.r", "irradiance.g", "irradiance.b"]
            .into_iter()
            .zip(irradiance)
        {
            if !(value.is_finite() && value >= 0.0) {
                return Err(ReferenceError::BadParameter {
                    field,
                    value,
                    requirement: "must be finite and ≥ 0",
                });
            }
        }
        Ok(Self { to_sun, irradiance })
    }

    /// A sun at `elevation` above the horizon (z up) and `azimuth` from +x toward +y, radians.
    pub fn from_elevation_azimuth(
        elevation: f64,
        azimuth: f64,
        irradiance: [f64; 3],
    ) -> Result<Self, ReferenceError> {
        let (se, ce) = elevation.sin_cos();
        let (sa, ca) = azimuth.sin_cos();
        Self::new([ce * ca, ce * sa, se], irradiance)
    }

    /// Unit vector toward the sun.
    pub fn to_sun(&self) -> [f64; 3] {
        self.to_sun
    }

    /// Irradiance, RGB.
    pub fn irradiance(&self) -> [f64; 3] {
        self.irradiance
    }
}

/// Normalises a direction, naming the component that is not finite or the zero vector.
pub(crate) fn unit(
    v: [f64; 3],
    fields: [&'static str; 3],
    name: &'static str,
) -> Result<[f64; 3], ReferenceError> {
    for (field, value) in fields.into_iter().zip(v) {
        if !value.is_finite() {
            return Err(bad(field, value, "must be finite"));
        }
    }
    let norm = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    if !(norm > 0.0 && norm.is_finite()) {
        return Err(bad(name, norm, "must be non-zero"));
    }
    Ok(v.map(|c| c / norm))
}

/// The cloud's phase function (1/sr), in the cosine of the scattering angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// Henyey–Greenstein with asymmetry `g` ∈ (−1, 1) (`atmos::phase`).
    HenyeyGreenstein {
        /// Asymmetry.
        g: f64,
    },
    /// `(1 − back_weight)·HG(g_forward) + back_weight·HG(g_back)`
    /// ([`crate::cone::dual_lobe_henyey_greenstein`]).
    DualLobe {
        /// Forward lobe's asymmetry, (−1, 1).
        g_forward: f64,
        /// Back lobe's asymmetry, (−1, 1).
        g_back: f64,
        /// The back lobe's weight, [0, 1].
        back_weight: f64,
    },
}

impl Phase {
    /// Checks the parameters' domains, naming the field.
    pub fn validate(&self) -> Result<(), ReferenceError> {
        let check_g = |field: &'static str, g: f64| {
            if g.is_finite() && g.abs() < 1.0 {
                Ok(())
            } else {
                Err(ReferenceError::BadParameter {
                    field,
                    value: g,
                    requirement: "asymmetry must lie in (−1, 1)",
                })
            }
        };
        match *self {
            Phase::HenyeyGreenstein { g } => check_g("g", g),
            Phase::DualLobe {
                g_forward,
                g_back,
                back_weight,
            } => {
                check_g("g_forward", g_forward)?;
                check_g("g_back", g_back)?;
                if (0.0..=1.0).contains(&back_weight) {
                    Ok(())
                } else {
                    Err(ReferenceError::BadParameter {
                        field: "back_weight",
                        value: back_weight,
                        requirement: "must lie in [0, 1]",
                    })
                }
            }
        }
    }

    /// The phase function at scattering-angle cosine `cos_theta` (1/sr).
    pub fn value(&self, cos_theta: f64) -> f64 {
        match *self {
            Phase::HenyeyGreenstein { g } => atmos::phase::henyey_greenstein_phase(cos_theta, g),
            Phase::DualLobe {
                g_forward,
                g_back,
                back_weight,
            } => {
                crate::cone::dual_lobe_henyey_greenstein(cos_theta, g_forward, g_back, back_weight)
            }
        }
    }

    /// A scattering-angle cosine distributed as the phase function, from two uniforms in
    /// [0, 1) (the first picks the lobe of a dual lobe, the second inverts its CDF).
    pub fn sample_cosine(&self, u_lobe: f64, u: f64) -> f64 {
        let g = match *self {
            Phase::HenyeyGreenstein { g } => g,
            Phase::DualLobe {
                g_forward,
                g_back,
                back_weight,
            } => {
                if u_lobe < back_weight {
                    g_back
                } else {
                    g_forward
                }
            }
        };
        if g.abs() < 1e-6 {
            return 2.0 * u - 1.0;
        }
        let s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
        ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
    }
}

/// A [`DensityField<f64>`] the reference can light.
pub trait ReferenceField: DensityField<f64> + Sync {
    /// An upper bound of the density anywhere (delta tracking's majorant is
    /// `extinction_per_density × density_bound`). The path tracer returns
    /// [`ReferenceError::MajorantExceeded`] if the field ever exceeds it.
    fn density_bound(&self) -> f64;

    /// Optical depth along `origin + t·direction`, `t ∈ [0, length]` (unit `direction`,
    /// `length = ∞` to the field's end), to within `tolerance` (absolute). The default is
    /// an adaptive Simpson march of every [`ray_spans`](DensityField::ray_spans) piece
    /// (split at [`breakpoints`](Self::breakpoints), then into at least 8 panels no longer
    /// than [`max_panel_length`](Self::max_panel_length)) with Richardson's
    /// convergence test, at most [`OPTICAL_DEPTH_BUDGET`] evaluations; its reached error is in
    /// the result.
    fn reference_optical_depth(
        &self,
        origin: [f64; 3],
        direction: [f64; 3],
        length: f64,
        tolerance: f64,
    ) -> Result<Integral, ReferenceError> {
        let spans = self.ray_spans(origin, direction);
        let sigma = self.extinction_per_density();
        let mut total = Integral::exact(0.0);
        let pieces: Vec<(f64, f64)> = spans
            .as_slice()
            .iter()
            .map(|&(a, b)| (a, b.min(length)))
            .filter(|&(a, b)| b > a)
            .collect();
        let share = tolerance / pieces.len().max(1) as f64;
        let mut budget = OPTICAL_DEPTH_BUDGET;
        for (a, b) in pieces {
            let mut cuts = self.breakpoints(origin, direction, a, b);
            cuts.push(a);
            cuts.push(b);
            cuts.sort_by(f64::total_cmp);
            let whole = b - a;
            for w in cuts.windows(2) {
                if w[1] <= w[0] {
                    continue;
                }
                let mut f =
                    |t: f64| sigma * self.density([0, 1, 2].map(|i| origin[i] + t * direction[i]));
                total.add(adaptive_simpson(
                    &mut f,
                    w[0],
                    w[1],
                    share * (w[1] - w[0]) / whole,
                    initial_panels(w[1] - w[0], self.max_panel_length()).max(8),
                    &mut budget,
                ));
            }
        }
        Ok(total)
    }

    /// The longest first panel an adaptive quadrature of this field may start from,
    /// metres: about its smallest feature, so that a convergence test cannot be fooled by
    /// panels that all miss it (a noise field's lattice spacing). The default is ∞ (none).
    fn max_panel_length(&self) -> f64 {
        f64::INFINITY
    }

    /// The `t ∈ (t0, t1)` where the density along the ray may change formula (a grid's
    /// cell boundaries); quadratures split there. The default is none.
    fn breakpoints(&self, origin: [f64; 3], direction: [f64; 3], t0: f64, t1: f64) -> Vec<f64> {
        let _ = (origin, direction, t0, t1);
        Vec::new()
    }
}

/// The volume: exact optical depth ([`optical_depth`], error 0), the largest cell (× (1 + 10⁻¹²)) as the
/// bound (trilinear interpolation never exceeds it), the cell-centre planes and faces as
/// breakpoints.
impl ReferenceField for CloudVolume {
    fn density_bound(&self) -> f64 {
        // Raised by 1e-12 relative: the eight-weight trilinear sum can round a few ULPs above
        // the largest cell (measured 1 + 2.2e-16 for a cell of 1 on the cumulus).
        self.density()
            .iter()
            .fold(0.0f64, |m, &v| m.max(f64::from(v)))
            * (1.0 + 1e-12)
    }

    fn reference_optical_depth(
        &self,
        origin: [f64; 3],
        direction: [f64; 3],
        length: f64,
        _tolerance: f64,
    ) -> Result<Integral, ReferenceError> {
        optical_depth(self, origin, direction, length).map(Integral::exact)
    }

    fn breakpoints(&self, origin: [f64; 3], direction: [f64; 3], t0: f64, t1: f64) -> Vec<f64> {
        let mut breaks = volume_breaks(self, origin, direction);
        breaks.retain(|&t| t > t0 && t < t1);
        breaks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn homogeneous_slab_matches_beer_lambert_at_any_angle() {
        // 4×4×4 cells of 50 m, density 0.75, σ_t 0.01 /m: a 200 m cube.
        let v = CloudVolume::new([4, 4, 4], [0.0; 3], 50.0, 0.01, vec![0.75; 64]).unwrap();
        let along_x =
            transmittance(&v, [-10.0, 100.0, 100.0], [1.0, 0.0, 0.0], f64::INFINITY).unwrap();
        assert!(
            (along_x - (-0.01f64 * 0.75 * 200.0).exp()).abs() < 1e-14,
            "{along_x}"
        );
        // Oblique through the top face: path length 200 / cos θ inside the slab z ∈ [0, 200].
        let dir = [0.3, 0.2, 1.0];
        let norm = (0.09f64 + 0.04 + 1.0).sqrt();
        let start = [60.0, 70.0, 0.0];
        let tau = optical_depth(&v, start, dir, f64::INFINITY).unwrap();
        let exit_t = 200.0 * norm; // reaches z = 200 at x = 120, y = 110: inside the cube
        assert!((tau - 0.01 * 0.75 * exit_t).abs() < 1e-12, "{tau}");
        // A finite length stops inside.
        let half = optical_depth(&v, start, dir, 0.5 * exit_t).unwrap();
        assert!((half - 0.5 * tau).abs() < 1e-12);
    }

    #[test]
    fn exact_on_a_gradient_and_agrees_with_a_converged_march() {
        // Density rising along x (cell-centre values 0, 1, 2, …) with a y wobble.
        let dims = [6u32, 5, 4];
        let density: Vec<f32> = (0..dims[2])
            .flat_map(|z| {
                (0..dims[1]).flat_map(move |y| (0..dims[0]).map(move |x| (x + (y * z) % 3) as f32))
            })
            .collect();
        let v = CloudVolume::new(dims, [-30.0, 5.0, 0.0], 10.0, 0.002, density).unwrap();
        let start = [-40.0, 7.0, 3.0];
        let dir = [1.0, 0.61, 0.37];
        let exact = optical_depth(&v, start, dir, f64::INFINITY).unwrap();
        assert!(exact > 0.05, "{exact}");
        // Midpoint march with 2^20 steps over the same span. The density jumps to 0 at the
        // volume's faces (two crossings), so the march errs by up to h·σ_t·ρ_max per crossing;
        // elsewhere its error is O(h²) (~1e-10 here). The exact sum must lie within that bound.
        let norm = (1.0f64 + 0.61 * 0.61 + 0.37 * 0.37).sqrt();
        let d = dir.map(|c| c / norm);
        let span = 200.0;
        let steps = 1 << 20;
        let h = span / steps as f64;
        let marched: f64 = (0..steps)
            .map(|i| {
                let t = (i as f64 + 0.5) * h;
                v.density_at([0, 1, 2].map(|a| start[a] + t * d[a]))
            })
            .sum::<f64>()
            * h
            * 0.002;
        // ρ_max = 5 + 2.
        let bound = 2.0 * h * 0.002 * 7.0 + 1e-9;
        assert!(
            (exact - marched).abs() < bound,
            "{exact} vs {marched} (bound {bound})"
        );
    }

    #[test]
    fn bad_rays_are_named() {
        let v = CloudVolume::new([1, 1, 1], [0.0; 3], 1.0, 0.1, vec![1.0]).unwrap();
        let err = optical_depth(&v, [0.0; 3], [0.0; 3], 1.0).unwrap_err();
        assert!(err.to_string().starts_with("direction = 0"), "{err}");
        let err = optical_depth(&v, [f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0], 1.0).unwrap_err();
        assert!(err.to_string().starts_with("start.x = NaN"), "{err}");
        let err = optical_depth(&v, [0.0; 3], [1.0, 0.0, 0.0], -1.0).unwrap_err();
        assert!(err.to_string().starts_with("length = -1"), "{err}");
    }
}
