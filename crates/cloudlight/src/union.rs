//! [`UnionField`]: two density fields marched as one cloud, so that one
//! [`march_view`](crate::march::march_view) interleaves their samples along the view ray
//! and its light and ambient marches cross both (each cloud shadows the other).
//!
//! The union is written in the first field's frame and σ_t units: at a point `p` its
//! density is `ρ_a(p) + (k_b/k_a)·ρ_b(p + offset)`, `k` each field's
//! [`extinction_per_density`](DensityField::extinction_per_density) and `offset` the
//! position of the first frame's origin in the second's (the frames differ by a
//! translation only), so `k_a × density` is the sum of the two extinctions. The march's
//! albedo, phase and octaves are the march's own, one for both: the union is exact where
//! the two clouds share them. Its spans are the two fields' spans merged, at most two
//! ([`RaySpans`]): where three remain the two closest are joined across their gap, which
//! holds no density, so the union's density is unchanged (its march only spreads some
//! steps over that gap).

use atmos::real::Real;

use crate::density::{DensityField, RaySpans};

/// A union's construction error, naming the field and value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnionError {
    /// The first field's extinction per density must be finite and > 0 (the union's
    /// density is in its units).
    #[error("first field's extinction_per_density = {value}: must be finite and > 0")]
    FirstExtinction {
        /// The value given.
        value: f64,
    },
    /// The second field's extinction per density must be finite and ≥ 0.
    #[error("second field's extinction_per_density = {value}: must be finite and ≥ 0")]
    SecondExtinction {
        /// The value given.
        value: f64,
    },
    /// The frames' offset must be finite.
    #[error("offset component {axis} = {value}: must be finite")]
    Offset {
        /// The axis (0, 1, 2).
        axis: usize,
        /// The value given.
        value: f64,
    },
}

/// Two density fields as one, in the first one's frame and σ_t units (module docs).
#[derive(Debug, Clone, Copy)]
pub struct UnionField<'a, F, A: ?Sized, B: ?Sized> {
    first: &'a A,
    second: &'a B,
    offset: [F; 3],
    scale: F,
}

impl<'a, F: Real, A: DensityField<F> + ?Sized, B: DensityField<F> + ?Sized>
    UnionField<'a, F, A, B>
{
    /// `first` and `second`, a point `p` of the first's frame being `p + offset` (m) in
    /// the second's.
    pub fn new(first: &'a A, second: &'a B, offset: [f64; 3]) -> Result<Self, UnionError> {
        let to_f64 = |v: F| v.to_f64().unwrap_or(f64::NAN);
        let k_a = to_f64(first.extinction_per_density());
        let k_b = to_f64(second.extinction_per_density());
        if !(k_a > 0.0 && k_a.is_finite()) {
            return Err(UnionError::FirstExtinction { value: k_a });
        }
        if !(k_b >= 0.0 && k_b.is_finite()) {
            return Err(UnionError::SecondExtinction { value: k_b });
        }
        for (axis, &value) in offset.iter().enumerate() {
            if !value.is_finite() {
                return Err(UnionError::Offset { axis, value });
            }
        }
        Ok(Self {
            first,
            second,
            offset: offset.map(F::of),
            scale: F::of(k_b / k_a),
        })
    }

    /// A point of the first field's frame in the second's.
    pub fn to_second(&self, p: [F; 3]) -> [F; 3] {
        std::array::from_fn(|a| p[a] + self.offset[a])
    }

    /// Each field's own density at `p` (first frame), in its own units.
    pub fn densities(&self, p: [F; 3]) -> [F; 2] {
        [
            self.first.density(p),
            self.second.density(self.to_second(p)),
        ]
    }
}

/// Joins `spans` (sorted by entry) that overlap or touch, then the closest pairs across
/// their gaps until at most two remain.
fn merge_spans<F: Real>(mut spans: Vec<(F, F)>) -> RaySpans<F> {
    spans.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
    let mut merged: Vec<(F, F)> = Vec::with_capacity(spans.len());
    for (enter, exit) in spans {
        match merged.last_mut() {
            Some(last) if enter <= last.1 => last.1 = last.1.max(exit),
            _ => merged.push((enter, exit)),
        }
    }
    while merged.len() > 2 {
        let closest = (1..merged.len())
            .min_by(|&i, &j| {
                let gap = |k: usize| merged[k].0 - merged[k - 1].1;
                gap(i)
                    .partial_cmp(&gap(j))
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
            .expect("more than two spans");
        merged[closest - 1].1 = merged[closest].1;
        merged.remove(closest);
    }
    let mut out = RaySpans::none();
    for (i, &span) in merged.iter().enumerate() {
        out.spans[i] = span;
    }
    out.count = merged.len();
    out
}

impl<F: Real, A: DensityField<F> + ?Sized, B: DensityField<F> + ?Sized> DensityField<F>
    for UnionField<'_, F, A, B>
{
    fn density(&self, p: [F; 3]) -> F {
        let [a, b] = self.densities(p);
        a + self.scale * b
    }

    fn extinction_per_density(&self) -> F {
        self.first.extinction_per_density()
    }

    fn ray_spans(&self, origin: [F; 3], direction: [F; 3]) -> RaySpans<F> {
        let a = self.first.ray_spans(origin, direction);
        let b = self.second.ray_spans(self.to_second(origin), direction);
        merge_spans(a.as_slice().iter().chain(b.as_slice()).copied().collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::CloudVolume;
    use crate::march::{Lighting, MarchConfig, MarchSettings, march_view};

    fn block(origin: [f64; 3], sigma: f64) -> CloudVolume {
        CloudVolume::new([2, 2, 2], origin, 10.0, sigma, vec![1.0; 8]).unwrap()
    }

    #[test]
    fn a_union_sums_the_extinctions_in_the_second_frame() {
        // Two 20 m unit blocks along +x: the first at x ∈ [0, 20] (σ 0.02), the second
        // in a frame shifted by 1000 m at x ∈ [1040, 1060] there, i.e. [40, 60] here
        // (σ 0.05).
        let a = block([0.0; 3], 0.02);
        let b = block([1040.0, 1000.0, 1000.0], 0.05);
        let union = UnionField::<f64, _, _>::new(&a, &b, [1000.0; 3]).unwrap();
        assert_eq!(union.density([10.0, 10.0, 10.0]), 1.0);
        assert!((union.density([50.0, 10.0, 10.0]) - 2.5).abs() < 1e-12);
        assert_eq!(union.density([30.0, 10.0, 10.0]), 0.0);
        let spans = union.ray_spans([-10.0, 10.0, 10.0], [1.0, 0.0, 0.0]);
        assert_eq!(spans.as_slice(), &[(10.0, 30.0), (50.0, 70.0)]);
        // One march: e^{−(0.02·20 + 0.05·20)} (the steps align with the blocks).
        let settings = MarchSettings::new(MarchConfig {
            view_steps: 8,
            ..MarchConfig::default()
        })
        .unwrap();
        let lighting = Lighting::white_sun([0.0, 0.0, 1.0]).unwrap();
        let r = march_view(
            &union,
            [-10.0, 10.0, 10.0],
            [1.0, 0.0, 0.0],
            &settings,
            &lighting,
        );
        assert!((r.transmittance - (-1.4f64).exp()).abs() < 1e-12);
        // Overlapping: the second block moved onto the first doubles its σ_t sum.
        let c = block([1000.0; 3], 0.05);
        let overlap = UnionField::<f64, _, _>::new(&a, &c, [1000.0; 3]).unwrap();
        assert!((overlap.density([5.0, 5.0, 5.0]) - 3.5).abs() < 1e-12);
        let r = march_view(
            &overlap,
            [-10.0, 10.0, 10.0],
            [1.0, 0.0, 0.0],
            &settings,
            &lighting,
        );
        assert!((r.transmittance - (-1.4f64).exp()).abs() < 1e-12);
    }

    #[test]
    fn three_spans_join_the_closest_two_and_bad_inputs_are_named() {
        let merged = merge_spans(vec![(0.0, 1.0), (10.0, 11.0), (2.0, 3.0)]);
        assert_eq!(merged.as_slice(), &[(0.0, 3.0), (10.0, 11.0)]);
        let touching = merge_spans(vec![(0.0, 1.0), (1.0, 2.0)]);
        assert_eq!(touching.as_slice(), &[(0.0, 2.0)]);
        let a = block([0.0; 3], 0.02);
        let err = UnionField::<f64, _, _>::new(&a, &a, [f64::NAN, 0.0, 0.0]).unwrap_err();
        assert!(matches!(err, UnionError::Offset { axis: 0, value } if value.is_nan()));
    }
}
