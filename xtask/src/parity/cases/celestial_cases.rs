//! Parity cases of `celestial`: the equatorial → horizontal transform, Pogson's
//! magnitude → illuminance, the moon disc's incidence cosine, and the drawing of the sky
//! objects (`celestial::draw`: the sun's limb darkening and aureole, the moon's
//! Lommel–Seeliger disc, the disc objects through their transmittance, star detection
//! thresholds, point-source irradiance, sprite weights, pixel solid angles and the
//! camera projection).

use super::*;
use crate::parity::compare::ulp_f32;

const PI64: f64 = std::f64::consts::PI;
const TAU64: f64 = std::f64::consts::TAU;

/// East/north/up components of the unit vector in f64 (inputs already f32-rounded).
fn enu(h: f64, d: f64, p: f64) -> [f64; 3] {
    [
        -d.cos() * h.sin(),
        d.sin() * p.cos() - d.cos() * h.cos() * p.sin(),
        d.sin() * p.sin() + d.cos() * h.cos() * p.cos(),
    ]
}

/// Absolute error of each f32 component: six sin/cos (lavapipe a few ULP of 1; 4
/// allowed each) and two products and a sum per component: ≤ 16u.
const COMPONENT_ERROR: f64 = 16.0 * U;

/// Forward bounds of (azimuth, elevation). Both are atan2 of components carrying
/// `COMPONENT_ERROR`: the angle moves by at most that over the length of the pair
/// (|(e, n)| for the azimuth, 1 for the elevation), plus atan2's own error (lavapipe
/// ≈ 300 ULP, 512 allowed). On the north meridian (|east| within the component
/// error) a sign flip of `east` wraps the azimuth by 2π, which is the same direction.
fn transform_bound(x: &[f64]) -> Vec<f64> {
    let [east, north, _] = enu(x[0], x[1], x[2]);
    let horizontal = east.hypot(north);
    let [azimuth, elevation] = celestial::equatorial_to_horizontal(x[0], x[1], x[2]);
    let mut azimuth_bound = 512.0 * ulp_f32(azimuth)
        + if horizontal > 0.0 {
            (2.0 * COMPONENT_ERROR / horizontal).min(PI64)
        } else {
            PI64
        };
    if horizontal <= 2.0 * COMPONENT_ERROR {
        // Within rounding of the zenith or nadir both components may change sign: the
        // azimuth is atan2 of rounding noise, any angle in [0, 2π] (the function's
        // contract). The NVIDIA H100 (Vulkan) differs here from lavapipe at the
        // celestial pole seen from the pole (components ~4e-8): error 4.5 rad.
        azimuth_bound = TAU64 + 512.0 * ulp_f32(TAU64);
    } else if east.abs() <= COMPONENT_ERROR && north >= 0.0 {
        // The wrapped value is a + TAU in f32: TAU's own rounding (1.7e-7) and the
        // sum's (½ ULP of 2π) come on top of the 2π.
        azimuth_bound += TAU64 + ulp_f32(TAU64);
    }
    vec![
        azimuth_bound,
        512.0 * ulp_f32(elevation) + 2.0 * COMPONENT_ERROR,
    ]
}

fn transform_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for h in linspace(-PI64, PI64, 49) {
        for d in linspace(-PI64 / 2.0, PI64 / 2.0, 25) {
            for p in linspace(-PI64 / 2.0, PI64 / 2.0, 25) {
                grid.push(vec![h, d, p]);
            }
        }
    }
    // Near the zenith (δ → φ, H → 0), at the poles and beyond one turn of hour angle.
    for k in 1..=6 {
        let e = 10f64.powi(-k);
        grid.extend([
            vec![e, 0.7 + e, 0.7],
            vec![-e, 0.7, 0.7 + e],
            vec![e, PI64 / 2.0 - e, PI64 / 2.0],
            vec![3.0, -PI64 / 2.0 + e, -PI64 / 2.0],
        ]);
    }
    grid.extend([
        vec![0.0, 0.7, 0.7],
        vec![7.5, 0.3, -0.4],
        vec![-12.0, -1.2, 1.1],
        vec![PI64, 0.0, 0.0],
    ]);
    grid
}

fn magnitude_grid() -> Vec<Vec<f64>> {
    let mut grid: Vec<Vec<f64>> = linspace(-27.0, 30.0, 11_401).map(|m| vec![m]).collect();
    grid.extend([vec![0.0], vec![-1.46], vec![-12.7], vec![-26.74], vec![6.5]]);
    grid
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "celestial::equatorial_to_horizontal",
            imports: &["celestial::coordinates"],
            arity: (3, 2),
            wgsl: "let r = equatorial_to_horizontal(x0, x1, x2); y0 = r.x; y1 = r.y;",
            grid: transform_grid,
            cpu: |x| celestial::equatorial_to_horizontal(x[0], x[1], x[2]).to_vec(),
            reference: |x| celestial::equatorial_to_horizontal(x[0], x[1], x[2]).to_vec(),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(transform_bound),
                why: "components carry ≤ 16u (sin/cos, products, sums); each angle is an atan2 \
                      (512 ULP) moved by that error over the pair's length (|(e, n)| for azimuth, \
                      so it grows toward the zenith); a 2π wrap is allowed only on the north \
                      meridian, where east's sign is within rounding, and any azimuth where \
                      |(e, n)| is within rounding of 0 (zenith, nadir: atan2 of noise)",
            },
        },
        Case {
            name: "celestial::illuminance_from_magnitude",
            imports: &["celestial::coordinates"],
            arity: (1, 1),
            wgsl: "y0 = illuminance_from_magnitude(x0);",
            grid: magnitude_grid,
            cpu: |x| vec![celestial::illuminance_from_magnitude(x[0])],
            reference: |x| vec![celestial::illuminance_from_magnitude(x[0])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 8.0,
                bound: Some(|x| {
                    // The exponent −0.921·m rounds (u·|arg|, amplified 1:1 by exp),
                    // the constants round (2u), exp itself: WGSL's 3 + 2|arg| ULP.
                    let arg = (0.4 * std::f64::consts::LN_10 * x[0]).abs();
                    let y = celestial::illuminance_from_magnitude(x[0]);
                    vec![y * U * (2.0 + 3.0 * arg)]
                }),
                why: "exp's argument −0.4 ln10·m rounds (relative u·|arg| in the result), two \
                      constants round (2u), exp within WGSL's 3 + 2|arg| ULP",
            },
        },
        Case {
            name: "celestial::moon_disc_incidence_cosine",
            imports: &["celestial::moon"],
            arity: (4, 1),
            wgsl: "y0 = moon_disc_incidence_cosine(x0, x1, x2, x3);",
            grid: moon_disc_grid,
            cpu: |x| {
                vec![celestial::moon_disc_incidence_cosine(
                    x[0], x[1], x[2], x[3],
                )]
            },
            reference: |x| {
                vec![celestial::moon_disc_incidence_cosine(
                    x[0], x[1], x[2], x[3],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(moon_disc_bound),
                why: "four sin/cos (4 ULP of 1 each), products and a sum of three unit-bounded \
                      terms (≤ 16u), and √(1 − ρ²) whose rounding of 1 − ρ² is amplified by \
                      1/(2√(1 − ρ²)) toward the limb",
            },
        },
    ]
    .into_iter()
    .chain(draw_cases())
    .chain(cloud_cases())
    .collect()
}

/// Disc points on a grid over the square around the disc (the outside must be 0)
/// plus points just inside and outside the limb, for phases 0…π and limbs 0…2π.
fn moon_disc_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for phase in linspace(0.0, PI64, 7) {
        for limb in linspace(0.0, TAU64, 9) {
            for east in linspace(-1.05, 1.05, 22) {
                for north in linspace(-1.05, 1.05, 22) {
                    grid.push(vec![east, north, phase, limb]);
                }
            }
            for k in 0..16 {
                let a = TAU64 * f64::from(k) / 16.0;
                for r in [1.0 - 1e-3, 1.0 - 1e-6, 1.0 + 1e-6] {
                    grid.push(vec![r * a.sin(), r * a.cos(), phase, limb]);
                }
            }
        }
    }
    grid
}

/// 16u for the unit-bounded products and sum (sin/cos included), plus the limb term:
/// 1 − ρ² carries ≤ 3u absolute, and √ amplifies it by 1/(2√(1 − ρ²)) (capped at the
/// √(3u) a rounding can produce from 0).
fn moon_disc_bound(x: &[f64]) -> Vec<f64> {
    let rho2 = x[0] * x[0] + x[1] * x[1];
    let depth = (1.0 - rho2).max(0.0);
    let limb = if depth > 3.0 * U {
        3.0 * U / (2.0 * depth.sqrt())
    } else {
        (6.0 * U).sqrt()
    };
    // The grid keeps every point ≥ 10⁻⁶ from the rim (≫ u), so no point is inside
    // the disc in one precision and outside in the other.
    vec![16.0 * U + limb]
}

// ---------------------------------------------------------------- celestial::draw

/// WGSL `log`: absolute error 2⁻²¹ on [0.5, 2], 3 ULP elsewhere (the spec); as a
/// relative error of exp(α·ln μ) it is α·(that absolute error).
fn log_absolute_error(x: f64) -> f64 {
    if (0.5..=2.0).contains(&x) {
        2f64.powi(-21)
    } else {
        3.0 * U * x.ln().abs()
    }
}

/// Forward bound of the limb factor when sin θ carries the absolute error `d_sin`:
/// the f64 function's change over sin θ ± d_sin (its sensitivity, which grows without
/// bound at the limb where μ = √((1 − q)(1 + q)) → 0), plus what μ^α = exp(α ln μ) adds
/// by itself: log's absolute error (2⁻²¹ on [0.5, 2]) times α, exp's 3 + 2|arg| ULP,
/// and 4u for the quotient, the root and the factor.
fn limb_factor_error(
    sin_offset: f64,
    cos_offset: f64,
    sin_radius: f64,
    exponent: f64,
    d_sin: f64,
) -> f64 {
    let f = |s: f64| celestial::twins::sun_disc_limb_factor(s, cos_offset, sin_radius, exponent);
    let y = f(sin_offset);
    let sensitivity = (f(sin_offset + d_sin) - y)
        .abs()
        .max((f((sin_offset - d_sin).max(0.0)) - y).abs());
    if y == 0.0 {
        return sensitivity;
    }
    let ratio = sin_offset / sin_radius;
    let mu = ((1.0 - ratio) * (1.0 + ratio)).sqrt();
    sensitivity
        + y * (exponent * log_absolute_error(mu) + exp_relative_error(exponent * mu.ln()) + 4.0 * U)
}

fn limb_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for sin_radius in [0.004_65, 0.01, 0.2] {
        for exponent in [0.0, 0.406, 0.508, 0.641, 1.5] {
            let mut ratios: Vec<f64> = linspace(0.0, 1.08, 216).collect();
            for k in 2..=6 {
                ratios.extend([1.0 - 10f64.powi(-k), 1.0 + 10f64.powi(-k)]);
            }
            for ratio in ratios {
                // No row within rounding of the rim (inside in one precision, outside in
                // the other): both answers are right there.
                if (ratio - 1.0).abs() < 1e-5 {
                    continue;
                }
                for cos_offset in [1.0, 0.999, -0.3] {
                    grid.push(vec![ratio * sin_radius, cos_offset, sin_radius, exponent]);
                }
            }
        }
    }
    grid
}

fn limb_bound(x: &[f64]) -> Vec<f64> {
    // The quotient sin θ / sin ρ rounds: as a relative error of sin θ, 2u.
    vec![limb_factor_error(x[0], x[1], x[2], x[3], 2.0 * U * x[0])]
}

fn aureole_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for g in [0.0, 0.3, 0.7, 0.76, 0.8, 0.9, 0.99] {
        for theta in logspace(1e-4, 0.6, 360) {
            for (irradiance, transmittance, depth) in [
                (1.0, 0.8, 0.05),
                (1.3e5, 0.02, 1.2),
                (2.0, 1.0, 1e-4),
                (1.0, 0.0, 0.3),
            ] {
                grid.push(vec![theta.cos(), g, irradiance, transmittance, depth]);
            }
        }
        grid.push(vec![1.0, g, 1.0, 0.5, 0.1]);
        grid.push(vec![-1.0, g, 1.0, 0.5, 0.1]);
    }
    grid
}

/// The offset and its error of the moon's disc point (see `ls_bound`).
fn ls_parts(x: &[f64]) -> ([f64; 3], f64, f64, f64) {
    let view = [x[0], x[1], x[2]];
    let moon = [x[3], x[4], x[5]];
    let sin_radius = x[6];
    let along: f64 = (0..3).map(|i| view[i] * moon[i]).sum();
    let offset: [f64; 3] = std::array::from_fn(|i| (view[i] - moon[i] * along) / sin_radius);
    let rho2: f64 = offset.iter().map(|c| c * c).sum();
    (offset, rho2, along, sin_radius)
}

/// Forward bound of the Lommel–Seeliger factor: each offset component carries
/// 5u/sin ρ (the difference of nearly equal unit components, then the division) plus
/// u of itself; ρ², the emergence √(1 − ρ²) (amplified 1/(2e) toward the limb), the
/// incidence n·s and finally i/(i + e) (∂/∂i = e/(i + e)², ∂/∂e = −i/(i + e)²).
fn ls_error(x: &[f64], offset_component_error: f64) -> f64 {
    let (offset, rho2, along, _) = ls_parts(x);
    if along <= 0.0 || rho2 >= 1.0 {
        return 0.0;
    }
    let moon = [x[3], x[4], x[5]];
    let to_sun = [x[7], x[8], x[9]];
    let length = (offset.iter().map(|c| c * c).sum::<f64>()).sqrt();
    let d_offset = offset_component_error + U * length;
    let d_rho2 = 2.0 * length * 3f64.sqrt() * d_offset + 3.0 * U;
    let e = (1.0 - rho2).sqrt();
    let d_e = (d_rho2 / (2.0 * e)).min(d_rho2.sqrt()) + U;
    let normal: [f64; 3] = std::array::from_fn(|i| offset[i] - moon[i] * e);
    let i: f64 = (0..3).map(|k| normal[k] * to_sun[k]).sum();
    let d_i = 3f64.sqrt() * d_offset + d_e + 5.0 * U;
    let lit = i.max(0.0) + d_i;
    let denominator = (i.max(0.0) + e).max(1e-30);
    ((e * d_i + lit * d_e) / (denominator * denominator)).min(1.0) + 4.0 * U
}

fn ls_bound(x: &[f64]) -> Vec<f64> {
    vec![ls_error(x, 5.0 * U / x[6])]
}

/// Unit east/north/up-like vector at elevation `e` and azimuth `a` (radians).
fn unit(e: f64, a: f64) -> [f64; 3] {
    [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()]
}

/// A view at (`east`, `north`) disc radii from the centre of a disc at `centre` of
/// angular radius asin(`sin_radius`).
fn disc_view(centre: [f64; 3], sin_radius: f64, east: f64, north: f64) -> [f64; 3] {
    let up = [0.0, 0.0, 1.0];
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut e = cross(up, centre);
    let n_e = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
    if n_e < 1e-9 {
        e = [1.0, 0.0, 0.0];
    } else {
        e = e.map(|c| c / n_e);
    }
    let n = cross(centre, e);
    let v: [f64; 3] =
        std::array::from_fn(|i| centre[i] + sin_radius * (east * e[i] + north * n[i]));
    let length = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / length)
}

fn ls_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let sin_radius = 0.004_5;
    for elevation in [0.05, 0.6, 1.4] {
        let moon = unit(elevation, 2.0);
        for phase in linspace(0.0, PI64 * 0.98, 8) {
            for limb in linspace(0.0, TAU64, 5) {
                // The sun from the moon: away from the observer by π − phase, tilted
                // toward `limb` in the sky plane.
                let side = disc_view(moon, 1.0, limb.sin(), limb.cos());
                let perpendicular: [f64; 3] = std::array::from_fn(|i| side[i] - moon[i]);
                let length = perpendicular.iter().map(|c| c * c).sum::<f64>().sqrt();
                let to_sun: [f64; 3] = std::array::from_fn(|i| {
                    -moon[i] * phase.cos() + perpendicular[i] / length * phase.sin()
                });
                for east in linspace(-1.1, 1.1, 14) {
                    for north in linspace(-1.1, 1.1, 14) {
                        let rho2: f64 = east * east + north * north;
                        if (rho2 - 1.0).abs() < 2e-3 {
                            continue;
                        }
                        let view = disc_view(moon, sin_radius, east, north);
                        let mut row = view.to_vec();
                        row.extend(moon);
                        row.push(sin_radius);
                        row.extend(to_sun);
                        grid.push(row);
                    }
                }
            }
        }
    }
    grid
}

fn threshold_grid() -> Vec<Vec<f64>> {
    let mut grid: Vec<Vec<f64>> = logspace(1e-7, 1e5, 12_000).map(|b| vec![b]).collect();
    grid.extend([
        vec![0.0],
        vec![1479.0 / (PI64 * 1e5)],
        vec![1.9e-4],
        vec![-1.0],
    ]);
    grid
}

/// Point sources: bright and faint, over dark and bright skies (around the threshold),
/// through clear and thick air.
fn point_source_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for magnitude in linspace(-4.6, 8.0, 64) {
        let illuminance = celestial::illuminance_from_magnitude(magnitude);
        for background in logspace(1e-5, 1e4, 40) {
            for (colour, transmittance) in [
                ([1.0, 1.0, 1.0], [0.9, 0.85, 0.7]),
                ([1.3, 0.95, 0.6], [0.3, 0.2, 0.05]),
                ([0.8, 1.0, 1.4], [1.0, 1.0, 1.0]),
                ([1.0, 1.0, 1.0], [0.0, 0.0, 0.0]),
            ] {
                let mut row = vec![illuminance];
                row.extend(colour);
                row.extend(transmittance);
                row.extend([background, 1.0, 1.3e5]);
                grid.push(row);
            }
        }
    }
    grid
}

/// (seen, threshold, luminance transmittance) of a point-source row in f64.
fn point_source_parts(x: &[f64]) -> (f64, f64, f64) {
    let weights = atmos::ladder::LUMINANCE_WEIGHTS;
    let t: f64 = (0..3).map(|i| weights[i] * x[1 + i] * x[4 + i]).sum();
    let seen = x[0] * x[8] * t;
    (seen, celestial::draw::star_detection_threshold(x[7]), t)
}

fn point_source_reference(x: &[f64]) -> Vec<f64> {
    let (seen, threshold, t) = point_source_parts(x);
    if t <= 0.0 {
        return vec![0.0; 3];
    }
    let visible = (seen - threshold).max(0.0);
    (0..3)
        .map(|i| x[1 + i] * x[4 + i] * visible / (x[9] * t))
        .collect()
}

/// The visible illuminance seen − threshold cancels: its absolute error is 6u·seen
/// (the luminance sum and products) plus the threshold's 16u; then 6u for the colour
/// scale.
fn point_source_bound(x: &[f64]) -> Vec<f64> {
    let (seen, threshold, t) = point_source_parts(x);
    if t <= 0.0 {
        return vec![0.0; 3];
    }
    let absolute = 6.0 * U * seen + 16.0 * U * threshold;
    let reference = point_source_reference(x);
    (0..3)
        .map(|i| x[1 + i] * x[4 + i] * absolute / (x[9] * t) + 6.0 * U * reference[i])
        .collect()
}

fn sprite_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for sigma in [0.75, 1.0, 1.7, 3.0, 8.0] {
        for r in linspace(0.0, 4.5 * sigma, 2100) {
            grid.push(vec![r * r, sigma]);
        }
    }
    grid
}

fn projection_cameras() -> Vec<atmos::frame::FrameCamera> {
    let mut cameras = Vec::new();
    for (forward, fov, width, height) in [
        (glam::DVec3::new(0.3, 1.0, 0.2), 1.0, 64, 48),
        (glam::DVec3::new(-1.0, 0.2, 0.05), 0.2, 1920, 1080),
        (glam::DVec3::new(0.0, 0.3, 1.0), 2.0, 512, 512),
    ] {
        cameras.push(
            atmos::frame::FrameCamera::look_at(
                glam::DVec3::new(0.0, 0.0, 6_360_100.0),
                forward,
                glam::DVec3::Z,
                fov,
                width,
                height,
                glam::DVec3::Z,
                None,
            )
            .expect("valid camera"),
        );
    }
    cameras
}

fn projection_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for camera in projection_cameras() {
        for i in 0..60 {
            for j in 0..60 {
                let pixel = [
                    (f64::from(i) / 59.0 * f64::from(camera.width - 1)) as u32,
                    (f64::from(j) / 59.0 * f64::from(camera.height - 1)) as u32,
                ];
                let view = atmos::frame::frame_view_direction(pixel, &camera);
                let mut row: Vec<f64> = view.iter().map(|&c| f64::from(c)).collect();
                for v in [camera.right, camera.up, camera.forward] {
                    row.extend(v.iter().map(|&c| f64::from(c)));
                }
                row.extend([
                    f64::from(camera.width),
                    f64::from(camera.height),
                    f64::from(camera.tan_half_fov_y),
                ]);
                grid.push(row);
            }
        }
    }
    grid
}

fn camera_from(x: &[f32]) -> atmos::frame::FrameCamera {
    atmos::frame::FrameCamera {
        position: [0.0; 3],
        width: x[12] as u32,
        right: [x[3], x[4], x[5]],
        height: x[13] as u32,
        up: [x[6], x[7], x[8]],
        tan_half_fov_y: x[14],
        forward: [x[9], x[10], x[11]],
        max_distance: atmos::frame::UNLIMITED_DISTANCE,
        sun: [0.0, 0.0, 1.0],
        padding: 0,
    }
}

fn projection_reference(x: &[f64]) -> Vec<f64> {
    let d = |a: usize| x[0] * x[a] + x[1] * x[a + 1] + x[2] * x[a + 2];
    let (px, py, pz) = (d(3), d(6), d(9));
    let (width, height, tan) = (x[12], x[13], x[14]);
    let ndc_x = px / (pz * tan * width / height);
    let ndc_y = py / (pz * tan);
    vec![
        (ndc_x + 1.0) * 0.5 * width,
        (1.0 - ndc_y) * 0.5 * height,
        pz,
    ]
}

/// Each dot product carries 3u (unit vectors); ndc = dot/(z·tan·aspect) adds 5u
/// relative plus the numerator's 3u absolute over z·tan·aspect; the pixel coordinate
/// multiplies by W/2.
fn projection_bound(x: &[f64]) -> Vec<f64> {
    let r = projection_reference(x);
    let (width, height, tan) = (x[12], x[13], x[14]);
    let z = r[2];
    let ndc_x = (r[0] / (0.5 * width)) - 1.0;
    let ndc_y = 1.0 - r[1] / (0.5 * height);
    let dndc_x = ndc_x.abs() * 8.0 * U + 3.0 * U / (z * tan * width / height);
    let dndc_y = ndc_y.abs() * 8.0 * U + 3.0 * U / (z * tan);
    vec![
        0.5 * width * dndc_x + 4.0 * U * r[0].abs(),
        0.5 * height * dndc_y + 4.0 * U * r[1].abs(),
        3.0 * U,
    ]
}

/// Disc objects: a sun or a moon at several elevations (near the horizon included, at
/// the ground and 10 km up), views across and around the disc, a transmittance fit.
fn disc_object_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for (kind, sin_radius) in [(1.0, 0.004_65), (2.0, 0.004_5)] {
        for elevation in [-0.01, 0.003, 0.05, 0.7, 1.5] {
            let centre = unit(elevation, 1.0);
            let to_sun = {
                let side = disc_view(centre, 1.0, 0.6, 0.8);
                let p: [f64; 3] = std::array::from_fn(|i| side[i] - centre[i]);
                let length = p.iter().map(|c| c * c).sum::<f64>().sqrt();
                let phase: f64 = 1.1;
                std::array::from_fn::<f64, 3, _>(|i| {
                    -centre[i] * phase.cos() + p[i] / length * phase.sin()
                })
            };
            let shading = if kind == 1.0 {
                [0.406, 0.508, 0.641]
            } else {
                to_sun
            };
            for r in [R_GROUND, R_GROUND + 10_000.0] {
                for (log_t, slope, curvature) in [(-0.1, 0.5, -2.0), (-4.0, 60.0, -800.0)] {
                    for east in linspace(-1.2, 1.2, 25) {
                        for north in linspace(-1.2, 1.2, 25) {
                            let rho2: f64 = east * east + north * north;
                            if (rho2 - 1.0).abs() < 2e-3 {
                                continue;
                            }
                            let view = disc_view(centre, sin_radius, east, north);
                            // Views within rounding of the horizon at the ground decide
                            // sky/ground differently in each precision: left out.
                            if view[2].abs() < 1e-6 {
                                continue;
                            }
                            let mut row = view.to_vec();
                            row.extend(centre);
                            row.extend([sin_radius, kind]);
                            row.extend(shading);
                            row.extend([centre[2], log_t, slope, curvature, r]);
                            grid.push(row);
                        }
                    }
                }
            }
        }
    }
    grid
}

/// The channel scales the disc-object case applies to its one log-transmittance input.
const DISC_CHANNEL_SCALE: [f64; 3] = [1.0, 1.5, 2.5];
/// The disc radiance per channel in the disc-object case.
const DISC_RADIANCE: [f64; 3] = [1.0, 0.5, 0.25];

fn disc_object_f32(x: &[f32]) -> celestial::draw::DiscObject {
    let s = DISC_CHANNEL_SCALE.map(|c| c as f32);
    celestial::draw::DiscObject {
        direction: [x[3], x[4], x[5]],
        sin_radius: x[6],
        radiance: DISC_RADIANCE.map(|c| c as f32),
        kind: x[7] as u32,
        shading: [x[8], x[9], x[10]],
        mu_centre: x[11],
        log_transmittance: s.map(|c| x[12] * c),
        padding0: 0.0,
        log_transmittance_slope: s.map(|c| x[13] * c),
        padding1: 0.0,
        log_transmittance_curvature: s.map(|c| x[14] * c),
        padding2: 0.0,
    }
}

/// The disc object in f64: the same steps with f64 functions.
fn disc_object_reference(x: &[f64]) -> Vec<f64> {
    let view = [x[0], x[1], x[2]];
    let d = [x[3], x[4], x[5]];
    let mu = view[2];
    let ground = f64ref::ray_sphere_intersect(x[15], mu, R_GROUND);
    if mu < 0.0 && ground[0] >= 0.0 {
        return vec![0.0; 3];
    }
    let cross = [
        view[1] * d[2] - view[2] * d[1],
        view[2] * d[0] - view[0] * d[2],
        view[0] * d[1] - view[1] * d[0],
    ];
    let sin_offset = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
    let cos_offset = view[0] * d[0] + view[1] * d[1] + view[2] * d[2];
    let dmu = mu - x[11];
    (0..3)
        .map(|i| {
            let shape = if x[7] == 1.0 {
                celestial::twins::sun_disc_limb_factor(sin_offset, cos_offset, x[6], x[8 + i])
            } else {
                celestial::twins::moon_disc_lommel_seeliger(view, d, x[6], [x[8], x[9], x[10]])
            };
            let c = DISC_CHANNEL_SCALE[i];
            let log_t = x[12] * c + dmu * (x[13] * c + dmu * x[14] * c);
            DISC_RADIANCE[i] * shape * log_t.min(0.0).exp()
        })
        .collect()
}

/// The shape's bound (the cross product's sin θ carries 5u absolute, so the ratio
/// 5u/sin ρ; the moon's offset the same as in `ls_bound`) plus the transmittance's:
/// μ carries 3u, so the exponent moves by 4u·|slope + 2·curvature·Δμ| plus its own
/// rounding 4u·(|terms|), and exp adds 3 + 2|arg| ULP.
fn disc_object_bound(x: &[f64]) -> Vec<f64> {
    let view = [x[0], x[1], x[2]];
    let d = [x[3], x[4], x[5]];
    let reference = disc_object_reference(x);
    if reference.iter().all(|&v| v == 0.0) {
        return vec![0.0; 3];
    }
    let cross = [
        view[1] * d[2] - view[2] * d[1],
        view[2] * d[0] - view[0] * d[2],
        view[0] * d[1] - view[1] * d[0],
    ];
    let sin_offset = (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt();
    let dmu = view[2] - x[11];
    (0..3)
        .map(|i| {
            let c = DISC_CHANNEL_SCALE[i];
            let slope = x[13] * c;
            let curvature = x[14] * c;
            let log_t = x[12] * c + dmu * (slope + dmu * curvature);
            let argument_error = 4.0 * U * (slope + 2.0 * curvature * dmu).abs()
                + 4.0 * U * (x[12] * c).abs()
                + 4.0 * U * (dmu * slope).abs()
                + 4.0 * U * (dmu * dmu * curvature).abs();
            let transmittance = log_t.min(0.0).exp();
            let transmittance_relative = argument_error + exp_relative_error(log_t.min(0.0));
            let shape_error = if x[7] == 1.0 {
                // |view × d| carries 5u absolute (products of unit components and their
                // differences, the root), the quotient 2u relative.
                let cos_offset = view[0] * d[0] + view[1] * d[1] + view[2] * d[2];
                limb_factor_error(
                    sin_offset,
                    cos_offset,
                    x[6],
                    x[8 + i],
                    5.0 * U + 2.0 * U * sin_offset,
                )
            } else {
                let mut row = view.to_vec();
                row.extend(d);
                row.push(x[6]);
                row.extend([x[8], x[9], x[10]]);
                ls_error(&row, 5.0 * U / x[6])
            };
            DISC_RADIANCE[i] * transmittance * shape_error
                + reference[i] * (transmittance_relative + 3.0 * U)
        })
        .collect()
}

fn draw_cases() -> Vec<Case> {
    vec![
        Case {
            name: "celestial::sun_disc_limb_factor",
            imports: &["celestial::draw"],
            arity: (4, 1),
            wgsl: "y0 = sun_disc_limb_factor(x0, x1, x2, x3);",
            grid: limb_grid,
            cpu: |x| {
                vec![celestial::twins::sun_disc_limb_factor(
                    x[0], x[1], x[2], x[3],
                )]
            },
            reference: |x| {
                vec![celestial::twins::sun_disc_limb_factor(
                    x[0], x[1], x[2], x[3],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(limb_bound),
                why: "q = sin θ/sin ρ rounds (2u): the f64 function's change over that input \
                      error (unbounded growth at the limb, μ → 0); μ^α = exp(α ln μ) adds \
                      α × log's 2⁻²¹ absolute error and exp's 3 + 2|α ln μ| ULP; 4u for the \
                      quotient, root and factor",
            },
        },
        Case {
            name: "celestial::sun_aureole_radiance",
            imports: &["celestial::draw"],
            arity: (5, 1),
            wgsl: "y0 = sun_aureole_radiance(x0, x1, x2, x3, x4);",
            grid: aureole_grid,
            cpu: |x| {
                vec![celestial::draw::sun_aureole_radiance(
                    x[0], x[1], x[2], x[3], x[4],
                )]
            },
            reference: |x| {
                vec![celestial::twins::sun_aureole_radiance_f64(
                    x[0], x[1], x[2], x[3], x[4],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 24.0 * U,
                ulp: 4.0,
                bound: None,
                why: "atmos' Cornette–Shanks phase in its stable form (the (1 − g)² + 2g(1 − \
                      cos θ) base keeps its digits at θ → 0; base^{3/2} and the quotient: \
                      ≤ 16u) and three products (3u)",
            },
        },
        Case {
            name: "celestial::moon_disc_lommel_seeliger",
            imports: &["celestial::draw"],
            arity: (10, 1),
            wgsl: "y0 = moon_disc_lommel_seeliger(vec3<f32>(x0, x1, x2), vec3<f32>(x3, x4, x5), \
                   x6, vec3<f32>(x7, x8, x9));",
            grid: ls_grid,
            cpu: |x| {
                vec![celestial::twins::moon_disc_lommel_seeliger(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    x[6],
                    [x[7], x[8], x[9]],
                )]
            },
            reference: |x| {
                vec![celestial::twins::moon_disc_lommel_seeliger(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    x[6],
                    [x[7], x[8], x[9]],
                )]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(ls_bound),
                why: "the disc offset (view − moon·(view·moon))/sin ρ cancels: 5u/sin ρ per \
                      component; through ρ², √(1 − ρ²) (1/(2e) near the limb), n·s and \
                      i/(i + e) by its partial derivatives",
            },
        },
        Case {
            name: "celestial::star_detection_threshold",
            imports: &["celestial::draw"],
            arity: (1, 1),
            wgsl: "y0 = star_detection_threshold(x0);",
            grid: threshold_grid,
            cpu: |x| vec![celestial::draw::star_detection_threshold(x[0])],
            reference: |x| vec![celestial::draw::star_detection_threshold(x[0])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 12.0 * U,
                ulp: 2.0,
                bound: None,
                why: "products of rounded constants (4u), √ (1u, halved), the square (2u), the \
                      final scale (2u): ≤ 12u per branch; min picks the same branch except \
                      where the two agree to that",
            },
        },
        Case {
            name: "celestial::point_source_irradiance",
            imports: &["celestial::draw"],
            arity: (10, 3),
            wgsl: "let e = point_source_irradiance(x0, vec3<f32>(x1, x2, x3), \
                   vec3<f32>(x4, x5, x6), x7, x8, x9); y0 = e.x; y1 = e.y; y2 = e.z;",
            grid: point_source_grid,
            cpu: |x| {
                celestial::draw::point_source_irradiance(
                    x[0],
                    [x[1], x[2], x[3]],
                    [x[4], x[5], x[6]],
                    x[7],
                    x[8],
                    x[9],
                )
                .to_vec()
            },
            reference: point_source_reference,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(point_source_bound),
                why: "seen − threshold cancels near the threshold: 6u·seen (luminance sum and \
                      products) + 16u·threshold absolute, then 6u for the colour scale",
            },
        },
        Case {
            name: "celestial::point_sprite_weight",
            imports: &["celestial::draw"],
            arity: (2, 1),
            wgsl: "y0 = point_sprite_weight(x0, x1);",
            grid: sprite_grid,
            cpu: |x| vec![celestial::twins::point_sprite_weight(x[0], x[1])],
            reference: |x| vec![celestial::twins::point_sprite_weight(x[0], x[1])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| {
                    let argument = x[0] / (2.0 * x[1] * x[1]);
                    let y = celestial::twins::point_sprite_weight(x[0], x[1]);
                    vec![y * (exp_relative_error(argument) + 3.0 * U * argument + 4.0 * U)]
                }),
                why: "the exponent r²/(2σ²) rounds (3u relative, amplified 1:1 by exp), exp's \
                      3 + 2|arg| ULP, the normalisation 4u",
            },
        },
        Case {
            name: "celestial::pixel_solid_angle",
            imports: &["celestial::draw"],
            arity: (3, 1),
            wgsl: "y0 = pixel_solid_angle(x0, u32(x1), x2);",
            grid: || {
                let mut grid = Vec::new();
                for tan in logspace(0.01, 20.0, 40) {
                    for height in [1.0, 48.0, 1080.0, 4320.0] {
                        for cos in linspace(0.05, 1.0, 64) {
                            grid.push(vec![tan, height, cos]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![celestial::draw::pixel_solid_angle(x[0], x[1] as u32, x[2])],
            reference: |x| {
                let side = 2.0 * x[0] / x[1];
                vec![side * side * x[2] * x[2] * x[2]]
            },
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 8.0 * U,
                ulp: 1.0,
                bound: None,
                why: "a product and a quotient for the side, then five products: ≤ 7u",
            },
        },
        Case {
            name: "celestial::project_direction",
            imports: &["celestial::draw"],
            arity: (15, 3),
            wgsl: "let camera = FrameCamera(vec3<f32>(0.0), u32(x12), vec3<f32>(x3, x4, x5), \
                   u32(x13), vec3<f32>(x6, x7, x8), x14, vec3<f32>(x9, x10, x11), 1e30, \
                   vec3<f32>(0.0, 0.0, 1.0), 0u); \
                   let p = project_direction(vec3<f32>(x0, x1, x2), camera); \
                   y0 = p.x; y1 = p.y; y2 = p.z;",
            grid: projection_grid,
            cpu: |x| {
                celestial::draw::project_direction([x[0], x[1], x[2]], &camera_from(x)).to_vec()
            },
            reference: projection_reference,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(projection_bound),
                why: "three dot products (3u each), ndc = x/(z·tan·aspect) (5u relative plus \
                      the numerator's 3u over the denominator), the pixel coordinate ×W/2",
            },
        },
        Case {
            name: "celestial::disc_object_radiance",
            imports: &["celestial::draw"],
            arity: (16, 3),
            wgsl: "let scale = vec3<f32>(1.0, 1.5, 2.5); \
                   let object = DiscObject(vec3<f32>(x3, x4, x5), x6, vec3<f32>(1.0, 0.5, 0.25), \
                   u32(x7), vec3<f32>(x8, x9, x10), x11, x12 * scale, 0.0, x13 * scale, 0.0, \
                   x14 * scale, 0.0); \
                   let l = disc_object_radiance(vec3<f32>(x0, x1, x2), object, \
                   vec3<f32>(0.0, 0.0, 1.0), x15, 6360000.0); y0 = l.x; y1 = l.y; y2 = l.z;",
            grid: disc_object_grid,
            cpu: |x| {
                celestial::draw::disc_object_radiance(
                    [x[0], x[1], x[2]],
                    &disc_object_f32(x),
                    [0.0, 0.0, 1.0],
                    x[15],
                    R_GROUND as f32,
                )
                .to_vec()
            },
            reference: disc_object_reference,
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(disc_object_bound),
                why: "sin θ = |view × d| carries 5u absolute (ratio 5u/sin ρ), then the limb \
                      factor's or the Lommel–Seeliger bound; the transmittance exponent moves \
                      by μ's 3u times its slope plus its own rounding, exp's 3 + 2|arg| ULP",
            },
        },
    ]
}

// ---------------------------------------------------------------- celestial::clouds

use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};

/// f64 value noise: the same lattice hashes (integers, bit-equal), f64 blending.
fn noise64(x: f64, y: f64, seed: u32) -> f64 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i32, fy as i32);
    let (tx, ty) = (x - fx, y - fy);
    let corner = |dx: i32, dy: i32| {
        f64::from(unit_float_from_bits(hash_combine(
            hash_combine(seed, ix.wrapping_add(dx) as u32),
            iy.wrapping_add(dy) as u32,
        )))
    };
    let sx = tx * tx * (3.0 - 2.0 * tx);
    let sy = ty * ty * (3.0 - 2.0 * ty);
    let bottom = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    let top = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

fn fbm64(x: f64, y: f64, octaves: u32, seed: u32) -> f64 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0, 1.0, 0.0, 1.0);
    for octave in 0..octaves {
        sum += amplitude * noise64(x * frequency, y * frequency, hash_combine(seed, octave));
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total
}

/// Blending error of the value noise: the smoothstep weights (≈ 6u) and two lerps of
/// corner differences ≤ 1 (≈ 6u): 12u absolute.
const NOISE_ERROR: f64 = 12.0 * U;

/// Largest slope of the value noise per lattice unit: the smoothstep's 1.5 times a
/// corner difference ≤ 1, in each axis.
const NOISE_SLOPE: f64 = 1.5;

/// The fBm's absolute error when its coordinates carry `dx` (lattice units of the
/// first octave): each octave's blending error and slope·frequency·dx, weighted by
/// its amplitude over the total; the coordinate scalings by powers of two are exact.
fn fbm_error(octaves: u32, dx: f64) -> f64 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0, 1.0, 0.0, 1.0);
    for _ in 0..octaves {
        sum += amplitude * (NOISE_ERROR + 2.0 * NOISE_SLOPE * frequency * dx);
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total + 4.0 * U * f64::from(octaves)
}

fn noise_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for seed in [0.0, 7.0, 123_456.0] {
        for x in linspace(-40.0, 40.0, 61) {
            for y in linspace(-3.1, 57.3, 61) {
                grid.push(vec![x, y, seed]);
            }
        }
    }
    grid
}

fn fbm_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for octaves in [1.0, 3.0, 5.0] {
        for seed in [0.0, 99.0] {
            for x in linspace(-20.0, 60.0, 41) {
                for y in linspace(-5.5, 30.25, 41) {
                    grid.push(vec![x, y, octaves, seed]);
                }
            }
        }
    }
    grid
}

/// The case's layers: one per kind (texture constants, τ, g) at 2 km, 300 m thick,
/// seed 5, coverage 0.5.
fn case_layers() -> Vec<celestial::clouds::CloudLayerUniforms> {
    static LAYERS: std::sync::OnceLock<Vec<celestial::clouds::CloudLayerUniforms>> =
        std::sync::OnceLock::new();
    LAYERS.get_or_init(make_case_layers).clone()
}

fn make_case_layers() -> Vec<celestial::clouds::CloudLayerUniforms> {
    let frame = celestial::clouds::CloudLayerFrame {
        planet_radius_m: R_GROUND,
        offset_m: [300.0, -200.0],
        fog_extinction_per_m: 3.912 / 30_000.0,
        exp2_fog: false,
        sun_direction: [0.0, 0.6, 0.8],
        sunlight: [1.0, 0.95, 0.9],
        skylight: [0.3, 0.4, 0.6],
        fog_colour: [0.2, 0.25, 0.3],
    };
    celestial::clouds::CloudKind::ALL
        .iter()
        .map(|&kind| {
            let layer = celestial::clouds::CloudLayer {
                seed: 5,
                coverage: 0.5,
                ..celestial::clouds::CloudLayer::new(2000.0, 300.0, 100.0, 40_000.0, kind)
                    .expect("valid layer")
            };
            layer.uniforms(&frame)
        })
        .collect()
}

/// A layer uniform from a case row: x[k0..] = base, top, curved, feature, stretch,
/// octaves, seed, threshold, softness, τ, g, exp2, core depth (the rest fixed as
/// `case_layers`).
fn layer_from(x: &[f64], k0: usize) -> celestial::clouds::CloudLayerUniforms {
    static FIRST: std::sync::OnceLock<celestial::clouds::CloudLayerUniforms> =
        std::sync::OnceLock::new();
    let mut layer = *FIRST.get_or_init(|| case_layers()[0]);
    layer.base_radius = x[k0] as f32;
    layer.top_radius = x[k0 + 1] as f32;
    layer.curved = x[k0 + 2] as u32;
    layer.feature_size = x[k0 + 3] as f32;
    layer.stretch = x[k0 + 4] as f32;
    layer.octaves = x[k0 + 5] as u32;
    layer.seed = x[k0 + 6] as u32;
    layer.threshold = x[k0 + 7] as f32;
    layer.softness = x[k0 + 8] as f32;
    layer.optical_thickness = x[k0 + 9] as f32;
    layer.asymmetry = x[k0 + 10] as f32;
    layer.exp2_fog = x[k0 + 11] as u32;
    layer.core_depth = x[k0 + 12] as f32;
    layer
}

fn layer_row(layer: &celestial::clouds::CloudLayerUniforms, curved: u32, exp2: u32) -> Vec<f64> {
    vec![
        f64::from(layer.base_radius),
        f64::from(layer.top_radius),
        f64::from(curved),
        f64::from(layer.feature_size),
        f64::from(layer.stretch),
        f64::from(layer.octaves),
        f64::from(layer.seed),
        f64::from(layer.threshold),
        f64::from(layer.softness),
        f64::from(layer.optical_thickness),
        f64::from(layer.asymmetry),
        f64::from(exp2),
        f64::from(layer.core_depth),
    ]
}

/// The WGSL constructor of the case's layer from `x{k0}…` (the fixed fields as
/// `case_layers`): offset (300, −200), half span 20 km, fog 3.912/30 km, the light.
macro_rules! layer_wgsl {
    ($k:literal, $k1:literal, $k2:literal, $k3:literal, $k4:literal, $k5:literal, $k6:literal, $k7:literal, $k8:literal, $k9:literal, $k10:literal, $k11:literal, $k12:literal) => {
        concat!(
            "let layer = CloudLayerUniforms(",
            $k,
            ", ",
            $k1,
            ", 6360000.0, u32(",
            $k2,
            "), ",
            $k3,
            ", ",
            $k4,
            ", u32(",
            $k5,
            "), u32(",
            $k6,
            "), ",
            $k7,
            ", ",
            $k8,
            ", ",
            $k9,
            ", ",
            $k10,
            ", vec2<f32>(300.0, -200.0), 20000.0, 0.0001304, ",
            "vec3<f32>(0.0, 0.6, 0.8), u32(",
            $k11,
            "), vec3<f32>(1.0, 0.95, 0.9), ",
            $k12,
            ", ",
            "vec3<f32>(0.3, 0.4, 0.6), 0.0, vec3<f32>(0.2, 0.25, 0.3), 0.0); "
        )
    };
}

fn density64(u: f64, v: f64, l: &celestial::clouds::CloudLayerUniforms) -> f64 {
    let x = u / (f64::from(l.feature_size) * f64::from(l.stretch));
    let y = v / f64::from(l.feature_size);
    let n = fbm64(x, y, l.octaves, l.seed);
    let t = ((n - f64::from(l.threshold)) / f64::from(l.softness) + 0.5).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Density error when (u, v) carry `duv` metres: the coordinates' own quotient
/// rounding (WGSL division 2.5 ULP, twice: 6u relative) plus `duv`, through the fBm's
/// slope, then the threshold map's slope 1.5/softness.
fn density_error(u: f64, v: f64, duv: f64, l: &celestial::clouds::CloudLayerUniforms) -> f64 {
    let scale = f64::from(l.feature_size);
    let dx = (6.0 * U * u.abs().max(v.abs()) + duv) / scale;
    1.5 / f64::from(l.softness) * (fbm_error(l.octaves, dx) + 4.0 * U) + 4.0 * U
}

fn density_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for (k, layer) in case_layers().iter().enumerate() {
        for u in linspace(-25_000.0, 25_000.0, 45) {
            for v in linspace(-25_000.0, 25_000.0, 45) {
                let mut row = vec![u + 37.0 * k as f64, v];
                row.extend(layer_row(layer, 1, 0));
                grid.push(row);
            }
        }
    }
    grid
}

fn reflectance64(tau: f64, g: f64, mu: f64) -> f64 {
    if mu <= 0.0 {
        return 0.0;
    }
    let scaled = (1.0 - g) * tau;
    let direct = 1.0 - (-tau / mu).exp();
    ((scaled + (2.0 / 3.0 - mu) * direct) / (4.0 / 3.0 + scaled)).clamp(0.0, 1.0)
}

fn distance64(r: f64, mu: f64, layer_radius: f64, curved: u32) -> f64 {
    if curved != 0 {
        let hit = f64ref::ray_sphere_intersect(r, mu, layer_radius);
        if r < layer_radius {
            return hit[1];
        }
        if hit[0] >= 0.0 && mu < 0.0 {
            return hit[0];
        }
        return -1.0;
    }
    let height = layer_radius - r;
    if (height > 0.0 && mu > 0.0) || (height < 0.0 && mu < 0.0) {
        return height / mu;
    }
    -1.0
}

fn layer_distance_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for altitude in [0.0, 500.0, 2_000.0, 2_150.0, 9_000.0] {
        let r = R_GROUND + altitude;
        for layer_altitude in [1_000.0, 2_100.0, 6_000.0] {
            let radius = R_GROUND + layer_altitude;
            for curved in [0.0, 1.0] {
                for mu in cosines(341) {
                    let mu32 = f64::from(mu as f32);
                    let (r32, radius32) = (f64::from(r as f32), f64::from(radius as f32));
                    if curved == 1.0 {
                        let (d, error) = discriminant_and_error(r32, mu32, radius32);
                        if d.abs() < error {
                            continue;
                        }
                    }
                    grid.push(vec![r, mu, radius, curved]);
                }
            }
        }
    }
    grid
}

/// Flat: height/μ (the height difference is exact, the quotient 2.5 ULP in WGSL);
/// curved: the ray–sphere bound.
fn layer_distance_bound(x: &[f64]) -> Vec<f64> {
    let d = distance64(x[0], x[1], x[2], x[3] as u32);
    if x[3] == 0.0 {
        return vec![3.0 * U * d.abs()];
    }
    let bounds = ray_sphere_bound(&[x[0], x[1], x[2]]);
    vec![bounds[0].max(bounds[1])]
}

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

/// f64 `cloud_shadow` (the case layer's sun (0, 0.6, 0.8), half span 20 km, offset
/// (300, −200)), with the crossing point it samples.
fn shadow64(p: [f64; 3], r: f64, l: &celestial::clouds::CloudLayerUniforms) -> (f64, [f64; 2]) {
    let sun = l.sun_direction.map(f64::from);
    let point_radius = r + p[2];
    if sun[2] <= 0.0 || point_radius >= f64::from(l.top_radius) {
        return (1.0, [0.0; 2]);
    }
    let distance = (f64::from(l.base_radius) - point_radius).max(0.0) / sun[2];
    let x = p[0] + sun[0] * distance;
    let y = p[1] + sun[1] * distance;
    if x.hypot(y) >= f64::from(l.half_span) {
        return (1.0, [x, y]);
    }
    let density = density64(x + f64::from(l.offset[0]), y + f64::from(l.offset[1]), l);
    (
        (-f64::from(l.optical_thickness) * density / sun[2]).exp(),
        [x, y],
    )
}

fn cloud_shadow_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    let r = 6_360_000.0 + 1000.0;
    for (k, layer) in case_layers().iter().enumerate() {
        for x in linspace(-9_000.0, 9_000.0, 31) {
            for y in linspace(-9_000.0, 9_000.0, 31) {
                // Points from 800 m below the viewer to above the layer's top.
                for z in [-800.0, -250.0, 0.0, 400.0, 900.0, 2_500.0] {
                    let mut row = vec![x + 41.0 * k as f64, y, z, r];
                    row.extend(layer_row(layer, 1, 0));
                    grid.push(row);
                }
            }
        }
    }
    grid
}

fn cloud_cases() -> Vec<Case> {
    vec![
        Case {
            name: "celestial::cloud_shadow",
            imports: &["celestial::clouds"],
            arity: (17, 1),
            wgsl: concat!(
                layer_wgsl!(
                    "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13", "x14", "x15",
                    "x16"
                ),
                "y0 = cloud_shadow(vec3<f32>(x0, x1, x2), x3, layer);"
            ),
            grid: cloud_shadow_grid,
            cpu: |x| {
                let l = layer_from(&x.iter().map(|&v| f64::from(v)).collect::<Vec<_>>(), 4);
                vec![celestial::clouds::cloud_shadow(
                    [x[0], x[1], x[2]],
                    x[3],
                    &l,
                )]
            },
            reference: |x| vec![shadow64([x[0], x[1], x[2]], x[3], &layer_from(x, 4)).0],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| {
                    let l = layer_from(x, 4);
                    let (shadow, [cx, cy]) = shadow64([x[0], x[1], x[2]], x[3], &l);
                    if shadow == 1.0 {
                        return vec![0.0];
                    }
                    let mu = f64::from(l.sun_direction[2]);
                    let base = f64::from(l.base_radius);
                    let point_radius = x[3] + x[2];
                    let distance = (base - point_radius) / mu;
                    // The crossing point moves by the f32 rounding of the point's radius
                    // r + z (half an ULP: 0.25 m at 6.4e6 m; the difference with the base
                    // is then exact, Sterbenz) over μ☉, plus the quotient's, products'
                    // and sums' roundings; the density moves by that times its local
                    // slope (a central difference over ±duv, doubled for curvature), plus
                    // its own rounding (the cloud_density case's bound at exact inputs).
                    let radius_rounding = 0.5 * ulp_f32(point_radius);
                    let duv = (radius_rounding + 4.0 * U * distance) / mu
                        + 3.0 * U * (cx.abs() + cy.abs() + 500.0);
                    let (u0, v0) = (cx + 300.0, cy - 200.0);
                    let slope_change = [(duv, 0.0), (0.0, duv)]
                        .iter()
                        .map(|&(du, dv)| {
                            (density64(u0 + du, v0 + dv, &l) - density64(u0 - du, v0 - dv, &l))
                                .abs()
                                * 0.5
                        })
                        .fold(0.0, f64::max);
                    let density_shift = 2.0 * 2.0 * slope_change + density_error(u0, v0, 0.0, &l);
                    let tau_over_mu = f64::from(l.optical_thickness) / mu;
                    let density = density64(u0, v0, &l);
                    let arg = tau_over_mu * density;
                    vec![
                        shadow
                            * (tau_over_mu * density_shift
                                + 3.0 * U * arg
                                + exp_relative_error(arg)),
                    ]
                }),
                why: "the sun's crossing of the base moves with the f32 rounding of the \
                      point's radius (0.25 m at 6.4e6 m) over μ☉ and the sums', through the \
                      density's local slope there (a central difference, ×2 for curvature, \
                      both axes) plus the cloud_density case's own rounding bound, times τ/μ☉ \
                      in the exponent; the exponent's two roundings and WGSL exp's 3 + 2|x| ULP",
            },
        },
        Case {
            name: "celestial::cloud_value_noise",
            imports: &["celestial::clouds"],
            arity: (3, 1),
            wgsl: "y0 = cloud_value_noise(x0, x1, u32(x2));",
            grid: noise_grid,
            cpu: |x| vec![celestial::twins::cloud_value_noise(x[0], x[1], x[2] as u32)],
            reference: |x| vec![noise64(x[0], x[1], x[2] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: NOISE_ERROR,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "the lattice hashes are integers (bit-equal); the smoothstep weights (6u) \
                      and two lerps of corner differences ≤ 1 (6u) round: 12u absolute",
            },
        },
        Case {
            name: "celestial::cloud_fbm",
            imports: &["celestial::clouds"],
            arity: (4, 1),
            wgsl: "y0 = cloud_fbm(x0, x1, u32(x2), u32(x3));",
            grid: fbm_grid,
            cpu: |x| {
                vec![celestial::twins::cloud_fbm(
                    x[0],
                    x[1],
                    x[2] as u32,
                    x[3] as u32,
                )]
            },
            reference: |x| vec![fbm64(x[0], x[1], x[2] as u32, x[3] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 0.0,
                bound: Some(|x| vec![fbm_error(x[2] as u32, 0.0)]),
                why: "each octave's 12u blending error weighted by its amplitude (the \
                      frequency scalings are powers of two, exact), 4u per octave for the \
                      weighted sum and the normalisation",
            },
        },
        Case {
            name: "celestial::cloud_density",
            imports: &["celestial::clouds"],
            arity: (15, 1),
            wgsl: concat!(
                layer_wgsl!(
                    "x2", "x3", "x4", "x5", "x6", "x7", "x8", "x9", "x10", "x11", "x12", "x13",
                    "x14"
                ),
                "y0 = cloud_density(x0, x1, layer);"
            ),
            grid: density_grid,
            cpu: |x| {
                let l = layer_from(&x.iter().map(|&v| f64::from(v)).collect::<Vec<_>>(), 2);
                vec![celestial::twins::cloud_density(x[0], x[1], &l)]
            },
            reference: |x| vec![density64(x[0], x[1], &layer_from(x, 2))],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(|x| vec![density_error(x[0], x[1], 0.0, &layer_from(x, 2))]),
                why: "u/(size·stretch) and v/size round (WGSL division 2.5 ULP: 6u of the \
                      coordinate), moving the fBm by its slope (1.5 per lattice unit per octave, \
                      ×frequency×amplitude) plus its blending error; the threshold map scales by \
                      1.5/softness",
            },
        },
        Case {
            name: "celestial::cloud_reflectance",
            imports: &["celestial::clouds"],
            arity: (3, 1),
            wgsl: "y0 = cloud_reflectance(x0, x1, x2);",
            grid: || {
                let mut grid = Vec::new();
                for tau in logspace(1e-3, 200.0, 60) {
                    for g in [0.0, 0.75, 0.85, 0.95] {
                        for mu in linspace(-0.2, 1.0, 49) {
                            grid.push(vec![tau, g, mu]);
                        }
                    }
                }
                grid
            },
            cpu: |x| vec![celestial::twins::cloud_reflectance(x[0], x[1], x[2])],
            reference: |x| vec![reflectance64(x[0], x[1], x[2])],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 4.0,
                bound: Some(|x| {
                    if x[2] <= 0.0 {
                        return vec![0.0];
                    }
                    let arg = x[0] / x[2];
                    let direct = 1.0 - (-arg).exp();
                    let scaled = (1.0 - x[1]) * x[0];
                    let denominator = 4.0 / 3.0 + scaled;
                    // exp (3 + 2|arg| ULP of e^{−arg}, times |2/3 − μ|), the sums' rounding
                    // relative to their terms, the quotient.
                    let numerator_error =
                        exp_relative_error(arg) * (-arg).exp() * (2.0 / 3.0 - x[2]).abs()
                            + 6.0 * U * (scaled.abs() + (2.0 / 3.0 - x[2]).abs() * direct);
                    vec![numerator_error / denominator + 4.0 * U * reflectance64(x[0], x[1], x[2])]
                }),
                why: "exp(−τ/μ) (3 + 2|τ/μ| ULP) times |2/3 − μ|, the numerator's sum (6u of \
                      its terms), over the denominator, and the quotient's 4u",
            },
        },
        Case {
            name: "celestial::cloud_layer_distance",
            imports: &["celestial::clouds"],
            arity: (4, 1),
            wgsl: "y0 = cloud_layer_distance(x0, x1, x2, u32(x3));",
            grid: layer_distance_grid,
            cpu: |x| {
                vec![celestial::twins::cloud_layer_distance(
                    x[0],
                    x[1],
                    x[2],
                    x[3] as u32,
                )]
            },
            reference: |x| vec![distance64(x[0], x[1], x[2], x[3] as u32)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 0.0,
                rel: 0.0,
                ulp: 2.0,
                bound: Some(layer_distance_bound),
                why: "flat: the height difference is exact (Sterbenz), the quotient 2.5 ULP; \
                      curved: atmos' ray–sphere forward bound (rays within rounding of \
                      tangency are left out, as in atmos' case)",
            },
        },
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
                let l = layer_from(&x.iter().map(|&v| f64::from(v)).collect::<Vec<_>>(), 4);
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
                let l = layer_from(&x.iter().map(|&v| f64::from(v)).collect::<Vec<_>>(), 2);
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
                let l = layer_from(&x.iter().map(|&v| f64::from(v)).collect::<Vec<_>>(), 2);
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
