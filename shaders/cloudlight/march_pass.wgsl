// Seed 003's view ray-march of a CloudVolume as a compute pass: one invocation per pixel
// of a pinhole camera marches the view ray through the volume's trilinear density, lit
// by a light march toward the sun at every sample (cone 6 + 1 or full), multiple-
// scattering octaves and an ambient term. Twin: cloudlight::march::render_image::<f32>
// on a CloudVolume (whose density lookup is f64 rounded once; this one is f32).

#import cloudlight::cone
#import cloudlight::jitter
#import cloudlight::march
#import cloudlight::outside_shadow

struct MarchParams {
    // Camera position (xyz, m); w unused.
    cam_origin: vec4<f32>,
    // Unit forward (xyz); w: tan of the horizontal half field of view.
    cam_forward: vec4<f32>,
    // Unit right (xyz); w: tan of the vertical half field of view.
    cam_right: vec4<f32>,
    // Unit up (xyz); w: σ_t per unit density (1/m).
    cam_up: vec4<f32>,
    // The volume's box minimum corner (xyz, m); w: cell edge (m).
    box_lo: vec4<f32>,
    // The box maximum corner (xyz, m); w: early-exit transmittance ε.
    box_hi: vec4<f32>,
    // Unit direction toward the sun (xyz); w: albedo.
    sun_direction: vec4<f32>,
    // Sun irradiance (rgb); w: forward lobe g.
    sun_irradiance: vec4<f32>,
    // Ambient radiance (rgb); w: backward lobe g.
    ambient: vec4<f32>,
    // Unit up of the ambient visibility (xyz); w: backward lobe weight.
    ambient_up: vec4<f32>,
    // Octave factors a, b, c; w: the cone's step (m).
    octave_abc: vec4<f32>,
    // x: the cone's spread; y: 1 when max_distance holds a per-pixel limit, 0 when none;
    // zw unused.
    cone: vec4<f32>,
    // Cells along x, y, z; w: view steps.
    dims: vec4<u32>,
    // Image width, height; z: jitter (0 none, 1 Bayer 4×4, 2 interleaved gradient);
    // w: light march (0 full, 1 raw cone, 2 partitioned cone).
    image: vec4<u32>,
    // Light steps, octave count, powder (0/1), ambient steps.
    counts: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: MarchParams;
@group(0) @binding(1) var<storage, read> density: array<f32>;
// Two texels per pixel (x fastest): (radiance rgb, transmittance), (depth, 0, 0, 0).
@group(0) @binding(2) var<storage, read_write> image_out: array<vec4<f32>>;
// The distance (m) along each pixel's ray (x fastest) where its march stops; read only
// when cone.y is 1 (otherwise a placeholder is bound).
@group(0) @binding(3) var<storage, read> max_distance: array<f32>;

const INFINITE_DISTANCE: f32 = 3.40282347e+38;

fn cell_density(x: u32, y: u32, z: u32) -> f32 {
    let dims = params.dims.xyz;
    return density[x + dims.x * (y + dims.y * z)];
}

// The volume's trilinear density at p: zero outside, cell-centre values interpolated
// inside, clamped to the outermost centres (CloudVolume::density_at in f32).
fn volume_density(p: vec3<f32>) -> f32 {
    var base = vec3<u32>(0u);
    var frac = vec3<f32>(0.0);
    for (var a = 0; a < 3; a++) {
        let n = params.dims[a];
        let u = (p[a] - params.box_lo[a]) / params.box_lo.w;
        if !(u >= 0.0 && u <= f32(n)) {
            return 0.0;
        }
        let c = clamp(u - 0.5, 0.0, f32(n - 1u));
        let i = min(u32(floor(c)), max(n, 2u) - 2u);
        base[a] = i;
        if n == 1u {
            frac[a] = 0.0;
        } else {
            frac[a] = c - f32(i);
        }
    }
    var sum = 0.0;
    for (var corner = 0u; corner < 8u; corner++) {
        var weight = 1.0;
        var cell = vec3<u32>(0u);
        for (var a = 0; a < 3; a++) {
            let bit = (corner >> u32(a)) & 1u;
            cell[a] = min(base[a] + bit, params.dims[a] - 1u);
            if bit == 1u {
                weight = weight * frac[a];
            } else {
                weight = weight * (1.0 - frac[a]);
            }
        }
        if weight != 0.0 {
            sum = sum + weight * cell_density(cell.x, cell.y, cell.z);
        }
    }
    return sum;
}

// The ray's span inside the box: (1, enter, exit) or (0, 0, 0) (DensityField::ray_spans
// of a CloudVolume).
fn volume_span(o: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    var enter = 0.0;
    var exit = INFINITE_DISTANCE;
    for (var a = 0; a < 3; a++) {
        let lo = params.box_lo[a];
        let hi = params.box_hi[a];
        if d[a] == 0.0 {
            if o[a] < lo || o[a] > hi {
                return vec3<f32>(0.0);
            }
            continue;
        }
        let t0 = (lo - o[a]) / d[a];
        let t1 = (hi - o[a]) / d[a];
        enter = max(enter, min(t0, t1));
        exit = min(exit, max(t0, t1));
    }
    if enter <= exit {
        return vec3<f32>(1.0, enter, exit);
    }
    return vec3<f32>(0.0);
}

// The span clipped to [0, limit] (march::clip_spans): dropped when it starts at or
// beyond the limit, ended there when it crosses it; a limit not below the largest f32
// (or NaN) is none, a negative one is 0.
fn clip_span(span: vec3<f32>, limit_in: f32) -> vec3<f32> {
    if !(limit_in < INFINITE_DISTANCE) {
        return span;
    }
    let limit = max(limit_in, 0.0);
    if span.x == 0.0 || !(span.y < limit) {
        return vec3<f32>(0.0);
    }
    var exit = span.z;
    if exit > limit {
        exit = limit;
    }
    return vec3<f32>(1.0, span.y, exit);
}

// Distance to the last exit of the spans along d (0 if none).
fn volume_exit_distance(p: vec3<f32>, d: vec3<f32>) -> f32 {
    let span = volume_span(p, d);
    if span.x == 0.0 {
        return 0.0;
    }
    return max(span.z, 0.0);
}

// σ_t Σ ρ(p + (j + ½)h·l)·h, h = exit / steps (cone::march_optical_depth).
fn volume_march_optical_depth(p: vec3<f32>, l: vec3<f32>, exit: f32, steps: u32) -> f32 {
    let h = exit / f32(steps);
    var sum = 0.0;
    for (var j = 0u; j < steps; j++) {
        let t = (f32(j) + 0.5) * h;
        sum = sum + volume_density(vec3<f32>(p.x + t * l.x, p.y + t * l.y, p.z + t * l.z));
    }
    return params.cam_up.w * sum * h;
}

// The optical depth toward the sun by the selected light march (march::light_optical_depth).
fn light_optical_depth(p: vec3<f32>, to_sun: vec3<f32>) -> f32 {
    let exit = volume_exit_distance(p, to_sun);
    if exit == 0.0 {
        return 0.0;
    }
    let mode = params.image.w;
    if mode == 0u {
        return volume_march_optical_depth(p, to_sun, exit, params.counts.x);
    }
    var sum = 0.0;
    for (var i = 0u; i < 7u; i++) {
        let s = cone_sample(i, to_sun, params.octave_abc.w, exit, params.cone.x, mode == 2u);
        sum = sum + s.w * volume_density(vec3<f32>(p.x + s.x, p.y + s.y, p.z + s.z));
    }
    return params.cam_up.w * sum;
}

fn ambient_visibility(p: vec3<f32>) -> f32 {
    let steps = params.counts.w;
    if steps == 0u {
        return 1.0;
    }
    let up = params.ambient_up.xyz;
    let exit = volume_exit_distance(p, up);
    if exit == 0.0 {
        return 1.0;
    }
    return beer_lambert(volume_march_optical_depth(p, up, exit, steps));
}

@compute @workgroup_size(8, 8)
fn march_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = params.image.xy;
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let o = params.cam_origin.xyz;
    let d = pixel_direction(
        gid.xy,
        size,
        params.cam_forward.xyz,
        params.cam_right.xyz,
        params.cam_up.xyz,
        vec2<f32>(params.cam_forward.w, params.cam_right.w),
    );
    var offset = 0.5;
    if params.image.z == 1u {
        offset = bayer_jitter_4x4(gid.xy);
    } else if params.image.z == 2u {
        offset = interleaved_gradient_noise(gid.xy);
    }
    offset = offset - floor(offset);
    var radiance = vec3<f32>(0.0);
    var transmittance = 1.0;
    var depth = 0.0;
    var span = volume_span(o, d);
    if params.cone.y != 0.0 {
        span = clip_span(span, max_distance[gid.x + size.x * gid.y]);
    }
    let total = 0.0 + (span.z - span.y);
    if span.x != 0.0 && total > 0.0 && total < INFINITE_DISTANCE {
        let steps = params.dims.w;
        let dt = total / f32(steps);
        let sigma_per_density = params.cam_up.w;
        let albedo = params.sun_direction.w;
        let to_sun = params.sun_direction.xyz;
        let cos_theta = d.x * to_sun.x + d.y * to_sun.y + d.z * to_sun.z;
        let sun = params.sun_irradiance.xyz;
        let ambient = params.ambient.xyz;
        let sun_lit = any(sun > vec3<f32>(0.0));
        let ambient_lit = any(ambient > vec3<f32>(0.0));
        let epsilon = params.box_hi.w;
        var weight_sum = 0.0;
        var depth_sum = 0.0;
        for (var k = 0u; k < steps; k++) {
            let u = (f32(k) + offset) * dt;
            let t = span.y + u;
            let p = vec3<f32>(o.x + t * d.x, o.y + t * d.y, o.z + t * d.z);
            let rho = volume_density(p);
            if !(rho > 0.0) {
                continue;
            }
            let sigma_t = sigma_per_density * rho;
            let sigma_s = albedo * sigma_t;
            var sun_term = 0.0;
            if sun_lit {
                // Another cloud's shadow map adds its optical depth (0 without one).
                let tau = light_optical_depth(p, to_sun) + outside_depth(p);
                sun_term = octave_scattering(
                    tau,
                    cos_theta,
                    params.sun_irradiance.w,
                    params.ambient.w,
                    params.ambient_up.w,
                    params.counts.y,
                    params.octave_abc.x,
                    params.octave_abc.y,
                    params.octave_abc.z,
                );
                if params.counts.z != 0u {
                    sun_term = sun_term * powder(tau);
                }
            }
            var visibility = 0.0;
            if ambient_lit {
                visibility = ambient_visibility(p);
            }
            var next = transmittance;
            for (var ch = 0; ch < 3; ch++) {
                let source = sigma_s * (sun[ch] * sun_term + ambient[ch] * visibility);
                let step = scatter_step(transmittance, source, sigma_t, dt);
                radiance[ch] = radiance[ch] + step.x;
                next = step.y;
            }
            let opacity = transmittance - next;
            weight_sum = weight_sum + opacity;
            depth_sum = depth_sum + opacity * t;
            transmittance = next;
            if transmittance < epsilon {
                break;
            }
        }
        if weight_sum > 0.0 {
            depth = depth_sum / weight_sum;
        }
    }
    let index = 2u * (gid.x + size.x * gid.y);
    image_out[index] = vec4<f32>(radiance, transmittance);
    image_out[index + 1u] = vec4<f32>(depth, 0.0, 0.0, 0.0);
}
