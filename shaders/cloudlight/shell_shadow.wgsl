// The ground's cloud shadow map of a procedural cloud shell: the shadow_map march with
// the shell's density (procedural weather or a user grid, evaluated noise) per sample.
// The grid's (coverage, cloud type) per cell, x fastest, is this module's binding 2
// (a pass importing it binds a one-cell placeholder for procedural weather).
// Twin: cloudlight::shell_shadow (Rust, generic over the float type: the f32
// instantiation mirrors these operations, and equals shadow_map::shadow_texel::<f32> on
// a CloudShell bit for bit).

#import cloudlight::shadow_map
#import cloudlight::shell
#import cloudlight::cone

// A shell (lengths in metres, planet-centred); weather_kind 0: the procedural weather's
// fields, 1: the grid's (grid_size cells of grid_cell_size metres).
struct ShellField {
    planet_radius: f32,
    inner_radius: f32,
    outer_radius: f32,
    shape_period: f32,
    detail_period: f32,
    erosion: f32,
    extinction_per_density: f32,
    weather_period: f32,
    coverage_mean: f32,
    coverage_contrast: f32,
    cloud_type_mean: f32,
    cloud_type_contrast: f32,
    seed: u32,
    weather_seed: u32,
    weather_cells: u32,
    weather_kind: u32,
    grid_size: vec2<u32>,
    grid_cell_size: f32,
}

@group(0) @binding(2) var<storage, read> shell_weather_grid: array<vec2<f32>>;

// The shell's (coverage, cloud type) at xy (metres): the procedural weather, or the
// grid's taps read from shell_weather_grid then weather_grid_bilinear.
fn shell_field_weather(field: ShellField, xy: vec2<f32>) -> vec2<f32> {
    if field.weather_kind == 1u {
        let taps = weather_grid_taps(field.grid_size, field.grid_cell_size, xy);
        var values: array<vec2<f32>, 4>;
        for (var k = 0; k < 4; k++) {
            values[k] = shell_weather_grid[taps.index[k]];
        }
        return weather_grid_bilinear(values, taps.fraction);
    }
    return procedural_weather(
        xy,
        field.weather_period,
        field.weather_cells,
        field.weather_seed,
        field.coverage_mean,
        field.coverage_contrast,
        field.cloud_type_mean,
        field.cloud_type_contrast,
    );
}

// The shell's density at planet-centred p: zero outside (inner, outer), else
// shell_density with the weather at (x, y) (shell_field_weather).
fn shell_field_density(field: ShellField, p: vec3<f32>) -> f32 {
    let inner = field.inner_radius;
    let outer = field.outer_radius;
    let r = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
    if !(r > inner && r < outer) {
        return 0.0;
    }
    let weather = shell_field_weather(field, p.xy);
    return shell_density(
        p,
        inner,
        outer,
        weather.x,
        weather.y,
        field.shape_period,
        field.detail_period,
        field.erosion,
        field.seed,
    );
}

// The marched transmittance toward the sun (unit to_sun) from ground (planet-centred)
// through the shell: steps midpoint samples on each of its spans, exp(−Σ τ).
fn shell_shadow_texel(field: ShellField, ground: vec3<f32>, to_sun: vec3<f32>, steps: u32) -> f32 {
    let spans = shell_ray_spans(ground, to_sun, field.planet_radius, field.inner_radius, field.outer_radius);
    let sigma_t = field.extinction_per_density;
    var tau = 0.0;
    for (var s = 0u; s < spans.count; s++) {
        let span = spans.spans[s];
        var sum = 0.0;
        for (var k = 0u; k < steps; k++) {
            let rho = shell_field_density(field, shadow_march_point(ground, to_sun, span, k, steps));
            sum = shadow_accumulate(sum, rho);
        }
        tau = min(tau + shadow_span_optical_depth(sum, span, steps, sigma_t), SHADOW_SATURATION);
    }
    return beer_lambert(tau);
}
