// The ground's cloud shadow map, per texel: the texel's ground point, the sun ray's span
// through the volume's box, the march's sample points and a span's optical depth.
// Twin: cloudlight::shadow_map (Rust, generic over the float type: the f32 instantiation
// mirrors these operations).
#import cloudlight::slice_propagation

// Ground point of texel (i, j): (x0 + (i + ½)·cell, y0 + (j + ½)·cell, ground_height).
fn shadow_texel_centre(texel: vec2<u32>, origin: vec2<f32>, cell_size: f32, ground_height: f32) -> vec3<f32> {
    return vec3<f32>(
        origin.x + (f32(texel.x) + 0.5) * cell_size,
        origin.y + (f32(texel.y) + 0.5) * cell_size,
        ground_height,
    );
}

// (t_enter, t_exit) of the ray p + t·l (t ≥ 0) through the box [lo, hi] (slab method);
// t_enter > t_exit when it misses.
fn shadow_box_span(p: vec3<f32>, l: vec3<f32>, lo: vec3<f32>, hi: vec3<f32>) -> vec2<f32> {
    var enter = 0.0;
    var exit = 3.40282347e+38;
    for (var a = 0; a < 3; a++) {
        if l[a] == 0.0 {
            if p[a] < lo[a] || p[a] > hi[a] {
                return vec2<f32>(1.0, 0.0);
            }
        } else {
            let t0 = (lo[a] - p[a]) / l[a];
            let t1 = (hi[a] - p[a]) / l[a];
            enter = max(enter, min(t0, t1));
            exit = min(exit, max(t0, t1));
        }
    }
    return vec2<f32>(enter, exit);
}

// Sample k of n midpoint steps over span = (t_enter, t_exit): p + (t_enter + (k + ½)·h)·l,
// h = (t_exit − t_enter)/n.
fn shadow_march_point(p: vec3<f32>, l: vec3<f32>, span: vec2<f32>, k: u32, n: u32) -> vec3<f32> {
    let h = (span.y - span.x) / f32(n);
    let t = span.x + (f32(k) + 0.5) * h;
    return vec3<f32>(p.x + t * l.x, p.y + t * l.y, p.z + t * l.z);
}

// Densities, sums and optical depths saturate at 1e30: exp(−τ) is 0 long before, and
// every product stays finite (a huge density never meets σ_t = 0 or h = 0 as 0·∞).
const SHADOW_SATURATION: f32 = 1e30;

// The march's running sum plus one sample's density (saturated).
fn shadow_accumulate(density_sum: f32, density: f32) -> f32 {
    return density_sum + min(density, SHADOW_SATURATION);
}

// A span's optical depth from its n midpoint densities' sum: min(σ_t, S)·min(Σρ·h, S),
// saturated at S.
fn shadow_span_optical_depth(density_sum: f32, span: vec2<f32>, n: u32, sigma_t: f32) -> f32 {
    let h = (span.y - span.x) / f32(n);
    let depth = min(density_sum * h, SHADOW_SATURATION);
    return min(min(sigma_t, SHADOW_SATURATION) * depth, SHADOW_SATURATION);
}

// The optical depth toward the light of a cloud spanning altitudes [base, top] above a
// point at altitude `height`, from the transmittance its shadow map holds where the
// point's light ray meets the map's plane (the cloud's base):
// −ln max(T, 1e-30) · f², f = clamp((top − h)/(top − base), 0, 1) (inside the cloud's
// altitudes an empirical fade).
fn shadow_depth_above(transmittance: f32, height: f32, base: f32, top: f32) -> f32 {
    let above = min(max((top - height) / (top - base), 0.0), 1.0);
    let depth = -log(max(transmittance, 1e-30));
    return depth * (above * above);
}

// Where `point` reads a shadow map whose plane lies at height `plane` (z up): carried
// along unit `to_light` to the plane, in texel-centre coordinates ((x − origin)/cell − ½:
// texel (i, j)'s centre is (i, j)).
fn shadow_map_texel(point: vec3<f32>, to_light: vec3<f32>, plane: f32, origin: vec2<f32>, cell_size: f32) -> vec2<f32> {
    let t = (plane - point.z) / to_light.z;
    let x = point.x + t * to_light.x;
    let y = point.y + t * to_light.y;
    return vec2<f32>((x - origin.x) / cell_size - 0.5, (y - origin.y) / cell_size - 0.5);
}

// The four texels a shadow map's bilinear lookup reads: flat indices (east fastest) of
// texels (i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1), i = ⌊x⌋, j = ⌊y⌋, −1 for one
// outside the map (its value 1: no cloud there); and (x − i, y − j).
struct ShadowMapTaps {
    index: vec4<i32>,
    fraction: vec2<f32>,
}

// The texels and fractions of a bilinear lookup between texel centres at texel-centre
// coordinates `texel` (shadow_map_texel) of a map of `resolution` texels. The caller
// reads each index's value from its binding (1 for −1), then shadow_map_bilinear.
fn shadow_map_taps(texel: vec2<f32>, resolution: vec2<u32>) -> ShadowMapTaps {
    let f = floor(texel);
    let i = i32(f.x);
    let j = i32(f.y);
    let size = vec2<i32>(resolution);
    var index = vec4<i32>(-1);
    let x = vec4<i32>(i, i + 1, i, i + 1);
    let y = vec4<i32>(j, j, j + 1, j + 1);
    for (var k = 0; k < 4; k++) {
        if x[k] >= 0 && y[k] >= 0 && x[k] < size.x && y[k] < size.y {
            index[k] = x[k] + size.x * y[k];
        }
    }
    return ShadowMapTaps(index, texel - f);
}

// The lookup's value from its four texels' values (in ShadowMapTaps.index's order, 1 for
// a texel outside the map) at `fraction`: cloudlight's bilinear.
fn shadow_map_bilinear(values: vec4<f32>, fraction: vec2<f32>) -> f32 {
    return bilinear(values.x, values.y, values.z, values.w, fraction.x, fraction.y);
}
