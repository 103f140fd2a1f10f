// celestial::draw — the sun's limb-darkened disc and aureole, the moon's lit disc,
// stars and planets as point sprites, seen through the atmosphere's transmittance.
// Twin: crates/celestial/src/draw.rs (Rust; the generic functions' f32 instances mirror
// this file operation for operation): same names, argument order and units. Radiance in
// the unit of atmos' sun_irradiance per sr; directions are unit vectors away from the
// viewer.

#import atmos::geometry
#import atmos::phase
#import atmos::frame

// (α + 2)/2 · μ^α with μ = √(1 − (sin θ / sin ρ)²): the sun's radiance relative to its
// disc mean (Hestroffer & Magnan 1998 power law); 0 outside the disc.
fn sun_disc_limb_factor(sin_offset: f32, cos_offset: f32, sin_radius: f32, exponent: f32) -> f32 {
    if cos_offset <= 0.0 || sin_offset >= sin_radius {
        return 0.0;
    }
    let ratio = sin_offset / sin_radius;
    let mu = sqrt((1.0 - ratio) * (1.0 + ratio));
    if mu <= 0.0 {
        return 0.0;
    }
    return (exponent + 2.0) / 2.0 * exp(exponent * log(mu));
}

// Single-scattered Mie radiance near the sun: E · T · τ_M · p_CS(cos θ, g).
fn sun_aureole_radiance(cos_offset: f32, mie_g: f32, irradiance: f32, transmittance: f32, mie_optical_depth: f32) -> f32 {
    return irradiance * transmittance * mie_optical_depth * cornette_shanks_phase(cos_offset, mie_g);
}

// Lommel–Seeliger factor μ0/(μ0 + μ) of the moon's sphere where `view` meets it; 0 off
// the disc and on the night side.
fn moon_disc_lommel_seeliger(view: vec3<f32>, moon: vec3<f32>, sin_radius: f32, to_sun: vec3<f32>) -> f32 {
    let along = view.x * moon.x + view.y * moon.y + view.z * moon.z;
    if along <= 0.0 {
        return 0.0;
    }
    let offset = vec3<f32>(
        (view.x - moon.x * along) / sin_radius,
        (view.y - moon.y * along) / sin_radius,
        (view.z - moon.z * along) / sin_radius,
    );
    let rho2 = offset.x * offset.x + offset.y * offset.y + offset.z * offset.z;
    if rho2 >= 1.0 {
        return 0.0;
    }
    let emergence = sqrt(1.0 - rho2);
    let normal = vec3<f32>(
        offset.x - moon.x * emergence,
        offset.y - moon.y * emergence,
        offset.z - moon.z * emergence,
    );
    let incidence = normal.x * to_sun.x + normal.y * to_sun.y + normal.z * to_sun.z;
    if incidence <= 0.0 {
        return 0.0;
    }
    return incidence / (incidence + emergence);
}

// Naked-eye detection threshold (lux) of a point source against a background of
// `background_luminance` cd/m² (Hecht's fits after Schaefer 1990): the smaller of the
// rod and cone branches c1 (1 + √(c2 B))², B in nL, result in foot-candles.
fn star_detection_threshold(background_luminance: f32) -> f32 {
    let nanolamberts = max(background_luminance, 0.0) * 314159.2653589793;
    let rod_root = 1.0 + sqrt(0.012589254117941675 * nanolamberts);
    let rods = 1.584893192461111e-10 * (rod_root * rod_root);
    let cone_root = 1.0 + sqrt(1.2589254117941661e-06 * nanolamberts);
    let cones = 4.466835921509635e-09 * (cone_root * cone_root);
    return min(rods, cones) * 10.763910416709722;
}

// The part of a point source's illuminance above the detection threshold.
fn star_visible_illuminance(illuminance: f32, threshold: f32) -> f32 {
    return max(illuminance - threshold, 0.0);
}

// Per-channel irradiance (atmos units) a point source delivers: illuminance ×
// scintillation through the transmittance, minus the threshold against its background.
fn point_source_irradiance(illuminance_lux: f32, colour: vec3<f32>, transmittance: vec3<f32>, background_luminance: f32, scintillation: f32, lux_per_unit: f32) -> vec3<f32> {
    let seen_colour = vec3<f32>(colour.x * transmittance.x, colour.y * transmittance.y, colour.z * transmittance.z);
    let luminance_transmittance = 0.2126 * seen_colour.x + 0.7152 * seen_colour.y + 0.0722 * seen_colour.z;
    if luminance_transmittance <= 0.0 {
        return vec3<f32>(0.0);
    }
    let seen = illuminance_lux * scintillation * luminance_transmittance;
    let visible = star_visible_illuminance(seen, star_detection_threshold(background_luminance));
    let scale = visible / (lux_per_unit * luminance_transmittance);
    return seen_colour * scale;
}

// Gaussian point-sprite weight per pixel at squared offset r² (pixels²).
fn point_sprite_weight(offset_squared: f32, sigma: f32) -> f32 {
    let variance = sigma * sigma;
    return exp(-offset_squared / (2.0 * variance)) / (6.283185307179586 * variance);
}

// Sprites are cut at this many σ.
const SPRITE_CUTOFF_SIGMAS: f32 = 4.0;

// Solid angle (sr) of the pixel a view at cos θ from the forward axis passes through.
fn pixel_solid_angle(tan_half_fov_y: f32, height: u32, cos_forward: f32) -> f32 {
    let side = 2.0 * tan_half_fov_y / f32(height);
    return side * side * cos_forward * cos_forward * cos_forward;
}

// (x, y) pixel coordinates of a direction (pixel centres at i + 0.5) and its cosine to
// the forward axis (≤ 0: behind the camera).
fn project_direction(direction: vec3<f32>, camera: FrameCamera) -> vec3<f32> {
    let x = direction.x * camera.right.x + direction.y * camera.right.y + direction.z * camera.right.z;
    let y = direction.x * camera.up.x + direction.y * camera.up.y + direction.z * camera.up.z;
    let z = direction.x * camera.forward.x + direction.y * camera.forward.y + direction.z * camera.forward.z;
    let aspect = f32(camera.width) / f32(camera.height);
    let ndc_x = x / (z * camera.tan_half_fov_y * aspect);
    let ndc_y = y / (z * camera.tan_half_fov_y);
    return vec3<f32>((ndc_x + 1.0) * 0.5 * f32(camera.width), (1.0 - ndc_y) * 0.5 * f32(camera.height), z);
}

const DISC_NONE: u32 = 0u;
const DISC_SUN: u32 = 1u;
const DISC_MOON: u32 = 2u;

// The sun or the moon; twin of celestial::draw::DiscObject.
struct DiscObject {
    direction: vec3<f32>,
    sin_radius: f32,
    radiance: vec3<f32>,
    kind: u32,
    // Sun: limb-darkening exponents; moon: unit direction from the moon to the sun.
    shading: vec3<f32>,
    mu_centre: f32,
    log_transmittance: vec3<f32>,
    padding0: f32,
    log_transmittance_slope: vec3<f32>,
    padding1: f32,
    log_transmittance_curvature: vec3<f32>,
    padding2: f32,
}

// Radiance a view ray receives from a disc, through the transmittance fitted across the
// disc in the view's zenith cosine; 0 where the view ray hits the ground.
fn disc_object_radiance(view: vec3<f32>, object: DiscObject, zenith: vec3<f32>, r: f32, planet_radius: f32) -> vec3<f32> {
    if object.kind == DISC_NONE {
        return vec3<f32>(0.0);
    }
    let mu = view.x * zenith.x + view.y * zenith.y + view.z * zenith.z;
    let ground = ray_sphere_intersect(r, mu, planet_radius);
    if mu < 0.0 && ground.x >= 0.0 {
        return vec3<f32>(0.0);
    }
    let d = object.direction;
    let cross = vec3<f32>(
        view.y * d.z - view.z * d.y,
        view.z * d.x - view.x * d.z,
        view.x * d.y - view.y * d.x,
    );
    let sin_offset = sqrt(cross.x * cross.x + cross.y * cross.y + cross.z * cross.z);
    let cos_offset = view.x * d.x + view.y * d.y + view.z * d.z;
    var shape: vec3<f32>;
    if object.kind == DISC_SUN {
        shape = vec3<f32>(
            sun_disc_limb_factor(sin_offset, cos_offset, object.sin_radius, object.shading.x),
            sun_disc_limb_factor(sin_offset, cos_offset, object.sin_radius, object.shading.y),
            sun_disc_limb_factor(sin_offset, cos_offset, object.sin_radius, object.shading.z),
        );
    } else {
        shape = vec3<f32>(moon_disc_lommel_seeliger(view, d, object.sin_radius, object.shading));
    }
    let dmu = mu - object.mu_centre;
    var result: vec3<f32>;
    for (var i = 0; i < 3; i++) {
        let log_t = object.log_transmittance[i]
            + dmu * (object.log_transmittance_slope[i] + dmu * object.log_transmittance_curvature[i]);
        result[i] = object.radiance[i] * shape[i] * exp(min(log_t, 0.0));
    }
    return result;
}

// A star or planet; twin of celestial::draw::PointSource.
struct PointSource {
    direction: vec3<f32>,
    illuminance_lux: f32,
    colour: vec3<f32>,
    background_luminance: f32,
    transmittance: vec3<f32>,
    scintillation: f32,
}
