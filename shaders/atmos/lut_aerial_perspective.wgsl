// Bake of the aerial-perspective volume for the frame camera (per frame): one
// invocation per froxel column, marched front to back, steps_per_slice uniform steps
// per depth slice, clipped to the atmosphere, writing each slice's radiance and
// transmittance to two 3-D textures (froxel x, y, depth slice). Twin:
// atmos::lut::aerial_perspective.
#import atmos::lut_sampling

@group(2) @binding(0) var aerial_perspective_radiance_out: texture_storage_3d<rgba32float, write>;
@group(2) @binding(1) var aerial_perspective_transmittance_out: texture_storage_3d<rgba32float, write>;

@compute @workgroup_size(8, 8)
fn bake_aerial_perspective(@builtin(global_invocation_id) id: vec3<u32>) {
    let w = lut_settings.aerial_perspective_width;
    let h = lut_settings.aerial_perspective_height;
    if id.x >= w || id.y >= h {
        return;
    }
    let uv = vec2<f32>((f32(id.x) + 0.5) / f32(w), (f32(id.y) + 0.5) / f32(h));
    let direction = froxel_view_direction(uv, frame_camera);
    let cosines = view_cosines(frame_camera, direction, lut_atmosphere.planet_radius);
    let r = cosines.x;
    let mu = cosines.y;
    let mu_s = cosines.z;
    let nu = cosines.w;
    let segment = ray_segment_in_atmosphere(r, mu, lut_atmosphere.planet_radius, lut_atmosphere.top_radius);
    // A column that meets the ground goes on through it (air at ground density) to
    // the top, so the lookup's blend of neighbouring columns stays right at a low
    // camera's horizon (Rust: aerial_perspective_column).
    var end = segment.y;
    if segment.z > 0.5 {
        end = ray_sphere_intersect(r, mu, lut_atmosphere.top_radius).y;
    }
    let rayleigh_phase_value = rayleigh_phase(nu);
    let mie_phase_value = cornette_shanks_phase(nu, lut_atmosphere.mie_g);
    let depth = lut_settings.aerial_perspective_depth;
    let steps = lut_settings.aerial_perspective_steps_per_slice;
    let step_length = lut_settings.aerial_perspective_range / f32(depth * steps);
    var march = ScatteringSegment(vec3<f32>(0.0), vec3<f32>(1.0));
    for (var slice = 0u; slice < depth; slice++) {
        for (var step = 0u; step < steps; step++) {
            let a = f32(slice * steps + step) * step_length;
            let lo = max(a, segment.x);
            let hi = min(a + step_length, end);
            if hi > lo {
                let dt = hi - lo;
                let point = point_along_ray(r, mu, mu_s, nu, lo + 0.5 * dt);
                let r_t = max(point.x, lut_atmosphere.planet_radius);
                let medium = medium_at_altitude(lut_atmosphere, r_t - lut_atmosphere.planet_radius);
                let source = scattering_source(medium, r_t, point.y, point.z, nu, rayleigh_phase_value, mie_phase_value);
                march = integrate_scattering_step(march, source, medium.extinction, dt);
            }
        }
        let froxel = vec3<u32>(id.x, id.y, slice);
        textureStore(aerial_perspective_radiance_out, froxel, vec4<f32>(march.radiance * lut_atmosphere.sun_irradiance, 1.0));
        textureStore(aerial_perspective_transmittance_out, froxel, vec4<f32>(march.transmittance, 1.0));
    }
}
