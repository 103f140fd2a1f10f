//! Shading a layer: its frame uniforms, texture, shadow, reflectance and radiance
//! (the WGSL twins).

use skyscape_wgsl::common::{hash_combine, unit_float_from_bits};

/// What a layer needs from the frame: the planet, the fog, the light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CloudLayerFrame {
    /// Ground radius (m).
    pub planet_radius_m: f64,
    /// Texture offset (m, east and north): the viewer's travel plus wind drift.
    pub offset_m: [f64; 2],
    /// Fog extinction (1/m) between the viewer and the layer: 3.912 / visibility.
    pub fog_extinction_per_m: f64,
    /// SGSky's exp² fog instead of the exponential one.
    pub exp2_fog: bool,
    /// Unit direction toward the sun (east/north/up).
    pub sun_direction: [f64; 3],
    /// The sun's irradiance at the layer (after the atmosphere), per channel.
    pub sunlight: [f64; 3],
    /// The sky's irradiance on a horizontal surface at the layer, per channel.
    pub skylight: [f64; 3],
    /// Radiance of the fog the layer fades into (the horizon sky), per channel.
    pub fog_colour: [f64; 3],
}

/// A layer's uniform block; layout identical to WGSL `CloudLayerUniforms`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs)]
pub struct CloudLayerUniforms {
    pub base_radius: f32,
    pub top_radius: f32,
    pub planet_radius: f32,
    pub curved: u32,
    pub feature_size: f32,
    pub stretch: f32,
    pub octaves: u32,
    pub seed: u32,
    pub threshold: f32,
    pub softness: f32,
    pub optical_thickness: f32,
    pub asymmetry: f32,
    pub offset: [f32; 2],
    pub half_span: f32,
    pub fog_extinction: f32,
    pub sun_direction: [f32; 3],
    pub exp2_fog: u32,
    pub sunlight: [f32; 3],
    pub padding0: f32,
    pub skylight: [f32; 3],
    pub padding1: f32,
    pub fog_colour: [f32; 3],
    pub padding2: f32,
}

/// −ln 0.02: the optical depth at which Koschmieder's contrast threshold is reached.
const KOSCHMIEDER_OPTICAL_DEPTH: f32 = 3.912_023;

/// Value noise in [0, 1) at (x, y) (lattice units): the four corners' hashes (seed,
/// cell x, cell y) blended with the smoothstep of the fractional position.
#[doc(hidden)]
pub fn cloud_value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let (fx, fy) = (x.floor(), y.floor());
    let (ix, iy) = (fx as i32, fy as i32);
    let (tx, ty) = (x - fx, y - fy);
    let corner = |dx: i32, dy: i32| {
        unit_float_from_bits(hash_combine(
            hash_combine(seed, ix.wrapping_add(dx) as u32),
            iy.wrapping_add(dy) as u32,
        ))
    };
    let sx = tx * tx * (3.0 - 2.0 * tx);
    let sy = ty * ty * (3.0 - 2.0 * ty);
    let bottom = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    let top = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    bottom + (top - bottom) * sy
}

/// fBm: `octaves` octaves of [`cloud_value_noise`], each twice the frequency and half
/// the amplitude of the previous (with its own seed), normalised to [0, 1).
#[doc(hidden)]
pub fn cloud_fbm(x: f32, y: f32, octaves: u32, seed: u32) -> f32 {
    let (mut sum, mut amplitude, mut total, mut frequency) = (0.0f32, 1.0f32, 0.0f32, 1.0f32);
    for octave in 0..octaves {
        sum +=
            amplitude * cloud_value_noise(x * frequency, y * frequency, hash_combine(seed, octave));
        total += amplitude;
        amplitude *= 0.5;
        frequency *= 2.0;
    }
    sum / total
}

/// Cloud density in [0, 1] at horizontal position (`u`, `v`) metres on the layer:
/// fBm at the layer's scale, stretched along u, through the coverage threshold with
/// the kind's soft edge (a smoothstep of width `softness` centred on `threshold`).
#[doc(hidden)]
pub fn cloud_density(u: f32, v: f32, layer: &CloudLayerUniforms) -> f32 {
    let x = u / (layer.feature_size * layer.stretch);
    let y = v / layer.feature_size;
    let n = cloud_fbm(x, y, layer.octaves, layer.seed);
    let t = ((n - layer.threshold) / layer.softness + 0.5).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Fraction of the direct sun that reaches a point under the layer: the sun's ray from
/// the point crosses the layer's base where the texture has density ρ, and the
/// element's vertical optical thickness τ along the slant leaves exp(−τρ/μ☉) — the
/// `direct` term `cloud_layer_radiance` lights the layer with. `point` is east/north/up
/// metres from the viewer (on the +z axis at radius `r`), the sun the layer's
/// `sun_direction`. 1 for a point at or above the layer's top, outside its patch, or
/// with the sun at or below the horizon (no direct sun for the layer to block). The
/// base is taken flat over the point (the layer's curvature over a shadow's reach is
/// left out: 0.2 m at 1.6 km).
pub fn cloud_shadow(point: [f32; 3], r: f32, layer: &CloudLayerUniforms) -> f32 {
    let sun = layer.sun_direction;
    let mu_sun = sun[2];
    let point_radius = r + point[2];
    if mu_sun <= 0.0 || point_radius >= layer.top_radius {
        return 1.0;
    }
    let distance = (layer.base_radius - point_radius).max(0.0) / mu_sun;
    let x = point[0] + sun[0] * distance;
    let y = point[1] + sun[1] * distance;
    if (x * x + y * y).sqrt() >= layer.half_span {
        return 1.0;
    }
    let density = cloud_density(x + layer.offset[0], y + layer.offset[1], layer);
    (-layer.optical_thickness * density / mu_sun).exp()
}

/// Eddington two-stream reflectance of a conservative layer of optical thickness
/// `optical_thickness` and asymmetry `asymmetry`, lit at cosine `mu_sun` (Lacis &
/// Hansen 1974); the sun below the layer's horizon (μ₀ ≤ 0) reflects nothing.
#[doc(hidden)]
pub fn cloud_reflectance(optical_thickness: f32, asymmetry: f32, mu_sun: f32) -> f32 {
    if mu_sun <= 0.0 {
        return 0.0;
    }
    let scaled = (1.0 - asymmetry) * optical_thickness;
    let direct = 1.0 - (-optical_thickness / mu_sun).exp();
    ((scaled + (2.0 / 3.0 - mu_sun) * direct) / (4.0 / 3.0 + scaled)).clamp(0.0, 1.0)
}

/// Distance (m) along a view from radius `r` with zenith cosine `mu` to the layer
/// surface of radius `layer_radius`: the sphere (curved) or the plane at that altitude
/// (flat); −1 when the view does not reach it (or the viewer is on it).
#[doc(hidden)]
pub fn cloud_layer_distance(r: f32, mu: f32, layer_radius: f32, curved: u32) -> f32 {
    if curved != 0 {
        let hit = atmos::geometry::ray_sphere_intersect(r, mu, layer_radius);
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

/// The diffusivity factor: a slab's diffuse transmission of its own uniform source,
/// `1 − 2E₃(τ)`, is close to `1 − exp(−1.66 τ)` (Elsasser 1942; Liou 2002, An
/// Introduction to Atmospheric Radiation, §4.4).
pub const DIFFUSIVITY: f32 = 1.66;

/// The layer seen along `view` (unit, east/north/up) from a viewer at radius `r` on
/// the +z axis, composited over `background` (the radiance behind it, per channel):
/// the layer's surface facing the viewer (its base from below, its top from above;
/// nothing from inside), the texture's density there, the cloud's opacity
/// `1 − exp(−τ·density/|μ_layer|)` and source radiance J (the reflected or diffusely
/// transmitted sun and sky light of Eddington's two-stream slab, over the slab's
/// emissivity `1 − exp(−1.66 τ)`: a thin edge is as bright as its scattering, not
/// darker than the sky behind it), faded into the fog colour by the fog over the distance and
/// toward the patch's rim (linearly over its outer half). Returns the composited
/// radiance.
pub fn cloud_layer_radiance(
    view: [f32; 3],
    r: f32,
    layer: &CloudLayerUniforms,
    background: [f32; 3],
) -> [f32; 3] {
    let mu = view[2];
    let inside = r >= layer.base_radius && r <= layer.top_radius;
    if inside {
        return background;
    }
    let below = r < layer.base_radius;
    let surface = if below {
        layer.base_radius
    } else {
        layer.top_radius
    };
    let distance = cloud_layer_distance(r, mu, surface, layer.curved);
    if distance < 0.0 {
        return background;
    }
    let horizontal = [view[0] * distance, view[1] * distance];
    let reach = (horizontal[0] * horizontal[0] + horizontal[1] * horizontal[1]).sqrt();
    if reach >= layer.half_span {
        return background;
    }
    let rim = (2.0 * (1.0 - reach / layer.half_span)).min(1.0);
    let density = cloud_density(
        horizontal[0] + layer.offset[0],
        horizontal[1] + layer.offset[1],
        layer,
    );
    if density <= 0.0 || layer.optical_thickness <= 0.0 {
        return background;
    }
    // Zenith cosine of the view at the hit point (the local vertical there for a
    // curved layer) and of the sun.
    let hit_z = r + mu * distance;
    let hit_radius = if layer.curved != 0 { surface } else { hit_z };
    let mu_hit = if layer.curved != 0 {
        (view[0] * horizontal[0] + view[1] * horizontal[1] + view[2] * hit_z) / hit_radius
    } else {
        mu
    };
    let slant = mu_hit.abs().max(0.01);
    let tau = layer.optical_thickness * density;
    let opacity = (1.0 - (-tau / slant).exp()) * rim;
    let sun = layer.sun_direction;
    let mu_sun = sun[2];
    let reflectance = cloud_reflectance(tau, layer.asymmetry, mu_sun);
    let direct = if mu_sun > 0.0 {
        (-tau / mu_sun).exp()
    } else {
        1.0
    };
    let diffuse_factor = if below {
        (1.0 - reflectance - direct).max(0.0)
    } else {
        reflectance
    };
    let sky_factor = if below {
        (1.0 - cloud_reflectance(tau, layer.asymmetry, 0.5) - (-tau / 0.5).exp()).max(0.0)
    } else {
        cloud_reflectance(tau, layer.asymmetry, 0.5)
    };
    let fog = if layer.exp2_fog != 0 {
        // SGSky's exp² fog with the same 2 % at the visibility: exp(−(βd)²/3.912).
        let x = layer.fog_extinction * distance;
        (-(x * x) / KOSCHMIEDER_OPTICAL_DEPTH).exp()
    } else {
        (-layer.fog_extinction * distance).exp()
    };
    // The Eddington factors give what the whole slab sends out (a thin slab little);
    // over the background the view sees the slab's source function J through its
    // opacity, so J is that output over the slab's own emissivity 1 − exp(−1.66 τ).
    let emissivity = atmos::transmittance::one_minus_exp_neg(DIFFUSIVITY * tau);
    std::array::from_fn(|i| {
        let lit = (diffuse_factor * layer.sunlight[i] * mu_sun.max(0.0)
            + sky_factor * layer.skylight[i])
            * skyscape_wgsl::common::INV_PI
            / emissivity;
        let seen = fog * lit + (1.0 - fog) * layer.fog_colour[i];
        background[i] + opacity * (seen - background[i])
    })
}
