// The air in front of a billboard particle (no bindings: render::billboard_clouds
// imports it, and the parity case calls it alone).

// The colour a particle carries once seen through the air in front of it:
// colour · T_air + L_air. Twin: render::billboard_clouds::billboard_seen_through_air.
fn billboard_seen_through_air(colour: vec3<f32>, air_transmittance: vec3<f32>, air_radiance: vec3<f32>) -> vec3<f32> {
    return colour * air_transmittance + air_radiance;
}
