// Rung 1's frame renderer: the closed-form sky per pixel, or per vertex of a dome
// (pass 1 evaluates the vertices, pass 2 interpolates them per pixel, as a rasteriser
// interpolates a vertex shader's outputs). Writes the FrameOutput textures (radiance, transmittance).
// CPU twins: atmos::closed_form_sky::ClosedFormSky and atmos::dome::DomeInterpolated.

#import atmos::frame
#import atmos::dome
#import atmos::closed_form_sky

@group(0) @binding(0) var<uniform> camera: FrameCamera;
@group(0) @binding(1) var<uniform> params: ClosedFormSkyParameters;
@group(0) @binding(2) var radiance_out: texture_storage_2d<rgba32float, write>;
@group(0) @binding(3) var transmittance_out: texture_storage_2d<rgba32float, write>;
// Dome vertices: radiance rgb + transmittance (green) is not enough for rgb, so two
// vec4 per vertex: [2i] radiance, [2i + 1] transmittance.
@group(0) @binding(4) var<storage, read_write> dome: array<vec4<f32>>;

// Mesh resolution of the dome (per-vertex variant only): `dome_rings` bands plus the
// horizon seam, so dome_rings + 2 rows of dome_segments + 1 vertices.
override dome_rings: u32 = 16u;
override dome_segments: u32 = 32u;
// The radii the dome's rows are placed for (m): the ground and the atmosphere's top.
override dome_planet_radius: f32 = 6360000.0;
override dome_top_radius: f32 = 6460000.0;

const HALF_PI: f32 = 1.5707963267948966;
const TWO_PI: f32 = 6.283185307179586;

struct LocalFrame {
    zenith: vec3<f32>,
    east: vec3<f32>,
    north: vec3<f32>,
}

fn local_frame() -> LocalFrame {
    let zenith = normalize(camera.position);
    let horizontal_sun = camera.sun - zenith * dot(camera.sun, zenith);
    var east: vec3<f32>;
    if dot(horizontal_sun, horizontal_sun) > 1e-12 {
        east = normalize(horizontal_sun);
    } else {
        // Sun at the zenith or nadir: any horizontal direction.
        var helper = vec3<f32>(1.0, 0.0, 0.0);
        if abs(zenith.x) > 0.9 {
            helper = vec3<f32>(0.0, 1.0, 0.0);
        }
        east = normalize(cross(helper, zenith));
    }
    return LocalFrame(zenith, east, cross(zenith, east));
}

fn shade(view: vec3<f32>) -> array<vec3<f32>, 2> {
    let r = length(camera.position);
    let up = camera.position / r;
    let mu = dot(view, up);
    let mu_s = dot(camera.sun, up);
    let nu = dot(view, camera.sun);
    let sunlight = closed_form_sunlight(r, mu_s, params);
    return array<vec3<f32>, 2>(
        closed_form_sky_radiance(r, mu, mu_s, nu, camera.max_distance, sunlight, params),
        closed_form_sky_transmittance(r, mu, camera.max_distance, params),
    );
}

@compute @workgroup_size(8, 8)
fn render_closed_form_pixels(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= camera.width || gid.y >= camera.height {
        return;
    }
    let result = shade(frame_view_direction(gid.xy, camera));
    textureStore(radiance_out, gid.xy, vec4<f32>(result[0], 1.0));
    textureStore(transmittance_out, gid.xy, vec4<f32>(result[1], 1.0));
}

@compute @workgroup_size(64)
fn evaluate_dome_vertices(@builtin(global_invocation_id) gid: vec3<u32>) {
    let stride = dome_segments + 1u;
    if gid.x >= (dome_rings + 2u) * stride {
        return;
    }
    let row = gid.x / stride;
    let segment = gid.x % stride;
    let frame = local_frame();
    let r = length(camera.position);
    let mu = dome_row_mu(row, dome_rings, r, dome_planet_radius, dome_top_radius);
    let horizontal = sqrt(max(1.0 - mu * mu, 0.0));
    let azimuth = TWO_PI * f32(segment) / f32(dome_segments);
    let view = normalize(frame.zenith * mu
        + horizontal * (frame.east * cos(azimuth) + frame.north * sin(azimuth)));
    let result = shade(view);
    dome[2u * gid.x] = vec4<f32>(result[0], 1.0);
    dome[2u * gid.x + 1u] = vec4<f32>(result[1], 1.0);
}

@compute @workgroup_size(8, 8)
fn interpolate_dome(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= camera.width || gid.y >= camera.height {
        return;
    }
    let view = frame_view_direction(gid.xy, camera);
    let frame = local_frame();
    let mu = clamp(dot(view, frame.zenith), -1.0, 1.0);
    var azimuth = atan2(dot(view, frame.north), dot(view, frame.east));
    if azimuth < 0.0 {
        azimuth += TWO_PI;
    }
    let segments = f32(dome_segments);
    let v = dome_row_coordinate(mu, dome_rings, length(camera.position), dome_planet_radius, dome_top_radius);
    let u = clamp(azimuth / TWO_PI * segments, 0.0, segments);
    let i0 = min(u32(floor(v)), dome_rings);
    let j0 = min(u32(floor(u)), dome_segments - 1u);
    let fv = v - f32(i0);
    let fu = u - f32(j0);
    let stride = dome_segments + 1u;
    let a = i0 * stride + j0;
    let b = a + stride;
    let w = vec4<f32>((1.0 - fv) * (1.0 - fu), (1.0 - fv) * fu, fv * (1.0 - fu), fv * fu);
    textureStore(radiance_out, gid.xy, w.x * dome[2u * a] + w.y * dome[2u * (a + 1u)] + w.z * dome[2u * b] + w.w * dome[2u * (b + 1u)]);
    textureStore(transmittance_out, gid.xy, w.x * dome[2u * a + 1u] + w.y * dome[2u * (a + 1u) + 1u] + w.z * dome[2u * b + 1u] + w.w * dome[2u * (b + 1u) + 1u]);
}
