//! Parity passes of `cloudlight`'s cloud shadow map: the whole map of a lumpy 40×32×20
//! volume on a 128×96 ground grid, at a high and a low sun. Reference: the generic march
//! at f64 (`shadow_map::<f64>`); cpu: the same march at f32 (the WGSL's twin); gpu:
//! `cloudlight::gpu::ShadowMapPass` (an R32Float texture read back).

use super::*;
use cloudlight::shadow_map::{ShadowGrid, ShadowMapPlan, shadow_box_span, shadow_map};

const U: f64 = super::super::compare::UNIT_ROUNDOFF;

/// Sun elevations and azimuths (degrees) and march steps of the cases, in order.
const SETTINGS: [(f64, f64, u32); 2] = [(53.0, 30.0, 64), (8.0, 200.0, 64)];

/// The pass cases of this file, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "cloudlight::shadow_map_pass (sun 53°, 64 steps, 128x96 over 40x32x20)",
            cpu: || shadow_cpu(0),
            gpu: |gpu| shadow_gpu(gpu, 0),
            audit: Audit::INDEPENDENT,
            tolerance: TOLERANCE,
        },
        PassCase {
            name: "cloudlight::shadow_map_pass (sun 8°, 64 steps, 128x96 over 40x32x20)",
            cpu: || shadow_cpu(1),
            gpu: |gpu| shadow_gpu(gpu, 1),
            audit: Audit::INDEPENDENT,
            tolerance: TOLERANCE,
        },
    ]
}

const TOLERANCE: Tolerance = Tolerance {
    abs: 0.0,
    rel: 0.0,
    ulp: 0.0,
    bound: None,
    why: "per texel, the march's forward error (pass bounds are per output, so the \
          tightness audit does not see them: the f32 twin's worst texel uses 1/420 of its \
          bound at sun 53° and 1/940 at 8°, the GPU's errors on lavapipe are as large, \
          max 1.3e-6 and 3.0e-6): each sample point carries \
          12u(|p| + |t|) per component, moving the trilinear density by ≤ √3·G·|δq| (G: \
          the largest neighbouring-cell difference per metre) plus 16u·ρ_max for the f32 \
          lookup (the GPU's; the CPU's is f64 rounded once); n samples summed (+ n·u·Σρ); \
          h from the span's ends (16u·max|t|/n + 5u·h); σ_t·Σρ·h (3u·τ); exp 5 + 2τ ULP of \
          T; a grazing span found by one precision only is 8u·(|p| + the box's reach) long",
};

/// A lumpy cloud: two overlapping ellipsoids with a hashed wobble, densities in [0, 1].
fn volume() -> Result<cloudlight::CloudVolume, String> {
    let dims = [40u32, 32, 20];
    let mut density = Vec::new();
    for z in 0..dims[2] {
        for y in 0..dims[1] {
            for x in 0..dims[0] {
                let p = [x, y, z].map(f64::from);
                let lump = |c: [f64; 3], r: [f64; 3]| {
                    (1.0 - (0..3).map(|a| ((p[a] - c[a]) / r[a]).powi(2)).sum::<f64>()).max(0.0)
                };
                let base = lump([15.0, 15.0, 9.0], [13.0, 12.0, 8.0])
                    .max(lump([27.0, 17.0, 11.0], [11.0, 13.0, 8.0]));
                let hash = skyscape_wgsl::common::hash_u32(x + 64 * (y + 64 * z)) & 0xff;
                density.push((base * (0.6 + 0.4 * f64::from(hash) / 255.0)) as f32);
            }
        }
    }
    cloudlight::CloudVolume::new(dims, [-600.0, -480.0, 1500.0], 30.0, 0.02, density)
        .map_err(|e| e.to_string())
}

fn sun(case: usize) -> [f64; 3] {
    let (e, a, _) = SETTINGS[case];
    let (e, a) = (e.to_radians(), a.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// The volume and a 128×96 grid of 15 m texels centred on the shadow of the volume's
/// centre (0, 0, 1800) on flat ground at 0 m.
fn plan(case: usize) -> Result<(cloudlight::CloudVolume, ShadowMapPlan), String> {
    let v = volume()?;
    let l = sun(case);
    let lift = 1800.0 / l[2];
    let corner = [-lift * l[0] - 64.0 * 15.0, -lift * l[1] - 48.0 * 15.0];
    let grid = ShadowGrid::new(corner, 15.0, [128, 96], 0.0).map_err(|e| e.to_string())?;
    let plan = ShadowMapPlan::new(grid, l, SETTINGS[case].2).map_err(|e| e.to_string())?;
    Ok((v, plan))
}

/// The largest density difference between neighbouring cells, per metre (the trilinear
/// density's largest slope; the faces are checked to hold 0, so the drop to 0 outside the
/// volume is no jump).
fn density_slope(v: &cloudlight::CloudVolume) -> f64 {
    let [nx, ny, nz] = v.dims();
    let mut slope = 0.0f64;
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let c = f64::from(v.cell(x, y, z).unwrap_or(0.0));
                for (dx, dy, dz) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
                    if let Some(n) = v.cell(x + dx, y + dy, z + dz) {
                        slope = slope.max((f64::from(n) - c).abs());
                    }
                }
            }
        }
    }
    slope / v.voxel_size()
}

fn shadow_cpu(case: usize) -> Result<PassCpu, String> {
    let (v, plan) = plan(case)?;
    let reference = shadow_map::<f64, _>(&v, &plan);
    let cpu = shadow_map::<f32, _>(&v, &plan);
    if !reference.iter().any(|&t| t < 0.5) {
        return Err("shadow parity volume casts no shadow: the case would prove nothing".into());
    }
    let [nx_v, ny_v, nz_v] = v.dims();
    for z in 0..nz_v {
        for y in 0..ny_v {
            for x in 0..nx_v {
                let face =
                    x == 0 || y == 0 || z == 0 || x + 1 == nx_v || y + 1 == ny_v || z + 1 == nz_v;
                if face && v.cell(x, y, z) != Some(0.0) {
                    return Err(format!(
                        "cell ({x}, {y}, {z}) on a face is not 0: the bound assumes it"
                    ));
                }
            }
        }
    }
    let slope = density_slope(&v);
    let rho_max = f64::from(v.density().iter().copied().fold(0.0f32, f32::max));
    let sigma = v.extinction_per_density();
    let (lo, dims, voxel) = (v.origin(), v.dims(), v.voxel_size());
    let hi: [f64; 3] = [0, 1, 2].map(|a| lo[a] + f64::from(dims[a]) * voxel);
    let reach = (0..3).map(|a| lo[a].abs().max(hi[a].abs())).sum::<f64>();
    let l = plan.to_sun();
    let n = f64::from(plan.steps());
    let [nx, ny] = plan.grid.resolution();
    let mut bounds = Vec::with_capacity(reference.len());
    for j in 0..ny {
        for i in 0..nx {
            let t_ref = reference[(i + nx * j) as usize];
            let tau = -t_ref.ln();
            let exp_error = (5.0 + 2.0 * tau) * super::super::compare::ulp_f32(t_ref);
            let p = plan.grid.texel_centre(i, j);
            let p_norm = p.iter().map(|c| c.abs()).fold(0.0, f64::max);
            let grazing = 8.0 * U * (p_norm + reach) * sigma * rho_max;
            let [s0, s1] = shadow_box_span(p, l, lo, hi);
            if s0 > s1 {
                bounds.push(t_ref * grazing + exp_error);
                continue;
            }
            let t_max = s0.abs().max(s1.abs());
            let h = (s1 - s0) / n;
            let dq = 3f64.sqrt() * 12.0 * U * (p_norm + t_max);
            let d_rho = 3f64.sqrt() * slope * dq + 16.0 * U * rho_max;
            // Σρ ≤ τ/(σ·h) (the f64 march's own sum).
            let sum = if sigma * h > 0.0 {
                tau / (sigma * h)
            } else {
                0.0
            };
            let d_sum = n * d_rho + n * U * sum;
            let d_h = (16.0 * U * t_max + U * (s1 - s0)) / n + 5.0 * U * h;
            let d_tau = sigma * (d_sum * h + sum * d_h) + 3.0 * U * tau;
            bounds.push(t_ref * (d_tau + grazing) + exp_error);
        }
    }
    Ok(PassCpu {
        inputs: reference.len(),
        reference,
        bounds: Some(bounds),
        cpu,
    })
}

fn shadow_gpu(gpu: &skyscape_harness::GpuContext, case: usize) -> Result<Vec<f32>, String> {
    let (v, plan) = plan(case)?;
    let mut pass = cloudlight::gpu::ShadowMapPass::new(&gpu.device).map_err(|e| e.to_string())?;
    pass.prepare(&gpu.device, &gpu.queue, &v, &plan)
        .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let texture = pass.texture().ok_or("no shadow texture after prepare")?;
    let bytes = skyscape_harness::read_texture(gpu, "cloudlight shadow map", texture)
        .map_err(|e| e.to_string())?;
    pass.decode(&bytes).map_err(|e| e.to_string())
}
