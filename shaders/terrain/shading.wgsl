// terrain::shading — the terrain surface term of Hoffman & Preetham 2002.
// Twin: terrain::shadow::terrain_shading (Rust): same name, argument order and units.

// (N.L) * albedo * self_shadow * cloud_shadow, N.L clamped at 0; normal and
// sun_direction are unit vectors in the same frame (east-north-up for terrain maps).
fn terrain_shading(normal: vec3<f32>, sun_direction: vec3<f32>, albedo: vec3<f32>, self_shadow: f32, cloud_shadow: f32) -> vec3<f32> {
    let k = max(dot(normal, sun_direction), 0.0) * self_shadow * cloud_shadow;
    return albedo * k;
}
