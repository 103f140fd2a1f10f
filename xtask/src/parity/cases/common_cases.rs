//! Parity cases of `skyscape-wgsl` common modules: the shared hash and the frame
//! rotation between a world (x east, y up, z south) and east-north-up.

use super::*;

/// Vectors over every sign and a wide range of magnitudes, zeros included.
fn vectors() -> Vec<Vec<f64>> {
    let values: Vec<f64> = [
        -1e30, -3.5e5, -12.5, -1.0, -1e-20, 0.0, 1e-38, 3e-7, 0.5, 2.0, 6.36e6,
    ]
    .into_iter()
    .chain(linspace(-1.0, 1.0, 11))
    .collect();
    let mut v = Vec::new();
    for &x in &values {
        for &y in &values {
            for &z in &values {
                v.push(vec![x, y, z]);
            }
        }
    }
    v
}

/// The frames' cases: a permutation and a sign, exact on every side.
fn frame_cases() -> Vec<Case> {
    let exact = Tolerance {
        abs: 0.0,
        rel: 0.0,
        ulp: 0.0,
        bound: None,
        why: "a permutation and a sign change: exact on every side; the reference names the \
              axes (east, north, up from east, up, south) instead of copying the swizzle",
    };
    vec![
        Case {
            name: "common::world_to_enu",
            imports: &["common::frames"],
            arity: (3, 3),
            wgsl: "let v = world_to_enu(vec3<f32>(x0, x1, x2)); y0 = v.x; y1 = v.y; y2 = v.z;",
            grid: vectors,
            cpu: |x| skyscape_wgsl::common::world_to_enu([x[0], x[1], x[2]]).to_vec(),
            reference: |x| {
                let (east, up, south) = (x[0], x[1], x[2]);
                vec![east, -south, up]
            },
            audit: Audit::INDEPENDENT,
            tolerance: exact,
        },
        Case {
            name: "common::enu_to_world",
            imports: &["common::frames"],
            arity: (3, 3),
            wgsl: "let v = enu_to_world(vec3<f32>(x0, x1, x2)); y0 = v.x; y1 = v.y; y2 = v.z;",
            grid: vectors,
            cpu: |x| skyscape_wgsl::common::enu_to_world([x[0], x[1], x[2]]).to_vec(),
            reference: |x| {
                let (east, north, up) = (x[0], x[1], x[2]);
                vec![east, up, -north]
            },
            audit: Audit::INDEPENDENT,
            tolerance: exact,
        },
    ]
}

/// The cases, in report order.
pub fn cases() -> Vec<Case> {
    let mut cases = vec![Case {
        name: "common::hash_u32",
        imports: &["common::hash"],
        arity: (2, 2),
        wgsl: "let h = hash_u32(u32(x0) | (u32(x1) << 16u)); y0 = f32(h >> 8u); y1 = f32(h & 0xffu);",
        grid: || {
            let mut v = Vec::new();
            for hi in (0..65_536u32).step_by(4099) {
                for lo in (0..65_536u32).step_by(97) {
                    v.push(vec![f64::from(lo), f64::from(hi)]);
                }
            }
            v.push(vec![65_535.0, 65_535.0]);
            v
        },
        cpu: |x| {
            let h = skyscape_wgsl::common::hash_u32(x[0] as u32 | ((x[1] as u32) << 16));
            vec![(h >> 8) as f32, (h & 0xff) as f32]
        },
        reference: |x| {
            let h = super::integer_references::lowbias32(x[0] as u32 | ((x[1] as u32) << 16));
            vec![f64::from(h >> 8), f64::from(h & 0xff)]
        },
        audit: Audit::INDEPENDENT,
        tolerance: Tolerance {
            abs: 0.0,
            rel: 0.0,
            ulp: 0.0,
            bound: None,
            why: "integer arithmetic wraps identically in WGSL and Rust: bit-exact against the \
                  published lowbias32 written a second time (u64 reduced modulo 2^32 by hand)",
        },
    }];
    cases.extend(frame_cases());
    cases
}
