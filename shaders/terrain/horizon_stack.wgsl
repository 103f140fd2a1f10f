// terrain::horizon_stack — lookups in a horizon stack texture (terrain::horizon_texture's
// GpuHorizonStack): the horizon angle anywhere on the map for any azimuth, and the
// self-shadow of the sun's disc. Twin: terrain::horizon_stack (Rust): same names,
// argument order and units; the texture and its parameters are arguments, so a
// caller declares them at the group and bindings it chooses. Positions in texels
// (texel (x, y) at (x, y), x east, rows south), angles in radians, azimuths clockwise
// from north, directions east-north-up towards the sun.
#import terrain::shadow

struct HorizonStackParams {
    width: u32,
    height: u32,
    // Azimuth layers N (layer k at k * TAU / N).
    count: u32,
    // 0: u8 (R8Unorm), 1: u16 as two bytes (Rg8Unorm, high then low), 2: f32 (R32Float).
    encoding: u32,
}

// The horizon angle of texel `texel` of layer `layer`, decoded from its encoding.
fn horizon_stack_angle(stack: texture_2d_array<f32>, params: HorizonStackParams, texel: vec2<u32>, layer: u32) -> f32 {
    let value = textureLoad(stack, texel, layer, 0);
    if params.encoding == 0u {
        return decode_horizon_angle(value.r);
    }
    if params.encoding == 1u {
        return decode_horizon_angle((round(value.r * 255.0) * 256.0 + round(value.g * 255.0)) / 65535.0);
    }
    return value.r;
}

// The horizon angle at `position` (texels, clamped to the map) for `sun_azimuth`:
// bilinear between the four texels around the position in the two layers around the
// azimuth, linear between the layers.
fn sample_horizon(stack: texture_2d_array<f32>, params: HorizonStackParams, position: vec2<f32>, sun_azimuth: f32) -> f32 {
    let x = clamp(position.x, 0.0, f32(params.width - 1u));
    let y = clamp(position.y, 0.0, f32(params.height - 1u));
    let x0f = floor(x);
    let y0f = floor(y);
    let fx = x - x0f;
    let fy = y - y0f;
    let x0 = u32(x0f);
    let y0 = u32(y0f);
    let x1 = min(x0 + 1u, params.width - 1u);
    let y1 = min(y0 + 1u, params.height - 1u);
    let layers = azimuth_layers(sun_azimuth, params.count);
    var angles: array<f32, 2>;
    let which = array<u32, 2>(layers.lower, layers.upper);
    for (var i = 0u; i < 2u; i++) {
        let a = horizon_stack_angle(stack, params, vec2<u32>(x0, y0), which[i]);
        let b = horizon_stack_angle(stack, params, vec2<u32>(x1, y0), which[i]);
        let c = horizon_stack_angle(stack, params, vec2<u32>(x0, y1), which[i]);
        let d = horizon_stack_angle(stack, params, vec2<u32>(x1, y1), which[i]);
        let top = a + (b - a) * fx;
        let bottom = c + (d - c) * fx;
        angles[i] = top + (bottom - top) * fy;
    }
    return angles[0] + (angles[1] - angles[0]) * layers.weight;
}

// The visible fraction of the sun's disc (angular radius sun_angular_radius; <= 0: the
// hard shadow) above the horizon at `position`, the sun along `sun_direction`.
fn self_shadow(stack: texture_2d_array<f32>, params: HorizonStackParams, position: vec2<f32>, sun_direction: vec3<f32>, sun_angular_radius: f32) -> f32 {
    let horizon = sample_horizon(stack, params, position, sun_azimuth(sun_direction));
    return soft_shadow(sun_elevation(sun_direction), horizon, sun_angular_radius);
}
