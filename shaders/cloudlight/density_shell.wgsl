// A procedural cloud shell as the density field a march reads (the source bound to
// cloudlight::density_source): its parameters (ShellField) at binding 4 and, for a
// weather grid, the grid's (coverage, cloud type) per cell, x fastest, at binding 5 (a
// one-cell placeholder for procedural weather); the noise is evaluated per sample.
// Planet-centred metres. Twin: cloudlight::shell_shadow (Rust, generic over the float
// type: the f32 instantiation mirrors these operations, and is DensityField for
// CloudShell in f32 bit for bit).
#import cloudlight::ray_spans
#import cloudlight::shell

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

@group(0) @binding(4) var<uniform> shell_field: ShellField;
@group(0) @binding(5) var<storage, read> shell_weather_grid: array<vec2<f32>>;

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

fn field_density(p: vec3<f32>) -> f32 {
    return shell_field_density(shell_field, p);
}

fn field_extinction_per_density() -> f32 {
    return shell_field.extinction_per_density;
}

// The ray's spans inside the shell, stopping at the planet (shell_ray_spans).
fn field_ray_spans(origin: vec3<f32>, direction: vec3<f32>) -> RaySpans {
    return shell_ray_spans(origin, direction, shell_field.planet_radius, shell_field.inner_radius, shell_field.outer_radius);
}
