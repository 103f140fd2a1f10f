//! Parity case of `celestial::dome`: where a view ray meets SGSky's 12-sided dome
//! (`sky_dome_weights`: the sector by azimuth, the band by the rings' chords,
//! Möller–Trumbore over its triangles; the skirt's chord below it), compared through
//! the blend of vertex colours that differ in every channel (the slots alone jump at
//! shared edges, where the blend is continuous). The f32 twin and the f64 reference
//! are one generic function instantiated twice.

use super::*;

/// Vertex colours that differ from vertex to vertex in every channel (integers, exact
/// in f32), as the WGSL snippet builds them.
fn colours() -> [[f64; 3]; celestial::dome::DOME_VERTICES] {
    std::array::from_fn(|k| [(k % 7) as f64, ((k * 5) % 11) as f64, ((k * 3) % 13) as f64])
}

const WGSL: &str = "var colours: array<vec4<f32>, 49>; \
    for (var k = 0u; k < 49u; k++) { \
        colours[k] = vec4<f32>(f32(k % 7u), f32((k * 5u) % 11u), f32((k * 3u) % 13u), 1.0); \
    } \
    let hit = sky_dome_weights(vec3<f32>(x0, x1, x2), x3); \
    let c = hit.weights.x * colours[hit.slots.x].xyz + hit.weights.y * colours[hit.slots.y].xyz \
        + hit.weights.z * colours[hit.slots.z].xyz; \
    y0 = c.x; y1 = c.y; y2 = c.z;";

/// Directions over the sphere at four rotations, the vertices themselves, the sector
/// edges, the horizon and the skirt's lower edge, and straight down.
fn grid() -> Vec<Vec<f64>> {
    let n = 2600u32;
    let directions: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(n);
            let r = (1.0 - z * z).sqrt();
            let phi = f64::from(k) * 2.399_963_229_728_653;
            [r * phi.cos(), r * phi.sin(), z]
        })
        .collect();
    let mut grid = Vec::new();
    for spin in [0.0, 0.37, -2.1, std::f64::consts::FRAC_PI_2] {
        for d in &directions {
            grid.push(vec![d[0], d[1], d[2], spin]);
        }
        for ring in 0..5 {
            for index in 0..celestial::dome::DOME_SIDES {
                let v =
                    celestial::dome::dome_vertex(ring, index, celestial::Angle::from_radians(spin))
                        .normalize();
                grid.push(vec![v.x, v.y, v.z, spin]);
            }
        }
        for k in 0..48 {
            let phi = spin + f64::from(k) * std::f64::consts::TAU / 48.0;
            for elevation in [0.0f64, 0.3, -0.02, -0.0399, -0.04, -0.5] {
                let (s, c) = phi.sin_cos();
                let e = elevation.cos();
                grid.push(vec![e * s, -e * c, elevation.sin(), spin]);
            }
        }
        grid.push(vec![0.0, 0.0, -1.0, spin]);
        grid.push(vec![0.0, 0.0, 1.0, spin]);
    }
    grid
}

/// The case.
pub fn cases() -> Vec<Case> {
    vec![Case {
        name: "celestial::sky_dome_weights",
        imports: &["celestial::dome"],
        arity: (4, 3),
        wgsl: WGSL,
        grid,
        cpu: |x| {
            let c = colours().map(|c| c.map(|v| v as f32));
            celestial::dome::sky_dome_radiance([x[0], x[1], x[2]], x[3], &c).to_vec()
        },
        reference: |x| {
            celestial::dome::sky_dome_radiance([x[0], x[1], x[2]], x[3], &colours()).to_vec()
        },
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 4e-5,
            rel: 0.0,
            ulp: 0.0,
            bound: None,
            why: "a blend of colours ≤ 12 with weights from Möller–Trumbore in f32: vertex \
                  positions (≤ 80 km) and the spin's sin/cos to a few ULP, the weights to \
                  ~1e-6 (tens of ULP where rays graze the skirt's band); a ray that rounding \
                  puts in the neighbouring triangle at a shared edge gets the same blend \
                  (continuous): ≤ 3e-6 × 12",
        },
    }]
}
