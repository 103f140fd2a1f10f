// Optical length through an exponential density layer.
// Twin: atmos::optical_depth (f32) and atmos::reference (f64).
#import atmos::geometry

// ∫₀^ray_length exp(−altitude(t)/scale_height) dt (m), by the midpoint rule with
// sample_count samples. Multiply by the sea-level extinction coefficient (1/m) to
// get the optical depth. Altitudes below the ground count as density exp(−h/H) > 1
// (the caller clips rays at the ground).
fn optical_length_exponential(
    r: f32,
    mu: f32,
    ray_length: f32,
    planet_radius: f32,
    scale_height: f32,
    sample_count: u32,
) -> f32 {
    let n = max(sample_count, 1u);
    let dt = ray_length / f32(n);
    var sum = 0.0;
    for (var i = 0u; i < n; i++) {
        let t = (f32(i) + 0.5) * dt;
        sum += exp(-altitude_along_ray(r, mu, t, planet_radius) / scale_height);
    }
    return sum * dt;
}
