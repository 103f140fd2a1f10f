// Aerial perspective and sunlight for a caller's own geometry, read from the
// precomputed rung's tables (atmos::lut_bindings: compose with
// `atmos::gpu::composer_with_lut_groups` to choose the bind groups). Points are given
// as their offset from the frame camera in the planet frame's axes; a caller whose
// world is a local frame (+y up, −z north, +x east, metres) converts its offsets with
// local_to_planet_direction (a rotation: lengths are kept). Twin: atmos::lut::drop_in.
#import atmos::lut_shading
#import common::frames

// A local-frame vector (+y up, −z north, +x east) in the planet frame's axes (x east,
// y north, z up at the local frame's origin: east-north-up), common::frames'
// world_to_enu. Twin: atmos::frame::local_to_planet_direction.
fn local_to_planet_direction(direction: vec3<f32>) -> vec3<f32> {
    return world_to_enu(direction);
}

// Where a unit direction lands on the frame camera's image: (u, v, depth) with u, v in
// [0, 1] over the image (x right, y down) and depth = the cosine to the camera's
// forward axis (≤ 0: behind the camera). Inverse of frame_view_direction.
fn frame_screen_position(camera: FrameCamera, direction: vec3<f32>) -> vec3<f32> {
    let aspect = f32(camera.width) / f32(camera.height);
    let depth = dot(direction, camera.forward);
    let x = dot(direction, camera.right) / (depth * camera.tan_half_fov_y * aspect);
    let y = dot(direction, camera.up) / (depth * camera.tan_half_fov_y);
    return vec3<f32>(0.5 * (x + 1.0), 0.5 * (1.0 - y), depth);
}

// In-scattered radiance (the sun irradiance included) and transmittance between the
// frame camera and the point `offset` metres from it (planet-frame axes): the
// aerial-perspective volume where the point is in the camera's frustum and range, a
// LUT march of `pixel_samples` steps elsewhere (the same choice as shade_pixel).
fn aerial_perspective(offset: vec3<f32>) -> ScatteringSegment {
    let distance = length(offset);
    if distance <= 0.0 {
        return ScatteringSegment(vec3<f32>(0.0), vec3<f32>(1.0));
    }
    let camera = frame_camera;
    let direction = offset / distance;
    let screen = frame_screen_position(camera, direction);
    let on_screen = screen.z > 0.0 && screen.x >= 0.0 && screen.x <= 1.0 && screen.y >= 0.0 && screen.y <= 1.0;
    if on_screen && distance <= lut_settings.aerial_perspective_range {
        return lookup_aerial_perspective(screen.xy, distance);
    }
    let cosines = view_cosines(camera, direction, lut_atmosphere.planet_radius);
    return march_view_segment(cosines.x, cosines.y, cosines.z, cosines.w, distance, lut_settings.pixel_samples);
}

// A surface's radiance (seen at the surface) as the frame camera sees it through the
// atmosphere: attenuated by the segment's transmittance, plus its in-scatter.
fn apply_aerial_perspective(surface_radiance: vec3<f32>, offset: vec3<f32>) -> vec3<f32> {
    let segment = aerial_perspective(offset);
    return surface_radiance * segment.transmittance + segment.radiance;
}

// The sun's irradiance (per unit area facing the sun) reaching the point `offset`
// metres from the frame camera: sun_irradiance through the transmittance LUT, 0 in the
// planet's shadow.
fn sunlight_at(offset: vec3<f32>) -> vec3<f32> {
    let position = frame_camera.position + offset;
    let r = length(position);
    let mu_s = clamp(dot(frame_camera.sun, position) / r, -1.0, 1.0);
    return lut_atmosphere.sun_irradiance * sun_transmittance(max(r, lut_atmosphere.planet_radius), mu_s);
}

// The sun's transmittance to the planet-centred point `position` (m), the sun along
// frame_camera.sun: through the transmittance LUT, 0 in the planet's shadow. Times
// lut_atmosphere.sun_irradiance and the cosine to the sun: a surface's direct light.
fn sun_transmittance_at(position: vec3<f32>) -> vec3<f32> {
    let r = length(position);
    let mu_s = clamp(dot(frame_camera.sun, position) / r, -1.0, 1.0);
    return sun_transmittance(max(r, lut_atmosphere.planet_radius), mu_s);
}

// Irradiance (the unit of sun_irradiance) that a surface of unit normal `normal`
// (planet-frame axes) at the planet-centred point `position` (m) receives from the
// sky, the sun along frame_camera.sun: every order of scattered sunlight and the
// ground's Lambertian radiance, from the sky-irradiance LUT. The direct sun is not
// included (sun_transmittance_at). Points above the atmosphere read its top.
fn sky_irradiance(position: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let r = length(position);
    let zenith = position / r;
    let mu_s = clamp(dot(frame_camera.sun, zenith), -1.0, 1.0);
    let mu_n = clamp(dot(normal, zenith), -1.0, 1.0);
    let nu_n = clamp(dot(normal, frame_camera.sun), -1.0, 1.0);
    let direction = sun_frame_direction(mu_n, mu_s, nu_n);
    return lookup_sky_irradiance(clamp(r, lut_atmosphere.planet_radius, lut_atmosphere.top_radius), mu_s, direction);
}
