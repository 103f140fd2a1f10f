// Bake of the multiple-scattering LUT (after Hillaire 2020 §5.5): one invocation per
// texel, n × n stratified directions, each marched with uniform midpoint steps.
// Ψ_ms = Σ_{k≥2} Ψ_k, one pass per order: `bake_multiple_scattering_lut` writes Ψ₂
// (true phases of the sun's scattering, ground bounce) to both outputs;
// `bake_multiple_scattering_next_order` reads Ψ_k (group 1 binding 1), writes Ψ_{k+1}
// and adds it to the sum. Twin: atmos::lut::multiple_scattering_lut.
#import atmos::lut_sampling

// Ψ₂ or Ψ_{k+1}: this pass's order.
@group(2) @binding(0) var<storage, read_write> multiple_scattering_out: array<vec4<f32>>;
// Σ of the orders so far: the LUT the other passes read.
@group(2) @binding(1) var<storage, read_write> multiple_scattering_sum: array<vec4<f32>>;

// The (r, μ_s) of texel (x, y) of the multiple-scattering LUT.
fn texel_r_mu_s(x: u32, y: u32) -> vec2<f32> {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    let uv = vec2<f32>((f32(x) + 0.5) / f32(w), (f32(y) + 0.5) / f32(h));
    return multiple_scattering_lut_r_mu_s(uv, lut_atmosphere.planet_radius, lut_atmosphere.top_radius, w, h);
}

fn multiple_scattering_texel(x: u32, y: u32) -> vec4<f32> {
    let r_mu_s = texel_r_mu_s(x, y);
    let r = r_mu_s.x;
    let mu_s = r_mu_s.y;
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    let k = lut_settings.multiple_scattering_direction_sqrt;
    var second_order = vec3<f32>(0.0);
    for (var i = 0u; i < k; i++) {
        let mu = -1.0 + (f32(i) + 0.5) * 2.0 / f32(k);
        let sin_v = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
        let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
        let n = lut_settings.multiple_scattering_samples;
        let dt = (segment.y - segment.x) / f32(n);
        for (var j = 0u; j < k; j++) {
            let azimuth = 2.0 * PI * (f32(j) + 0.5) / f32(k);
            let nu = mu * mu_s + sin_v * sin_s * cos(azimuth);
            // Sunlight scattered at p into −ω turns by the angle whose cosine is ω·s = ν.
            let rayleigh_phase_value = rayleigh_phase(nu);
            let mie_phase_value = cornette_shanks_phase(nu, lut_atmosphere.mie_g);
            var throughput = vec3<f32>(1.0);
            for (var step = 0u; step < n; step++) {
                let t = segment.x + (f32(step) + 0.5) * dt;
                let r_t = radius_along_ray(r, mu, t);
                let mu_s_t = clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0);
                let medium = medium_at_altitude(lut_atmosphere, r_t - lut_atmosphere.planet_radius);
                let sun = sun_transmittance(r_t, mu_s_t);
                let scattering = medium.rayleigh_scattering * rayleigh_phase_value
                    + medium.mie_scattering * mie_phase_value;
                let weight = vec3<f32>(
                    scattering_step_fraction(medium.extinction.x, dt),
                    scattering_step_fraction(medium.extinction.y, dt),
                    scattering_step_fraction(medium.extinction.z, dt),
                );
                second_order += throughput * scattering * sun * weight;
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
    return vec4<f32>(second_order / directions, 1.0);
}

fn multiple_scattering_next_order_texel(x: u32, y: u32) -> vec4<f32> {
    let r_mu_s = texel_r_mu_s(x, y);
    let r = r_mu_s.x;
    let mu_s = r_mu_s.y;
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    let k = lut_settings.multiple_scattering_direction_sqrt;
    var next_order = vec3<f32>(0.0);
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
                let previous = lookup_multiple_scattering(r_t, mu_s_t);
                let scattering = medium.rayleigh_scattering + medium.mie_scattering;
                let weight = vec3<f32>(
                    scattering_step_fraction(medium.extinction.x, dt),
                    scattering_step_fraction(medium.extinction.y, dt),
                    scattering_step_fraction(medium.extinction.z, dt),
                );
                next_order += throughput * scattering * previous * weight;
                throughput *= exp(-medium.extinction * dt);
            }
            if segment.z > 0.5 {
                // The ground under an isotropic field Ψ_k receives π Ψ_k and reflects
                // ρ/π of it as radiance.
                let r_g = radius_along_ray(r, mu, segment.y);
                let mu_s_g = clamp((r * mu_s + segment.y * nu) / r_g, -1.0, 1.0);
                let previous = lookup_multiple_scattering(r_g, mu_s_g);
                next_order += throughput * previous * lut_atmosphere.ground_albedo;
            }
        }
    }
    let directions = f32(k * k);
    return vec4<f32>(next_order / directions, 1.0);
}

@compute @workgroup_size(8, 8)
fn bake_multiple_scattering_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.multiple_scattering_width;
    if id.x >= w || id.y >= lut_settings.multiple_scattering_height {
        return;
    }
    let texel = multiple_scattering_texel(id.x, id.y);
    multiple_scattering_out[id.x + w * id.y] = texel;
    multiple_scattering_sum[id.x + w * id.y] = texel;
}

@compute @workgroup_size(8, 8)
fn bake_multiple_scattering_next_order(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.multiple_scattering_width;
    if id.x >= w || id.y >= lut_settings.multiple_scattering_height {
        return;
    }
    let index = id.x + w * id.y;
    let texel = multiple_scattering_next_order_texel(id.x, id.y);
    multiple_scattering_out[index] = texel;
    let total = multiple_scattering_sum[index];
    multiple_scattering_sum[index] = vec4<f32>(total.xyz + texel.xyz, 1.0);
}
