//! Slice propagation (Dobashi et al. 2000): the light reaching every cell centre of a
//! [`CloudVolume`], in one sweep of slices perpendicular to the volume axis most aligned
//! with the light, each slice computed from the one before it (toward the sun).
//!
//! Written once, generic over [`Real`]: [`propagate::<f64>`](propagate) is the reference
//! the parity report compares against, [`propagate::<f32>`](propagate) the CPU twin of
//! `shaders/cloudlight/slice_propagation.wgsl` (one dispatch per slice, two ping-pong
//! slice buffers, the light written into one 3-D output), operation for operation.
//!
//! Two modes ([`SliceMode`]):
//!
//! * **physical**: each slice carries the optical depth `τ` toward the sun. Slice `k`'s
//!   texel `(i, j)` reads the previous slice at `(i + s_b, j + s_c)`, where the light ray
//!   through this centre crossed it (`s` = the light's in-slice components over its axis
//!   component, in texels), and adds the trapezoid `½·σ_t·Δs·(ρ_prev + ρ)` over the true
//!   spacing along the light `Δs = voxel / |l_axis|`. The light is `exp(−τ)`. The depth is
//!   resampled with a Catmull–Rom bicubic clamped to the four nearest texels
//!   ([`Resampling::CatmullRom`], the default) or bilinearly ([`Resampling::Bilinear`]);
//!   the density (the original field, no accumulated blur) always bilinearly. Repeated
//!   bilinear resampling at the same fractional offset is first-order upwind advection: it
//!   diffuses shadow edges by about `√(k·f(1−f))` texels after `k` slices; the clamped
//!   cubic diffuses far less and cannot overshoot. Figures in `docs/cloudlight-methods.md`.
//! * **faithful**: Dobashi et al. 2000 as published: the light is shifted by whole texels (the offset of
//!   slice `k` is `round(k·s) − round((k−1)·s)`, so the shifts follow the light ray), and
//!   attenuated by the previous slice's 5-tap cross-smoothed density:
//!   `light = light_prev · (1 − (1 − attenuation_ratio)·ρ̄)`.
//!
//! The first slice (on the sun side) sees unattenuated light: physical mode integrates half
//! a spacing of its own density (the centre's distance to the face), faithful mode gives 1.
//! Outside the previous slice the light is unattenuated (`τ = 0`, light 1) and the density 0.

use atmos::real::Real;

use crate::CloudVolume;

/// Bad settings for a slice propagation, naming the field and its value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SliceError {
    /// A field is out of its domain.
    #[error("{field} = {value}: {requirement}")]
    BadParameter {
        /// The field name.
        field: &'static str,
        /// The value.
        value: f64,
        /// What the field must satisfy.
        requirement: &'static str,
    },
    /// The plan was made for a volume of other dimensions ([`propagate`]).
    #[error("plan is for a {plan:?} volume, the volume is {volume:?}")]
    PlanMismatch {
        /// The plan's `[nx, ny, nz]`.
        plan: [u32; 3],
        /// The volume's.
        volume: [u32; 3],
    },
}

fn bad(field: &'static str, value: f64, requirement: &'static str) -> SliceError {
    SliceError::BadParameter {
        field,
        value,
        requirement,
    }
}

/// How physical mode resamples the previous slice's optical depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Resampling {
    /// Bilinear (4 taps): diffuses oblique shadows (see the module documentation).
    Bilinear,
    /// Catmull–Rom bicubic (16 taps) clamped to the 4 nearest texels' range.
    #[default]
    CatmullRom,
}

/// How each slice attenuates the light (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SliceMode {
    /// Beer–Lambert over the true spacing, bilinear resampling of the optical depth.
    Physical,
    /// Dobashi et al. 2000: `1 − (1 − attenuation_ratio)·ρ̄`, 5-tap smoothing, whole-texel shifts.
    /// `attenuation_ratio` ∈ [0, 1] is the light a fully dense slice lets through; densities
    /// must lie in [0, 1] (cloudsim's do; [`SlicePlan::new`] refuses others by name).
    Faithful {
        /// Light passed by a slice of density 1.
        attenuation_ratio: f64,
    },
}

/// The geometry of one sweep: which axis the slices are perpendicular to, in which order
/// they are visited, how far the light shifts between slices, and the per-slice whole-texel
/// offsets of faithful mode. Built by [`SlicePlan::new`]; the GPU pass uploads the same
/// numbers (rounded to f32 once, as the f32 twin rounds them).
#[derive(Debug, Clone, PartialEq)]
pub struct SlicePlan {
    /// The volume axis (0 = x, 1 = y, 2 = z) the slices are perpendicular to.
    pub axis: usize,
    /// Cells along `[axis, axis + 1, axis + 2]` (mod 3): slices, then the in-slice `b`, `c`.
    pub dims_abc: [u32; 3],
    /// Whether the sweep starts at the last slice (the light comes from +axis).
    pub from_last: bool,
    /// Where the light ray through a centre crosses the previous slice, in texels along
    /// `b` and `c`: the light's in-slice components over `|l_axis|`.
    pub shift: [f64; 2],
    /// `σ_t · Δs`: optical depth per unit density over one slice spacing along the light.
    pub sigma_ds: f64,
    /// The mode.
    pub mode: SliceMode,
    /// Physical mode's resampling of the optical depth ([`Resampling::CatmullRom`] unless
    /// changed with [`SlicePlan::with_resampling`]).
    pub resampling: Resampling,
    /// Faithful mode's whole-texel offsets of each slice (index = position in the sweep;
    /// `[0, 0]` for the first): `round(k·s) − round((k−1)·s)` per in-slice axis.
    pub offsets: Vec<[i32; 2]>,
}

impl SlicePlan {
    /// The plan for `volume` lit from direction `to_sun` (toward the sun, any non-zero
    /// length; a sun below the horizon is fine: the sweep starts on whichever side the
    /// light enters).
    pub fn new(
        volume: &CloudVolume,
        to_sun: [f64; 3],
        mode: SliceMode,
    ) -> Result<Self, SliceError> {
        for (field, value) in ["to_sun.x", "to_sun.y", "to_sun.z"].into_iter().zip(to_sun) {
            if !value.is_finite() {
                return Err(bad(field, value, "must be finite"));
            }
        }
        let norm = to_sun.iter().map(|c| c * c).sum::<f64>().sqrt();
        if norm == 0.0 || !norm.is_finite() {
            return Err(bad("to_sun", norm, "must be non-zero and finite in length"));
        }
        if let SliceMode::Faithful { attenuation_ratio } = mode
            && !(0.0..=1.0).contains(&attenuation_ratio)
        {
            return Err(bad(
                "attenuation_ratio",
                attenuation_ratio,
                "must be in [0, 1] (light passed by a fully dense slice)",
            ));
        }
        if matches!(mode, SliceMode::Faithful { .. }) {
            let max = volume.density().iter().copied().fold(0.0f32, f32::max);
            if max > 1.0 {
                return Err(bad(
                    "max density",
                    f64::from(max),
                    "must be ≤ 1 in faithful mode: Dobashi et al. 2000's 1 − (1 − r)·ρ̄ needs ρ in [0, 1]",
                ));
            }
        }
        let l = to_sun.map(|c| c / norm);
        // Ties go to the later axis (z before y before x), so a zenith sun slices along z.
        let mut axis = 2;
        for a in [1, 0] {
            if l[a].abs() > l[axis].abs() {
                axis = a;
            }
        }
        let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
        let dims = volume.dims();
        let la = l[axis].abs();
        let shift = [l[b] / la, l[c] / la];
        let na = dims[axis];
        let round = |x: f64| (x + 0.5).floor() as i32;
        let offsets = (0..na)
            .map(|k| {
                if k == 0 {
                    [0, 0]
                } else {
                    let k = f64::from(k);
                    [0, 1].map(|s| round(k * shift[s]) - round((k - 1.0) * shift[s]))
                }
            })
            .collect();
        Ok(Self {
            axis,
            dims_abc: [na, dims[b], dims[c]],
            from_last: l[axis] >= 0.0,
            shift,
            sigma_ds: volume.extinction_per_density() * volume.voxel_size() / la,
            mode,
            resampling: Resampling::default(),
            offsets,
        })
    }

    /// The same plan with physical mode's depth resampled by `resampling`.
    pub fn with_resampling(mut self, resampling: Resampling) -> Self {
        self.resampling = resampling;
        self
    }

    /// The volume slice index visited at sweep position `k`.
    pub fn slice_at(&self, k: u32) -> u32 {
        if self.from_last {
            self.dims_abc[0] - 1 - k
        } else {
            k
        }
    }

    /// Linear cell index (x fastest) of slice `slice`, in-slice texel `(i, j)`.
    pub fn cell_index(&self, slice: u32, i: u32, j: u32) -> usize {
        let mut cell = [0u32; 3];
        cell[self.axis] = slice;
        cell[(self.axis + 1) % 3] = i;
        cell[(self.axis + 2) % 3] = j;
        let dims = self.volume_dims();
        cell[0] as usize
            + dims[0] as usize * (cell[1] as usize + dims[1] as usize * cell[2] as usize)
    }

    /// `[nx, ny, nz]` of the volume the plan was made for.
    pub fn volume_dims(&self) -> [u32; 3] {
        let mut dims = [0u32; 3];
        for s in 0..3 {
            dims[(self.axis + s) % 3] = self.dims_abc[s];
        }
        dims
    }
}

/// Physical mode's step: the optical depth at a centre from the depth `tau_prev` and
/// density `rho_prev` resampled on the previous slice and this centre's density `rho`,
/// `tau_prev + (½σ_tΔs·ρ_prev + ½σ_tΔs·ρ)` (trapezoid over one spacing), saturated at
/// [`TAU_SATURATION`]. WGSL twin
/// `slice_optical_depth`.
pub fn slice_optical_depth<F: Real>(tau_prev: F, rho_prev: F, rho: F, sigma_ds: F) -> F {
    // Each density times ½σΔs before the sum: σ_t = 0 gives 0 even for densities whose
    // sum overflows.
    let half_step = F::of(0.5) * sigma_ds;
    (tau_prev + (half_step * rho_prev + half_step * rho)).min(F::of(TAU_SATURATION))
}

/// Optical depths saturate here (1e30): `exp(−τ)` is already 0 beyond 746 in f64 (104 in
/// f32), so no light changes, and an infinite depth never meets a zero weight in the
/// resampling (`0·∞` = NaN).
pub const TAU_SATURATION: f64 = 1e30;

/// Dobashi et al. 2000's 5-tap cross smoothing: `(centre + left + right + down + up) / 5`. WGSL twin
/// `cross_smooth`.
pub fn cross_smooth<F: Real>(centre: F, left: F, right: F, down: F, up: F) -> F {
    (centre + left + right + down + up) / F::of(5.0)
}

/// Bilinear interpolation of four texels at fractions `(fu, fv)`: first along `u`, then
/// `v`. WGSL twin `bilinear`.
pub fn bilinear<F: Real>(c00: F, c10: F, c01: F, c11: F, fu: F, fv: F) -> F {
    let one = F::one();
    (one - fv) * ((one - fu) * c00 + fu * c10) + fv * ((one - fu) * c01 + fu * c11)
}

/// Catmull–Rom interpolation between `p1` and `p2` at `t` ∈ [0, 1] (`p0`, `p3` the outer
/// neighbours), Horner form. WGSL twin `catmull_rom`.
pub fn catmull_rom<F: Real>(p0: F, p1: F, p2: F, p3: F, t: F) -> F {
    let (half, two, three, four, five) =
        (F::of(0.5), F::of(2.0), F::of(3.0), F::of(4.0), F::of(5.0));
    p1 + half
        * t
        * (p2 - p0
            + t * (two * p0 - five * p1 + four * p2 - p3 + t * (three * (p1 - p2) + p3 - p0)))
}

/// Dobashi et al. 2000's attenuation (generic form of [`crate::slice::slice_attenuation`]).
pub fn attenuate<F: Real>(light_prev: F, smoothed_density: F, attenuation_ratio: F) -> F {
    light_prev * (F::one() - (F::one() - attenuation_ratio) * smoothed_density)
}

/// A slice of `nb × nc` values (`b` fastest) sampled at texel coordinates `(u, v)`:
/// `outside` beyond half a texel past the edge centres, the edge value within it;
/// bilinear, or Catmull–Rom with edge-clamped taps clamped to the 4 nearest texels' range.
fn sample<F: Real>(field: &[F], nb: u32, nc: u32, u: F, v: F, outside: F, cubic: bool) -> F {
    let half = F::of(0.5);
    let (max_u, max_v) = (F::of(f64::from(nb - 1)), F::of(f64::from(nc - 1)));
    if u < -half || v < -half || u > max_u + half || v > max_v + half {
        return outside;
    }
    let u = u.max(F::zero()).min(max_u);
    let v = v.max(F::zero()).min(max_v);
    let (fi, fj) = (u.floor(), v.floor());
    let (i, j) = (fi.to_i64().unwrap_or(0), fj.to_i64().unwrap_or(0));
    let at = |i: i64, j: i64| {
        let i = i.clamp(0, i64::from(nb) - 1) as u32;
        let j = j.clamp(0, i64::from(nc) - 1) as u32;
        field[(i + nb * j) as usize]
    };
    let (fu, fv) = (u - fi, v - fj);
    let (c00, c10, c01, c11) = (at(i, j), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1));
    if !cubic {
        return bilinear(c00, c10, c01, c11, fu, fv);
    }
    let row = |dj: i64| {
        catmull_rom(
            at(i - 1, j + dj),
            at(i, j + dj),
            at(i + 1, j + dj),
            at(i + 2, j + dj),
            fu,
        )
    };
    let value = catmull_rom(row(-1), row(0), row(1), row(2), fv);
    let lo = c00.min(c10).min(c01.min(c11));
    let hi = c00.max(c10).max(c01.max(c11));
    value.max(lo).min(hi)
}

/// Whole-texel read: `outside` off the slice.
fn texel<F: Real>(field: &[F], nb: u32, nc: u32, i: i64, j: i64, outside: F) -> F {
    if i < 0 || j < 0 || i >= i64::from(nb) || j >= i64::from(nc) {
        outside
    } else {
        field[(i as u32 + nb * j as u32) as usize]
    }
}

/// The light (transmittance toward the sun in physical mode, Dobashi et al. 2000's shading value in
/// faithful mode) at every cell centre, x fastest like the density. A plan made for a
/// volume of other dimensions is a [`SliceError::PlanMismatch`] naming both.
pub fn propagate<F: Real>(volume: &CloudVolume, plan: &SlicePlan) -> Result<Vec<F>, SliceError> {
    if plan.volume_dims() != volume.dims() {
        return Err(SliceError::PlanMismatch {
            plan: plan.volume_dims(),
            volume: volume.dims(),
        });
    }
    Ok(propagate_unchecked(volume, plan))
}

/// [`propagate`] without the check: panics if `plan` was made for a volume of other
/// dimensions (for callers that built the plan from this volume, e.g. in a loop).
pub fn propagate_unchecked<F: Real>(volume: &CloudVolume, plan: &SlicePlan) -> Vec<F> {
    let [na, nb, nc] = plan.dims_abc;
    assert_eq!(
        plan.volume_dims(),
        volume.dims(),
        "plan made for another volume"
    );
    let density = volume.density();
    let texels = (nb * nc) as usize;
    let mut out = vec![F::zero(); density.len()];
    // Ping-pong: `previous` holds the last slice's τ (physical) or light (faithful).
    let mut previous = vec![F::zero(); texels];
    let mut current = vec![F::zero(); texels];
    let mut previous_density = vec![F::zero(); texels];
    let mut current_density = vec![F::zero(); texels];
    let shift = plan.shift.map(F::of);
    let sigma_ds = F::of(plan.sigma_ds);
    let cubic = plan.resampling == Resampling::CatmullRom;
    for k in 0..na {
        let slice = plan.slice_at(k);
        let [ob, oc] = plan.offsets[k as usize].map(i64::from);
        for j in 0..nc {
            for i in 0..nb {
                let cell = plan.cell_index(slice, i, j);
                let rho = F::of(f64::from(density[cell]));
                let (carried, light) = match plan.mode {
                    SliceMode::Physical => {
                        let tau = if k == 0 {
                            slice_optical_depth(F::zero(), F::zero(), rho, sigma_ds)
                        } else {
                            let u = F::of(f64::from(i)) + shift[0];
                            let v = F::of(f64::from(j)) + shift[1];
                            let tau_prev = sample(&previous, nb, nc, u, v, F::zero(), cubic);
                            let rho_prev =
                                sample(&previous_density, nb, nc, u, v, F::zero(), false);
                            slice_optical_depth(tau_prev, rho_prev, rho, sigma_ds)
                        };
                        (tau, (-tau).exp())
                    }
                    SliceMode::Faithful { attenuation_ratio } => {
                        let light = if k == 0 {
                            F::one()
                        } else {
                            let (pi, pj) = (i64::from(i) + ob, i64::from(j) + oc);
                            let d = |di: i64, dj: i64| {
                                texel(&previous_density, nb, nc, pi + di, pj + dj, F::zero())
                            };
                            let smoothed =
                                cross_smooth(d(0, 0), d(-1, 0), d(1, 0), d(0, -1), d(0, 1));
                            let light_prev = texel(&previous, nb, nc, pi, pj, F::one());
                            attenuate(light_prev, smoothed, F::of(attenuation_ratio))
                        };
                        (light, light)
                    }
                };
                current[(i + nb * j) as usize] = carried;
                current_density[(i + nb * j) as usize] = rho;
                out[cell] = light;
            }
        }
        std::mem::swap(&mut previous, &mut current);
        std::mem::swap(&mut previous_density, &mut current_density);
    }
    out
}

/// [`propagate`] in f64 with a fresh plan: the light at every cell centre.
pub fn propagate_f64(
    volume: &CloudVolume,
    to_sun: [f64; 3],
    mode: SliceMode,
) -> Result<Vec<f64>, SliceError> {
    Ok(propagate_unchecked::<f64>(
        volume,
        &SlicePlan::new(volume, to_sun, mode)?,
    ))
}

/// [`propagate`] in f32 (the WGSL's twin) with a fresh plan.
pub fn propagate_f32(
    volume: &CloudVolume,
    to_sun: [f64; 3],
    mode: SliceMode,
) -> Result<Vec<f32>, SliceError> {
    Ok(propagate_unchecked::<f32>(
        volume,
        &SlicePlan::new(volume, to_sun, mode)?,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reference::transmittance;

    pub(crate) fn blob(n: u32, sigma: f64) -> CloudVolume {
        let c = (n as f64 - 1.0) / 2.0;
        let mut density = Vec::new();
        for z in 0..n {
            for y in 0..n {
                for x in 0..n {
                    let r2 = [x, y, z]
                        .iter()
                        .map(|&v| (v as f64 - c).powi(2))
                        .sum::<f64>();
                    density.push((1.0 - r2 / (c * c)).max(0.0) as f32);
                }
            }
        }
        CloudVolume::new([n; 3], [0.0; 3], 25.0, sigma, density).unwrap()
    }

    /// RMSE and max error of the light at every cell centre against the exact reference.
    pub(crate) fn rmse_max(
        volume: &CloudVolume,
        to_sun: [f64; 3],
        resampling: Resampling,
    ) -> (f64, f64) {
        let plan = SlicePlan::new(volume, to_sun, SliceMode::Physical)
            .unwrap()
            .with_resampling(resampling);
        let light = propagate_unchecked::<f64>(volume, &plan);
        let [nx, ny, nz] = volume.dims();
        let mut sum = 0.0;
        let mut max = 0.0f64;
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    let p = [x, y, z].map(|v| (v as f64 + 0.5) * volume.voxel_size());
                    let exact = transmittance(volume, p, to_sun, f64::INFINITY).unwrap();
                    let e = light[(x + nx * (y + ny * z)) as usize] - exact;
                    sum += e * e;
                    max = max.max(e.abs());
                }
            }
        }
        ((sum / light.len() as f64).sqrt(), max)
    }

    #[test]
    fn bad_settings_are_named() {
        let v = blob(2, 0.01);
        let err = SlicePlan::new(&v, [0.0; 3], SliceMode::Physical).unwrap_err();
        assert!(err.to_string().starts_with("to_sun = 0"), "{err}");
        let err = SlicePlan::new(&v, [0.0, f64::NAN, 1.0], SliceMode::Physical).unwrap_err();
        assert!(err.to_string().starts_with("to_sun.y = NaN"), "{err}");
        let mode = SliceMode::Faithful {
            attenuation_ratio: 1.5,
        };
        let err = SlicePlan::new(&v, [0.0, 0.0, 1.0], mode).unwrap_err();
        assert!(
            err.to_string().starts_with("attenuation_ratio = 1.5"),
            "{err}"
        );
    }

    #[test]
    fn physical_slices_against_the_exact_reference() {
        // A 24³ paraboloid blob of 25 m cells; σ_t 0.02 /m gives τ up to 6 through it.
        for sigma in [0.02, 0.005] {
            let v = blob(24, sigma);
            for to_sun in [[0.0, 0.0, 1.0], [0.3, -0.4, 0.86], [1.0, 0.2, -0.1]] {
                let (rmse, max) = rmse_max(&v, to_sun, Resampling::CatmullRom);
                let (rmse_bilinear, max_bilinear) = rmse_max(&v, to_sun, Resampling::Bilinear);
                eprintln!(
                    "sigma {sigma} to_sun {to_sun:?}: catmull-rom rmse {rmse:.4} max {max:.3}; \
                     bilinear rmse {rmse_bilinear:.4} max {max_bilinear:.3}"
                );
                if to_sun[0] == 0.0 && to_sun[1] == 0.0 {
                    // Axis-aligned: no resampling, the trapezoid is exact on the linear
                    // density between centres.
                    assert!(
                        rmse < 1e-6 && rmse_bilinear < 1e-6,
                        "{rmse} {rmse_bilinear}"
                    );
                } else {
                    // Measured: 0.0060/0.0083 (σ 0.02), 0.0030/0.0033 (σ 0.005).
                    assert!(rmse <= 0.01, "{to_sun:?}: rmse {rmse} max {max}");
                    assert!(rmse < rmse_bilinear, "{rmse} vs bilinear {rmse_bilinear}");
                }
            }
        }
    }

    #[test]
    fn extremes_give_light_in_0_1_without_nan() {
        // Grids from 1×1×1 up, densities 0 and huge, σ_t 0…1 /m, the sun at the zenith,
        // the horizon and below it.
        let suns = [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.6, 0.3, 1e-9],
            [0.3, 0.2, -0.9],
        ];
        for dims in [[1, 1, 1], [1, 1, 5], [5, 1, 1], [3, 4, 2]] {
            let cells = (dims[0] * dims[1] * dims[2]) as usize;
            for density in [0.0f32, 1.0, 1e6, f32::MAX] {
                for sigma in [0.0, 1e-3, 1.0] {
                    let v = CloudVolume::new(dims, [0.0; 3], 25.0, sigma, vec![density; cells])
                        .unwrap();
                    for to_sun in suns {
                        let modes = [
                            SliceMode::Physical,
                            SliceMode::Faithful {
                                attenuation_ratio: 0.0,
                            },
                        ];
                        for mode in modes {
                            for resampling in [Resampling::CatmullRom, Resampling::Bilinear] {
                                let plan = match SlicePlan::new(&v, to_sun, mode) {
                                    Ok(plan) => plan.with_resampling(resampling),
                                    Err(e) => {
                                        // Faithful mode refuses densities above 1, by name.
                                        assert!(density > 1.0, "{e}");
                                        assert!(e.to_string().starts_with("max density"), "{e}");
                                        continue;
                                    }
                                };
                                let a = propagate_unchecked::<f32>(&v, &plan);
                                let b = propagate_unchecked::<f64>(&v, &plan);
                                assert!(
                                    a.iter().all(|l| (0.0..=1.0).contains(l)),
                                    "{dims:?} {density} {sigma} {to_sun:?} {mode:?}: {a:?}"
                                );
                                assert!(b.iter().all(|l| (0.0..=1.0).contains(l)));
                            }
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn faithful_mode_is_dobashi_2000_on_a_column() {
        // One dense column lit from straight above: each slice below passes `ratio` of
        // the light above it (5-tap smoothing of a lone column: ρ̄ = 1/5).
        let mut density = vec![0f32; 27];
        for z in 0..3 {
            density[1 + 3 * (1 + 3 * z)] = 1.0;
        }
        let v = CloudVolume::new([3, 3, 3], [0.0; 3], 10.0, 0.0, density).unwrap();
        let mode = SliceMode::Faithful {
            attenuation_ratio: 0.5,
        };
        let light = propagate_f64(&v, [0.0, 0.0, 1.0], mode).unwrap();
        let centre = |z: usize| light[1 + 3 * (1 + 3 * z)];
        let per_slice = 1.0 - 0.5 / 5.0;
        assert_eq!(centre(2), 1.0);
        assert!((centre(1) - per_slice).abs() < 1e-15);
        assert!((centre(0) - per_slice * per_slice).abs() < 1e-15);
    }

    #[test]
    fn faithful_offsets_follow_the_ray() {
        let v = blob(8, 0.01);
        let mode = SliceMode::Faithful {
            attenuation_ratio: 0.5,
        };
        let plan = SlicePlan::new(&v, [0.3, -0.7, 1.0], mode).unwrap();
        let total = plan
            .offsets
            .iter()
            .fold([0, 0], |acc, o| [acc[0] + o[0], acc[1] + o[1]]);
        // After 7 steps the offsets add up to round(7·s).
        assert_eq!(total, [2, -5]);
    }

    #[test]
    fn f32_twin_tracks_the_f64_instantiation() {
        let v = blob(16, 0.02);
        for to_sun in [[0.2, 0.1, 1.0], [-1.0, 0.4, 0.3]] {
            let a = propagate_f64(&v, to_sun, SliceMode::Physical).unwrap();
            let b = propagate_f32(&v, to_sun, SliceMode::Physical).unwrap();
            let worst = a
                .iter()
                .zip(&b)
                .map(|(x, y)| (x - f64::from(*y)).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-5, "{worst}");
        }
    }
}
