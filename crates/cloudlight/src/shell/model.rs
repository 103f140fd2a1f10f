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
/// the detail noise's three and the detail `erosion` strength (in [0, 1)): the covered
/// density of steps 2–4 (`shell_covered_density`), then, where that is above zero, its
/// erosion by the detail (step 5, `shell_eroded_density`). WGSL twin
/// `shell_density_from_noise`.
pub fn shell_density_from_noise<F: Real>(
    h: F,
    coverage: F,
    cloud_type: F,
    shape: [F; 4],
    detail: [F; 3],
    erosion: F,
) -> F {
    let covered = shell_covered_density(height_gradient(h, cloud_type), coverage, shape);
    if covered <= F::zero() {
        return F::zero();
    }
    shell_eroded_density(h, covered, detail, erosion)
}

/// The density before detail erosion (module documentation, steps 2 and 4): the base
/// shape `b = (shape₀ + 1 − fbm)/(2 − fbm)` from the shape noise's four channels, times
/// the height profile `gradient` (step 3), through the coverage, `max(b·g + coverage − 1,
/// 0)`. A step of [`shell_density_from_noise`] (its parity case covers it). WGSL twin
/// `shell_covered_density`.
fn shell_covered_density<F: Real>(gradient: F, coverage: F, shape: [F; 4]) -> F {
    let one = F::one();
    let fbm = worley_channels_fbm([shape[1], shape[2], shape[3]]);
    let base = (shape[0] + one - fbm) / (F::of(2.0) - fbm);
    (base * gradient + coverage - one).max(F::zero())
}

/// The density after detail erosion (module documentation, step 5) of the density
/// `covered` (> 0, [`shell_covered_density`]) at height fraction `h`, from the detail
/// noise's three channels and the `erosion` strength (in [0, 1)): `e = erosion·mix(dfbm,
/// 1 − dfbm, clamp(10h, 0, 1))`, `max(covered − e, 0)/(1 − e)`. A step of
/// [`shell_density_from_noise`] (its parity case covers it). WGSL twin
/// `shell_eroded_density`.
fn shell_eroded_density<F: Real>(h: F, covered: F, detail: [F; 3], erosion: F) -> F {
    let (zero, one) = (F::zero(), F::one());
    let detail_fbm = worley_channels_fbm(detail);
    let wisp = (h * F::of(10.0)).max(zero).min(one);
    let modifier = detail_fbm + wisp * ((one - detail_fbm) - detail_fbm);
    let e = erosion * modifier;
    (covered - e).max(zero) / (one - e)
}

/// How far below zero `g + coverage − 1` must be for [`density_with`] to return zero
/// without looking up the noise. The base shape is at most 1 (shape channels in [0, 1]:
/// `shape₀ + 1 − fbm ≤ 2 − fbm`), so `b·g + coverage − 1 ≤ g + coverage − 1` and the
/// covered density is zero wherever the right side is negative; the margin absorbs the
/// roundings of both sides (a few ULP of values ≤ 2, and the base exceeding 1 by as
/// much), so the skip never changes a result. WGSL twin `COVERAGE_SKIP_MARGIN`.
const COVERAGE_SKIP_MARGIN: f64 = 1e-3;

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
        |q| cloud_shape_noise(q.map(|c| c / shape_period), seed),
        |q| cloud_detail_noise(q.map(|c| c / detail_period), seed),
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
        |q| shape.sample_trilinear(q.map(|c| c / shape_period)),
        |q| {
            let d = detail.sample_trilinear(q.map(|c| c / detail_period));
            [d[0], d[1], d[2]]
        },
    )
}

/// The shell density's steps around the noise lookups `shape_noise(q)` and
/// `detail_noise(q)`: [`shell_density_from_noise`] with each noise looked up only where
/// the result depends on it. Zero outside the shell, at zero coverage or height profile,
/// and where `g + coverage − 1` is below `−COVERAGE_SKIP_MARGIN` (the covered density is
/// zero whatever the shape); the detail only where the covered density is above zero.
#[allow(clippy::too_many_arguments)]
pub(super) fn density_with<F: Real>(
    p: [F; 3],
    inner_radius: F,
    outer_radius: F,
    coverage: F,
    cloud_type: F,
    erosion: F,
    shape_noise: impl Fn([F; 3]) -> [F; 4],
    detail_noise: impl Fn([F; 3]) -> [F; 3],
) -> F {
    let (zero, one) = (F::zero(), F::one());
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    if !(r > inner_radius && r < outer_radius) || coverage <= zero {
        return zero;
    }
    let height = r - inner_radius;
    let h = height / (outer_radius - inner_radius);
    let gradient = height_gradient(h, cloud_type);
    if gradient <= zero || gradient + coverage - one < -F::of(COVERAGE_SKIP_MARGIN) {
        return zero;
    }
    let q = [p[0], p[1], height];
    let covered = shell_covered_density(gradient, coverage, shape_noise(q));
    if covered <= zero {
        return zero;
    }
    shell_eroded_density(h, covered, detail_noise(q), erosion)
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
/// `noise_octave_seed(seed, 8)`. A field with zero contrast and a non-zero mean is its
/// clamped mean (`mean + 0·(2n − 1)` is `mean` for the finite `n` in [0, 1]), so its fBm is
/// not evaluated. WGSL twin `procedural_weather`.
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
    [
        procedural_weather_field(p, cells, seed, 7, coverage_mean, coverage_contrast),
        procedural_weather_field(p, cells, seed, 8, type_mean, type_contrast),
    ]
}

/// One field of [`procedural_weather`]: `clamp(mean + contrast·(2n − 1), 0, 1)` with `n`
/// the [`perlin_fbm`] at `p` under seed `noise_octave_seed(seed, k)`; the clamped mean,
/// without the fBm, where the contrast is zero and the mean is not. WGSL twin
/// `procedural_weather_field`.
fn procedural_weather_field<F: Real>(
    p: [F; 3],
    cells: u32,
    seed: u32,
    k: u32,
    mean: F,
    contrast: F,
) -> F {
    let (zero, one, two) = (F::zero(), F::one(), F::of(2.0));
    if contrast == zero && mean != zero {
        return mean.max(zero).min(one);
    }
    let n = perlin_fbm(p, cells, crate::noise::noise_octave_seed(seed, k));
    (mean + contrast * (two * n - one)).max(zero).min(one)
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

#[cfg(test)]
mod tests {
    use super::*;
    use skyscape_wgsl::common::hash_u32;

    /// The shell density looking up both noises wherever the height profile is above
    /// zero, then steps 2–5 in one piece: what [`density_with`] must equal bit for bit.
    #[allow(clippy::too_many_arguments)]
    fn density_looking_up_both<F: Real>(
        p: [F; 3],
        inner_radius: F,
        outer_radius: F,
        coverage: F,
        cloud_type: F,
        erosion: F,
        shape_noise: impl Fn([F; 3]) -> [F; 4],
        detail_noise: impl Fn([F; 3]) -> [F; 3],
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
        let q = [p[0], p[1], height];
        let (shape, detail) = (shape_noise(q), detail_noise(q));
        let one = F::one();
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

    /// A deterministic value in [0, 1) for sample `i` and channel `salt`.
    fn unit(i: u32, salt: u32) -> f64 {
        f64::from(hash_u32(i.wrapping_mul(0x9e37_79b9) ^ salt.wrapping_mul(0x85eb_ca6b)) >> 8)
            / 16_777_216.0
    }

    /// How many samples took each path: outside or no profile, skipped by the coverage
    /// bound, covered density zero after the shape lookup, eroded.
    #[derive(Debug, Default)]
    struct Paths {
        no_profile: u32,
        coverage_bound: u32,
        uncovered: u32,
        eroded: u32,
    }

    /// [`density_with`] against [`density_looking_up_both`] on `count` samples of a
    /// deck from 1 km to 1.8 km above the Earth: points over ±20 km at every height
    /// through and around the deck, coverage 0, 1, uniform, or within ±2e-3 of the
    /// bound `1 − g`, cloud types and erosion over their ranges.
    fn check_lazy_against_both<F: Real>(
        count: u32,
        shape_noise: impl Fn([F; 3]) -> [F; 4],
        detail_noise: impl Fn([F; 3]) -> [F; 3],
    ) -> Paths {
        let ground = 6_360_000.0;
        let (inner, outer) = (ground + 1_000.0, ground + 1_800.0);
        let mut paths = Paths::default();
        for i in 0..count {
            let x = 20_000.0 * (2.0 * unit(i, 1) - 1.0);
            let y = 20_000.0 * (2.0 * unit(i, 2) - 1.0);
            let r = inner - 50.0 + (outer - inner + 100.0) * unit(i, 3);
            let z = (r * r - x * x - y * y).sqrt();
            let cloud_type = [0.0, 0.5, 1.0, unit(i, 4)][i as usize % 4];
            let h = (r - inner) / (outer - inner);
            let g = height_gradient(h, cloud_type);
            let coverage = match (i / 4) % 4 {
                0 => 0.0,
                1 => 1.0,
                2 => unit(i, 5),
                _ => (1.0 - g + 2e-3 * (2.0 * unit(i, 5) - 1.0)).clamp(0.0, 1.0),
            };
            let erosion = 0.9 * unit(i, 6);
            let p = [x, y, z].map(F::of);
            let (inner_f, outer_f) = (F::of(inner), F::of(outer));
            let (coverage, cloud_type, erosion) =
                (F::of(coverage), F::of(cloud_type), F::of(erosion));
            let lazy = density_with(
                p,
                inner_f,
                outer_f,
                coverage,
                cloud_type,
                erosion,
                &shape_noise,
                &detail_noise,
            );
            let both = density_looking_up_both(
                p,
                inner_f,
                outer_f,
                coverage,
                cloud_type,
                erosion,
                &shape_noise,
                &detail_noise,
            );
            let bits = |v: F| v.to_f64().expect("widens").to_bits();
            assert_eq!(
                bits(lazy),
                bits(both),
                "sample {i}: p = {p:?}, coverage {coverage:?}, type {cloud_type:?}"
            );
            // Which path the lazy evaluation took (recomputed as it computes it).
            let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            let h = (r - inner_f) / (outer_f - inner_f);
            let gradient = height_gradient(h, cloud_type);
            if !(r > inner_f && r < outer_f) || coverage <= F::zero() || gradient <= F::zero() {
                paths.no_profile += 1;
            } else if gradient + coverage - F::one() < -F::of(COVERAGE_SKIP_MARGIN) {
                paths.coverage_bound += 1;
            } else if lazy == F::zero() {
                paths.uncovered += 1;
            } else {
                paths.eroded += 1;
            }
        }
        paths
    }

    /// Each path taken by at least `share` of `count` samples.
    fn assert_every_path(paths: &Paths, count: u32, share: f64) {
        let least = (share * f64::from(count)) as u32;
        for (name, n) in [
            ("no profile", paths.no_profile),
            ("coverage bound", paths.coverage_bound),
            ("uncovered", paths.uncovered),
            ("eroded", paths.eroded),
        ] {
            assert!(n >= least, "{name}: {n} of {count} samples ({paths:?})");
        }
    }

    fn check_procedural<F: Real>(count: u32) {
        let (shape_period, detail_period) = (F::of(6_000.0), F::of(800.0));
        let paths = check_lazy_against_both::<F>(
            count,
            |q| cloud_shape_noise(q.map(|c| c / shape_period), 3),
            |q| cloud_detail_noise(q.map(|c| c / detail_period), 3),
        );
        assert_every_path(&paths, count, 0.02);
    }

    #[test]
    fn lazy_noise_gives_the_same_density_in_f32() {
        check_procedural::<f32>(100_000);
    }

    #[test]
    fn lazy_noise_gives_the_same_density_in_f64() {
        check_procedural::<f64>(100_000);
    }

    /// Both fields' fBm evaluated whatever the contrast: what [`procedural_weather`] must
    /// equal bit for bit.
    fn weather_with_both_fbms<F: Real>(xy: [F; 2], means: [F; 2], contrasts: [F; 2]) -> [F; 2] {
        let (period, cells, seed) = (F::of(50_000.0), 4, 2026);
        let scale = F::of(f64::from(cells)) / period;
        let p = [xy[0] * scale, xy[1] * scale, F::zero()];
        let (zero, one, two) = (F::zero(), F::one(), F::of(2.0));
        std::array::from_fn(|k| {
            let n = perlin_fbm(
                p,
                cells,
                crate::noise::noise_octave_seed(seed, 7 + k as u32),
            );
            (means[k] + contrasts[k] * (two * n - one))
                .max(zero)
                .min(one)
        })
    }

    fn check_weather<F: Real>() {
        let means = [0.0, 0.35, 0.5, 1.0];
        let contrasts = [0.0, 0.25, 1.0];
        for i in 0..20_000u32 {
            let xy = [1, 2].map(|s| F::of(200_000.0 * (2.0 * unit(i, s) - 1.0)));
            let m = [means[i as usize % 4], means[(i / 4) as usize % 4]].map(F::of);
            let c = [
                contrasts[(i / 16) as usize % 3],
                contrasts[(i / 48) as usize % 3],
            ]
            .map(F::of);
            let lazy = procedural_weather(xy, F::of(50_000.0), 4, 2026, m[0], c[0], m[1], c[1]);
            let both = weather_with_both_fbms(xy, m, c);
            let bits = |v: [F; 2]| v.map(|x| x.to_f64().expect("widens").to_bits());
            assert_eq!(
                bits(lazy),
                bits(both),
                "xy {xy:?}, means {m:?}, contrasts {c:?}"
            );
        }
    }

    #[test]
    fn weather_without_contrast_skips_its_fbm_exactly() {
        check_weather::<f32>();
        check_weather::<f64>();
    }

    #[test]
    fn lazy_textures_give_the_same_density() {
        let (shape, detail) = (NoiseTexture::shape(3, 16), NoiseTexture::detail(3, 8));
        fn check<F: Real>(shape: &NoiseTexture, detail: &NoiseTexture) {
            let (shape_period, detail_period) = (F::of(6_000.0), F::of(800.0));
            let paths = check_lazy_against_both::<F>(
                100_000,
                |q| shape.sample_trilinear(q.map(|c| c / shape_period)),
                |q| {
                    let d = detail.sample_trilinear(q.map(|c| c / detail_period));
                    [d[0], d[1], d[2]]
                },
            );
            assert_every_path(&paths, 100_000, 0.02);
        }
        check::<f32>(&shape, &detail);
        check::<f64>(&shape, &detail);
    }
}
