//! Comparing one side (the f32 CPU twin or the GPU) against the f64 reference.

/// f32 unit roundoff, 2⁻²⁴: half an ULP at 1.0. Forward-error bounds are written in it.
pub const UNIT_ROUNDOFF: f64 = 1.0 / 16_777_216.0;

/// A forward-error bound: extra absolute allowance per output element, from the inputs.
pub type ForwardBound = fn(&[f64]) -> Vec<f64>;

/// Per-case tolerance. An output element passes when
/// `|value − reference| ≤ abs + rel·|reference| + ulp·ulp_f32(reference) + bound(inputs)`,
/// where `bound` is an optional forward-error bound computed from the inputs (for
/// functions whose conditioning depends on them, e.g. near-tangent rays).
#[derive(Clone, Copy)]
pub struct Tolerance {
    /// Absolute floor (e.g. `f32::MIN_POSITIVE` where WGSL may flush subnormals).
    pub abs: f64,
    /// Relative allowance.
    pub rel: f64,
    /// Allowance in f32 ULPs of the reference.
    pub ulp: f64,
    /// Extra absolute allowance per output element from a forward-error analysis.
    pub bound: Option<ForwardBound>,
    /// Why these numbers (printed in the report).
    pub why: &'static str,
}

impl std::fmt::Debug for Tolerance {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.describe())
    }
}

impl Tolerance {
    /// Short form for the table: `abs 1e-38 + rel 0 + 16 ulp (+ bound)`.
    pub fn describe(&self) -> String {
        let mut parts = Vec::new();
        if self.abs > 0.0 {
            parts.push(format!("abs {:.0e}", self.abs));
        }
        if self.rel > 0.0 {
            parts.push(format!("rel {:.0e}", self.rel));
        }
        if self.ulp > 0.0 {
            parts.push(format!("{} ulp", self.ulp));
        }
        if self.bound.is_some() {
            parts.push("fwd bound".into());
        }
        if parts.is_empty() {
            "exact".into()
        } else {
            parts.join(" + ")
        }
    }

    /// Allowed absolute error for output `k` of an element with these inputs.
    pub fn allowed(&self, reference: f64, bound: Option<f64>) -> f64 {
        self.abs + self.rel * reference.abs() + self.ulp * ulp_f32(reference) + bound.unwrap_or(0.0)
    }
}

/// The spacing of f32 values at `x` (the ULP), for finite `x`.
pub fn ulp_f32(x: f64) -> f64 {
    let v = (x as f32).abs();
    if !v.is_finite() {
        return f64::INFINITY;
    }
    let next = f32::from_bits(v.to_bits() + 1);
    f64::from(next) - f64::from(v)
}

/// Distance in representable f32 values between `a` and `b` (0 when equal).
pub fn ulp_distance(a: f32, b: f32) -> u64 {
    fn ordered(x: f32) -> i64 {
        let bits = i64::from(x.to_bits() as i32);
        if bits < 0 {
            i64::from(i32::MIN) - bits
        } else {
            bits
        }
    }
    if a.is_nan() || b.is_nan() {
        return u64::MAX;
    }
    ordered(a).abs_diff(ordered(b))
}

/// Statistics of one side against the reference.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SideStats {
    /// Elements compared (inputs × outputs).
    pub elements: usize,
    /// Largest absolute error.
    pub max_abs: f64,
    /// Largest relative error over elements with |reference| > the absolute floor.
    pub max_rel: f64,
    /// Largest distance in f32 ULPs from the reference rounded to f32, over the
    /// elements where the absolute floor does not govern.
    pub max_ulp: u64,
    /// 99th percentile of the relative error.
    pub p99_rel: f64,
    /// Largest error / allowed ratio (≤ 1 passes).
    pub worst_ratio: f64,
    /// Index of the element with the largest ratio.
    pub worst_index: usize,
    /// Elements over tolerance (including non-finite values).
    pub failures: usize,
}

impl SideStats {
    /// True when every element is within tolerance.
    pub fn passed(&self) -> bool {
        self.failures == 0
    }
}

/// Compares `values` (f32 side) with `reference` (f64) element by element.
/// `bounds[i]` is the optional forward-error allowance for element `i`.
pub fn compare(
    values: &[f32],
    reference: &[f64],
    bounds: Option<&[f64]>,
    tolerance: &Tolerance,
) -> SideStats {
    assert_eq!(
        values.len(),
        reference.len(),
        "side and reference lengths differ"
    );
    let mut stats = SideStats {
        elements: values.len(),
        ..Default::default()
    };
    let mut relative_errors = Vec::with_capacity(values.len());
    for (i, (&value, &expected)) in values.iter().zip(reference).enumerate() {
        let allowed = tolerance.allowed(expected, bounds.map(|b| b[i]));
        let error = if value.is_nan() || expected.is_nan() {
            f64::INFINITY
        } else if value.is_infinite() || expected.is_infinite() {
            if f64::from(value) == expected {
                0.0
            } else {
                f64::INFINITY
            }
        } else {
            (f64::from(value) - expected).abs()
        };
        let ratio = if error == 0.0 { 0.0 } else { error / allowed };
        // NaN ratios (a NaN error) fail too.
        let within = ratio <= 1.0;
        if !within {
            stats.failures += 1;
        }
        if ratio > stats.worst_ratio || (ratio.is_nan() && !stats.worst_ratio.is_nan()) {
            stats.worst_ratio = ratio;
            stats.worst_index = i;
        }
        stats.max_abs = stats.max_abs.max(error);
        // Relative and ULP errors are reported where the absolute floor does not
        // govern (e.g. not for subnormal results that WGSL may flush to zero).
        if expected.abs() > tolerance.abs.max(f64::from(f32::MIN_POSITIVE)) || expected == 0.0 {
            stats.max_ulp = stats.max_ulp.max(ulp_distance(value, expected as f32));
        }
        if expected.abs() > tolerance.abs.max(f64::from(f32::MIN_POSITIVE)) {
            let rel = error / expected.abs();
            stats.max_rel = stats.max_rel.max(rel);
            relative_errors.push(rel);
        }
    }
    if !relative_errors.is_empty() {
        relative_errors.sort_by(f64::total_cmp);
        let index = ((relative_errors.len() as f64) * 0.99).ceil() as usize;
        stats.p99_rel = relative_errors[index.clamp(1, relative_errors.len()) - 1];
    }
    stats
}

/// The injected difference used by self-tests and `--inject`: element `index` is moved
/// to four times its allowed error (at least one f32 step away from the reference).
pub fn inject_difference(
    values: &mut [f32],
    reference: &[f64],
    bounds: Option<&[f64]>,
    tolerance: &Tolerance,
    index: usize,
) {
    let expected = reference[index];
    let allowed = tolerance.allowed(expected, bounds.map(|b| b[index]));
    let target = expected + 4.0 * allowed.max(ulp_f32(expected));
    values[index] = if target.is_finite() {
        target as f32
    } else {
        f32::NAN
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: Tolerance = Tolerance {
        abs: 0.0,
        rel: 0.0,
        ulp: 4.0,
        bound: None,
        why: "test",
    };

    #[test]
    fn ulp_helpers() {
        assert_eq!(ulp_distance(1.0, 1.0), 0);
        assert_eq!(ulp_distance(1.0, f32::from_bits(1.0f32.to_bits() + 3)), 3);
        assert_eq!(ulp_distance(-0.0, 0.0), 0);
        assert_eq!(ulp_distance(-f32::from_bits(1), f32::from_bits(1)), 2);
        assert_eq!(ulp_f32(1.0), f64::from(f32::EPSILON));
    }

    #[test]
    fn exact_values_pass_and_injected_difference_fails() {
        let reference: Vec<f64> = (1..1000).map(|i| f64::from(i) * 0.37).collect();
        let mut values: Vec<f32> = reference.iter().map(|&r| r as f32).collect();
        assert!(compare(&values, &reference, None, &T).passed());
        inject_difference(&mut values, &reference, None, &T, 500);
        let stats = compare(&values, &reference, None, &T);
        assert_eq!(stats.failures, 1);
        assert_eq!(stats.worst_index, 500);
    }

    #[test]
    fn boundary_of_the_tolerance() {
        // 4 ULPs pass, 5 fail.
        let reference = [1.0f64];
        let four = f32::from_bits(1.0f32.to_bits() + 4);
        let five = f32::from_bits(1.0f32.to_bits() + 5);
        assert!(compare(&[four], &reference, None, &T).passed());
        assert!(!compare(&[five], &reference, None, &T).passed());
    }

    #[test]
    fn nan_and_infinity_fail() {
        assert!(!compare(&[f32::NAN], &[1.0], None, &T).passed());
        assert!(!compare(&[f32::INFINITY], &[1.0], None, &T).passed());
        assert!(!compare(&[1.0], &[f64::NAN], None, &T).passed());
    }

    #[test]
    fn bounds_widen_only_their_element() {
        let reference = [1.0f64, 1.0];
        let values = [1.001f32, 1.001];
        let bounds = [0.01, 0.0];
        let stats = compare(&values, &reference, Some(&bounds), &T);
        assert_eq!(stats.failures, 1);
        assert_eq!(stats.worst_index, 1);
    }

    #[test]
    fn absolute_floor_covers_flushed_subnormals() {
        let t = Tolerance {
            abs: f64::from(f32::MIN_POSITIVE),
            ..T
        };
        // exp(−95) ≈ 5.5e−42 flushes to 0 on GPUs: allowed by the floor, not by ULPs.
        let tiny = (-95.0f64).exp();
        assert!(compare(&[0.0], &[tiny], None, &t).passed());
        assert!(!compare(&[0.0], &[tiny], None, &T).passed());
    }
}
