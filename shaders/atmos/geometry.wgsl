// Ray geometry in the planet-centred frame: a point at distance r (m) from the
// centre, a direction whose cosine with the local zenith is mu.
// Twin: atmos::geometry (f32) and atmos::reference (f64).

// Sentinel for "the ray's line misses the sphere" (both components).
const RAY_MISS: f32 = -1.0;

// Signed distances (m) along the ray to the two intersections with a sphere of
// radius sphere_radius centred on the planet: (near, far), near <= far.
// Negative values lie behind the origin. Both are RAY_MISS when the line misses.
//
// Roots of t² + 2 r mu t + (r² − R²) = 0, in the stable form: the root with no
// cancellation, q = −(b + sign(b)√D), and its partner c/q. c = (r − R)(r + R) keeps
// full accuracy for grazing rays close to the sphere (1 m above a 6,360 km planet),
// and is exactly 0 for a camera on the sphere.
fn ray_sphere_intersect(r: f32, mu: f32, sphere_radius: f32) -> vec2<f32> {
    let b = r * mu;
    let c = (r - sphere_radius) * (r + sphere_radius);
    let discriminant = b * b - c;
    if discriminant < 0.0 {
        return vec2<f32>(RAY_MISS, RAY_MISS);
    }
    let sign_b = select(-1.0, 1.0, b >= 0.0);
    let q = -(b + sign_b * sqrt(discriminant));
    if q == 0.0 {
        // b = 0 and c = 0: origin on the sphere, tangent ray.
        return vec2<f32>(0.0, 0.0);
    }
    let t0 = q;
    let t1 = c / q;
    return vec2<f32>(min(t0, t1), max(t0, t1));
}

// Altitude (m) above a sphere of radius planet_radius of the point at distance t
// along the ray. Computed as (r_t² − R²)/(r_t + R) with
// r_t² − R² = (r − R)(r + R) + t (2 r mu + t), which avoids subtracting two
// nearly equal radii (worth ~0.5 m of altitude in f32 at Earth scale).
fn altitude_along_ray(r: f32, mu: f32, t: f32, planet_radius: f32) -> f32 {
    let radius_squared_excess = (r - planet_radius) * (r + planet_radius) + t * (2.0 * r * mu + t);
    let r_t = sqrt(max(r * r + t * (2.0 * r * mu + t), 0.0));
    return radius_squared_excess / (r_t + planet_radius);
}
