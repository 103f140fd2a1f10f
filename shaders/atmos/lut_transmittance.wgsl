// Bake of the transmittance LUT: one invocation per texel. Twin:
// atmos::lut::transmittance_lut::transmittance_texel.
#import atmos::lut_sampling

@group(2) @binding(0) var transmittance_out: texture_storage_2d<rgba32float, write>;

// exp(−optical depth to the top): uniform steps, exponential profiles integrated
// log-linearly, the ozone tent by the trapezoid rule.
fn transmittance_texel(x: u32, y: u32) -> vec4<f32> {
    let w = lut_settings.transmittance_width;
    let h = lut_settings.transmittance_height;
    let uv = vec2<f32>((f32(x) + 0.5) / f32(w), (f32(y) + 0.5) / f32(h));
    let r_mu = transmittance_lut_r_mu(uv, lut_atmosphere.planet_radius, lut_atmosphere.top_radius, w, h);
    let r = r_mu.x;
    let mu = r_mu.y;
    let ray_length = max(ray_sphere_intersect(r, mu, lut_atmosphere.top_radius).y, 0.0);
    let n = lut_settings.transmittance_samples;
    let dt = ray_length / f32(n);
    let a = lut_atmosphere;
    var rayleigh = 0.0;
    var mie = 0.0;
    var ozone = 0.0;
    var altitude_previous = altitude_along_ray(r, mu, 0.0, a.planet_radius);
    for (var i = 0u; i < n; i++) {
        let t = (f32(i) + 1.0) * dt;
        let altitude = altitude_along_ray(r, mu, t, a.planet_radius);
        rayleigh += exponential_step_integral(altitude_previous / a.rayleigh_scale_height, altitude / a.rayleigh_scale_height, dt);
        mie += exponential_step_integral(altitude_previous / a.mie_scale_height, altitude / a.mie_scale_height, dt);
        ozone += 0.5 * dt * (tent_density(altitude_previous, a.ozone_center_altitude, a.ozone_half_width)
            + tent_density(altitude, a.ozone_center_altitude, a.ozone_half_width));
        altitude_previous = altitude;
    }
    let optical_depth = a.rayleigh_scattering * rayleigh + a.mie_extinction * mie + a.ozone_absorption * ozone;
    return vec4<f32>(exp(-optical_depth), 1.0);
}

@compute @workgroup_size(8, 8)
fn bake_transmittance_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.transmittance_width;
    if id.x >= w || id.y >= lut_settings.transmittance_height {
        return;
    }
    textureStore(transmittance_out, id.xy, transmittance_texel(id.x, id.y));
}
