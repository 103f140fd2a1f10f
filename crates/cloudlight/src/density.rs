//! [`DensityField`]: what a view or light march needs to know about a cloud, whatever
//! made it — a [`CloudVolume`] grid (Dobashi et al. 2000's automaton, or any user grid) or a
//! procedural shell around the planet (Schneider's Nubis).
//!
//! A field is written in one frame of metres (the volume's world frame, or planet-centred
//! for a shell) and answers two questions: the dimensionless density at a point, and the
//! spans of a ray (at most two: a spherical shell seen through its inner sphere) outside
//! which the density is zero. The extinction is `extinction_per_density() × density`, in
//! 1/m. The trait is generic over the float type so the f64 reference and the f32 twin of
//! the WGSL march the same field.

use atmos::real::Real;

use crate::CloudVolume;

/// The parts of a ray `origin + t·direction` (`t ≥ 0`, metres) where a field may be
/// non-zero, nearest first; `count` of the two `spans` are used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaySpans<F> {
    /// `(t_enter, t_exit)` pairs, `0 ≤ t_enter ≤ t_exit`, ordered and disjoint.
    pub spans: [(F, F); 2],
    /// How many of `spans` hold (0, 1 or 2).
    pub count: usize,
}

impl<F: Real> RaySpans<F> {
    /// No span: the ray misses the field.
    pub fn none() -> Self {
        Self {
            spans: [(F::zero(), F::zero()); 2],
            count: 0,
        }
    }

    /// One span `[enter, exit]`.
    pub fn one(enter: F, exit: F) -> Self {
        Self {
            spans: [(enter, exit), (F::zero(), F::zero())],
            count: 1,
        }
    }

    /// The used spans.
    pub fn as_slice(&self) -> &[(F, F)] {
        &self.spans[..self.count]
    }

    /// Total length inside the spans, metres.
    pub fn length(&self) -> F {
        self.as_slice()
            .iter()
            .fold(F::zero(), |sum, &(a, b)| sum + (b - a))
    }
}

/// A cloud's density in space, in one precision `F`.
pub trait DensityField<F: Real> {
    /// Dimensionless density (≥ 0) at point `p`, metres in the field's frame.
    fn density(&self, p: [F; 3]) -> F;

    /// Extinction per unit density σ_t, 1/m (the cloud's extinction is `σ_t · density`).
    fn extinction_per_density(&self) -> F;

    /// The spans of the ray `origin + t·direction` (unit `direction`, `t ≥ 0`) outside
    /// which [`density`](Self::density) is zero.
    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> RaySpans<F>;
}

/// The volume's trilinear density ([`CloudVolume::density_at`]), evaluated in f64 for
/// either precision: the grid stores f32 and the f64 interpolation is exact enough that
/// the march, not the lookup, is what a twin's error measures.
impl<F: Real> DensityField<F> for CloudVolume {
    fn density(&self, p: [F; 3]) -> F {
        let p = p.map(|c| c.to_f64().unwrap_or(f64::NAN));
        F::of(self.density_at(p))
    }

    fn extinction_per_density(&self) -> F {
        F::of(CloudVolume::extinction_per_density(self))
    }

    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> RaySpans<F> {
        let lo = self.origin();
        let dims = self.dims();
        let size = self.voxel_size();
        let mut enter = F::zero();
        let mut exit = F::infinity();
        for axis in 0..3 {
            let lo_axis = F::of(lo[axis]);
            let hi_axis = F::of(lo[axis] + f64::from(dims[axis]) * size);
            let (o, d) = (origin[axis], direction[axis]);
            if d == F::zero() {
                if o < lo_axis || o > hi_axis {
                    return RaySpans::none();
                }
                continue;
            }
            let (t0, t1) = ((lo_axis - o) / d, (hi_axis - o) / d);
            enter = enter.max(t0.min(t1));
            exit = exit.min(t0.max(t1));
        }
        if enter <= exit {
            RaySpans::one(enter, exit)
        } else {
            RaySpans::none()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_volume_spans_its_box_along_a_ray() {
        let v = CloudVolume::new([4, 2, 1], [10.0, 0.0, 0.0], 5.0, 0.1, vec![1.0; 8]).unwrap();
        // Along +x through the middle: enters at x = 10, leaves at x = 30.
        let spans: RaySpans<f64> = v.ray_spans([0.0, 5.0, 2.5], [1.0, 0.0, 0.0]);
        assert_eq!(spans.as_slice(), &[(10.0, 30.0)]);
        assert_eq!(spans.length(), 20.0);
        // Starting inside: the span starts at 0.
        let inside: RaySpans<f32> = v.ray_spans([20.0, 5.0, 2.5], [0.0, 0.0, 1.0]);
        assert_eq!(inside.as_slice(), &[(0.0, 2.5)]);
        // Parallel to a face, outside it: no span.
        let miss: RaySpans<f64> = v.ray_spans([0.0, 20.0, 2.5], [1.0, 0.0, 0.0]);
        assert_eq!(miss.count, 0);
        // Pointing away: no span.
        let away: RaySpans<f64> = v.ray_spans([0.0, 5.0, 2.5], [-1.0, 0.0, 0.0]);
        assert_eq!(away.count, 0);
        assert_eq!(DensityField::<f64>::density(&v, [15.0, 5.0, 2.5]), 1.0);
        assert_eq!(DensityField::<f32>::extinction_per_density(&v), 0.1);
    }
}
