// The terrain's procedural materials: rock, grass and snow weighted by slope, altitude
// and aspect, with a value-noise detail band-limited by the pixel's footprint on the
// ground; and the bilinear lookup of a colour texture. Twin: render::terrain_materials
// (Rust, generic over the float type), same names, argument order and units.
#import common::hash

// The materials' parameters. Rust: MaterialParams (f32: MaterialsUniform).
struct MaterialParams {
    // Linear RGB albedos.
    rock_albedo: vec3<f32>,
    // Elevation of the snow line on flat ground (m).
    snow_line: f32,
    grass_albedo: vec3<f32>,
    // How much lower the snow line lies per unit of the normal's horizontal component
    // toward the pole (m): shaded slopes keep snow lower down.
    snow_line_aspect: f32,
    snow_albedo: vec3<f32>,
    // Elevation above which grass gives way to rock and scree (m).
    grass_line: f32,
    // Width of the altitude transitions (m).
    transition: f32,
    // cos of the slopes where rock starts and is complete (up components of the normal).
    cos_rock_gentle: f32,
    cos_rock_steep: f32,
    // cos of the slopes where snow starts to slide off and is gone.
    cos_snow_gentle: f32,
    cos_snow_steep: f32,
    // Metres by which the detail noise moves the altitude lines.
    line_noise: f32,
    // Relative albedo variation of the detail noise.
    albedo_noise: f32,
    // The noise's seed.
    seed: u32,
    // +1: the pole is north (northern hemisphere), −1: south.
    pole_north: f32,
    padding0: f32,
    padding1: f32,
    padding2: f32,
}

// Octaves of the detail noise: wavelengths 256 m halving down to 0.5 m (powers of two,
// so the lattice coordinates east × frequency are exact in any precision).
const DETAIL_OCTAVES: u32 = 10u;
const DETAIL_LONGEST_WAVELENGTH: f32 = 256.0;
const DETAIL_LOWEST_FREQUENCY: f32 = 0.00390625;

// t²(3 − 2t) of t clamped to [0, 1].
fn smooth_unit(t: f32) -> f32 {
    let c = clamp(t, 0.0, 1.0);
    return c * c * (3.0 - 2.0 * c);
}

// A lattice value in [−1, 1) at integer point (ix, iy).
fn lattice_value(ix: i32, iy: i32, seed: u32) -> f32 {
    let h = hash_combine(hash_combine(hash_u32(seed), bitcast<u32>(ix)), bitcast<u32>(iy));
    return 2.0 * unit_float_from_bits(h) - 1.0;
}

// Value noise of unit lattice spacing at (x, y), smoothly interpolated, in [−1, 1].
fn value_noise(x: f32, y: f32, seed: u32) -> f32 {
    let fx = floor(x);
    let fy = floor(y);
    let ix = i32(fx);
    let iy = i32(fy);
    let sx = smooth_unit(x - fx);
    let sy = smooth_unit(y - fy);
    let a = lattice_value(ix, iy, seed);
    let b = lattice_value(ix + 1, iy, seed);
    let c = lattice_value(ix, iy + 1, seed);
    let d = lattice_value(ix + 1, iy + 1, seed);
    let bottom = a + (b - a) * sx;
    let top = c + (d - c) * sx;
    return bottom + (top - bottom) * sy;
}

// Detail noise at map position (east, south) in metres, in [−1, 1]: octaves of value
// noise of halving wavelength and amplitude, each faded out as its wavelength drops from
// eight to four footprints (m): twice the Nyquist limit of two footprints, as a pixel's
// footprint is no ideal low-pass filter; the faded detail is left at its mean (0)
// instead of aliasing.
fn detail_noise(east: f32, south: f32, footprint: f32, seed: u32) -> f32 {
    let inverse_quadruple_footprint = 1.0 / (4.0 * footprint);
    var sum = 0.0;
    var norm = 0.0;
    var wavelength = DETAIL_LONGEST_WAVELENGTH;
    var frequency = DETAIL_LOWEST_FREQUENCY;
    var amplitude = 1.0;
    for (var k = 0u; k < DETAIL_OCTAVES; k++) {
        let fade = clamp(wavelength * inverse_quadruple_footprint - 1.0, 0.0, 1.0);
        if fade > 0.0 {
            sum += amplitude * fade * value_noise(east * frequency, south * frequency, seed + k);
        }
        norm += amplitude;
        wavelength *= 0.5;
        frequency *= 2.0;
        amplitude *= 0.5;
    }
    return sum / norm;
}

// Weights (rock, grass, snow), summing to 1, of a surface with unit normal `normal`
// (east, north, up) at `elevation` (m), its altitude lines moved by `detail` × the
// line noise.
fn material_weights(normal: vec3<f32>, elevation: f32, detail: f32, params: MaterialParams) -> vec3<f32> {
    let perturbed = elevation + detail * params.line_noise;
    let poleward = params.pole_north * normal.y;
    let snow_line = params.snow_line - params.snow_line_aspect * poleward;
    let inverse_transition = 1.0 / params.transition;
    let snow_by_altitude = smooth_unit((perturbed - snow_line) * inverse_transition + 0.5);
    let snow_slides = smooth_unit((params.cos_snow_gentle - normal.z) / (params.cos_snow_gentle - params.cos_snow_steep));
    let snow = snow_by_altitude * (1.0 - snow_slides);
    let rock_by_slope = smooth_unit((params.cos_rock_gentle - normal.z) / (params.cos_rock_gentle - params.cos_rock_steep));
    let rock_by_altitude = smooth_unit((perturbed - params.grass_line) * inverse_transition + 0.5);
    let rock = 1.0 - (1.0 - rock_by_slope) * (1.0 - rock_by_altitude);
    return vec3<f32>((1.0 - snow) * rock, (1.0 - snow) * (1.0 - rock), snow);
}

// Albedo of the procedural materials: the weights' mix of rock, `ground_albedo` (the
// grass's, or a colour texture's) and snow, its brightness varied by the detail.
fn procedural_albedo(normal: vec3<f32>, elevation: f32, detail: f32, ground_albedo: vec3<f32>, params: MaterialParams) -> vec3<f32> {
    let w = material_weights(normal, elevation, detail, params);
    let mixed = params.rock_albedo * w.x + ground_albedo * w.y + params.snow_albedo * w.z;
    return min(mixed * (1.0 + params.albedo_noise * detail), vec3<f32>(1.0));
}

// The pixel's footprint on the ground (m) at distance `distance` (m) for a pixel of
// `pixel_angle` (rad), seen at cosine `cos_incidence` from the normal: stretched by
// 1/cos, at most tenfold.
fn pixel_footprint(distance: f32, pixel_angle: f32, cos_incidence: f32) -> f32 {
    return distance * pixel_angle / max(abs(cos_incidence), 0.1);
}

// Bilinear weights of a colour texel position `texel` (texels from texel (0, 0)'s
// centre) in a `size` texture (at least 2×2): the four flat indices (x fastest) and
// their weights, clamped to the texture.
struct ColourTaps {
    index: vec4<u32>,
    weight: vec4<f32>,
}

fn colour_taps(texel: vec2<f32>, size: vec2<u32>) -> ColourTaps {
    let limit = vec2<f32>(size - vec2<u32>(1u));
    let t = clamp(texel, vec2<f32>(0.0), limit);
    let i = min(u32(floor(t.x)), size.x - 2u);
    let j = min(u32(floor(t.y)), size.y - 2u);
    let fx = t.x - f32(i);
    let fy = t.y - f32(j);
    return ColourTaps(
        vec4<u32>(j * size.x + i, j * size.x + i + 1u, (j + 1u) * size.x + i, (j + 1u) * size.x + i + 1u),
        vec4<f32>((1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy),
    );
}
