// The procedural cloud shell (Schneider 2015, 2017): the height profiles per
// cloud type, the density from the shape and detail noise, the density at a
// planet-centred point, procedural weather, a weather grid's bilinear lookup, the
// horizon fade and a ray's spans inside the shell (atmos' stable ray–sphere roots,
// imported). Twin: cloudlight::shell (Rust,
// generic over the float type: the f32 instantiation mirrors these operations).
// Lengths in metres, planet-centred.
#import atmos::geometry
#import cloudlight::noise
#import cloudlight::ray_spans

// Height profile corners (a, b, c, d) over the height fraction.
const STRATUS_GRADIENT: vec4<f32> = vec4<f32>(0.0, 0.1, 0.2, 0.3);
const STRATOCUMULUS_GRADIENT: vec4<f32> = vec4<f32>(0.02, 0.2, 0.48, 0.625);
const CUMULUS_GRADIENT: vec4<f32> = vec4<f32>(0.0, 0.1625, 0.88, 0.98);

// Hermite smoothstep t²(3 − 2t), t = clamp((x − lo)/(hi − lo), 0, 1), spelled out.
fn shell_smoothstep(lo: f32, hi: f32, x: f32) -> f32 {
    let t = min(max((x - lo) / (hi - lo), 0.0), 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// The height profile in [0, 1] at height fraction h for cloud type t (0 stratus,
// ½ stratocumulus, 1 cumulus): a trapezoid of two smoothsteps between blended corners.
fn height_gradient(h: f32, cloud_type: f32) -> f32 {
    let stratus = 1.0 - min(max(cloud_type * 2.0, 0.0), 1.0);
    let stratocumulus = 1.0 - abs(cloud_type - 0.5) * 2.0;
    let cumulus = min(max(cloud_type - 0.5, 0.0), 1.0) * 2.0;
    let corner = stratus * STRATUS_GRADIENT + stratocumulus * STRATOCUMULUS_GRADIENT + cumulus * CUMULUS_GRADIENT;
    return max(shell_smoothstep(corner.x, corner.y, h) - shell_smoothstep(corner.z, corner.w, h), 0.0);
}

// The density in [0, 1] from the height fraction, the weather, the shape noise (4
// channels), the detail noise (3) and the detail erosion strength: Schneider's base
// remap, height profile, coverage (max(b·g + coverage − 1, 0)) and, where that is above
// zero, detail erosion.
fn shell_density_from_noise(h: f32, coverage: f32, cloud_type: f32, shape: vec4<f32>, detail: vec3<f32>, erosion: f32) -> f32 {
    let covered = shell_covered_density(height_gradient(h, cloud_type), coverage, shape);
    if covered <= 0.0 {
        return 0.0;
    }
    return shell_eroded_density(h, covered, detail, erosion);
}

// The density before detail erosion: the base shape b = (shape.x + 1 − fbm)/(2 − fbm)
// (fbm the Worley fBm of shape.yzw) times the height profile, through the coverage,
// max(b·g + coverage − 1, 0).
fn shell_covered_density(gradient: f32, coverage: f32, shape: vec4<f32>) -> f32 {
    let fbm = worley_channels_fbm(shape.yzw);
    let base = (shape.x + 1.0 - fbm) / (2.0 - fbm);
    return max(base * gradient + coverage - 1.0, 0.0);
}

// The density after detail erosion of the covered density (> 0) at height fraction h:
// e = erosion·mix(dfbm, 1 − dfbm, clamp(10h, 0, 1)), max(covered − e, 0)/(1 − e).
fn shell_eroded_density(h: f32, covered: f32, detail: vec3<f32>, erosion: f32) -> f32 {
    let detail_fbm = worley_channels_fbm(detail);
    let wisp = min(max(h * 10.0, 0.0), 1.0);
    let modifier = detail_fbm + wisp * ((1.0 - detail_fbm) - detail_fbm);
    let e = erosion * modifier;
    return max(covered - e, 0.0) / (1.0 - e);
}

// How far below zero g + coverage − 1 must be for the density to be zero whatever the
// shape noise: the base shape is at most 1 (channels in [0, 1]), so b·g + coverage − 1 ≤
// g + coverage − 1; the margin absorbs both sides' roundings.
const COVERAGE_SKIP_MARGIN: f32 = 1e-3;

// The shell's density at planet-centred p for the weather there; zero outside
// (inner_radius, outer_radius). Noise in the local frame q = (x, y, |p| − inner), each
// looked up only where the density depends on it: the shape noise not where
// g + coverage − 1 < −COVERAGE_SKIP_MARGIN, the detail only where the covered density is
// above zero (the same result as shell_density_from_noise of both).
fn shell_density(p: vec3<f32>, inner_radius: f32, outer_radius: f32, coverage: f32, cloud_type: f32, shape_period: f32, detail_period: f32, erosion: f32, seed: u32) -> f32 {
    let r = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if !(r > inner_radius && r < outer_radius) || coverage <= 0.0 {
        return 0.0;
    }
    let height = r - inner_radius;
    let h = height / (outer_radius - inner_radius);
    let gradient = height_gradient(h, cloud_type);
    if gradient <= 0.0 || gradient + coverage - 1.0 < -COVERAGE_SKIP_MARGIN {
        return 0.0;
    }
    let q = vec3<f32>(p.x, p.y, height);
    let covered = shell_covered_density(gradient, coverage, cloud_shape_noise(q / shape_period, seed));
    if covered <= 0.0 {
        return 0.0;
    }
    return shell_eroded_density(h, covered, cloud_detail_noise(q / detail_period, seed), erosion);
}

// shell_density with the noise looked up in baked textures (NoiseBake's shape and
// detail textures, trilinear and repeating) instead of evaluated, each only where the
// density depends on it (as shell_density).
fn shell_density_textured(p: vec3<f32>, inner_radius: f32, outer_radius: f32, coverage: f32, cloud_type: f32, shape_period: f32, detail_period: f32, erosion: f32, shape_tex: texture_3d<f32>, detail_tex: texture_3d<f32>) -> f32 {
    let r = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if !(r > inner_radius && r < outer_radius) || coverage <= 0.0 {
        return 0.0;
    }
    let height = r - inner_radius;
    let h = height / (outer_radius - inner_radius);
    let gradient = height_gradient(h, cloud_type);
    if gradient <= 0.0 || gradient + coverage - 1.0 < -COVERAGE_SKIP_MARGIN {
        return 0.0;
    }
    let q = vec3<f32>(p.x, p.y, height);
    let covered = shell_covered_density(gradient, coverage, noise_texture_trilinear(shape_tex, q / shape_period));
    if covered <= 0.0 {
        return 0.0;
    }
    return shell_eroded_density(h, covered, noise_texture_trilinear(detail_tex, q / detail_period).xyz, erosion);
}

// 1 − smoothstep(fade_start, fade_end, t): the view march's fade toward the horizon.
fn horizon_fade(t: f32, fade_start: f32, fade_end: f32) -> f32 {
    return 1.0 - shell_smoothstep(fade_start, fade_end, t);
}

// One field of procedural_weather: clamp(mean + contrast·(2n − 1), 0, 1) with n the Perlin
// fBm at p under octave seed k; the clamped mean, without the fBm, where the contrast is
// zero and the mean is not (mean + 0·(2n − 1) = mean for the finite n in [0, 1]).
fn procedural_weather_field(p: vec3<f32>, cells: u32, seed: u32, k: u32, mean: f32, contrast: f32) -> f32 {
    if contrast == 0.0 && mean != 0.0 {
        return min(max(mean, 0.0), 1.0);
    }
    let n = perlin_fbm(p, cells, noise_octave_seed(seed, k));
    return min(max(mean + contrast * (2.0 * n - 1.0), 0.0), 1.0);
}

// Procedural weather at (x, y) metres: (coverage, cloud type), each
// clamp(mean + contrast·(2n − 1), 0, 1) of a Perlin fBm repeating every period metres.
fn procedural_weather(xy: vec2<f32>, period: f32, cells: u32, seed: u32, coverage_mean: f32, coverage_contrast: f32, type_mean: f32, type_contrast: f32) -> vec2<f32> {
    let scale = f32(cells) / period;
    let p = vec3<f32>(xy.x * scale, xy.y * scale, 0.0);
    let coverage = procedural_weather_field(p, cells, seed, 7u, coverage_mean, coverage_contrast);
    let cloud_type = procedural_weather_field(p, cells, seed, 8u, type_mean, type_contrast);
    return vec2<f32>(coverage, cloud_type);
}

// The four cells a weather grid's bilinear lookup reads: flat indices (x fastest) of
// cells (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1) wrapped into the grid,
// i = ⌊x/cell − ½⌋, j = ⌊y/cell − ½⌋; and the fractions (gx − i, gy − j).
struct WeatherGridTaps {
    index: vec4<u32>,
    fraction: vec2<f32>,
}

// The cells and fractions of a bilinear lookup of a repeating grid of `size` cells of
// `cell` metres at xy (metres; cell (i, j)'s centre at ((i + ½)·cell, (j + ½)·cell)).
// The caller reads each index's (coverage, cloud type) from its binding, then
// weather_grid_bilinear. i32() saturates, so exact for |xy/cell| < 2³¹.
fn weather_grid_taps(size: vec2<u32>, cell: f32, xy: vec2<f32>) -> WeatherGridTaps {
    let gx = xy.x / cell - 0.5;
    let gy = xy.y / cell - 0.5;
    let fx = floor(gx);
    let fy = floor(gy);
    let n = vec2<i32>(size);
    let ix = vec2<i32>(i32(fx), i32(fx + 1.0));
    let iy = vec2<i32>(i32(fy), i32(fy + 1.0));
    let x = vec2<u32>(((ix % n.x) + n.x) % n.x);
    let y = vec2<u32>(((iy % n.y) + n.y) % n.y);
    let index = vec4<u32>(x.x + size.x * y.x, x.y + size.x * y.x, x.x + size.x * y.y, x.y + size.x * y.y);
    return WeatherGridTaps(index, vec2<f32>(gx - fx, gy - fy));
}

// The grid's (coverage, cloud type) at `fraction` from its four cells' values (in
// WeatherGridTaps.index's order): per layer a + ty·(b − a), a = v00 + tx·(v10 − v00),
// b = v01 + tx·(v11 − v01).
fn weather_grid_bilinear(values: array<vec2<f32>, 4>, fraction: vec2<f32>) -> vec2<f32> {
    let a = values[0] + fraction.x * (values[1] - values[0]);
    let b = values[2] + fraction.x * (values[3] - values[2]);
    return a + fraction.y * (b - a);
}

// Appends the span (a, b) to a ray's spans inside the shell when it is not empty.
fn shell_push_span(spans: ptr<function, RaySpans>, a: f32, b: f32) {
    if b > a {
        (*spans).spans[(*spans).count] = vec2<f32>(a, b);
        (*spans).count += 1u;
    }
}

// The spans of origin + t·direction (unit direction, t ≥ 0) inside the shell, the ray
// stopping where it meets the planet; zero-length spans are dropped.
fn shell_ray_spans(origin: vec3<f32>, direction: vec3<f32>, planet_radius: f32, inner_radius: f32, outer_radius: f32) -> RaySpans {
    var spans = ray_spans_none();
    let r = sqrt(origin.x * origin.x + origin.y * origin.y + origin.z * origin.z);
    let mu = (origin.x * direction.x + origin.y * direction.y + origin.z * direction.z) / r;
    let outer = ray_sphere_intersect(r, mu, outer_radius);
    if !(outer.y > 0.0) {
        return spans;
    }
    let enter = max(outer.x, 0.0);
    var exit = outer.y;
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    if ground.y > 0.0 {
        exit = min(exit, max(ground.x, 0.0));
    }
    let inner = ray_sphere_intersect(r, mu, inner_radius);
    if inner.y > 0.0 {
        shell_push_span(&spans, enter, min(exit, inner.x));
        shell_push_span(&spans, max(enter, inner.y), exit);
    } else {
        shell_push_span(&spans, enter, exit);
    }
    return spans;
}
