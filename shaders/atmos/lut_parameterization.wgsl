// Texture parameterisations of the precomputed rung's LUTs and the pure geometry its
// raymarches share. Twin: atmos::lut::parameterization and atmos::lut::raymarch /
// atmos::lut::aerial_perspective (Rust f32), same names, arguments and units
// (metres, cosines). No bindings here: every function is a parity case.
#import common::constants
#import atmos::geometry
#import atmos::frame
#import atmos::transmittance

// x ∈ [0, 1] → texture coordinate whose 0 and 1 are the first and last texel centres
// (Bruneton 2017): the LUT holds values at the ends of its domain.
fn unit_range_to_texel_uv(x: f32, texel_count: u32) -> f32 {
    let n = f32(texel_count);
    return 0.5 / n + x * (1.0 - 1.0 / n);
}

fn texel_uv_to_unit_range(u: f32, texel_count: u32) -> f32 {
    let n = f32(texel_count);
    return (u - 0.5 / n) / (1.0 - 1.0 / n);
}

// √((a − b)(a + b)), 0 when a < b: a horizon distance without the cancellation of
// a² − b² at Earth radii.
fn horizon_distance(a: f32, b: f32) -> f32 {
    return sqrt(max((a - b) * (a + b), 0.0));
}

// Bruneton's transmittance parameterisation: u = (d − d_min)/(d_max − d_min) with d
// the distance to the top boundary (u = 1 at the horizon), v = ρ/H.
fn transmittance_lut_uv(r_in: f32, mu: f32, planet_radius: f32, top_radius: f32, width: u32, height: u32) -> vec2<f32> {
    let r = clamp(r_in, planet_radius, top_radius);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = horizon_distance(r, planet_radius);
    let d = max(ray_sphere_intersect(r, mu, top_radius).y, 0.0);
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let x_mu = clamp((d - d_min) / (d_max - d_min), 0.0, 1.0);
    let x_r = rho / top_horizon;
    return vec2<f32>(unit_range_to_texel_uv(x_mu, width), unit_range_to_texel_uv(x_r, height));
}

// Inverse of transmittance_lut_uv: (r, mu).
fn transmittance_lut_r_mu(uv: vec2<f32>, planet_radius: f32, top_radius: f32, width: u32, height: u32) -> vec2<f32> {
    let x_mu = clamp(texel_uv_to_unit_range(uv.x, width), 0.0, 1.0);
    let x_r = clamp(texel_uv_to_unit_range(uv.y, height), 0.0, 1.0);
    let top_horizon = horizon_distance(top_radius, planet_radius);
    let rho = top_horizon * x_r;
    let r = sqrt(rho * rho + planet_radius * planet_radius);
    let d_min = top_radius - r;
    let d_max = rho + top_horizon;
    let d = d_min + x_mu * (d_max - d_min);
    var mu = 1.0;
    if d != 0.0 {
        // Law of cosines, with top² − r² = H² − ρ² as a product.
        mu = ((top_horizon - rho) * (top_horizon + rho) - d * d) / (2.0 * r * d);
    }
    return vec2<f32>(r, clamp(mu, -1.0, 1.0));
}

// Multiple-scattering LUT: linear in mu_s and altitude.
fn multiple_scattering_lut_uv(r: f32, mu_s: f32, planet_radius: f32, top_radius: f32, width: u32, height: u32) -> vec2<f32> {
    let x_mu_s = clamp(mu_s * 0.5 + 0.5, 0.0, 1.0);
    let x_r = clamp((r - planet_radius) / (top_radius - planet_radius), 0.0, 1.0);
    return vec2<f32>(unit_range_to_texel_uv(x_mu_s, width), unit_range_to_texel_uv(x_r, height));
}

// Inverse of multiple_scattering_lut_uv: (r, mu_s).
fn multiple_scattering_lut_r_mu_s(uv: vec2<f32>, planet_radius: f32, top_radius: f32, width: u32, height: u32) -> vec2<f32> {
    let x_mu_s = clamp(texel_uv_to_unit_range(uv.x, width), 0.0, 1.0);
    let x_r = clamp(texel_uv_to_unit_range(uv.y, height), 0.0, 1.0);
    return vec2<f32>(planet_radius + x_r * (top_radius - planet_radius), x_mu_s * 2.0 - 1.0);
}

// Zenith angle (rad) of the horizon seen from radius r: atan2(R, −ρ) ∈ [π/2, π).
fn horizon_zenith_angle(r_in: f32, planet_radius: f32) -> f32 {
    let r = max(r_in, planet_radius);
    return atan2(planet_radius, -horizon_distance(r, planet_radius));
}

// Hillaire's sky-view mapping: rows quadratic around the horizon (v = ½ exactly at
// the horizon), columns sin(φ/2) of the azimuth from the sun.
fn sky_view_lut_uv(r: f32, mu: f32, cos_azimuth: f32, planet_radius: f32, width: u32, height: u32) -> vec2<f32> {
    let horizon = horizon_zenith_angle(r, planet_radius);
    let zenith_angle = atan2(sqrt(max((1.0 - mu) * (1.0 + mu), 0.0)), mu);
    var y: f32;
    if zenith_angle < horizon {
        let coord = 1.0 - sqrt(max(1.0 - zenith_angle / horizon, 0.0));
        y = 0.5 * coord;
    } else {
        let coord = sqrt(max((zenith_angle - horizon) / (PI - horizon), 0.0));
        y = 0.5 + 0.5 * min(coord, 1.0);
    }
    let x = min(sqrt(max(0.5 - 0.5 * cos_azimuth, 0.0)), 1.0);
    return vec2<f32>(unit_range_to_texel_uv(x, width), unit_range_to_texel_uv(y, height));
}

// Inverse of sky_view_lut_uv: (mu, cos_azimuth).
fn sky_view_lut_direction(uv: vec2<f32>, r: f32, planet_radius: f32, width: u32, height: u32) -> vec2<f32> {
    let x = clamp(texel_uv_to_unit_range(uv.x, width), 0.0, 1.0);
    let y = clamp(texel_uv_to_unit_range(uv.y, height), 0.0, 1.0);
    let horizon = horizon_zenith_angle(r, planet_radius);
    var zenith_angle: f32;
    if y < 0.5 {
        let coord = 1.0 - 2.0 * y;
        zenith_angle = horizon * (1.0 - coord * coord);
    } else {
        let coord = 2.0 * y - 1.0;
        zenith_angle = horizon + (PI - horizon) * coord * coord;
    }
    return vec2<f32>(cos(zenith_angle), 1.0 - 2.0 * x * x);
}

// Cosine of the azimuth between view and sun around the local zenith (1 when either
// is vertical).
fn view_sun_cos_azimuth(mu: f32, mu_s: f32, nu: f32) -> f32 {
    let denominator = sqrt(max((1.0 - mu) * (1.0 + mu) * (1.0 - mu_s) * (1.0 + mu_s), 0.0));
    if denominator < 1e-6 {
        return 1.0;
    }
    return clamp((nu - mu * mu_s) / denominator, -1.0, 1.0);
}

// Where bilinear interpolation reads: columns x0/x1, rows y0/y1 and the weights of
// x1 and y1. Texel i's centre is at (i + ½)/n; rows are limited to
// first_row..=last_row (sky and ground rows of the sky view stay apart).
struct BilinearFootprint {
    x0: u32,
    y0: u32,
    x1: u32,
    y1: u32,
    fx: f32,
    fy: f32,
}

fn bilinear_footprint(uv: vec2<f32>, width: u32, height: u32, first_row: u32, last_row: u32) -> BilinearFootprint {
    let x = clamp(uv.x * f32(width) - 0.5, 0.0, f32(width - 1u));
    let y = clamp(uv.y * f32(height) - 0.5, f32(first_row), f32(last_row));
    let x0 = floor(x);
    let y0 = floor(y);
    return BilinearFootprint(u32(x0), u32(y0), min(u32(x0) + 1u, width - 1u), min(u32(y0) + 1u, last_row), x - x0, y - y0);
}

// (1 − fy)·mix(a, b, fx) + fy·mix(c, d, fx), written out as the Rust twin does.
fn bilinear_blend(a: vec3<f32>, b: vec3<f32>, c: vec3<f32>, d: vec3<f32>, fx: f32, fy: f32) -> vec3<f32> {
    let top = a * (1.0 - fx) + b * fx;
    let bottom = c * (1.0 - fx) + d * fx;
    return top * (1.0 - fy) + bottom * fy;
}

// ∫ over one step of e^{−x(t)}, x linear in t from x0 to x1: dt·e^{−x0}(1 − e^{−Δ})/Δ,
// exact for vertical rays (the midpoint rule misses the 1.2 km Mie layer by 19 % at
// 40 samples).
fn exponential_step_integral(x0: f32, x1: f32, dt: f32) -> f32 {
    let delta = x1 - x0;
    let start = exp(-x0);
    if delta == 0.0 {
        return dt * start;
    }
    return dt * start * (one_minus_exp_neg(delta) / delta);
}

// Distance from the planet centre of the point t metres along the ray.
fn radius_along_ray(r: f32, mu: f32, t: f32) -> f32 {
    return sqrt(max(r * r + t * (2.0 * r * mu + t), 0.0));
}

// 1 when the sun is above the planet's geometric horizon at radius r, else 0.
fn sun_visibility(r: f32, mu_s: f32, planet_radius: f32) -> f32 {
    let horizon_mu = -horizon_distance(r, planet_radius) / r;
    return select(0.0, 1.0, mu_s >= horizon_mu);
}

// ∫₀^dt e^{−σ s} ds: the weight of a constant source over one step (Hillaire's
// energy-conserving step), dt where σ = 0.
fn scattering_step_fraction(extinction: f32, dt: f32) -> f32 {
    if extinction > 0.0 {
        return one_minus_exp_neg(extinction * dt) / extinction;
    }
    return dt;
}

// In-scattered radiance and transmittance of a segment (or of a march so far).
struct ScatteringSegment {
    radiance: vec3<f32>,
    transmittance: vec3<f32>,
}

// The point t metres along the ray (r, mu) whose sun zenith cosine is mu_s and
// view–sun cosine nu: (its radius, view zenith cosine, sun zenith cosine).
fn point_along_ray(r: f32, mu: f32, mu_s: f32, nu: f32, t: f32) -> vec3<f32> {
    let r_t = radius_along_ray(r, mu, t);
    return vec3<f32>(r_t, clamp((r * mu + t) / r_t, -1.0, 1.0), clamp((r * mu_s + t * nu) / r_t, -1.0, 1.0));
}

// One step of every march of this rung (Hillaire 2020 §5.6.3's energy-conserving
// step): the source (per metre) integrated over dt against the step's extinction,
// seen through the march's transmittance so far, is added to its radiance; the
// transmittance is multiplied by the step's.
fn integrate_scattering_step(march: ScatteringSegment, source: vec3<f32>, extinction: vec3<f32>, dt: f32) -> ScatteringSegment {
    let weight = vec3<f32>(
        scattering_step_fraction(extinction.x, dt),
        scattering_step_fraction(extinction.y, dt),
        scattering_step_fraction(extinction.z, dt),
    );
    return ScatteringSegment(march.radiance + march.transmittance * source * weight, march.transmittance * exp(-extinction * dt));
}

// The part of a ray inside the atmosphere: (t_start, t_end, hits_ground ∈ {0, 1});
// (0, 0, 0) when it misses. r is clamped to ≥ planet_radius.
fn ray_segment_in_atmosphere(r_in: f32, mu: f32, planet_radius: f32, top_radius: f32) -> vec3<f32> {
    let r = max(r_in, planet_radius);
    let top = ray_sphere_intersect(r, mu, top_radius);
    if top.y < 0.0 {
        return vec3<f32>(0.0);
    }
    let t_start = max(top.x, 0.0);
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu < 0.0 && ground.x >= 0.0 {
        return vec3<f32>(t_start, ground.x, 1.0);
    }
    return vec3<f32>(t_start, top.y, 0.0);
}

// Unit view direction through screen coordinate uv ∈ [0, 1]² (x right, y down): the
// continuous form of frame_view_direction.
fn froxel_view_direction(uv: vec2<f32>, camera: FrameCamera) -> vec3<f32> {
    let aspect = f32(camera.width) / f32(camera.height);
    let ndc_x = (2.0 * uv.x - 1.0) * camera.tan_half_fov_y * aspect;
    let ndc_y = (1.0 - 2.0 * uv.y) * camera.tan_half_fov_y;
    let d = camera.forward + ndc_x * camera.right + ndc_y * camera.up;
    return d / sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
}

// (r, mu, mu_s, nu) of a view direction from the camera (r ≥ planet_radius).
fn view_cosines(camera: FrameCamera, direction: vec3<f32>, planet_radius: f32) -> vec4<f32> {
    let p = camera.position;
    let len = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    let up = p / len;
    return vec4<f32>(
        max(len, planet_radius),
        clamp(dot(direction, up), -1.0, 1.0),
        clamp(dot(camera.sun, up), -1.0, 1.0),
        clamp(dot(direction, camera.sun), -1.0, 1.0),
    );
}

// The sky-irradiance LUT's layout (twin: atmos::lut::sky_irradiance): μ_s columns, r
// rows quadratic in altitude, one layer per normal (n_z = −1 + 2i/31, φ_n = πj/7 from
// the sun, layer 8i + j), and the bake's direction quadrature.
const SKY_IRRADIANCE_WIDTH: u32 = 64u;
const SKY_IRRADIANCE_HEIGHT: u32 = 32u;
const SKY_IRRADIANCE_NORMAL_ZENITHS: u32 = 32u;
const SKY_IRRADIANCE_NORMAL_AZIMUTHS: u32 = 8u;
const SKY_IRRADIANCE_LAYERS: u32 = 256u;
const SKY_IRRADIANCE_DIRECTION_ZENITHS: u32 = 32u;
const SKY_IRRADIANCE_DIRECTION_AZIMUTHS: u32 = 32u;
const SKY_IRRADIANCE_SAMPLES: u32 = 24u;

// Texture coordinates of (r, μ_s) in the sky-irradiance LUT.
fn sky_irradiance_lut_uv(r: f32, mu_s: f32, planet_radius: f32, top_radius: f32) -> vec2<f32> {
    let x_mu_s = clamp(mu_s * 0.5 + 0.5, 0.0, 1.0);
    let x_r = sqrt(clamp((r - planet_radius) / (top_radius - planet_radius), 0.0, 1.0));
    return vec2<f32>(unit_range_to_texel_uv(x_mu_s, SKY_IRRADIANCE_WIDTH), unit_range_to_texel_uv(x_r, SKY_IRRADIANCE_HEIGHT));
}

// Inverse of sky_irradiance_lut_uv: (r, μ_s).
fn sky_irradiance_lut_r_mu_s(uv: vec2<f32>, planet_radius: f32, top_radius: f32) -> vec2<f32> {
    let x_mu_s = clamp(texel_uv_to_unit_range(uv.x, SKY_IRRADIANCE_WIDTH), 0.0, 1.0);
    let x_r = clamp(texel_uv_to_unit_range(uv.y, SKY_IRRADIANCE_HEIGHT), 0.0, 1.0);
    return vec2<f32>(planet_radius + x_r * x_r * (top_radius - planet_radius), x_mu_s * 2.0 - 1.0);
}

// The normal of a sky-irradiance layer in the sun frame.
fn sky_irradiance_layer_normal(layer: u32) -> vec3<f32> {
    let zenith = layer / SKY_IRRADIANCE_NORMAL_AZIMUTHS;
    let azimuth = layer % SKY_IRRADIANCE_NORMAL_AZIMUTHS;
    let n_z = -1.0 + 2.0 * f32(zenith) / f32(SKY_IRRADIANCE_NORMAL_ZENITHS - 1u);
    let phi = PI * f32(azimuth) / f32(SKY_IRRADIANCE_NORMAL_AZIMUTHS - 1u);
    let horizontal = sqrt(max((1.0 - n_z) * (1.0 + n_z), 0.0));
    return vec3<f32>(horizontal * cos(phi), horizontal * sin(phi), n_z);
}

// max(0, n·ω) + max(0, n·ω′) for the bake direction of zenith cosine mu and azimuth
// index `azimuth` and its mirror image ω′ (y negated).
fn sky_irradiance_cosines(normal: vec3<f32>, mu: f32, azimuth: u32) -> f32 {
    let phi = PI * (f32(azimuth) + 0.5) / f32(SKY_IRRADIANCE_DIRECTION_AZIMUTHS);
    let sin_v = sqrt(max((1.0 - mu) * (1.0 + mu), 0.0));
    let x = normal.x * sin_v * cos(phi) + normal.z * mu;
    let y = normal.y * sin_v * sin(phi);
    return max(x + y, 0.0) + max(x - y, 0.0);
}
