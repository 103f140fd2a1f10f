// Slice propagation (Dobashi et al. 2000), the per-texel arithmetic. Twins: cloudlight::propagate
// (Rust, generic over the float type: the f32 instantiation mirrors these operations).
// The pass that sweeps the slices is cloudlight::slice_propagation_pass.

// Physical mode: the optical depth at a centre from the depth and density resampled on
// the previous slice and this centre's density, a trapezoid over one spacing along the
// light; sigma_ds = σ_t·Δs (1/m per unit density times metres).
fn slice_optical_depth(tau_prev: f32, rho_prev: f32, rho: f32, sigma_ds: f32) -> f32 {
    // Each density times ½σΔs before the sum: σ_t = 0 gives 0 even for huge densities.
    let half_step = 0.5 * sigma_ds;
    // Saturated at 1e30 (exp(−τ) is 0 long before): no ∞ meets a zero weight later.
    return min(tau_prev + (half_step * rho_prev + half_step * rho), 1e30);
}

// Dobashi et al. 2000's 5-tap cross smoothing of the density.
fn cross_smooth(centre: f32, left: f32, right: f32, down: f32, up: f32) -> f32 {
    return (centre + left + right + down + up) / 5.0;
}

// Bilinear interpolation of four texels at fractions (fu, fv): along u, then v.
fn bilinear(c00: f32, c10: f32, c01: f32, c11: f32, fu: f32, fv: f32) -> f32 {
    return (1.0 - fv) * ((1.0 - fu) * c00 + fu * c10) + fv * ((1.0 - fu) * c01 + fu * c11);
}

// Catmull–Rom interpolation between p1 and p2 at t in [0, 1] (p0, p3 the outer
// neighbours), Horner form.
fn catmull_rom(p0: f32, p1: f32, p2: f32, p3: f32, t: f32) -> f32 {
    return p1 + 0.5 * t * (p2 - p0 + t * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3 + t * (3.0 * (p1 - p2) + p3 - p0)));
}
