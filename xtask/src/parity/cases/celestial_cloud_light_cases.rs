//! Parity cases of `celestial::clouds`' light: a layer's cover and column, its area-mean
//! optical thickness, the column's sun scattering and the layer's radiance over a
//! background.

use super::celestial_cloud_cases::*;
use super::celestial_draw_cases::unit;
use super::*;

/// The case's background behind the layer.
const CLOUD_BACKGROUND: [f64; 3] = [0.1, 0.2, 0.5];

/// f64 `cloud_column`: the edge's smoothstep cover and the column's τ × the noise's
/// height above the edge's foot, floored at the threshold, over the core depth.
fn column64(u: f64, v: f64, l: &celestial::clouds::CloudLayerUniforms) -> [f64; 2] {
    let x = u / (f64::from(l.feature_size) * f64::from(l.stretch));
    let y = v / f64::from(l.feature_size);
    let n = fbm64(x, y, l.octaves, l.seed);
    let softness = f64::from(l.softness);
    let height = (n - f64::from(l.threshold)) / softness + 0.5;
    let t = height.clamp(0.0, 1.0);
    [
        t * t * (3.0 - 2.0 * t),
        f64::from(l.optical_thickness) * height.max(0.5) * softness / f64::from(l.core_depth),
    ]
}

/// f64 `cloud_optical_thickness`: coverage × the column's τ.
fn optical_thickness64(u: f64, v: f64, l: &celestial::clouds::CloudLayerUniforms) -> f64 {
    let [coverage, column] = column64(u, v, l);
    coverage * column
}

/// The optical thickness's error when (u, v) carry `duv` metres: the noise's error (the
/// cloud_density case's coordinate and fBm terms) over the softness moves the height;
/// d(S(h)·h)/dh ≤ 2.5 on [0, 1] (S the smoothstep, S' ≤ 1.5) and 1 above, times
/// τ·softness/core depth; the height's own three roundings and the products' 6u.
fn optical_thickness_error(
    u: f64,
    v: f64,
    duv: f64,
    l: &celestial::clouds::CloudLayerUniforms,
) -> f64 {
    let scale = f64::from(l.feature_size);
    let dx = (6.0 * U * u.abs().max(v.abs()) + duv) / scale;
    let softness = f64::from(l.softness);
    let height = 3.0 + 1.0 / softness;
    let noise_error = fbm_error(l.octaves, dx) + 4.0 * U;
    let tau_scale = f64::from(l.optical_thickness) * softness / f64::from(l.core_depth);
    tau_scale * 2.5 * (noise_error / softness + 3.0 * U * height)
        + 6.0 * U * optical_thickness64(u, v, l)
}

/// `cloud_column`'s errors when (u, v) carry `duv` metres: the height's error as in
/// [`optical_thickness_error`]; the coverage's smoothstep has slope ≤ 1.5 in the height
/// (plus its own 4u), the column's max(h, ½)·τ·softness/core depth slope ≤ 1 (plus its
/// products' 4u).
fn column_error(u: f64, v: f64, duv: f64, l: &celestial::clouds::CloudLayerUniforms) -> [f64; 2] {
    let scale = f64::from(l.feature_size);
    let dx = (6.0 * U * u.abs().max(v.abs()) + duv) / scale;
    let softness = f64::from(l.softness);
    let height = 3.0 + 1.0 / softness;
    let height_error = (fbm_error(l.octaves, dx) + 4.0 * U) / softness + 3.0 * U * height;
    let [coverage, column] = column64(u, v, l);
    let tau_scale = f64::from(l.optical_thickness) * softness / f64::from(l.core_depth);
    [
        1.5 * height_error + 4.0 * U * coverage,
        tau_scale * height_error + 4.0 * U * column,
    ]
}

/// f64 twin of `cloud_layer_radiance` with the hit distance scaled by `1 + stretch` and
/// the column's optical thickness moved by `tau_shift` (to measure the result's
/// sensitivity to their rounding); `cloud_sun_scattering` instantiated in f64.
fn layer_radiance64(x: &[f64], stretch: f64, tau_shift: f64) -> Vec<f64> {
    let l = layer_from(x, 4);
    let view = [x[0], x[1], x[2]];
    let r = x[3];
    let (base, top) = (f64::from(l.base_radius), f64::from(l.top_radius));
    let background = CLOUD_BACKGROUND;
    if r >= base && r <= top {
        return background.to_vec();
    }
    let below = r < base;
    let surface = if below { base } else { top };
    let mut distance = distance64(r, view[2], surface, l.curved);
    if distance < 0.0 {
        return background.to_vec();
    }
    distance *= 1.0 + stretch;
    let horizontal = [view[0] * distance, view[1] * distance];
    let reach = horizontal[0].hypot(horizontal[1]);
    let half_span = f64::from(l.half_span);
    if reach >= half_span {
        return background.to_vec();
    }
    let rim = (2.0 * (1.0 - reach / half_span)).min(1.0);
    let hit_z = r + view[2] * distance;
    let mu_hit = if l.curved != 0 {
        (view[0] * horizontal[0] + view[1] * horizontal[1] + view[2] * hit_z) / surface
    } else {
        view[2]
    };
    let slant = mu_hit.abs().max(0.01);
    let [coverage, tau] = column64(
        horizontal[0] + f64::from(l.offset[0]),
        horizontal[1] + f64::from(l.offset[1]),
        &l,
    );
    if coverage <= 0.0 {
        return background.to_vec();
    }
    let tau = (tau + tau_shift).max(0.0);
    let g = f64::from(l.asymmetry);
    let opacity = -(-tau / slant).exp_m1();
    let sun = l.sun_direction.map(f64::from);
    let cos_scattering = view[0] * sun[0] + view[1] * sun[1] + view[2] * sun[2];
    let sun_scattering = celestial::twins::cloud_sun_scattering::<f64>(
        tau,
        g,
        sun[2],
        slant,
        cos_scattering,
        u32::from(below),
    );
    let sky = if below {
        (1.0 - reflectance64(tau, g, 0.5) - (-tau / 0.5).exp()).max(0.0)
    } else {
        reflectance64(tau, g, 0.5)
    };
    let beta = f64::from(l.fog_extinction);
    let fog = if l.exp2_fog != 0 {
        let x = beta * distance;
        (-(x * x) / 3.912_023_005_428_146).exp()
    } else {
        (-beta * distance).exp()
    };
    let emissivity = -(-f64::from(celestial::clouds::DIFFUSIVITY) * tau).exp_m1();
    (0..3)
        .map(|i| {
            let lit = sun_scattering * f64::from(l.sunlight[i])
                + sky * f64::from(l.skylight[i]) / std::f64::consts::PI * opacity / emissivity;
            let faded = fog * lit + (1.0 - fog) * opacity * f64::from(l.fog_colour[i]);
            background[i] + rim * coverage * (faded - opacity * background[i])
        })
        .collect()
}

/// The layer radiance's forward bound: its change when the hit distance moves by its
/// rounding (a relative 4u for flat layers, the ray–sphere bound for curved ones,
/// which also moves the texture coordinates) and when the column's optical thickness
/// moves by its own bound (the cloud_optical_thickness case's), plus 64u of the
/// radiance for the exponentials, the phase function and the blend.
fn layer_radiance_bound(x: &[f64]) -> Vec<f64> {
    let reference = layer_radiance64(x, 0.0, 0.0);
    let l = layer_from(x, 4);
    let r = x[3];
    let below = r < f64::from(l.base_radius);
    let surface = if below {
        f64::from(l.base_radius)
    } else {
        f64::from(l.top_radius)
    };
    let distance = distance64(r, x[2], surface, l.curved);
    if distance <= 0.0 {
        return vec![0.0; 3];
    }
    let relative = if l.curved != 0 {
        let b = ray_sphere_bound(&[r, x[2], surface]);
        b[0].max(b[1]) / distance + 4.0 * U
    } else {
        4.0 * U
    };
    let horizontal = [x[0] * distance, x[1] * distance];
    let tau_bound = optical_thickness_error(
        horizontal[0] + f64::from(l.offset[0]),
        horizontal[1] + f64::from(l.offset[1]),
        4.0 * U * distance,
        &l,
    );
    let shifted = [
        layer_radiance64(x, relative, 0.0),
        layer_radiance64(x, -relative, 0.0),
        layer_radiance64(x, 0.0, tau_bound),
        layer_radiance64(x, 0.0, -tau_bound),
    ];
    (0..3)
        .map(|i| {
            let distance_change = (shifted[0][i] - reference[i])
                .abs()
                .max((shifted[1][i] - reference[i]).abs());
            let tau_change = (shifted[2][i] - reference[i])
                .abs()
                .max((shifted[3][i] - reference[i]).abs());
            // The distance's rounding moves the texture too: a step in τ there is caught
            // by the shifted twin, the slope within the step by doubling it.
            2.0 * distance_change + 2.0 * tau_change + 64.0 * U * reference[i].abs()
        })
        .collect()
}

/// `cloud_sun_scattering`'s forward bound: the exponentials' (3 + 2|x| ULP each, at the
/// largest argument), the mean attenuations' arguments (a difference of reciprocals:
/// 4u of τ(1/μ + 1/μ₀), moving ln φ by at most that), the phase function's base
/// 1 + g² − 2g·cosθ (3u of its terms, relative to the base, ×1.5 for its 3/2 power), and
/// 16u for the products; the multiple-scattering flux is a difference of terms ≤ 1 (16u
/// absolute plus the direct beam's exp error) carried through μ₀/π·opacity/emissivity.
fn sun_scattering_bound(x: &[f64]) -> Vec<f64> {
    let (tau, g, mu_sun, mu_view, cos) = (x[0], x[1], x[2], x[3], x[4]);
    if mu_sun <= 0.0 || tau <= 0.0 {
        return vec![0.0];
    }
    let value =
        celestial::twins::cloud_sun_scattering::<f64>(tau, g, mu_sun, mu_view, cos, x[5] as u32);
    let base = 1.0 + g * g - 2.0 * g * cos;
    let phase_error = 1.5 * 3.0 * U * (1.0 + g * g + 2.0 * (g * cos).abs()) / base;
    let largest = tau * (1.0 / mu_sun + 1.0 / mu_view + 1.66);
    let single_error =
        2.0 * exp_relative_error(largest) + 4.0 * U * largest + phase_error + 16.0 * U;
    let opacity = -(-tau / mu_view).exp_m1();
    let emissivity = -(-1.66 * tau).exp_m1();
    let flux_error = (16.0 * U + exp_relative_error(tau / mu_sun) + exp_relative_error(1.66 * tau))
        * mu_sun
        / std::f64::consts::PI
        * opacity
        / emissivity;
    vec![value * single_error + flux_error]
}

fn layer_radiance_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let layers = case_layers();
    for (k, layer) in layers.iter().enumerate() {
        for altitude in [500.0, 4_000.0] {
            for curved in [0u32, 1] {
                for exp2 in [0u32, 1] {
                    for e in linspace(-1.45, 1.45, 15) {
                        for a in linspace(0.0, 6.0, 14) {
                            let view = unit(e, a + 0.1 * k as f64);
                            let mut row = view.to_vec();
                            row.push(R_GROUND + altitude);
                            row.extend(layer_row(layer, curved, exp2));
                            grid.push(row);
                        }
                    }
                }
            }
        }
    }
    grid
}

/// The cases, in report order.
pub(super) fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "celestial::cloud_layer_radiance",
            imports: &["celestial::clouds"],
            arity: (17, 3),
            wgsl: concat!(
                layer_wgsl!(
                    "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13", "x14", "x15",
                    "x16"
                ),
                "let l = cloud_layer_radiance(vec3<f32>(x0, x1, x2), x3, layer, \
                 vec3<f32>(0.1, 0.2, 0.5)); y0 = l.x; y1 = l.y; y2 = l.z;"
            ),
            grid: layer_radiance_grid,
            cpu: |x| {
                let l = layer_from_f32(x, 4);
                celestial::clouds::cloud_layer_radiance(
                    [x[0], x[1], x[2]],
                    x[3],
                    &l,
                    [0.1, 0.2, 0.5],
                )
                .to_vec()
            },
            reference: |x| layer_radiance64(x, 0.0, 0.0),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(layer_radiance_bound),
                why: "the f64 twin's change when the hit distance moves by its rounding (flat \
                      4u, curved the ray–sphere bound; it moves the texture too) and when the \
                      column's optical thickness moves by the cloud_optical_thickness case's \
                      bound, each doubled; 64u for the exponentials, phase function and blends",
            },
        },
        Case {
            name: "celestial::cloud_column",
            imports: &["celestial::clouds"],
            arity: (15, 2),
            wgsl: concat!(
                layer_wgsl!(
                    "x2", "x3", "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13",
                    "x14"
                ),
                "let column = cloud_column(x0, x1, layer); y0 = column.x; y1 = column.y;"
            ),
            grid: density_grid,
            cpu: |x| {
                let l = layer_from_f32(x, 2);
                celestial::twins::cloud_column(x[0], x[1], &l).to_vec()
            },
            reference: |x| column64(x[0], x[1], &layer_from(x, 2)).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| column_error(x[0], x[1], 0.0, &layer_from(x, 2)).to_vec()),
                why: "the noise's error (coordinates' quotients 6u, the fBm's blending) over the \
                      softness moves the height; the coverage's smoothstep slope ≤ 1.5 and the \
                      column's max(h, ½) slope ≤ 1 times τ·softness/core depth; their own \
                      roundings 4u",
            },
        },
        Case {
            name: "celestial::cloud_optical_thickness",
            imports: &["celestial::clouds"],
            arity: (15, 1),
            wgsl: concat!(
                layer_wgsl!(
                    "x2", "x3", "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13",
                    "x14"
                ),
                "y0 = cloud_optical_thickness(x0, x1, layer);"
            ),
            grid: density_grid,
            cpu: |x| {
                let l = layer_from_f32(x, 2);
                vec![celestial::twins::cloud_optical_thickness(x[0], x[1], &l)]
            },
            reference: |x| vec![optical_thickness64(x[0], x[1], &layer_from(x, 2))],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| vec![optical_thickness_error(x[0], x[1], 0.0, &layer_from(x, 2))]),
                why: "the noise's error (coordinates' quotients 6u, the fBm's blending) over the \
                      softness moves the height; d(S(h)·max(h, ½))/dh ≤ 2.5 times τ·softness/core depth; \
                      the height's three roundings and the products' 6u",
            },
        },
        Case {
            name: "celestial::cloud_sun_scattering",
            imports: &["celestial::clouds"],
            arity: (6, 1),
            wgsl: "y0 = cloud_sun_scattering(x0, x1, x2, x3, x4, u32(x5));",
            grid: || {
                let mut grid = Vec::new();
                for tau in logspace(1e-3, 200.0, 24) {
                    for g in [0.75, 0.85] {
                        for mu_sun in linspace(-0.1, 1.0, 12) {
                            for mu_view in [0.01, 0.05, 0.2, 0.45, 0.8, 1.0] {
                                for cos in linspace(-1.0, 1.0, 9) {
                                    for transmitted in [0.0, 1.0] {
                                        grid.push(vec![tau, g, mu_sun, mu_view, cos, transmitted]);
                                    }
                                }
                            }
                        }
                    }
                }
                grid
            },
            cpu: |x| {
                vec![celestial::twins::cloud_sun_scattering(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                )]
            },
            reference: |x| {
                vec![celestial::twins::cloud_sun_scattering::<f64>(
                    x[0],
                    x[1],
                    x[2],
                    x[3],
                    x[4],
                    x[5] as u32,
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(sun_scattering_bound),
                why: "one formula instantiated in f64: the exponentials' 3 + 2|x| ULP at the \
                      largest argument, the mean attenuations' arguments (differences of \
                      reciprocals, 4u of τ(1/μ + 1/μ₀)), the phase function's base relative to \
                      its terms (×1.5), 16u for products; the flux difference's 16u through \
                      μ₀/π·opacity/emissivity",
            },
        },
    ]
}
