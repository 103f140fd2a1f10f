//! Parity cases of `render::terrain_materials`: the detail noise and the procedural
//! materials' weights and albedo. The reference is each generic formula's `f64`
//! instance on the f32-rounded inputs and the f32-rounded parameters.

use render::terrain_materials::{
    MaterialParams, detail_noise, material_weights, procedural_albedo,
};

use super::*;

/// The parameters of the material cases, as WGSL writes them below (each decimal
/// rounds to the same f32 in both languages).
fn params() -> MaterialParams<f32> {
    MaterialParams {
        rock_albedo: [0.21, 0.2, 0.18],
        snow_line: 2850.0,
        grass_albedo: [0.06, 0.1, 0.04],
        snow_line_aspect: 400.0,
        snow_albedo: [0.88, 0.91, 0.93],
        grass_line: 2500.0,
        transition: 150.0,
        cos_rock_gentle: 0.866_025_4,
        cos_rock_steep: 0.766_044_4,
        cos_snow_gentle: std::f32::consts::FRAC_1_SQRT_2,
        cos_snow_steep: 0.573_576_4,
        line_noise: 60.0,
        albedo_noise: 0.25,
        seed: 0,
        pole_north: 1.0,
    }
}

/// Unit normals (east, north, up) at slopes 0–80° and eight aspects, elevations across
/// the grass and snow lines, and details from −1 to 1.
fn material_grid() -> Vec<Vec<f64>> {
    let mut grid = Vec::new();
    for slope_step in 0..17 {
        let slope = (5.0 * f64::from(slope_step)).to_radians();
        for aspect_step in 0..8 {
            let aspect = (45.0 * f64::from(aspect_step)).to_radians();
            let normal = [
                slope.sin() * aspect.sin(),
                slope.sin() * aspect.cos(),
                slope.cos(),
            ];
            for elevation in linspace(2000.0, 3400.0, 41) {
                for detail in [-1.0, -0.3, 0.0, 0.5, 1.0] {
                    grid.push(vec![normal[0], normal[1], normal[2], elevation, detail]);
                }
            }
        }
    }
    grid
}

fn normal_of(x: &[f32]) -> [f32; 3] {
    [x[0], x[1], x[2]]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "render::detail_noise",
            imports: &["render::terrain_materials"],
            arity: (3, 1),
            wgsl: "y0 = detail_noise(x0, x1, x2, 7u);",
            grid: || {
                // Map positions over a 10 km map (fractions of every octave's lattice),
                // footprints from 5 cm (every octave) to 100 m (none), through each
                // octave's fade.
                let mut grid = Vec::new();
                for (i, east) in linspace(0.0, 10_000.0, 97).enumerate() {
                    for footprint in logspace(0.05, 100.0, 110) {
                        grid.push(vec![
                            east + 0.37 * i as f64,
                            7_000.0 - 0.61 * east,
                            footprint,
                        ]);
                    }
                }
                grid.extend([vec![0.0, 0.0, 0.05], vec![12_345.678, 0.001, 1e-3]]);
                grid
            },
            cpu: |x| vec![detail_noise(x[0], x[1], x[2], 7)],
            reference: |x| vec![detail_noise::<f64>(x[0], x[1], x[2], 7)],
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 64.0 * U,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "the lattice (power-of-two frequencies, floor, hash) is exact in both \
                      precisions; per octave the smoothstep and three lerps of values ≤ 1 \
                      round ~8u, the fade's WGSL division (2.5 ULP) and product ~4u near its \
                      edge; ten octaves of halving weight over a sum of 2: about 32u absolute",
            },
        },
        Case {
            name: "render::material_weights",
            imports: &["render::terrain_materials"],
            arity: (5, 3),
            wgsl: "let p = MaterialParams(vec3<f32>(0.21, 0.2, 0.18), 2850.0, \
                   vec3<f32>(0.06, 0.1, 0.04), 400.0, vec3<f32>(0.88, 0.91, 0.93), 2500.0, 150.0, \
                   0.8660254, 0.7660444, 0.70710677, 0.5735764, 60.0, 0.25, 0u, 1.0, 0.0, 0.0, 0.0); \
                   let w = material_weights(vec3<f32>(x0, x1, x2), x3, x4, p); \
                   y0 = w.x; y1 = w.y; y2 = w.z;",
            grid: material_grid,
            cpu: |x| material_weights(normal_of(x), x[3], x[4], &params()).to_vec(),
            reference: |x| {
                material_weights([x[0], x[1], x[2]], x[3], x[4], &params().cast::<f64>()).to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: material_tolerance(),
        },
        Case {
            name: "render::procedural_albedo",
            imports: &["render::terrain_materials"],
            arity: (5, 3),
            wgsl: "let p = MaterialParams(vec3<f32>(0.21, 0.2, 0.18), 2850.0, \
                   vec3<f32>(0.06, 0.1, 0.04), 400.0, vec3<f32>(0.88, 0.91, 0.93), 2500.0, 150.0, \
                   0.8660254, 0.7660444, 0.70710677, 0.5735764, 60.0, 0.25, 0u, 1.0, 0.0, 0.0, 0.0); \
                   let a = procedural_albedo(vec3<f32>(x0, x1, x2), x3, x4, vec3<f32>(0.3, 0.5, 0.1), p); \
                   y0 = a.x; y1 = a.y; y2 = a.z;",
            grid: material_grid,
            cpu: |x| {
                procedural_albedo(normal_of(x), x[3], x[4], [0.3, 0.5, 0.1], &params()).to_vec()
            },
            reference: |x| {
                let ground = [0.3f32, 0.5, 0.1].map(f64::from);
                procedural_albedo(
                    [x[0], x[1], x[2]],
                    x[3],
                    x[4],
                    ground,
                    &params().cast::<f64>(),
                )
                .to_vec()
            },
            audit: Audit::INDEPENDENT,
            tolerance: material_tolerance(),
        },
    ]
}

/// The weights' and the albedo's tolerance.
fn material_tolerance() -> Tolerance {
    Tolerance {
        abs: 256.0 * U,
        rel: 0.0,
        ulp: 0.0,
        bound: None,
        why: "elevation + detail·noise and the snow line round at ~3000 m (2u each), \
              divided by the 150 m transition: ~80u on the smoothstep's argument, whose \
              slope is ≤ 1.5; the slope terms divide a rounded cosine difference by \
              ≥ 0.1 (~20u); products of weights ≤ 1 and albedos ≤ 1 add a few u",
    }
}
