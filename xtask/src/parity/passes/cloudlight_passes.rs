//! Parity passes of `cloudlight`: Dobashi et al. 2000's slice propagation (physical and faithful
//! modes, oblique light) on a lumpy 40×32×20 volume. Reference: the generic sweep at f64;
//! cpu: the same sweep at f32 (the WGSL's twin); gpu: `cloudlight::gpu::SlicePropagation`.

use super::*;
use cloudlight::propagate::{SliceMode, SlicePlan, propagate};

const U: f64 = super::super::compare::UNIT_ROUNDOFF;

/// Light directions and modes of the cases, in order.
const SETTINGS: [([f64; 3], SliceMode); 3] = [
    ([0.35, -0.5, 0.8], SliceMode::Physical),
    ([-1.0, 0.3, 0.17], SliceMode::Physical),
    (
        [0.35, -0.5, 0.8],
        SliceMode::Faithful {
            attenuation_ratio: 0.6,
        },
    ),
];

/// The pass cases of this crate, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "cloudlight::slice_propagation (physical, sun 53° oblique, 40x32x20)",
            cpu: || slices_cpu(0),
            gpu: |gpu| slices_gpu(gpu, 0),
            audit: Audit::INDEPENDENT,
            tolerance: PHYSICAL,
        },
        PassCase {
            name: "cloudlight::slice_propagation (physical, sun 10°, x-sweep, 40x32x20)",
            cpu: || slices_cpu(1),
            gpu: |gpu| slices_gpu(gpu, 1),
            audit: Audit::INDEPENDENT,
            tolerance: PHYSICAL,
        },
        PassCase {
            name: "cloudlight::slice_propagation (faithful, ratio 0.6, 40x32x20)",
            cpu: || slices_cpu(2),
            gpu: |gpu| slices_gpu(gpu, 2),
            audit: Audit::INDEPENDENT,
            tolerance: FAITHFUL,
        },
    ]
}

const PHYSICAL: Tolerance = Tolerance {
    abs: 0.0,
    rel: 0.0,
    ulp: 0.0,
    bound: None,
    why: "per cell at sweep position k with depth τ and light T: each slice's resampling of \
          the previous depth errs by ≤ 80u·τ (two nested Catmull-Rom passes, 40u of the \
          largest tap each: the catmull_rom case's bound), the trapezoid and the bilinear \
          density by ≤ 4u·τ, the coordinate's rounding (u·n texels) by u·n·τ, where τ is \
          the largest depth of the taps (bounded by τ_max of slices 0..k): |δτ| ≤ \
          (k+1)(84 + n)u·τ_max, |δT| ≤ T·|δτ| + WGSL exp's (3 + 2τ) ULP of T",
};

const FAITHFUL: Tolerance = Tolerance {
    abs: 0.0,
    rel: 0.0,
    ulp: 0.0,
    bound: None,
    why: "a product of k factors 1 − (1 − r)ρ̄, each 3u absolute (the cancellation bound of \
          cloudlight::slice_attenuation) plus the 5-tap mean's 6.5u: ≤ (k+1)·10u",
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

fn plan(case: usize) -> Result<(cloudlight::CloudVolume, SlicePlan), String> {
    let v = volume()?;
    let (to_sun, mode) = SETTINGS[case];
    let plan = SlicePlan::new(&v, to_sun, mode).map_err(|e| e.to_string())?;
    Ok((v, plan))
}

fn slices_cpu(case: usize) -> Result<PassCpu, String> {
    let (v, plan) = plan(case)?;
    let reference = propagate::<f64>(&v, &plan).expect("the plan was made for this volume");
    let cpu = propagate::<f32>(&v, &plan).expect("the plan was made for this volume");
    let [na, nb, nc] = plan.dims_abc;
    let n = f64::from(nb.max(nc));
    let mut bounds = vec![0.0; reference.len()];
    let mut tau_max = 0.0f64;
    for k in 0..na {
        let slice = plan.slice_at(k);
        for j in 0..nc {
            for i in 0..nb {
                tau_max = tau_max.max(-reference[plan.cell_index(slice, i, j)].ln());
            }
        }
        let slice = plan.slice_at(k);
        for j in 0..nc {
            for i in 0..nb {
                let cell = plan.cell_index(slice, i, j);
                let light = reference[cell];
                let steps = f64::from(k + 1);
                bounds[cell] = match plan.mode {
                    SliceMode::Physical => {
                        let tau = -light.ln();
                        light * steps * (84.0 + n) * U * tau_max
                            + (3.0 + 2.0 * tau) * super::super::compare::ulp_f32(light)
                    }
                    SliceMode::Faithful { .. } => steps * 10.0 * U,
                };
            }
        }
    }
    if !reference.iter().any(|&l| l < 0.5) {
        return Err("slice parity volume casts no shadow: the case would prove nothing".into());
    }
    Ok(PassCpu {
        inputs: reference.len(),
        reference,
        bounds: Some(bounds),
        cpu,
    })
}

fn slices_gpu(gpu: &skyscape_harness::GpuContext, case: usize) -> Result<Vec<f32>, String> {
    let (v, plan) = plan(case)?;
    let mut pass =
        cloudlight::gpu::SlicePropagation::new(&gpu.device).map_err(|e| e.to_string())?;
    pass.prepare(&gpu.device, &gpu.queue, &v, &plan)
        .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let buffer = pass.light_buffer().ok_or("no light buffer after prepare")?;
    let bytes =
        skyscape_harness::read_buffer(gpu, "cloudlight light", buffer, 0, pass.light_size())
            .map_err(|e| e.to_string())?;
    pass.decode_light(&bytes).map_err(|e| e.to_string())
}
