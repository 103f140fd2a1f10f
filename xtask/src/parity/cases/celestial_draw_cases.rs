//! Parity cases of `celestial::draw`: the sun's limb darkening and aureole, the moon's
//! Lommel–Seeliger disc, the disc objects through their transmittance, star detection
//! thresholds, point-source irradiance, sprite weights, pixel solid angles and the
//! camera projection.

use super::*;

const PI64: f64 = std::f64::consts::PI;
const TAU64: f64 = std::f64::consts::TAU;

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
pub(super) fn unit(e: f64, a: f64) -> [f64; 3] {
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

/// The cases, in report order.
pub(super) fn cases() -> Vec<Case> {
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
