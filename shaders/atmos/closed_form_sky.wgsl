// Rung 1 of the ladder: Hoffman & Preetham's (2002) closed form in spherical geometry. A path through
// Earth's exponential layers becomes its equivalent sea-level path (the length of air
// at ground density with the same optical depth, through an exponential layer of the
// Rayleigh scale height H_R, by the Chapman function in closed form), valid for a
// camera at any altitude; the Mie coefficient is scaled by H_M / H_R, so both keep
// their vertical optical depth; sunlight driving the in-scatter is attenuated by the
// transmittance averaged over the sun's path to space.
// Twin: atmos::closed_form_sky (Rust). Units: metres, 1/m; radiance per unit sun
// irradiance times `sun_irradiance`.

#import atmos::geometry
#import atmos::closed_form
#import atmos::transmittance

struct ClosedFormSkyParameters {
    beta_rayleigh: vec3<f32>,
    mie_g: f32,
    // Homogeneous-equivalent Mie scattering (1/m).
    beta_mie: vec3<f32>,
    planet_radius: f32,
    sun_irradiance: vec3<f32>,
    // planet_radius + H_R (m): the equivalent path's layer has the scale height
    // shell_radius − planet_radius.
    shell_radius: f32,
}

// Sunlight driving the in-scatter at a viewer at radius r with sun zenith cosine mu_s:
// irradiance × (1 − e^{−τ})/τ over the sun's equivalent path to space; 0 when the
// planet hides the sun's centre.
fn closed_form_sunlight(r: f32, mu_s: f32, params: ClosedFormSkyParameters) -> vec3<f32> {
    let sun_ground = ray_sphere_intersect(r, mu_s, params.planet_radius);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu_s < 0.0 && sun_ground.x >= 0.0 {
        return vec3<f32>(0.0);
    }
    let path = closed_form_path_length(r, mu_s, F32_MAX_FINITE, params);
    let optical_depth = (params.beta_rayleigh + params.beta_mie) * path;
    var average = vec3<f32>(1.0);
    for (var i = 0; i < 3; i++) {
        if optical_depth[i] > 0.0 {
            average[i] = one_minus_exp_neg(optical_depth[i]) / optical_depth[i];
        }
    }
    return params.sun_irradiance * average;
}

// Largest finite f32 (Rust f32::MAX): an unbounded max_distance.
const F32_MAX_FINITE: f32 = 3.40282347e38;

// Layers this many scale heights up hold e^{−50} of the air: the equivalent path ends
// there. Twin: atmos::closed_form_sky::CLOSED_FORM_TOP_SCALE_HEIGHTS.
const CLOSED_FORM_TOP_SCALE_HEIGHTS: f32 = 50.0;

// e^{y²} erfc(y) for y ≥ 0 (Ren & MacKenzie 2007, a = 2.911).
fn scaled_complementary_error_function(y: f32) -> f32 {
    let a = 2.911;
    let pi = 3.14159265358979;
    return a / ((a - 1.0) * sqrt(pi) * y + sqrt(pi * y * y + a * a));
}

// Equivalent sea-level path (m) from a point at altitude (radius r) along zenith cosine
// mu ≥ 0 to space through an exponential layer: H e^{−h/H} Ch(r/H, μ), with
// Ch(x, μ) ≈ √(πx/2) erfcx(μ √(x/2)).
fn closed_form_path_to_space(altitude: f32, r: f32, mu: f32, scale_height: f32) -> f32 {
    let pi = 3.14159265358979;
    let x = r / scale_height;
    let chapman = sqrt(pi * x * 0.5) * scaled_complementary_error_function(sqrt(x * 0.5) * mu);
    return scale_height * exp(-altitude / scale_height) * chapman;
}

// Altitude along the ray as closed_form_segment_path computes it: (r_t, h_t).
fn closed_form_radius_and_altitude(r: f32, mu: f32, t: f32, planet_radius: f32) -> vec2<f32> {
    let excess = (r - planet_radius) * (r + planet_radius) + t * (2.0 * r * mu + t);
    let r_t = sqrt(max(r * r + t * (2.0 * r * mu + t), 0.0));
    return vec2<f32>(r_t, excess / (r_t + planet_radius));
}

// Equivalent sea-level path (m) of the segment [0, distance] of the ray (r, mu):
// differences of closed_form_path_to_space along climbing rays (a descending part is
// read backwards; a ray past its lowest point is split there).
fn closed_form_segment_path(r: f32, mu: f32, distance: f32, planet_radius: f32, scale_height: f32) -> f32 {
    let start_altitude = r - planet_radius;
    let end = closed_form_radius_and_altitude(r, mu, distance, planet_radius);
    let mu_end = clamp((r * mu + distance) / end.x, -1.0, 1.0);
    var path: f32;
    if mu >= 0.0 {
        path = closed_form_path_to_space(start_altitude, r, max(mu, 0.0), scale_height)
            - closed_form_path_to_space(end.y, end.x, max(mu_end, 0.0), scale_height);
    } else if distance <= -r * mu {
        path = closed_form_path_to_space(end.y, end.x, max(-mu_end, 0.0), scale_height)
            - closed_form_path_to_space(start_altitude, r, max(-mu, 0.0), scale_height);
    } else {
        let low = closed_form_radius_and_altitude(r, mu, -r * mu, planet_radius);
        path = 2.0 * closed_form_path_to_space(low.y, low.x, 0.0, scale_height)
            - closed_form_path_to_space(start_altitude, r, max(-mu, 0.0), scale_height)
            - closed_form_path_to_space(end.y, end.x, max(mu_end, 0.0), scale_height);
    }
    return max(path, 0.0);
}

// Equivalent sea-level path (m) of the view ray (r, mu) from the viewer to where it
// hits the ground, max_distance, or CLOSED_FORM_TOP_SCALE_HEIGHTS above the ground.
fn closed_form_path_length(r_in: f32, mu: f32, max_distance: f32, params: ClosedFormSkyParameters) -> f32 {
    // A viewer below the ground (terrain rounding) is treated as on it.
    let r = max(r_in, params.planet_radius);
    let scale_height = params.shell_radius - params.planet_radius;
    let top = params.planet_radius + CLOSED_FORM_TOP_SCALE_HEIGHTS * scale_height;
    let exit = ray_sphere_intersect(r, mu, top);
    if exit.y < 0.0 {
        return 0.0;
    }
    let ground = ray_sphere_intersect(r, mu, params.planet_radius);
    var end = min(exit.y, max_distance);
    // Tangent rays see the sky (docs/architecture.md, "Rays at the ground").
    if mu < 0.0 && ground.x >= 0.0 {
        end = min(end, ground.x);
    }
    return closed_form_segment_path(r, mu, max(end, 0.0), params.planet_radius, scale_height);
}

// Views within this of the sun's axis (1 − ν² below it) run parallel to the planet's
// shadow cylinder. Twin: atmos::closed_form_sky::CLOSED_FORM_SHADOW_PARALLEL.
const CLOSED_FORM_SHADOW_PARALLEL: f32 = 1e-6;

// The distances (t_in, t_out) (m, 0 ≤ t_in ≤ t_out) over which the view ray (r, mu)
// with sun zenith cosine mu_s and view–sun cosine nu is in the planet's shadow: the
// cylinder of radius planet_radius behind the planet (the sun's centre as a point at
// infinity); t_in == t_out when it never enters it, t_out = F32_MAX_FINITE when it stays
// in it. In τ = t/r the squared distance from the shadow's axis over r² is
// a τ² + 2 b τ + c, and the ray is behind the planet where μ_s + τ ν < 0.
fn closed_form_shadow_interval(r: f32, mu: f32, mu_s: f32, nu: f32, planet_radius: f32) -> vec2<f32> {
    let far = F32_MAX_FINITE;
    let k = planet_radius / r;
    let sin_s = sqrt(max(1.0 - mu_s * mu_s, 0.0));
    let a = max(1.0 - nu * nu, 0.0);
    let b = mu - mu_s * nu;
    let c = (sin_s - k) * (sin_s + k);
    var lo = 0.0;
    var hi = 0.0;
    if a < CLOSED_FORM_SHADOW_PARALLEL {
        if c < 0.0 {
            hi = far;
        }
    } else {
        let discriminant = b * b - a * c;
        if discriminant > 0.0 {
            // The root without cancellation first, the other from the product c/a.
            let root = sqrt(discriminant);
            var q = root - b;
            if b > 0.0 {
                q = -(b + root);
            }
            let x = q / a;
            var y = 0.0;
            if q != 0.0 {
                y = c / q;
            }
            lo = min(x, y);
            hi = max(x, y);
        }
    }
    // Behind the planet: μ_s + τ ν < 0.
    var behind_lo = 0.0;
    var behind_hi = 0.0;
    if nu > 0.0 {
        behind_hi = -mu_s / nu;
    } else if nu < 0.0 {
        behind_lo = -mu_s / nu;
        behind_hi = far;
    } else if mu_s < 0.0 {
        behind_hi = far;
    }
    let start = max(max(lo, behind_lo), 0.0);
    let end = min(hi, behind_hi);
    if end <= start {
        return vec2<f32>(0.0);
    }
    var t = vec2<f32>(start * r, end * r);
    if end >= far / r {
        t.y = far;
    }
    return t;
}

// In-scattered radiance along the view ray (r, mu) with sun zenith cosine mu_s and
// view–sun cosine nu, given the sunlight from closed_form_sunlight. Points in the
// planet's shadow get no sunlight: I(p_in) + e^{−β p_out} I(p_end − p_out) over the
// equivalent paths to the shadow's ends and the segment's end.
fn closed_form_sky_radiance(r: f32, mu: f32, mu_s: f32, nu: f32, max_distance: f32, sunlight: vec3<f32>, params: ClosedFormSkyParameters) -> vec3<f32> {
    let path = closed_form_path_length(r, mu, max_distance, params);
    let shadow = closed_form_shadow_interval(max(r, params.planet_radius), mu, mu_s, nu, params.planet_radius);
    var lit: vec3<f32>;
    if shadow.y > shadow.x {
        let path_in = closed_form_path_length(r, mu, min(shadow.x, max_distance), params);
        let path_out = closed_form_path_length(r, mu, min(shadow.y, max_distance), params);
        let before = closed_form_inscatter(params.beta_rayleigh, params.beta_mie, nu, params.mie_g, path_in);
        let after = closed_form_inscatter(params.beta_rayleigh, params.beta_mie, nu, params.mie_g, max(path - path_out, 0.0));
        let through = closed_form_extinction(params.beta_rayleigh, params.beta_mie, path_out);
        lit = before + through * after;
    } else {
        lit = closed_form_inscatter(params.beta_rayleigh, params.beta_mie, nu, params.mie_g, path);
    }
    return sunlight * lit;
}

// Transmittance of the same segment.
fn closed_form_sky_transmittance(r: f32, mu: f32, max_distance: f32, params: ClosedFormSkyParameters) -> vec3<f32> {
    let path = closed_form_path_length(r, mu, max_distance, params);
    return closed_form_extinction(params.beta_rayleigh, params.beta_mie, path);
}
