// Another cloud's shadow on a march (bindings 8 and 9 of the march passes'
// group 0): its shadow map toward the march's light, read where a view sample's light
// ray meets the map's plane, as the optical depth above the sample added to the light
// march's. Twin: cloudlight::shadow_map::OutsideShadowMap::outside_depth (the uniform's
// fields and the values its own); cloudlight::gpu::OutsideShadow fills the uniform.
#import cloudlight::shadow_map

struct OutsideShadowParams {
    // Texel (0, 0)'s corner east, north (m); z: texel edge (m); w: the plane's altitude (m).
    grid: vec4<f32>,
    // Unit direction toward the map's light (xyz, east/north/up); w: 1 with a map, 0 none.
    to_light: vec4<f32>,
    // The casting cloud's base and top altitude (m); z: the march frame's height of
    // altitude 0 (0 about the ground, the planet's radius planet-centred); w unused.
    extent: vec4<f32>,
    // Texels east, north; zw unused.
    size: vec4<u32>,
}

@group(0) @binding(8) var<uniform> outside_shadow: OutsideShadowParams;
// The map's transmittances, east fastest (a placeholder when to_light.w is 0).
@group(0) @binding(9) var<storage, read> outside_shadow_values: array<f32>;

// The map's value at flat index `index` (shadow_map_taps), 1 for −1 (outside it).
fn outside_shadow_value(index: i32) -> f32 {
    if index < 0 {
        return 1.0;
    }
    return outside_shadow_values[u32(index)];
}

// The casting cloud's optical depth toward the light above the march's sample `p` (the
// march's frame), 0 without a map.
fn outside_depth(p: vec3<f32>) -> f32 {
    if outside_shadow.to_light.w == 0.0 {
        return 0.0;
    }
    let point = vec3<f32>(p.x, p.y, p.z - outside_shadow.extent.z);
    let grid = outside_shadow.grid;
    let texel = shadow_map_texel(point, outside_shadow.to_light.xyz, grid.w, grid.xy, grid.z);
    let taps = shadow_map_taps(texel, outside_shadow.size.xy);
    let value = shadow_map_bilinear(vec4<f32>(outside_shadow_value(taps.index.x), outside_shadow_value(taps.index.y), outside_shadow_value(taps.index.z), outside_shadow_value(taps.index.w)), taps.fraction);
    return shadow_depth_above(value, point.z, outside_shadow.extent.x, outside_shadow.extent.y);
}
