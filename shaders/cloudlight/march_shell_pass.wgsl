// Seed 003's view ray-march of a procedural cloud shell as a compute pass: one invocation
// per pixel of a pinhole camera (planet-centred metres) marches the view ray through the
// shell's spans (up to two), lit by a light march toward the sun at every sample (cone
// 6 + 1 or full), multiple-scattering octaves and an ambient term, then fades the result
// toward the horizon at its transmittance-weighted depth. The weather is procedural or a
// user grid (grid.x; its cells in binding 3).
// Twin: cloudlight::march::render_image::<f32> on a CloudShell, each pixel then
// march::faded by CloudShell::horizon_fade(depth).

#import cloudlight::cone
#import cloudlight::jitter
#import cloudlight::march
#import cloudlight::outside_shadow
#import cloudlight::shell

struct ShellMarchParams {
    // Camera position (xyz, planet-centred m); w: planet radius (m).
    cam_origin: vec4<f32>,
    // Unit forward (xyz); w: tan of the horizontal half field of view.
    cam_forward: vec4<f32>,
    // Unit right (xyz); w: tan of the vertical half field of view.
    cam_right: vec4<f32>,
    // Unit up (xyz); w: σ_t per unit density (1/m).
    cam_up: vec4<f32>,
    // Inner radius, outer radius, shape period, detail period (m).
    shell: vec4<f32>,
    // Erosion, horizon fade start, fade end (m); w: early-exit transmittance ε.
    shell_more: vec4<f32>,
    // Weather: period (m), coverage mean, coverage contrast, cloud type mean.
    weather: vec4<f32>,
    // x: cloud type contrast; y: albedo; z: the cone's step (m); w: the cone's spread.
    weather_more: vec4<f32>,
    // Unit direction toward the sun (xyz); w: forward lobe g.
    sun_direction: vec4<f32>,
    // Sun irradiance (rgb); w: backward lobe g.
    sun_irradiance: vec4<f32>,
    // Ambient radiance (rgb); w: backward lobe weight.
    ambient: vec4<f32>,
    // Unit up of the ambient visibility (xyz); w: the weather grid's cell edge (m).
    ambient_up: vec4<f32>,
    // Octave factors a, b, c; w: 1 when max_distance holds a per-pixel limit, 0 when none.
    octave_abc: vec4<f32>,
    // Noise seed, weather seed, weather cells, view steps.
    seeds: vec4<u32>,
    // Image width, height; z: jitter (0 none, 1 Bayer 4×4, 2 interleaved gradient);
    // w: light march (0 full, 1 raw cone, 2 partitioned cone).
    image: vec4<u32>,
    // Light steps, octave count, powder (0/1), ambient steps.
    counts: vec4<u32>,
    // Weather kind (0 procedural, 1 grid), the grid's cells along x and y; w unused.
    grid: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: ShellMarchParams;
// Two texels per pixel (x fastest): (radiance rgb, transmittance), (depth, 0, 0, 0).
@group(0) @binding(1) var<storage, read_write> image_out: array<vec4<f32>>;
// The distance (m) along each pixel's ray (x fastest) where its march stops; read only
// when octave_abc.w is 1 (otherwise a placeholder is bound).
@group(0) @binding(2) var<storage, read> max_distance: array<f32>;
// The weather grid's (coverage, cloud type) per cell, x fastest; read only when grid.x
// is 1 (otherwise a one-cell placeholder is bound).
@group(0) @binding(3) var<storage, read> weather_grid: array<vec2<f32>>;

// The weather (coverage, cloud type) at (x, y) (CloudShell::weather_at): procedural, or
// the grid's taps read from weather_grid then weather_grid_bilinear.
fn field_weather(xy: vec2<f32>) -> vec2<f32> {
    if params.grid.x == 1u {
        let taps = weather_grid_taps(params.grid.yz, params.ambient_up.w, xy);
        var values: array<vec2<f32>, 4>;
        for (var k = 0; k < 4; k++) {
            values[k] = weather_grid[taps.index[k]];
        }
        return weather_grid_bilinear(values, taps.fraction);
    }
    return procedural_weather(
        xy,
        params.weather.x,
        params.seeds.z,
        params.seeds.y,
        params.weather.y,
        params.weather.z,
        params.weather.w,
        params.weather_more.x,
    );
}

// The shell's density with the weather at (x, y) (DensityField for CloudShell).
fn field_density(p: vec3<f32>) -> f32 {
    let inner = params.shell.x;
    let outer = params.shell.y;
    let r = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if !(r > inner && r < outer) {
        return 0.0;
    }
    let weather = field_weather(p.xy);
    return shell_density(
        p,
        inner,
        outer,
        weather.x,
        weather.y,
        params.shell.z,
        params.shell.w,
        params.shell_more.x,
        params.seeds.x,
    );
}

fn field_spans(o: vec3<f32>, d: vec3<f32>) -> ShellSpans {
    return shell_ray_spans(o, d, params.cam_origin.w, params.shell.x, params.shell.y);
}

// The spans clipped to [0, limit] (march::clip_spans): a span starting at or beyond the
// limit is dropped, one crossing it ends there; a limit not below the largest f32 (or
// NaN) is none, a negative one is 0.
fn clip_spans(spans: ShellSpans, limit_in: f32) -> ShellSpans {
    if !(limit_in < 3.40282347e+38) {
        return spans;
    }
    let limit = max(limit_in, 0.0);
    var out: ShellSpans;
    out.spans[0] = vec2<f32>(0.0);
    out.spans[1] = vec2<f32>(0.0);
    out.count = 0u;
    for (var s = 0u; s < spans.count; s++) {
        let enter = spans.spans[s].x;
        if enter < limit {
            var exit = spans.spans[s].y;
            if exit > limit {
                exit = limit;
            }
            out.spans[out.count] = vec2<f32>(enter, exit);
            out.count += 1u;
        }
    }
    return out;
}

// Distance to the last exit of the spans along d (0 if none).
fn field_exit_distance(p: vec3<f32>, d: vec3<f32>) -> f32 {
    let spans = field_spans(p, d);
    if spans.count == 0u {
        return 0.0;
    }
    return max(spans.spans[spans.count - 1u].y, 0.0);
}

// σ_t Σ ρ(p + (j + ½)h·l)·h, h = exit / steps (cone::march_optical_depth).
fn field_march_optical_depth(p: vec3<f32>, l: vec3<f32>, exit: f32, steps: u32) -> f32 {
    let h = exit / f32(steps);
    var sum = 0.0;
    for (var j = 0u; j < steps; j++) {
        let t = (f32(j) + 0.5) * h;
        sum = sum + field_density(vec3<f32>(p.x + t * l.x, p.y + t * l.y, p.z + t * l.z));
    }
    return params.cam_up.w * sum * h;
}

// The optical depth toward the sun by the selected light march (march::light_optical_depth).
fn light_optical_depth(p: vec3<f32>, to_sun: vec3<f32>) -> f32 {
    let exit = field_exit_distance(p, to_sun);
    if exit == 0.0 {
        return 0.0;
    }
    let mode = params.image.w;
    if mode == 0u {
        return field_march_optical_depth(p, to_sun, exit, params.counts.x);
    }
    var sum = 0.0;
    for (var i = 0u; i < 7u; i++) {
        let s = cone_sample(i, to_sun, params.weather_more.z, exit, params.weather_more.w, mode == 2u);
        sum = sum + s.w * field_density(vec3<f32>(p.x + s.x, p.y + s.y, p.z + s.z));
    }
    return params.cam_up.w * sum;
}

fn ambient_visibility(p: vec3<f32>) -> f32 {
    let steps = params.counts.w;
    if steps == 0u {
        return 1.0;
    }
    let up = params.ambient_up.xyz;
    let exit = field_exit_distance(p, up);
    if exit == 0.0 {
        return 1.0;
    }
    return beer_lambert(field_march_optical_depth(p, up, exit, steps));
}

@compute @workgroup_size(8, 8)
fn march_shell_main(@builtin(global_invocation_id) gid: vec3<u32>) {
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
    var spans = field_spans(o, d);
    if params.octave_abc.w != 0.0 {
        spans = clip_spans(spans, max_distance[gid.x + size.x * gid.y]);
    }
    var total = 0.0;
    for (var s = 0u; s < spans.count; s++) {
        total = total + (spans.spans[s].y - spans.spans[s].x);
    }
    if total > 0.0 && total < 3.40282347e+38 {
        let steps = params.seeds.w;
        let dt = total / f32(steps);
        let sigma_per_density = params.cam_up.w;
        let albedo = params.weather_more.y;
        let to_sun = params.sun_direction.xyz;
        let cos_theta = d.x * to_sun.x + d.y * to_sun.y + d.z * to_sun.z;
        let sun = params.sun_irradiance.xyz;
        let ambient = params.ambient.xyz;
        let sun_lit = any(sun > vec3<f32>(0.0));
        let ambient_lit = any(ambient > vec3<f32>(0.0));
        let epsilon = params.shell_more.w;
        var weight_sum = 0.0;
        var depth_sum = 0.0;
        var span = 0u;
        var span_start = 0.0;
        for (var k = 0u; k < steps; k++) {
            let u = (f32(k) + offset) * dt;
            while span + 1u < spans.count && u >= span_start + (spans.spans[span].y - spans.spans[span].x) {
                span_start = span_start + (spans.spans[span].y - spans.spans[span].x);
                span += 1u;
            }
            let t = spans.spans[span].x + (u - span_start);
            let p = vec3<f32>(o.x + t * d.x, o.y + t * d.y, o.z + t * d.z);
            let rho = field_density(p);
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
                    params.sun_direction.w,
                    params.sun_irradiance.w,
                    params.ambient.w,
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
    // The horizon fade at the cloud's depth (march::faded).
    let fade = horizon_fade(depth, params.shell_more.y, params.shell_more.z);
    radiance = vec3<f32>(radiance.x * fade, radiance.y * fade, radiance.z * fade);
    transmittance = 1.0 - fade * (1.0 - transmittance);
    let index = 2u * (gid.x + size.x * gid.y);
    image_out[index] = vec4<f32>(radiance, transmittance);
    image_out[index + 1u] = vec4<f32>(depth, 0.0, 0.0, 0.0);
}
