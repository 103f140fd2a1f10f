// Bake of the multiple-scattering LUT (Hillaire 2020 §5.5): one invocation per
// texel, n × n stratified directions, each marched with uniform midpoint steps;
// Ψ_ms = L₂ / (1 − f_ms). Twin: atmos::lut::multiple_scattering_lut.
#import atmos::lut_sampling

@group(2) @binding(0) var<storage, read_write> multiple_scattering_out: array<vec4<f32>>;

fn multiple_scattering_texel(x: u32, y: u32) -> vec4<f32> {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    let uv = vec2<f32>((f32(x) + 0.5) / f32(w), (f32(y) + 0.5) / f32(h));
    let r_mu_s = multiple_scattering_lut_r_mu_s(uv, lut_atmosphere.planet_radius, lut_atmosphere.top_radius, w, h);
    let r = r_mu_s.x;
    let mu_s = r_mu_s.y;
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    let k = lut_settings.multiple_scattering_direction_sqrt;
    let isotropic_phase = 1.0 / (4.0 * PI);
    var second_order = vec3<f32>(0.0);
    var transfer = vec3<f32>(0.0);
    for (var i = 0u; i < k; i++) {
        let mu = -1.0 + (f32(i) + 0.5) * 2.0 / f32(k);
        let sin_v = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
        let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
        let n = lut_settings.multiple_scattering_samples;
        let dt = (segment.y - segment.x) / f32(n);
        for (var j = 0u; j < k; j++) {
            let azimuth = 2.0 * PI * (f32(j) + 0.5) / f32(k);
            let nu = mu * mu_s + sin_v * sin_s * cos(azimuth);
            var throughput = vec3<f32>(1.0);
            for (var step = 0u; step < n; step++) {
                let t = segment.x + (f32(step) + 0.5) * dt;
                let r_t = radius_along_ray(r, mu, t);
                let mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
                let medium = medium_at_altitude(lut_atmosphere, r_t - lut_atmosphere.planet_radius);
                let sun = sun_transmittance(r_t, mu_s_t);
                let scattering = medium.rayleigh_scattering + medium.mie_scattering;
                let weight = vec3<f32>(
                    scattering_step_fraction(medium.extinction.x, dt),
                    scattering_step_fraction(medium.extinction.y, dt),
                    scattering_step_fraction(medium.extinction.z, dt),
                );
                second_order += throughput * scattering * sun * isotropic_phase * weight;
                transfer += throughput * scattering * weight;
                throughput *= exp(-medium.extinction * dt);
            }
            if segment.z > 0.5 {
                // Lambertian ground lit by the sun at the hit point.
                let r_g = radius_along_ray(r, mu, segment.y);
                let mu_s_g = clamp((r * mu_s + segment.y * nu) / r_g, -1.0, 1.0);
                let sun = sun_transmittance(r_g, mu_s_g);
                second_order += throughput * sun * max(mu_s_g, 0.0) * lut_atmosphere.ground_albedo / PI;
            }
        }
    }
    let directions = f32(k * k);
    let l2 = second_order / directions;
    // f_ms < 1 by construction (∫ T σ_s ≤ 1 − T); the cap only guards rounding.
    let f_ms = min(transfer / directions, vec3<f32>(0.999));
    return vec4<f32>(l2 / (1.0 - f_ms), 1.0);
}

@compute @workgroup_size(8, 8)
fn bake_multiple_scattering_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.multiple_scattering_width;
    if id.x >= w || id.y >= lut_settings.multiple_scattering_height {
        return;
    }
    multiple_scattering_out[id.x + w * id.y] = multiple_scattering_texel(id.x, id.y);
}
