// Bake of the multiple-scattering LUT (after Hillaire 2020 §5.5, direction-dependent):
// one invocation per texel; n zenith samples crowding at the horizon (see
// direction_zenith_sample) × n azimuths, each marched with uniform midpoint steps; the
// moments Ψ, d and A of the field of orders 1 … N−1 (atmos::lut::multiple_scattering_lut
// has the theory). One pass per order: `bake_multiple_scattering_lut` writes F₁'s
// moments (true phases of the sun's scattering, the sun's ground bounce) to both
// outputs; `bake_multiple_scattering_next_order` reads F_k's (group 1 binding 1),
// writes F_{k+1}'s and adds them to the sum (a storage buffer, planar: layer m of
// texel (x, y) at x + w·(y + h·m)); `finish_multiple_scattering_lut` copies the sum
// into the LUT texture the other passes read. Twin: atmos::lut::multiple_scattering_lut.
#import atmos::lut_sampling

// This pass's order (read as `multiple_scattering_lut` by the next order's pass).
@group(2) @binding(0) var multiple_scattering_out: texture_storage_2d_array<rgba32float, write>;
// Σ of the orders so far.
@group(2) @binding(1) var<storage, read_write> multiple_scattering_sum: array<vec4<f32>>;
// The LUT: the sum, once every order is in.
@group(2) @binding(2) var multiple_scattering_lut_out: texture_storage_2d_array<rgba32float, write>;

// The (r, μ_s) of texel (x, y) of the multiple-scattering LUT.
fn texel_r_mu_s(x: u32, y: u32) -> vec2<f32> {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    let uv = vec2<f32>((f32(x) + 0.5) / f32(w), (f32(y) + 0.5) / f32(h));
    return multiple_scattering_lut_r_mu_s(uv, lut_atmosphere.planet_radius, lut_atmosphere.top_radius, w, h);
}

// Weighted sums over the direction quadrature: of F, F ω, F ω ωᵀ, and of ω, ω ωᵀ
// alone (the quadrature's own means, subtracted so an isotropic field has no
// anisotropy).
struct MomentSums {
    radiance: vec3<f32>,
    radiance_x: vec3<f32>,
    radiance_z: vec3<f32>,
    radiance_xx: vec3<f32>,
    radiance_zz: vec3<f32>,
    radiance_xz: vec3<f32>,
    weight: f32,
    x: f32,
    z: f32,
    xx: f32,
    zz: f32,
}

fn moment_sums_add(sums: ptr<function, MomentSums>, radiance: vec3<f32>, x: f32, z: f32, weight: f32) {
    let f = radiance * weight;
    (*sums).radiance += f;
    (*sums).radiance_x += f * x;
    (*sums).radiance_z += f * z;
    (*sums).radiance_xx += f * x * x;
    (*sums).radiance_zz += f * z * z;
    (*sums).radiance_xz += f * x * z;
    (*sums).weight += weight;
    (*sums).x += weight * x;
    (*sums).z += weight * z;
    (*sums).xx += weight * x * x;
    (*sums).zz += weight * z * z;
}

fn moment_sums_moments(sums: MomentSums) -> MultipleScatteringMoments {
    let psi = sums.radiance / sums.weight;
    return MultipleScatteringMoments(
        psi,
        sums.radiance_x / sums.weight - sums.x / sums.weight * psi,
        sums.radiance_z / sums.weight - sums.z / sums.weight * psi,
        sums.radiance_xx / sums.weight - sums.xx / sums.weight * psi,
        sums.radiance_zz / sums.weight - sums.zz / sums.weight * psi,
        sums.radiance_xz / sums.weight,
    );
}

// One texel of one order's field moments: F₁ (sunlight scattered once, the sun's
// ground bounce) when next_order is false, else F_{k+1} from F_k's table. Both
// integrate the same directions and rays; only the source along a ray and the
// ground's bounce differ.
fn multiple_scattering_order_texel(x: u32, y: u32, next_order: bool) -> MultipleScatteringMoments {
    let r_mu_s = texel_r_mu_s(x, y);
    let r = r_mu_s.x;
    let mu_s = r_mu_s.y;
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    let k = lut_settings.multiple_scattering_direction_sqrt;
    var sums = MomentSums(vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), 0.0, 0.0, 0.0, 0.0, 0.0);
    for (var i = 0u; i < k; i++) {
        let zenith = direction_zenith_sample(r, lut_atmosphere.planet_radius, i, k);
        let mu = zenith.x;
        let sin_v = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
        let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
        let n = lut_settings.multiple_scattering_samples;
        let dt = (segment.y - segment.x) / f32(n);
        for (var j = 0u; j < k; j++) {
            let azimuth = 2.0 * PI * (f32(j) + 0.5) / f32(k);
            let cos_azimuth = cos(azimuth);
            let nu = mu * mu_s + sin_v * sin_s * cos_azimuth;
            // Sunlight scattered at p into −ω turns by the angle whose cosine is ω·s = ν.
            let rayleigh_phase_value = rayleigh_phase(nu);
            let mie_phase_value = cornette_shanks_phase(nu, lut_atmosphere.mie_g);
            var march = ScatteringSegment(vec3<f32>(0.0), vec3<f32>(1.0));
            for (var step = 0u; step < n; step++) {
                let t = segment.x + (f32(step) + 0.5) * dt;
                let point = point_along_ray(r, mu, mu_s, nu, t);
                let medium = medium_at_altitude(lut_atmosphere, point.x - lut_atmosphere.planet_radius);
                var source: vec3<f32>;
                if next_order {
                    source = multiple_scattering_source(medium, point.x, point.y, point.z, nu);
                } else {
                    source = (medium.rayleigh_scattering * rayleigh_phase_value
                        + medium.mie_scattering * mie_phase_value) * sun_transmittance(point.x, point.z);
                }
                march = integrate_scattering_step(march, source, medium.extinction, dt);
            }
            var radiance = march.radiance;
            let throughput = march.transmittance;
            if segment.z > 0.5 {
                // A Lambertian ground reflects ρ/π of its irradiance: the sun's at the hit
                // point (F₁), or the previous order's field's (F_{k+1}).
                let r_g = radius_along_ray(r, mu, segment.y);
                let mu_s_g = clamp((r * mu_s + segment.y * nu) / r_g, -1.0, 1.0);
                var irradiance_over_pi: vec3<f32>;
                if next_order {
                    irradiance_over_pi = multiple_scattering_ground_irradiance(lookup_multiple_scattering(r_g, mu_s_g));
                } else {
                    irradiance_over_pi = sun_transmittance(r_g, mu_s_g) * max(mu_s_g, 0.0) / PI;
                }
                radiance += throughput * irradiance_over_pi * lut_atmosphere.ground_albedo;
            }
            moment_sums_add(&sums, radiance, sin_v * cos_azimuth, mu, zenith.y);
        }
    }
    return moment_sums_moments(sums);
}

fn layers_of(moments: MultipleScatteringMoments) -> array<vec3<f32>, 6> {
    return array<vec3<f32>, 6>(
        moments.mean,
        moments.first_moment_x,
        moments.first_moment_z,
        moments.anisotropy_xx,
        moments.anisotropy_zz,
        moments.anisotropy_xz,
    );
}

@compute @workgroup_size(8, 8)
fn bake_multiple_scattering_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    if id.x >= w || id.y >= h {
        return;
    }
    var layers = layers_of(multiple_scattering_order_texel(id.x, id.y, false));
    for (var m = 0u; m < 6u; m++) {
        let index = id.x + w * (id.y + h * m);
        textureStore(multiple_scattering_out, id.xy, m, vec4<f32>(layers[m], 1.0));
        multiple_scattering_sum[index] = vec4<f32>(layers[m], 1.0);
    }
}

@compute @workgroup_size(8, 8)
fn bake_multiple_scattering_next_order(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    if id.x >= w || id.y >= h {
        return;
    }
    var layers = layers_of(multiple_scattering_order_texel(id.x, id.y, true));
    for (var m = 0u; m < 6u; m++) {
        let index = id.x + w * (id.y + h * m);
        textureStore(multiple_scattering_out, id.xy, m, vec4<f32>(layers[m], 1.0));
        let total = multiple_scattering_sum[index];
        multiple_scattering_sum[index] = vec4<f32>(total.xyz + layers[m], 1.0);
    }
}

@compute @workgroup_size(8, 8)
fn finish_multiple_scattering_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.multiple_scattering_width;
    let h = lut_settings.multiple_scattering_height;
    if id.x >= w || id.y >= h {
        return;
    }
    for (var m = 0u; m < 6u; m++) {
        textureStore(multiple_scattering_lut_out, id.xy, m, multiple_scattering_sum[id.x + w * (id.y + h * m)]);
    }
}
