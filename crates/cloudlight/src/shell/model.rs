//! The density model: height profiles, density from noise, weather, horizon fade,
//! the shell's ray spans.

use atmos::geometry::ray_sphere_intersect;
use atmos::real::Real;

use crate::density::RaySpans;
use crate::noise::{
    NoiseTexture, cloud_detail_noise, cloud_shape_noise, perlin_fbm, worley_channels_fbm,
};

/// Stratus height profile corners `(a, b, c, d)` over the height fraction.
pub const STRATUS_GRADIENT: [f64; 4] = [0.0, 0.1, 0.2, 0.3];
/// Stratocumulus height profile corners.
pub const STRATOCUMULUS_GRADIENT: [f64; 4] = [0.02, 0.2, 0.48, 0.625];
/// Cumulus height profile corners.
pub const CUMULUS_GRADIENT: [f64; 4] = [0.0, 0.1625, 0.88, 0.98];

/// Hermite `smoothstep`: `t²(3 − 2t)` with `t = clamp((x − lo)/(hi − lo), 0, 1)`
/// (`lo < hi`). Spelled out in WGSL as `shell_smoothstep` (not the built-in, whose
/// evaluation order is the driver's).
pub fn shell_smoothstep<F: Real>(lo: F, hi: F, x: F) -> F {
    let t = ((x - lo) / (hi - lo)).max(F::zero()).min(F::one());
    t * t * (F::of(3.0) - F::of(2.0) * t)
}

/// The height profile in [0, 1] at height fraction `h` for cloud type `cloud_type`
/// (0 stratus, ½ stratocumulus, 1 cumulus; module documentation). WGSL twin
/// `height_gradient`.
pub fn height_gradient<F: Real>(h: F, cloud_type: F) -> F {
    let (zero, one, two, half) = (F::zero(), F::one(), F::of(2.0), F::of(0.5));
    let stratus = one - (cloud_type * two).max(zero).min(one);
    let stratocumulus = one - (cloud_type - half).abs() * two;
    let cumulus = (cloud_type - half).max(zero).min(one) * two;
    let corner = |k: usize| {
        stratus * F::of(STRATUS_GRADIENT[k])
            + stratocumulus * F::of(STRATOCUMULUS_GRADIENT[k])
            + cumulus * F::of(CUMULUS_GRADIENT[k])
    };
    let (a, b, c, d) = (corner(0), corner(1), corner(2), corner(3));
    (shell_smoothstep(a, b, h) - shell_smoothstep(c, d, h)).max(zero)
}

/// The density (module documentation, steps 2–5) from the height fraction `h` (in
/// [0, 1]), the weather's `coverage` and `cloud_type`, the shape noise's four channels,
/// the detail noise's three and the detail `erosion` strength (in [0, 1)). WGSL twin
/// `shell_density_from_noise`.
pub fn shell_density_from_noise<F: Real>(
    h: F,
    coverage: F,
    cloud_type: F,
    shape: [F; 4],
    detail: [F; 3],
    erosion: F,
) -> F {
    let (zero, one) = (F::zero(), F::one());
    let fbm = worley_channels_fbm([shape[1], shape[2], shape[3]]);
    let base = (shape[0] + one - fbm) / (F::of(2.0) - fbm);
    let gradient = height_gradient(h, cloud_type);
    let covered = (base * gradient + coverage - one).max(zero);
    if covered <= zero {
        return zero;
    }
    let detail_fbm = worley_channels_fbm(detail);
    let wisp = (h * F::of(10.0)).max(zero).min(one);
    let modifier = detail_fbm + wisp * ((one - detail_fbm) - detail_fbm);
    let e = erosion * modifier;
    (covered - e).max(zero) / (one - e)
}

/// The shell's density at the planet-centred point `p` (metres) for the weather
/// `coverage` and `cloud_type` there: zero unless `inner_radius < |p| < outer_radius`,
/// else [`shell_density_from_noise`] of the shape noise at `q / shape_period` and the
/// detail noise at `q / detail_period` (`q = (x, y, |p| − inner_radius)`, periods in
/// metres; `seed` seeds both). WGSL twin `shell_density`.
#[allow(clippy::too_many_arguments)]
pub fn shell_density<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    shape_period: F,
    detail_period: F,
    erosion: F,
    seed: u32,
) -> F {
    density_with(
        p,
        inner_radius,
        outer_radius,
        coverage,
        cloud_type,
        erosion,
        |q| {
            let shape = cloud_shape_noise(q.map(|c| c / shape_period), seed);
            let detail = cloud_detail_noise(q.map(|c| c / detail_period), seed);
            (shape, detail)
        },
    )
}

/// [`shell_density`] with the noise looked up in baked textures (trilinear, repeating:
/// [`NoiseTexture::sample_trilinear`]) instead of evaluated: what a GPU march over
/// [`crate::gpu::NoiseBake`]'s textures computes. WGSL twin `shell_density_textured`.
#[allow(clippy::too_many_arguments)]
pub fn shell_density_textured<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    shape_period: F,
    detail_period: F,
    erosion: F,
    shape: &NoiseTexture,
    detail: &NoiseTexture,
) -> F {
    density_with(
        p,
        inner_radius,
        outer_radius,
        coverage,
        cloud_type,
        erosion,
        |q| {
            let s = shape.sample_trilinear(q.map(|c| c / shape_period));
            let d = detail.sample_trilinear(q.map(|c| c / detail_period));
            (s, [d[0], d[1], d[2]])
        },
    )
}

/// The shell density's steps around the noise lookup `noise(q)` (shape, detail).
pub(super) fn density_with<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    erosion: F,
    noise: impl Fn([F; 3]) -> ([F; 4], [F; 3]),
) -> F {
    let zero = F::zero();
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if !(r > inner_radius && r < outer_radius) || coverage <= zero {
        return zero;
    }
    let height = r - inner_radius;
    let h = height / (outer_radius - inner_radius);
    if height_gradient(h, cloud_type) <= zero {
        return zero;
    }
    let (shape, detail) = noise([p[0], p[1], height]);
    shell_density_from_noise(h, coverage, cloud_type, shape, detail, erosion)
}

/// The horizon fade at distance `t` (metres) along a view ray: 1 up to `fade_start`,
/// 0 from `fade_end` on, `1 − smoothstep` between (`fade_start < fade_end`). The view
/// march multiplies each sample's density by it (module documentation). WGSL twin
/// `horizon_fade`.
pub fn horizon_fade<F: Real>(t: F, fade_start: F, fade_end: F) -> F {
    F::one() - shell_smoothstep(fade_start, fade_end, t)
}

/// Procedural weather at horizontal position `(x, y)` (metres): `[coverage, cloud_type]`,
/// each `clamp(mean + contrast·(2n − 1), 0, 1)` with `n` the [`perlin_fbm`] on the plane
/// `z = 0` at `(x, y)·cells/period` with lattice period `cells`, so the map repeats every
/// `period` metres; coverage uses seed `noise_octave_seed(seed, 7)`, the type
/// `noise_octave_seed(seed, 8)`. WGSL twin `procedural_weather`.
#[allow(clippy::too_many_arguments)]
pub fn procedural_weather<F: Real>(
    xy: [F; 2],
    period: F,
    cells: u32,
    seed: u32,
    coverage_mean: F,
    coverage_contrast: F,
    type_mean: F,
    type_contrast: F,
) -> [F; 2] {
    let scale = F::of(f64::from(cells)) / period;
    let p = [xy[0] * scale, xy[1] * scale, F::zero()];
    let (zero, one, two) = (F::zero(), F::one(), F::of(2.0));
    let n_coverage = perlin_fbm(p, cells, crate::noise::noise_octave_seed(seed, 7));
    let n_type = perlin_fbm(p, cells, crate::noise::noise_octave_seed(seed, 8));
    let coverage = (coverage_mean + coverage_contrast * (two * n_coverage - one))
        .max(zero)
        .min(one);
    let cloud_type = (type_mean + type_contrast * (two * n_type - one))
        .max(zero)
        .min(one);
    [coverage, cloud_type]
}

/// The spans of the ray `origin + t·direction` (planet-centred metres, unit `direction`,
/// `t ≥ 0`) inside the shell `inner_radius < r < outer_radius`, the ray stopping where it
/// meets the planet (`planet_radius`). From `atmos`' stable ray–sphere roots with
/// `r = |origin|`, `μ = origin·direction / r`. Zero-length spans (a tangent ray) are
/// dropped. WGSL twin `shell_ray_spans`.
pub fn shell_ray_spans<F: Real>(
    origin: [F; 3],
    direction: [F; 3],
    planet_radius: F,
    inner_radius: F,
    outer_radius: F,
) -> RaySpans<F> {
    let zero = F::zero();
    let r = (origin[0] * origin[0] + origin[1] * origin[1] + origin[2] * origin[2]).sqrt();
    let mu = (origin[0] * direction[0] + origin[1] * direction[1] + origin[2] * direction[2]) / r;
    let outer = ray_sphere_intersect(r, mu, outer_radius);
    if outer[1].is_nan() || outer[1] <= zero {
        return RaySpans::none();
    }
    let enter = outer[0].max(zero);
    let mut exit = outer[1];
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    if ground[1] > zero {
        // The ray's line meets the planet ahead: it stops at the first hit (or at once
        // if the origin is inside the planet).
        exit = exit.min(ground[0].max(zero));
    }
    let inner = ray_sphere_intersect(r, mu, inner_radius);
    let mut spans = RaySpans::none();
    let mut push = |a: F, b: F| {
        if b > a {
            spans.spans[spans.count] = (a, b);
            spans.count += 1;
        }
    };
    if inner[1] > zero {
        push(enter, exit.min(inner[0]));
        push(enter.max(inner[1]), exit);
    } else {
        push(enter, exit);
    }
    spans
}
