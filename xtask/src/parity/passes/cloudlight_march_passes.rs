//! Parity passes of `cloudlight`'s view march (Schneider 2015): a 32×32 image of a lumpy 32³
//! blob by `cloudlight::gpu::MarchPass`, per pixel (radiance r, g, b, transmittance).
//! Reference: the generic march at f64 (`march::render_image::<f64>`); cpu: the same at
//! f32 (the WGSL's twin).

use super::*;
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchResult, MarchSettings, Octaves, PinholeCamera,
    octave_scattering, render_image,
};
use cloudlight::{CloudVolume, DensityField, RaySpans};

const U: f64 = super::super::compare::UNIT_ROUNDOFF;
const SIZE: [u32; 2] = [32, 32];

/// The pass cases of this file, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "cloudlight::march_pass (sun 53°, full light march 8, 3 octaves, ambient, \
                   Bayer, 24 steps, 32x32 over 32³)",
            cpu: || march_cpu(0),
            gpu: |gpu| march_gpu(gpu, 0),
            audit: Audit::INDEPENDENT,
            tolerance: TOLERANCE,
        },
        PassCase {
            name: "cloudlight::march_pass (sun 10°, partitioned cone, powder, IGN, 32 steps, \
                   32x32 over 32³)",
            cpu: || march_cpu(1),
            gpu: |gpu| march_gpu(gpu, 1),
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
    why: "per pixel, from the f64 march's own sensitivity: twice its change when every \
          density moves by 64u relative plus 16u·ρ_max (the f32 trilinear lookup) plus \
          √3·G·32u·(|o| + t_max) (sample positions from f32 directions, 12u + the pixel \
          direction's 20u, G the largest cell-to-cell slope), plus the span ends' rounding \
          times the largest source (σ·ρ_max·E·P), plus (8N + 40)u of the value for N steps' \
          exp (5 + 2x ULP each) and the phase's 16 ULP lobes",
};

/// A lumpy blob, zero on the faces (so no span end meets a density jump).
fn volume() -> Result<CloudVolume, String> {
    let n = 32u32;
    let mut density = Vec::new();
    for z in 0..n {
        for y in 0..n {
            for x in 0..n {
                let p = [x, y, z].map(|c| (f64::from(c) + 0.5) / f64::from(n) * 2.0 - 1.0);
                let r2 = 1.44 * (p[0] * p[0] + p[1] * p[1]) + 2.0 * p[2] * p[2];
                let hash = skyscape_wgsl::common::hash_u32(x + 64 * (y + 64 * z)) & 0xff;
                let wobble = 0.6 + 0.4 * f64::from(hash) / 255.0;
                density.push((1.5 * wobble * (1.0 - r2).max(0.0)) as f32);
            }
        }
    }
    CloudVolume::new([n, n, n], [-400.0, -400.0, 1000.0], 25.0, 0.02, density)
        .map_err(|e| e.to_string())
}

fn setup(case: usize) -> Result<(CloudVolume, PinholeCamera, MarchSettings, [f64; 3]), String> {
    let v = volume()?;
    let e = |s: &dyn std::fmt::Display| s.to_string();
    let (camera, config, elevation, azimuth) = match case {
        0 => (
            PinholeCamera::look_at([0.0, -100.0, 0.0], [0.0, 0.0, 1400.0], [0.0, 0.0, 1.0], 0.9),
            MarchConfig {
                view_steps: 24,
                jitter: Jitter::Bayer4x4,
                transmittance_epsilon: 0.0,
                light: LightMarch::Full {
                    steps: std::num::NonZeroU32::new(8).ok_or("8 > 0")?,
                },
                octaves: Octaves {
                    count: 3,
                    a: 0.5,
                    b: 0.6,
                    c: 0.5,
                },
                ambient_steps: 2,
                ..MarchConfig::default()
            },
            53.0f64,
            30.0f64,
        ),
        _ => (
            PinholeCamera::look_at(
                [-1500.0, -300.0, 1300.0],
                [0.0, 0.0, 1400.0],
                [0.0, 0.0, 1.0],
                0.8,
            ),
            MarchConfig {
                view_steps: 32,
                jitter: Jitter::InterleavedGradient,
                transmittance_epsilon: 0.0,
                light: LightMarch::Cone {
                    step: 60.0,
                    spread: 0.0,
                    weights: cloudlight::cone::ConeWeights::Partitioned,
                },
                powder: true,
                ambient_steps: 0,
                ..MarchConfig::default()
            },
            10.0,
            200.0,
        ),
    };
    let camera = camera.map_err(|x| e(&x))?;
    let settings = MarchSettings::new(config).map_err(|x| e(&x))?;
    let (el, az) = (elevation.to_radians(), azimuth.to_radians());
    let sun = [el.cos() * az.cos(), el.cos() * az.sin(), el.sin()];
    Ok((v, camera, settings, sun))
}

const SUN: [f64; 3] = [1.0, 0.95, 0.9];
const AMBIENT: [f64; 3] = [0.05, 0.08, 0.12];

fn lighting<F: atmos::real::Real>(sun: [f64; 3]) -> Result<Lighting<F>, String> {
    Lighting::new(sun, SUN, AMBIENT, [0.0, 0.0, 1.0]).map_err(|e| e.to_string())
}

/// The volume's density moved by `scale` relative and `add` absolute (never below 0).
struct Perturbed<'a> {
    volume: &'a CloudVolume,
    scale: f64,
    add: f64,
}

impl DensityField<f64> for Perturbed<'_> {
    fn density(&self, p: [f64; 3]) -> f64 {
        let rho: f64 = DensityField::<f64>::density(self.volume, p);
        if rho > 0.0 {
            (rho * self.scale + self.add).max(0.0)
        } else {
            0.0
        }
    }

    fn extinction_per_density(&self) -> f64 {
        DensityField::<f64>::extinction_per_density(self.volume)
    }

    fn ray_spans(&self, origin: [f64; 3], direction: [f64; 3]) -> RaySpans<f64> {
        self.volume.ray_spans(origin, direction)
    }
}

fn flatten<F: Into<f64> + Copy>(image: &[MarchResult<F>]) -> Vec<f64> {
    image
        .iter()
        .flat_map(|r| {
            [
                r.radiance[0].into(),
                r.radiance[1].into(),
                r.radiance[2].into(),
                r.transmittance.into(),
            ]
        })
        .collect()
}

fn march_cpu(case: usize) -> Result<PassCpu, String> {
    let (v, camera, settings, sun) = setup(case)?;
    let l64 = lighting::<f64>(sun)?;
    let reference_image = render_image::<f64>(&v, &camera, SIZE, &settings, &l64);
    let cpu_image = render_image::<f32>(&v, &camera, SIZE, &settings, &lighting::<f32>(sun)?);
    if !reference_image.iter().any(|r| r.transmittance < 0.5) {
        return Err("march parity image has no dense pixel: the case would prove nothing".into());
    }
    // The bound's ingredients.
    let [nx, ny, nz] = v.dims();
    let mut slope = 0.0f64;
    for z in 0..nz {
        for y in 0..ny {
            for x in 0..nx {
                let c = f64::from(v.cell(x, y, z).unwrap_or(0.0));
                let face = x == 0 || y == 0 || z == 0 || x + 1 == nx || y + 1 == ny || z + 1 == nz;
                if face && c != 0.0 {
                    return Err(format!("cell ({x}, {y}, {z}) on a face is not 0"));
                }
                for (dx, dy, dz) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
                    if let Some(n) = v.cell(x + dx, y + dy, z + dz) {
                        slope = slope.max((f64::from(n) - c).abs());
                    }
                }
            }
        }
    }
    let slope = slope / v.voxel_size();
    let rho_max = f64::from(v.density().iter().copied().fold(0.0f32, f32::max));
    let sigma = v.extinction_per_density();
    let origin = camera.origin();
    let o_norm = origin.iter().map(|c| c.abs()).fold(0.0, f64::max);
    let [forward, right, up] = camera.basis();
    let tan_half = camera.tan_half(SIZE);
    let c = settings.config();
    let steps = f64::from(c.view_steps);
    let mut spans_err = Vec::new();
    let mut t_max = 0.0f64;
    for y in 0..SIZE[1] {
        for x in 0..SIZE[0] {
            let d = cloudlight::march::pixel_direction([x, y], SIZE, forward, right, up, tan_half);
            let s64: RaySpans<f64> = v.ray_spans(origin, d);
            let s32: RaySpans<f32> = v.ray_spans(origin.map(|c| c as f32), d.map(|c| c as f32));
            let (a, b) = if s64.count == 1 {
                s64.spans[0]
            } else {
                (0.0, 0.0)
            };
            let (a32, b32) = if s32.count == 1 {
                (f64::from(s32.spans[0].0), f64::from(s32.spans[0].1))
            } else {
                (a, b)
            };
            t_max = t_max.max(b);
            spans_err.push(4.0 * ((a - a32).abs() + (b - b32).abs()) + 8.0 * U * (a + b));
        }
    }
    let add = 3f64.sqrt() * slope * 32.0 * U * (o_norm + t_max) + 16.0 * U * rho_max;
    let perturbed = |scale: f64, add: f64| {
        render_image::<f64>(
            &Perturbed {
                volume: &v,
                scale,
                add,
            },
            &camera,
            SIZE,
            &settings,
            &l64,
        )
    };
    let up_image = flatten(&perturbed(1.0 + 64.0 * U, add));
    let down_image = flatten(&perturbed(1.0 - 64.0 * U, -add));
    let reference = flatten(&reference_image);
    let to_sun = l64.sun_direction();
    let mut bounds = Vec::with_capacity(reference.len());
    for (i, r) in reference.iter().enumerate() {
        let pixel = i / 4;
        let (px, py) = (pixel as u32 % SIZE[0], pixel as u32 / SIZE[0]);
        let d = cloudlight::march::pixel_direction([px, py], SIZE, forward, right, up, tan_half);
        let cos = d[0] * to_sun[0] + d[1] * to_sun[1] + d[2] * to_sun[2];
        let phase_max = octave_scattering(
            0.0,
            cos,
            c.g_forward,
            c.g_back,
            c.back_weight,
            c.octaves.count,
            c.octaves.a,
            c.octaves.b,
            c.octaves.c,
        );
        let channel = i % 4;
        let source_max = if channel < 3 {
            sigma * rho_max * (SUN[channel] * phase_max + AMBIENT[channel])
        } else {
            sigma * rho_max
        };
        let sensitivity = (up_image[i] - r).abs().max((down_image[i] - r).abs());
        bounds.push(
            2.0 * sensitivity + spans_err[pixel] * source_max + (8.0 * steps + 40.0) * U * r.abs(),
        );
    }
    Ok(PassCpu {
        inputs: SIZE[0] as usize * SIZE[1] as usize,
        reference,
        bounds: Some(bounds),
        cpu: flatten(&cpu_image).into_iter().map(|x| x as f32).collect(),
    })
}

fn march_gpu(gpu: &skyscape_harness::GpuContext, case: usize) -> Result<Vec<f32>, String> {
    let (v, camera, settings, sun) = setup(case)?;
    let mut pass = cloudlight::gpu::MarchPass::new(&gpu.device).map_err(|e| e.to_string())?;
    pass.prepare(
        &gpu.device,
        &gpu.queue,
        &v,
        &camera,
        SIZE,
        &settings,
        &lighting::<f32>(sun)?,
    )
    .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let buffer = pass.image_buffer().ok_or("no image buffer after prepare")?;
    let bytes =
        skyscape_harness::read_buffer(gpu, "cloudlight march", buffer, 0, pass.image_size())
            .map_err(|e| e.to_string())?;
    let image = pass.decode(&bytes).map_err(|e| e.to_string())?;
    Ok(flatten(&image).into_iter().map(|x| x as f32).collect())
}
