// Bake of the sky-view LUT for the frame camera's altitude and sun (per frame): one
// invocation per texel, writing the radiance of its view ray (layer 0) and, when the
// table stores it, the ray's transmittance to the ground or space (layer 1). Twin:
// atmos::lut::sky_view_lut.
#import atmos::lut_sampling

@group(2) @binding(0) var sky_view_out: texture_storage_2d_array<rgba32float, write>;

// Viewer radius clamped to the atmosphere and sun zenith cosine (Rust: sky_view_r_mu_s).
fn sky_view_r_mu_s(camera: FrameCamera, planet_radius: f32, top_radius: f32) -> vec2<f32> {
    let p = camera.position;
    let len = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    let mu_s = (camera.sun.x * p.x + camera.sun.y * p.y + camera.sun.z * p.z) / len;
    return vec2<f32>(clamp(len, planet_radius, top_radius), clamp(mu_s, -1.0, 1.0));
}

// Radiance of the texel's view ray and, when the table stores it, the ray's
// transmittance to the ground or space (else not looked up and left 0: the Rust twin
// returns it as an Option).
fn sky_view_texel(r: f32, mu_s: f32, x: u32, y: u32) -> ScatteringSegment {
    let w = lut_settings.sky_view_width;
    let h = lut_settings.sky_view_height;
    let uv = vec2<f32>((f32(x) + 0.5) / f32(w), (f32(y) + 0.5) / f32(h));
    let direction = sky_view_lut_direction(uv, r, lut_atmosphere.planet_radius, w, h);
    let mu = direction.x;
    let sin_v = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    let sin_s = sqrt(max((1.0 - mu_s) * (1.0 + mu_s), 0.0));
    let nu = clamp(mu * mu_s + sin_v * sin_s * direction.y, -1.0, 1.0);
    let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    let result = raymarch_scattering(r, mu, mu_s, nu, segment.x, segment.y, lut_settings.sky_view_samples);
    var transmittance = vec3<f32>(0.0);
    if lut_settings.sky_view_transmittance != 0u {
        transmittance = transmittance_to_boundary(r, mu);
    }
    return ScatteringSegment(result.radiance, transmittance);
}

@compute @workgroup_size(8, 8)
fn bake_sky_view_lut(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.sky_view_width;
    if id.x >= w || id.y >= lut_settings.sky_view_height {
        return;
    }
    let r_mu_s = sky_view_r_mu_s(frame_camera, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    let texel = sky_view_texel(r_mu_s.x, r_mu_s.y, id.x, id.y);
    textureStore(sky_view_out, id.xy, 0u, vec4<f32>(texel.radiance, 1.0));
    if lut_settings.sky_view_transmittance != 0u {
        textureStore(sky_view_out, id.xy, 1u, vec4<f32>(texel.transmittance, 1.0));
    }
}
