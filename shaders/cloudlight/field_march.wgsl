// The marches over a density field, written once against cloudlight::density_source
// (the GPU's DensityField; a pass binds it to cloudlight::density_grid or
// cloudlight::density_shell): Schneider's (GPU Pro 7) view ray-march after Schneider's Nubis talks
// (GPU Pro 7) — per view sample a light march toward the sun (the 6 + 1 cone or the full
// march), the multiple-scattering octaves, the powder term and an ambient term, with
// Hillaire's (2016) energy-conserving step — and the ground's shadow-map march. Twins:
// cloudlight::march (march_view_lit_through, light_optical_depth, ambient_visibility,
// clip_spans) and cloudlight::shadow_map::shadow_texel, generic over the field: the f32
// instantiation mirrors these operations.
#import cloudlight::cone
#import cloudlight::density_source
#import cloudlight::jitter
#import cloudlight::march
#import cloudlight::outside_shadow
#import cloudlight::ray_spans
#import cloudlight::shadow_map

// A view march's camera, image, settings and lighting (the uniform of the march passes'
// entries, cloudlight::gpu::MarchPass and MarchShellPass fill it).
struct MarchParams {
    // Camera position (xyz, m, the field's frame); w: albedo.
    cam_origin: vec4<f32>,
    // Unit forward (xyz); w: tan of the horizontal half field of view.
    cam_forward: vec4<f32>,
    // Unit right (xyz); w: tan of the vertical half field of view.
    cam_right: vec4<f32>,
    // Unit up (xyz); w: early-exit transmittance ε.
    cam_up: vec4<f32>,
    // Unit direction toward the sun (xyz); w: forward lobe g.
    sun_direction: vec4<f32>,
    // Sun irradiance (rgb); w: backward lobe g.
    sun_irradiance: vec4<f32>,
    // Ambient radiance (rgb); w: backward lobe weight.
    ambient: vec4<f32>,
    // Unit up of the ambient visibility (xyz); w: the cone's step (m).
    ambient_up: vec4<f32>,
    // Octave factors a, b, c; w: the cone's spread.
    octave_abc: vec4<f32>,
    // The field's horizon fade start and end (m; the shell's entry fades by them); zw
    // unused.
    horizon_fade: vec4<f32>,
    // Image width, height; z: jitter (0 none, 1 Bayer 4×4, 2 interleaved gradient);
    // w: light march (0 full, 1 raw cone, 2 partitioned cone).
    image: vec4<u32>,
    // Light steps, octave count, powder (0/1), ambient steps.
    counts: vec4<u32>,
    // View steps; y: 1 when the entry reads a per-pixel distance limit, 0 when none;
    // z: 1 when the march is temporally amortised (cloudlight::gpu::TemporalMarch: only
    // the pixels its reprojection marked are marched); w: the frame's phase (0..3).
    view: vec4<u32>,
}

// One pixel's march (march::MarchResult): radiance (rgb), transmittance, and the
// transmittance-weighted depth (m, 0 when nothing was hit).
struct MarchResult {
    radiance: vec3<f32>,
    transmittance: f32,
    depth: f32,
}

// The spans clipped to [0, max_distance] (march::clip_spans): a span starting at or
// beyond the limit is dropped, one crossing it ends there; a limit not below the largest
// f32 (or NaN) is none, a negative one is 0.
fn clip_spans(spans: RaySpans, max_distance: f32) -> RaySpans {
    if !(max_distance < INFINITE_DISTANCE) {
        return spans;
    }
    let limit = max(max_distance, 0.0);
    var out = ray_spans_none();
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

// Distance to the last exit of the field's spans along dir (0 if none).
fn exit_distance(p: vec3<f32>, dir: vec3<f32>) -> f32 {
    let spans = field_ray_spans(p, dir);
    if spans.count == 0u {
        return 0.0;
    }
    return max(spans.spans[spans.count - 1u].y, 0.0);
}

// σ_t Σ ρ(p + (j + ½)h·l)·h, h = exit / steps (cone::march_optical_depth).
fn march_optical_depth(p: vec3<f32>, l: vec3<f32>, exit: f32, steps: u32) -> f32 {
    let h = exit / f32(steps);
    var sum = 0.0;
    for (var j = 0u; j < steps; j++) {
        let t = (f32(j) + 0.5) * h;
        sum = sum + field_density(vec3<f32>(p.x + t * l.x, p.y + t * l.y, p.z + t * l.z));
    }
    return field_extinction_per_density() * sum * h;
}

// The optical depth toward the sun by the light march `params` selects
// (march::light_optical_depth): the full march of counts.x steps, or the cone's six
// samples plus the long one.
fn light_optical_depth(p: vec3<f32>, to_sun: vec3<f32>, params: MarchParams) -> f32 {
    let exit = exit_distance(p, to_sun);
    if exit == 0.0 {
        return 0.0;
    }
    let mode = params.image.w;
    if mode == 0u {
        return march_optical_depth(p, to_sun, exit, params.counts.x);
    }
    var sum = 0.0;
    for (var i = 0u; i < 7u; i++) {
        let s = cone_sample(i, to_sun, params.ambient_up.w, exit, params.octave_abc.w, mode == 2u);
        sum = sum + s.w * field_density(vec3<f32>(p.x + s.x, p.y + s.y, p.z + s.z));
    }
    return field_extinction_per_density() * sum;
}

// The ambient sky's visibility at p: e^{−τ_up} by `steps` midpoint steps along unit `up`
// to the field's last exit (0 steps, or p at the exit: 1) (march::ambient_visibility).
fn ambient_visibility(p: vec3<f32>, up: vec3<f32>, steps: u32) -> f32 {
    if steps == 0u {
        return 1.0;
    }
    let exit = exit_distance(p, up);
    if exit == 0.0 {
        return 1.0;
    }
    return beer_lambert(march_optical_depth(p, up, exit, steps));
}

// The view march of origin + t·direction, step k sampled at (k + offset)·Δ over the
// field's spans clipped to max_distance, each sample lit by the sun (light march plus
// another cloud's outside_depth, octaves, powder) and the ambient sky
// (march::march_view_lit_through with the outside_shadow map as its outside_depth).
fn march_view_lit_through(origin: vec3<f32>, direction: vec3<f32>, params: MarchParams, offset: f32, max_distance: f32) -> MarchResult {
    let o = origin;
    let d = direction;
    var radiance = vec3<f32>(0.0);
    var transmittance = 1.0;
    var depth = 0.0;
    let spans = clip_spans(field_ray_spans(o, d), max_distance);
    var total = 0.0;
    for (var s = 0u; s < spans.count; s++) {
        total = total + (spans.spans[s].y - spans.spans[s].x);
    }
    if total > 0.0 && total < INFINITE_DISTANCE {
        let steps = params.view.x;
        let dt = total / f32(steps);
        let sigma_per_density = field_extinction_per_density();
        let albedo = params.cam_origin.w;
        let to_sun = params.sun_direction.xyz;
        let cos_theta = d.x * to_sun.x + d.y * to_sun.y + d.z * to_sun.z;
        let sun = params.sun_irradiance.xyz;
        let ambient = params.ambient.xyz;
        let sun_lit = any(sun > vec3<f32>(0.0));
        let ambient_lit = any(ambient > vec3<f32>(0.0));
        let epsilon = params.cam_up.w;
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
                let tau = light_optical_depth(p, to_sun, params) + outside_depth(p);
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
                visibility = ambient_visibility(p, params.ambient_up.xyz, params.counts.w);
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
    return MarchResult(radiance, transmittance, depth);
}

// The march of pixel (x, y) of params' image (y down): its ray through the pinhole
// camera (pixel_direction), its step offset by the jitter, stopped at max_distance
// (march::march_view_at_pixel_limited with the outside_shadow map).
fn march_pixel(params: MarchParams, pixel: vec2<u32>, max_distance: f32) -> MarchResult {
    let d = pixel_direction(
        pixel,
        params.image.xy,
        params.cam_forward.xyz,
        params.cam_right.xyz,
        params.cam_up.xyz,
        vec2<f32>(params.cam_forward.w, params.cam_right.w),
    );
    var offset = 0.5;
    if params.image.z == 1u {
        offset = bayer_jitter_4x4(pixel);
    } else if params.image.z == 2u {
        offset = interleaved_gradient_noise(pixel);
    }
    offset = offset - floor(offset);
    return march_view_lit_through(params.cam_origin.xyz, d, params, offset, max_distance);
}

// A ground shadow map's texel grid, light and march (the uniform of the shadow-map
// passes' entries, cloudlight::gpu::ShadowMapPass and ShellShadowMapPass fill it).
struct ShadowMapParams {
    // The grid's minimum corner (x, y), texel edge and ground height (z), metres.
    grid: vec4<f32>,
    // Unit direction toward the sun (xyz); w unused.
    to_sun: vec4<f32>,
    // Texels along x and y; z: midpoint steps per span; w unused.
    size: vec4<u32>,
}

// The marched transmittance toward the sun (unit to_sun) from `ground` through the
// field: `steps` midpoint samples on each of its spans, exp(−Σ τ), saturated
// (shadow_map::shadow_texel).
fn shadow_texel(ground: vec3<f32>, to_sun: vec3<f32>, steps: u32) -> f32 {
    let spans = field_ray_spans(ground, to_sun);
    let sigma_t = field_extinction_per_density();
    var tau = 0.0;
    for (var s = 0u; s < spans.count; s++) {
        let span = spans.spans[s];
        var sum = 0.0;
        for (var k = 0u; k < steps; k++) {
            let rho = field_density(shadow_march_point(ground, to_sun, span, k, steps));
            sum = shadow_accumulate(sum, rho);
        }
        tau = min(tau + shadow_span_optical_depth(sum, span, steps, sigma_t), SHADOW_SATURATION);
    }
    return beer_lambert(tau);
}
