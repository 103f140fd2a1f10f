//! Parity passes of `cloudlight`'s shadow map of a procedural cloud shell: the whole map
//! of the shipped `stratocumulus` deck (1000–1800 m over Earth, evaluated noise) on a
//! 112×90 grid on the plane of its base, at a high and a low sun. Reference: the march
//! at f64 (`shell_shadow::shell_shadow_map::<f64>`); cpu: the same at f32 (the WGSL's
//! twin, equal bit for bit to `shadow_map::<f32>` on the `CloudShell`); gpu:
//! `cloudlight::gpu::ShellShadowMapPass` (a storage buffer read back).

use super::*;
use cloudlight::shadow_map::{ShadowGrid, ShadowMapPlan, shadow_march_point};
use cloudlight::shell::shell_ray_spans;
use cloudlight::shell_shadow::{ShellField, shell_field_density, shell_shadow_map};
use cloudlight::{CloudShell, ShellSettings};

const U: f64 = super::super::compare::UNIT_ROUNDOFF;

/// Sun elevations and azimuths (degrees) and march steps of the cases, in order.
const SETTINGS: [(f64, f64, u32); 2] = [(40.0, 126.0, 16), (15.0, 250.0, 8)];
/// Texels of the grid (12,080: ≥ 10,000 inputs per case).
const SIZE: [u32; 2] = [112, 90];

/// The pass cases of this file, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "cloudlight::shell_shadow_map_pass (stratocumulus deck, sun 40°, 16 steps, \
                   112x90)",
            cpu: || shell_shadow_cpu(0),
            gpu: |gpu| shell_shadow_gpu(gpu, 0),
            audit: Audit::INDEPENDENT,
            tolerance: TOLERANCE,
        },
        PassCase {
            name: "cloudlight::shell_shadow_map_pass (stratocumulus deck, sun 15°, 8 steps, \
                   112x90)",
            cpu: || shell_shadow_cpu(1),
            gpu: |gpu| shell_shadow_gpu(gpu, 1),
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
    why: "per texel, the march's forward error at Earth scale from the f64 march's own \
          sensitivity (pass bounds are per output, so the tightness audit does not see \
          them; the f32 twin's worst texel uses 1/31 of its bound at sun 40° and 1/13 at \
          15°, max |T32 − T64| 5.7e-3 and 1.4e-2: f32 positions at Earth scale): the span ends are roots of the inner and outer spheres with \
          |δD| ≤ 8u·b² + 4u·r² + 4u|c| (through √D, plus 4u|b| + 12u·t: ~1 m here); each \
          sample point moves by that along the light and by 12u(|p| + t) (|p| ≈ 6.37e6 m: \
          ~4.6 m) radially, so its density by the larger f64 change over ± those shifts; \
          summed over the samples (σ·h·Σ|δρ|), h's relative error from the ends \
          (τ·δh/h), n·u·τ for the sum, 3u·τ for σ·Σρ·h, exp 5 + 2τ ULP of T; doubled",
};

/// The shipped `stratocumulus` scene's deck (scenes/stratocumulus.toml):
/// `ShellSettings::stratocumulus_deck` over Earth.
fn shell() -> Result<CloudShell, String> {
    let earth = atmos::Atmosphere::earth();
    let settings = ShellSettings::stratocumulus_deck(earth.planet_radius);
    CloudShell::new(&earth, settings).map_err(|e| e.to_string())
}

/// The deck and a 112×90 grid of 125 m texels (the shipped map's) on the plane of its
/// base, centred 3 km east of the camera's ground point.
fn plan(case: usize) -> Result<(CloudShell, ShadowMapPlan), String> {
    let shell = shell()?;
    let (e, a, steps) = SETTINGS[case];
    let (e, a) = (e.to_radians(), a.to_radians());
    let to_sun = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
    let cell = 125.0;
    let corner = [
        3000.0 - 0.5 * cell * f64::from(SIZE[0]),
        -0.5 * cell * f64::from(SIZE[1]),
    ];
    let grid = ShadowGrid::new(corner, cell, SIZE, shell.settings().inner_radius)
        .map_err(|e| e.to_string())?;
    let plan = ShadowMapPlan::new(grid, to_sun, steps).map_err(|e| e.to_string())?;
    Ok((shell, plan))
}

/// A sphere root's f32 error bound (as the `cloudlight::shell_ray_spans` case's): the
/// discriminant's error through √D, `b`'s and a few roundings of `t`.
fn root_error(r: f64, mu: f64, radius: f64) -> f64 {
    let b = r * mu;
    let c = (r - radius) * (r + radius);
    let d = b * b - c;
    let delta_d = 8.0 * U * b * b + 4.0 * U * r * r + 4.0 * U * c.abs();
    let sqrt_error = if d > 0.0 {
        (delta_d / (2.0 * d.sqrt())).min(delta_d.sqrt())
    } else {
        delta_d.sqrt()
    };
    let roots = atmos::reference::ray_sphere_intersect(r, mu, radius);
    let t = roots[0].abs().max(roots[1].abs());
    let t = if t.is_finite() { t } else { 0.0 };
    2.0 * sqrt_error + 4.0 * U * b.abs() + 12.0 * U * t
}

/// The bound of one texel (see [`TOLERANCE`]'s `why`).
fn texel_bound(field: &ShellField<f64>, p: [f64; 3], l: [f64; 3], n: u32, t_ref: f64) -> f64 {
    let tau = -t_ref.ln();
    let exp_error = (5.0 + 2.0 * tau) * super::super::compare::ulp_f32(t_ref);
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    let mu = (p[0] * l[0] + p[1] * l[1] + p[2] * l[2]) / r;
    let dt = [field.planet_radius, field.inner_radius, field.outer_radius]
        .map(|radius| root_error(r, mu, radius))
        .into_iter()
        .fold(0.0, f64::max);
    let up = p.map(|c| c / r);
    let spans = shell_ray_spans(
        p,
        l,
        field.planet_radius,
        field.inner_radius,
        field.outer_radius,
    );
    let sigma = field.extinction_per_density;
    let mut d_tau = 0.0;
    for &(s0, s1) in spans.as_slice() {
        let h = (s1 - s0) / f64::from(n);
        let dr = 12.0 * U * (r + s1.abs());
        let (mut sum, mut d_sum) = (0.0, 0.0);
        for k in 0..n {
            let q = shadow_march_point(p, l, [s0, s1], k, n);
            let rho = shell_field_density(field, q);
            let change = |dir: [f64; 3], by: f64| {
                [-by, by]
                    .map(|s| {
                        let moved = [0, 1, 2].map(|a| q[a] + s * dir[a]);
                        (shell_field_density(field, moved) - rho).abs()
                    })
                    .into_iter()
                    .fold(0.0, f64::max)
            };
            sum += rho;
            d_sum += change(l, dt) + change(up, dr);
        }
        d_tau += sigma * h * d_sum;
        let tau_span = sigma * sum * h;
        if h > 0.0 {
            d_tau += tau_span * (2.0 * dt / (s1 - s0) + 5.0 * U);
        } else {
            d_tau += sigma * dt;
        }
    }
    d_tau += (f64::from(n) + 3.0) * U * tau;
    2.0 * (t_ref * d_tau) + exp_error
}

fn shell_shadow_cpu(case: usize) -> Result<PassCpu, String> {
    let (shell, plan) = plan(case)?;
    let field64 = ShellField::<f64>::of(&shell);
    let field32 = ShellField::<f32>::of(&shell);
    let reference = shell_shadow_map(&field64, &plan);
    let cpu = shell_shadow_map(&field32, &plan);
    let shaded = reference.iter().filter(|&&t| t < 0.5).count();
    if shaded < reference.len() / 10 {
        return Err(format!(
            "the deck shades {shaded} of {} texels below 0.5: the case would prove little",
            reference.len()
        ));
    }
    let (l, n) = (plan.to_sun(), plan.steps());
    let [nx, ny] = plan.grid.resolution();
    // The bound re-evaluates the density four times per sample: two threads of rows.
    let rows = |range: std::ops::Range<u32>| -> Vec<f64> {
        range
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| {
                let t_ref = reference[(i + nx * j) as usize];
                texel_bound(&field64, plan.grid.texel_centre(i, j), l, n, t_ref)
            })
            .collect()
    };
    let bounds = std::thread::scope(|scope| {
        let upper = scope.spawn(|| rows(ny / 2..ny));
        let mut lower = rows(0..ny / 2);
        lower.extend(upper.join().unwrap_or_default());
        lower
    });
    if bounds.len() != reference.len() {
        return Err("a bound thread panicked".into());
    }
    Ok(PassCpu {
        inputs: reference.len(),
        reference,
        bounds: Some(bounds),
        cpu,
    })
}

fn shell_shadow_gpu(gpu: &skyscape_harness::GpuContext, case: usize) -> Result<Vec<f32>, String> {
    let (shell, plan) = plan(case)?;
    let field = ShellField::<f32>::of(&shell);
    let mut pass =
        cloudlight::gpu::ShellShadowMapPass::new(&gpu.device).map_err(|e| e.to_string())?;
    pass.prepare(&gpu.device, &gpu.queue, &field, &plan)
        .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let buffer = pass
        .buffer()
        .ok_or("no shell shadow buffer after prepare")?;
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "cloudlight shell shadow map",
        buffer,
        0,
        plan.grid.texels() as u64 * 4,
    )
    .map_err(|e| e.to_string())?;
    pass.decode(&bytes).map_err(|e| e.to_string())
}
