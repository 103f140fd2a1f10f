// The volume cloud seen through the air in front of it (no bindings, so parity can call
// it): the composite (render::volume_clouds) adds one term per light.

// Twin of render::volume_clouds::cloud_through_air: the cloud's radiance (cloud.rgb)
// attenuated by the air to its depth, plus the air's in-scatter in proportion to the
// cloud's opacity (1 − T_c, T_c = cloud.w); the caller adds T_c · L_behind.
fn cloud_through_air(cloud: vec4<f32>, air_transmittance: vec3<f32>, air_radiance: vec3<f32>) -> vec3<f32> {
    return cloud.rgb * air_transmittance + air_radiance * (1.0 - cloud.w);
}
