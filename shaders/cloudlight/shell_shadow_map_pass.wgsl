// The ground's cloud shadow map of a procedural cloud shell (procedural or grid weather,
// the grid's cells in shell_shadow.wgsl's binding 2) as a compute pass: one
// invocation per texel marches the sun ray through the shell (shell_shadow_texel) and
// writes exp(−τ) into a storage buffer, i fastest. Twin:
// cloudlight::shell_shadow::shell_shadow_map::<f32>.

#import cloudlight::shell_shadow

struct ShellShadowParams {
    // The grid's minimum corner (x, y), texel edge, ground height (planet-centred z), m.
    grid: vec4<f32>,
    // Unit direction toward the sun (xyz); w: σ_t per unit density (1/m).
    to_sun: vec4<f32>,
    // Planet radius, inner radius, outer radius, shape period (m).
    radii: vec4<f32>,
    // Detail period (m), erosion, weather period (m), coverage mean.
    shape: vec4<f32>,
    // Coverage contrast, cloud type mean, cloud type contrast; w: the grid's cell edge (m).
    weather: vec4<f32>,
    // Noise seed, weather seed, weather cells, midpoint steps per span.
    seeds: vec4<u32>,
    // Texels along x and y; zw unused.
    size: vec4<u32>,
    // Weather kind (0 procedural, 1 grid), the grid's cells along x and y; w unused.
    weather_grid: vec4<u32>,
}

@group(0) @binding(0) var<uniform> params: ShellShadowParams;
// One transmittance per texel, i fastest.
@group(0) @binding(1) var<storage, read_write> shadow_out: array<f32>;

@compute @workgroup_size(8, 8)
fn shell_shadow_map_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = params.size.xy;
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let field = ShellField(
        params.radii.x,
        params.radii.y,
        params.radii.z,
        params.radii.w,
        params.shape.x,
        params.shape.y,
        params.to_sun.w,
        params.shape.z,
        params.shape.w,
        params.weather.x,
        params.weather.y,
        params.weather.z,
        params.seeds.x,
        params.seeds.y,
        params.seeds.z,
        params.weather_grid.x,
        params.weather_grid.yz,
        params.weather.w,
    );
    let p = shadow_texel_centre(gid.xy, params.grid.xy, params.grid.z, params.grid.w);
    shadow_out[gid.x + size.x * gid.y] = shell_shadow_texel(field, p, params.to_sun.xyz, params.seeds.w);
}
