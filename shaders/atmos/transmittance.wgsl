// Beer–Lambert transmittance and its complement.
// Twin: atmos::transmittance (f32) and atmos::reference (f64).

// exp(−optical_depth) per channel.
fn transmittance_from_optical_depth(optical_depth: vec3<f32>) -> vec3<f32> {
    return exp(-optical_depth);
}

// 1 − exp(−x), accurate to a few ULP for all x, including x → 0 where the direct
// form loses every digit (x = 1e−8 gives 0 in f32). WGSL has no expm1: for
// |x| < 0.5 use the Taylor series in nested (Horner) form, truncated after x⁸
// (remainder < x⁹/9! ≤ 1.1e−8 relative, below half an f32 ULP); beyond, the direct
// form is well conditioned (relative error ≤ ~2.5× that of exp).
fn one_minus_exp_neg(x: f32) -> f32 {
    if abs(x) < 0.5 {
        return x * (1.0 - x * 0.5 * (1.0 - x * (1.0 / 3.0) * (1.0 - x * 0.25 * (1.0 - x * 0.2
            * (1.0 - x * (1.0 / 6.0) * (1.0 - x * (1.0 / 7.0) * (1.0 - x * 0.125)))))));
    }
    return 1.0 - exp(-x);
}
