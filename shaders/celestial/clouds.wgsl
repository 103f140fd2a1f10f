// celestial::clouds — SGSky's 2-D cloud layers: value-noise fBm textures with a
// coverage threshold, columns thin at their edges and thick at their cores, lit by exact
// single scattering plus Eddington two-stream multiple scattering, fading into the fog.
// Twin: crates/celestial/src/clouds.rs (Rust f32): same names, argument order and units
// (metres, radiance in atmos units per sr, directions east/north/up with the viewer on
// the +z axis).

#import common::hash
#import common::constants
#import atmos::geometry
#import atmos::transmittance
#import atmos::phase

// −ln 0.02: the optical depth of Koschmieder's contrast threshold.
const KOSCHMIEDER_OPTICAL_DEPTH: f32 = 3.912023;
// The diffusivity factor: a slab's diffuse transmission of its own uniform source,
// 1 − 2E₃(τ), is close to 1 − exp(−1.66 τ) (Elsasser 1942; Liou 2002, §4.4).
const DIFFUSIVITY: f32 = 1.66;

// Twin of celestial::clouds::CloudLayerUniforms.
struct CloudLayerUniforms {
    base_radius: f32,
    top_radius: f32,
    planet_radius: f32,
    curved: u32,
    feature_size: f32,
    stretch: f32,
    octaves: u32,
    seed: u32,
    threshold: f32,
    softness: f32,
    optical_thickness: f32,
    asymmetry: f32,
    offset: vec2<f32>,
    half_span: f32,
    fog_extinction: f32,
    sun_direction: vec3<f32>,
    exp2_fog: u32,
    sunlight: vec3<f32>,
    core_depth: f32,
    skylight: vec3<f32>,
    padding1: f32,
    fog_colour: vec3<f32>,
    padding2: f32,
}

fn cloud_corner(seed: u32, ix: i32, iy: i32) -> f32 {
    return unit_float_from_bits(hash_combine(hash_combine(seed, bitcast<u32>(ix)), bitcast<u32>(iy)));
}

// Value noise in [0, 1) at (x, y) lattice units: hashed corners, smoothstep blend.
fn cloud_value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let fx = floor(x);
    let fy = floor(y);
    let ix = i32(fx);
    let iy = i32(fy);
    let tx = x - fx;
    let ty = y - fy;
    let c00 = cloud_corner(seed, ix, iy);
    let c10 = cloud_corner(seed, ix + 1, iy);
    let c01 = cloud_corner(seed, ix, iy + 1);
    let c11 = cloud_corner(seed, ix + 1, iy + 1);
    let sx = tx * tx * (3.0 - 2.0 * tx);
    let sy = ty * ty * (3.0 - 2.0 * ty);
    let bottom = c00 + (c10 - c00) * sx;
    let top = c01 + (c11 - c01) * sx;
    return bottom + (top - bottom) * sy;
}

// fBm of value noise, octaves doubling in frequency and halving in amplitude,
// normalised to [0, 1).
fn cloud_fbm(x: f32, y: f32, octaves: u32, seed: u32) -> f32 {
    var sum = 0.0;
    var amplitude = 1.0;
    var total = 0.0;
    var frequency = 1.0;
    for (var octave = 0u; octave < octaves; octave++) {
        sum += amplitude * cloud_value_noise(x * frequency, y * frequency, hash_combine(seed, octave));
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    return sum / total;
}

// Density in [0, 1] at (u, v) metres on the layer.
fn cloud_density(u: f32, v: f32, layer: CloudLayerUniforms) -> f32 {
    let x = u / (layer.feature_size * layer.stretch);
    let y = v / layer.feature_size;
    let n = cloud_fbm(x, y, layer.octaves, layer.seed);
    let t = clamp((n - layer.threshold) / layer.softness + 0.5, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Eddington two-stream reflectance of a conservative layer (Lacis & Hansen 1974).
fn cloud_reflectance(optical_thickness: f32, asymmetry: f32, mu_sun: f32) -> f32 {
    if mu_sun <= 0.0 {
        return 0.0;
    }
    let scaled = (1.0 - asymmetry) * optical_thickness;
    let direct = 1.0 - exp(-optical_thickness / mu_sun);
    return clamp((scaled + (2.0 / 3.0 - mu_sun) * direct) / (4.0 / 3.0 + scaled), 0.0, 1.0);
}

// The cloud at (u, v) metres: (coverage, the column's vertical optical thickness where
// it is) — the edge's smoothstep cover of a column τ × the noise's height above the
// edge's foot, floored at the threshold, over the layer's core depth.
fn cloud_column(u: f32, v: f32, layer: CloudLayerUniforms) -> vec2<f32> {
    let x = u / (layer.feature_size * layer.stretch);
    let y = v / layer.feature_size;
    let n = cloud_fbm(x, y, layer.octaves, layer.seed);
    let height = (n - layer.threshold) / layer.softness + 0.5;
    let t = clamp(height, 0.0, 1.0);
    let coverage = t * t * (3.0 - 2.0 * t);
    return vec2<f32>(coverage, layer.optical_thickness * (max(height, 0.5) * layer.softness / layer.core_depth));
}

// The area-mean vertical optical thickness at (u, v): coverage × the column's.
fn cloud_optical_thickness(u: f32, v: f32, layer: CloudLayerUniforms) -> f32 {
    let column = cloud_column(u, v, layer);
    return column.x * column.y;
}

// (1 − e^{−y})/y for y ≥ 0 (1 at y = 0).
fn cloud_mean_attenuation(y: f32) -> f32 {
    if y < 1e-6 {
        return 1.0 - 0.5 * y;
    }
    return one_minus_exp_neg(y) / y;
}

// Radiance (1/sr per unit normal sun irradiance) of a uniform conservative column of
// vertical optical thickness τ toward a viewer at |μ| = mu_view, reflected (transmitted
// 0) or transmitted (1): exact single scattering with Henyey–Greenstein plus the rest
// of Eddington's flux (less the singly scattered flux, Meador & Weaver's β₀) as a
// uniform source seen through the opacity.
fn cloud_sun_scattering(optical_thickness: f32, asymmetry: f32, mu_sun: f32, mu_view: f32, cos_scattering: f32, transmitted: u32) -> f32 {
    let tau = optical_thickness;
    if mu_sun <= 0.0 || tau <= 0.0 {
        return 0.0;
    }
    let phase = henyey_greenstein_phase(cos_scattering, asymmetry);
    let backscatter = min(max(0.5 - 0.75 * asymmetry * mu_sun, 0.0), 1.0);
    let reflectance = cloud_reflectance(tau, asymmetry, mu_sun);
    var single: f32;
    var flux: f32;
    if transmitted != 0u {
        single = tau / mu_view
            * exp(-tau / max(mu_sun, mu_view))
            * cloud_mean_attenuation(tau * abs(1.0 / mu_view - 1.0 / mu_sun));
        let single_flux = (1.0 - backscatter) * tau / mu_sun
            * exp(-tau / max(mu_sun, 1.0 / DIFFUSIVITY))
            * cloud_mean_attenuation(tau * abs(DIFFUSIVITY - 1.0 / mu_sun));
        let diffuse = 1.0 - reflectance - exp(-tau / mu_sun);
        flux = max(diffuse - single_flux, 0.0);
    } else {
        single = tau / mu_view * cloud_mean_attenuation(tau * (1.0 / mu_sun + 1.0 / mu_view));
        let single_flux = backscatter * tau / mu_sun * cloud_mean_attenuation(tau * (1.0 / mu_sun + DIFFUSIVITY));
        flux = max(reflectance - single_flux, 0.0);
    }
    let opacity = one_minus_exp_neg(tau / mu_view);
    let emissivity = one_minus_exp_neg(DIFFUSIVITY * tau);
    return phase * single + flux * mu_sun * INV_PI * opacity / emissivity;
}

// Fraction of the direct sun reaching `point` (east/north/up metres from the viewer at
// radius r) under the layer: exp(−τρ/μ☉) with ρ the texture where the sun's ray from the
// point crosses the base (taken flat over the point); 1 at or above the top, outside
// the patch, or with the sun at or below the horizon.
fn cloud_shadow(point: vec3<f32>, r: f32, layer: CloudLayerUniforms) -> f32 {
    let sun = layer.sun_direction;
    let mu_sun = sun.z;
    let point_radius = r + point.z;
    if mu_sun <= 0.0 || point_radius >= layer.top_radius {
        return 1.0;
    }
    let distance = max(layer.base_radius - point_radius, 0.0) / mu_sun;
    let x = point.x + sun.x * distance;
    let y = point.y + sun.y * distance;
    if sqrt(x * x + y * y) >= layer.half_span {
        return 1.0;
    }
    let density = cloud_density(x + layer.offset.x, y + layer.offset.y, layer);
    return exp(-layer.optical_thickness * density / mu_sun);
}

// Distance along (r, mu) to the layer surface (sphere when curved, else the plane at
// that altitude); −1 when it is not reached.
fn cloud_layer_distance(r: f32, mu: f32, layer_radius: f32, curved: u32) -> f32 {
    if curved != 0u {
        let hit = ray_sphere_intersect(r, mu, layer_radius);
        if r < layer_radius {
            return hit.y;
        }
        if hit.x >= 0.0 && mu < 0.0 {
            return hit.x;
        }
        return -1.0;
    }
    let height = layer_radius - r;
    if (height > 0.0 && mu > 0.0) || (height < 0.0 && mu < 0.0) {
        return height / mu;
    }
    return -1.0;
}

// The layer along `view` from radius r (on +z), composited over `background`.
fn cloud_layer_radiance(view: vec3<f32>, r: f32, layer: CloudLayerUniforms, background: vec3<f32>) -> vec3<f32> {
    let mu = view.z;
    let inside = r >= layer.base_radius && r <= layer.top_radius;
    if inside {
        return background;
    }
    let below = r < layer.base_radius;
    var surface = layer.top_radius;
    if below {
        surface = layer.base_radius;
    }
    let distance = cloud_layer_distance(r, mu, surface, layer.curved);
    if distance < 0.0 {
        return background;
    }
    let horizontal = vec2<f32>(view.x * distance, view.y * distance);
    let reach = sqrt(horizontal.x * horizontal.x + horizontal.y * horizontal.y);
    if reach >= layer.half_span {
        return background;
    }
    let rim = min(2.0 * (1.0 - reach / layer.half_span), 1.0);
    let hit_z = r + mu * distance;
    var hit_radius = hit_z;
    var mu_hit = mu;
    if layer.curved != 0u {
        hit_radius = surface;
        mu_hit = (view.x * horizontal.x + view.y * horizontal.y + view.z * hit_z) / hit_radius;
    }
    let slant = max(abs(mu_hit), 0.01);
    let column = cloud_column(horizontal.x + layer.offset.x, horizontal.y + layer.offset.y, layer);
    let coverage = column.x;
    let tau = column.y;
    if coverage <= 0.0 {
        return background;
    }
    let opacity = one_minus_exp_neg(tau / slant);
    let sun = layer.sun_direction;
    let mu_sun = sun.z;
    let cos_scattering = view.x * sun.x + view.y * sun.y + view.z * sun.z;
    let sun_scattering = cloud_sun_scattering(tau, layer.asymmetry, mu_sun, slant, cos_scattering, u32(below));
    var sky_factor = cloud_reflectance(tau, layer.asymmetry, 0.5);
    if below {
        sky_factor = max(1.0 - cloud_reflectance(tau, layer.asymmetry, 0.5) - exp(-tau / 0.5), 0.0);
    }
    let emissivity = one_minus_exp_neg(DIFFUSIVITY * tau);
    var fog: f32;
    if layer.exp2_fog != 0u {
        let x = layer.fog_extinction * distance;
        fog = exp(-(x * x) / KOSCHMIEDER_OPTICAL_DEPTH);
    } else {
        fog = exp(-layer.fog_extinction * distance);
    }
    var result: vec3<f32>;
    for (var i = 0; i < 3; i++) {
        let lit = sun_scattering * layer.sunlight[i] + sky_factor * layer.skylight[i] * INV_PI * opacity / emissivity;
        let faded = fog * lit + (1.0 - fog) * opacity * layer.fog_colour[i];
        result[i] = background[i] + rim * coverage * (faded - opacity * background[i]);
    }
    return result;
}
