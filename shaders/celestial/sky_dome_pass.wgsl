// SGSky's dome as a frame renderer: each pixel's view ray in the dome's frame (up the
// viewer's position, x the sun's horizontal direction), the painted dome's colour
// there (celestial::dome) plus the sun's Mie aureole (celestial::draw), written into
// an atmos::gpu::FrameOutput; every ray's transmittance is the transmittance toward
// the sun (what draws its disc).
// CPU twin: celestial::dome_sky::SgskyDomeSky (evaluate), dome_local_frame.

#import atmos::frame
#import celestial::dome
#import celestial::draw

struct SkyDomeUniforms {
    colours: array<vec4<f32>, 49>,
    sun_irradiance: vec3<f32>,
    spin: f32,
    sun_transmittance: vec3<f32>,
    mie_g: f32,
    mie_optical_depth: vec3<f32>,
    padding: f32,
}

@group(0) @binding(0) var<uniform> camera: FrameCamera;
@group(0) @binding(1) var<uniform> dome: SkyDomeUniforms;
@group(0) @binding(2) var radiance_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(3) var transmittance_out: texture_storage_2d<rgba32float, write>;

// The dome's frame (x, y, up), as dome_local_frame builds it.
fn dome_local_frame(position: vec3<f32>, sun: vec3<f32>) -> mat3x3<f32> {
    let up = normalize(position);
    let horizontal = sun - up * dot(sun, up);
    var x: vec3<f32>;
    if dot(horizontal, horizontal) > 1e-12 {
        x = normalize(horizontal);
    } else {
        var helper = vec3<f32>(1.0, 0.0, 0.0);
        if abs(up.x) > 0.9 {
            helper = vec3<f32>(0.0, 1.0, 0.0);
        }
        x = normalize(cross(helper, up));
    }
    return mat3x3<f32>(x, cross(up, x), up);
}

@compute @workgroup_size(8, 8)
fn render_sky_dome(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= camera.width || gid.y >= camera.height {
        return;
    }
    let view = frame_view_direction(gid.xy, camera);
    let frame = dome_local_frame(camera.position, camera.sun);
    let local = vec3<f32>(dot(view, frame[0]), dot(view, frame[1]), dot(view, frame[2]));
    let local_sun = vec3<f32>(dot(camera.sun, frame[0]), dot(camera.sun, frame[1]), dot(camera.sun, frame[2]));
    let cos_offset = dot(local, local_sun);
    let hit = sky_dome_weights(local, dome.spin);
    var radiance = hit.weights.x * dome.colours[hit.slots.x].xyz
        + hit.weights.y * dome.colours[hit.slots.y].xyz
        + hit.weights.z * dome.colours[hit.slots.z].xyz;
    for (var c = 0; c < 3; c++) {
        radiance[c] += sun_aureole_radiance(cos_offset, dome.mie_g, dome.sun_irradiance[c], dome.sun_transmittance[c], dome.mie_optical_depth[c]);
    }
    textureStore(radiance_out, gid.xy, vec4<f32>(radiance, 1.0));
    textureStore(transmittance_out, gid.xy, vec4<f32>(dome.sun_transmittance, 1.0));
}
