//! Parity passes of a horizon stack texture (`terrain::horizon_texture`, WGSL
//! `terrain::horizon_stack`): the horizon angle for any point and azimuth
//! (`sample_horizon`) and the sun disc's self-shadow (`self_shadow`), read by a compute
//! kernel from the stack uploaded in each encoding (u8, u16 as two bytes, f32), against
//! the CPU twins and an f64 reference that decodes the stored integers in f64.

use std::f64::consts::{PI, TAU};

use super::*;
use terrain::horizon_stack::{HorizonStack, sample_horizon, self_shadow};
use terrain::horizon_texture::{GpuHorizonStack, horizon_stack_bindings_wgsl};
use terrain::{Algorithm, HorizonEncoding, HorizonOptions};
use wgpu::util::DeviceExt as _;

const SUN_RADIUS: f32 = terrain::shadow::SUN_ANGULAR_RADIUS;
const AZIMUTHS: usize = 8;

/// A 40×32 map at 25 m with two hills, its 8-azimuth stack in each encoding.
fn stacks() -> Result<Vec<HorizonStack>, String> {
    let hf = terrain::Heightfield::from_fn(40, 32, 25.0, |x, y| {
        let bump = |cx: f32, cy: f32, h: f32, s: f32| {
            let (dx, dy) = (x as f32 - cx, y as f32 - cy);
            h * (-(dx * dx + dy * dy) / s).exp()
        };
        bump(12.0, 10.0, 300.0, 30.0) + bump(28.0, 22.0, 180.0, 50.0)
    })
    .map_err(|e| e.to_string())?;
    let maps = terrain::bake_azimuths(&hf, AZIMUTHS, &HorizonOptions::flat(), Algorithm::HullSweep)
        .map_err(|e| e.to_string())?;
    HorizonEncoding::ALL
        .into_iter()
        .map(|encoding| HorizonStack::new(&maps, encoding).map_err(|e| e.to_string()))
        .collect()
}

/// The f64 angle of a stored texel: the integer decoded in f64 (the f32 value itself).
fn angle_f64(stack: &HorizonStack, x: u32, y: u32, layer: u32) -> f64 {
    let p = stack.params();
    let index = ((layer * p.height + y) * p.width + x) as usize;
    let b = stack.bytes();
    match stack.encoding() {
        HorizonEncoding::Unorm8 => f64::from(b[index]) / 255.0 * PI - 0.5 * PI,
        HorizonEncoding::Unorm16 => {
            let q = (u16::from(b[2 * index]) << 8) | u16::from(b[2 * index + 1]);
            f64::from(q) / 65535.0 * PI - 0.5 * PI
        }
        HorizonEncoding::F32 => f64::from(f32::from_le_bytes([
            b[4 * index],
            b[4 * index + 1],
            b[4 * index + 2],
            b[4 * index + 3],
        ])),
    }
}

/// [`sample_horizon`] in f64.
fn sample_horizon_f64(stack: &HorizonStack, position: [f64; 2], azimuth: f64) -> f64 {
    let p = stack.params();
    let x = position[0].clamp(0.0, f64::from(p.width - 1));
    let y = position[1].clamp(0.0, f64::from(p.height - 1));
    let (x0, y0) = (x.floor() as u32, y.floor() as u32);
    let (fx, fy) = (x - f64::from(x0), y - f64::from(y0));
    let (x1, y1) = ((x0 + 1).min(p.width - 1), (y0 + 1).min(p.height - 1));
    let bilinear = |layer: u32| {
        let top =
            angle_f64(stack, x0, y0, layer) * (1.0 - fx) + angle_f64(stack, x1, y0, layer) * fx;
        let bottom =
            angle_f64(stack, x0, y1, layer) * (1.0 - fx) + angle_f64(stack, x1, y1, layer) * fx;
        top * (1.0 - fy) + bottom * fy
    };
    let n = f64::from(p.count);
    let f = (azimuth / TAU * n).rem_euclid(n);
    let k = f.floor();
    let lower = (k as u32) % p.count;
    let upper = (lower + 1) % p.count;
    bilinear(lower) * (1.0 - (f - k)) + bilinear(upper) * (f - k)
}

/// Inputs: (position, azimuth) and a sun direction whose elevation sits at the
/// reference horizon there, 0.6 sun radii below or above it (the disc's soft edge).
fn inputs(stack: &HorizonStack) -> Vec<([f32; 4], [f32; 4])> {
    let mut rows = Vec::new();
    for j in 0..16u32 {
        for i in 0..20u32 {
            let position = [0.3 + 1.93 * f64::from(i), 0.2 + 1.97 * f64::from(j)];
            for a in 0..7u32 {
                let azimuth = (0.37 + 0.93 * f64::from(a)).rem_euclid(TAU);
                let horizon = sample_horizon_f64(stack, position, azimuth);
                let offset = [-0.6, 0.0, 0.6][((i + j + a) % 3) as usize] * f64::from(SUN_RADIUS);
                let elevation = (horizon + offset).clamp(-1.5, 1.5);
                let direction = [
                    elevation.cos() * azimuth.sin(),
                    elevation.cos() * azimuth.cos(),
                    elevation.sin(),
                ];
                rows.push((
                    [position[0] as f32, position[1] as f32, azimuth as f32, 0.0],
                    [
                        direction[0] as f32,
                        direction[1] as f32,
                        direction[2] as f32,
                        0.0,
                    ],
                ));
            }
        }
    }
    rows
}

/// Outputs per input: (sample_horizon, self_shadow), every encoding in turn.
fn stack_cpu(output: usize) -> Result<PassCpu, String> {
    let mut cpu = Vec::new();
    let mut reference = Vec::new();
    for stack in stacks()? {
        for (at, sun) in inputs(&stack) {
            let direction = glam::Vec3::new(sun[0], sun[1], sun[2]);
            let values = [
                sample_horizon(&stack, [at[0], at[1]], at[2]),
                self_shadow(&stack, [at[0], at[1]], direction, SUN_RADIUS),
            ];
            cpu.push(values[output]);
            let d = direction.as_dvec3();
            let elevation = d.z.atan2((d.x * d.x + d.y * d.y).sqrt());
            let azimuth = d.x.atan2(d.y).rem_euclid(TAU);
            let position = [f64::from(at[0]), f64::from(at[1])];
            reference.push(if output == 0 {
                sample_horizon_f64(&stack, position, f64::from(at[2]))
            } else {
                terrain::twins::soft_shadow_f64(
                    elevation,
                    sample_horizon_f64(&stack, position, azimuth),
                    f64::from(SUN_RADIUS),
                )
            });
        }
    }
    Ok(PassCpu {
        inputs: cpu.len(),
        reference,
        bounds: None,
        cpu,
    })
}

const KERNEL: &str = r"
@group(1) @binding(0) var<storage, read> inputs: array<vec4<f32>>;
@group(1) @binding(1) var<storage, read_write> results: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if 2u * id.x >= arrayLength(&inputs) {
        return;
    }
    let at = inputs[2u * id.x];
    let sun = inputs[2u * id.x + 1u].xyz;
    results[2u * id.x] = sample_horizon(horizon_stack, horizon_stack_params, at.xy, at.z);
    results[2u * id.x + 1u] = self_shadow(horizon_stack, horizon_stack_params, at.xy, sun, SUN_ANGULAR_RADIUS);
}
";

fn stack_gpu(gpu: &skyscape_harness::GpuContext, output: usize) -> Result<Vec<f32>, String> {
    let device = &gpu.device;
    let source = format!(
        "#import terrain::horizon_stack\n{}{KERNEL}",
        horizon_stack_bindings_wgsl(0)
    );
    let source = terrain::composer()
        .compose("stack kernel", &source)
        .map_err(|e| e.to_string())?;
    let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
        label: Some("stack kernel"),
        source: wgpu::ShaderSource::Wgsl(source.into()),
    });
    let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    };
    let own = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("stack kernel buffers"),
        entries: &[storage(0, true), storage(1, false)],
    });
    let mut values = Vec::new();
    for stack in stacks()? {
        let uploaded =
            GpuHorizonStack::upload(device, &gpu.queue, &stack).map_err(|e| e.to_string())?;
        let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("stack kernel"),
            bind_group_layouts: &[Some(uploaded.layout()), Some(&own)],
            immediate_size: 0,
        });
        let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
            label: Some("stack kernel"),
            layout: Some(&layout),
            module: &module,
            entry_point: Some("main"),
            compilation_options: Default::default(),
            cache: None,
        });
        let rows: Vec<[f32; 4]> = inputs(&stack)
            .into_iter()
            .flat_map(|(a, b)| [a, b])
            .collect();
        let count = rows.len() / 2;
        let input = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("inputs"),
            contents: bytemuck::cast_slice(&rows),
            usage: wgpu::BufferUsages::STORAGE,
        });
        let results = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("results"),
            size: (count * 2 * 4) as u64,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &own,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: input.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: results.as_entire_binding(),
                },
            ],
        });
        let mut encoder = device.create_command_encoder(&Default::default());
        {
            let mut pass = encoder.begin_compute_pass(&Default::default());
            pass.set_pipeline(&pipeline);
            pass.set_bind_group(0, uploaded.bind_group(), &[]);
            pass.set_bind_group(1, &group, &[]);
            pass.dispatch_workgroups((count as u32).div_ceil(64), 1, 1);
        }
        gpu.queue.submit([encoder.finish()]);
        let bytes = skyscape_harness::read_buffer(gpu, "results", &results, 0, results.size())
            .map_err(|e| e.to_string())?;
        let pairs: &[f32] = bytemuck::cast_slice(&bytes);
        values.extend(pairs.chunks_exact(2).map(|pair| pair[output]));
    }
    Ok(values)
}

/// The horizon-stack pass cases, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "terrain::sample_horizon (stack texture u8/u16/f32, 40x32x8)",
            cpu: || stack_cpu(0),
            gpu: |gpu| stack_gpu(gpu, 0),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 2e-6,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "reference: the stored integers decoded in f64; f32: the decode \
                      (a division, a product and a sum on angles ≤ π/2: ≤ 3 ULP of π/2 = \
                      3.6e-7), three lerps of the bilinear and one between layers whose \
                      weight comes from the azimuth's f32 products (each ≤ 2 ULP of \
                      angle differences ≤ π): 2e-6 rad",
            },
        },
        PassCase {
            name: "terrain::self_shadow (stack texture u8/u16/f32, 40x32x8)",
            cpu: || stack_cpu(1),
            gpu: |gpu| stack_gpu(gpu, 1),
            audit: Audit::INDEPENDENT,
            tolerance: Tolerance {
                abs: 4e-3,
                rel: 0.0,
                ulp: 0.0,
                bound: None,
                why: "the sun's elevation and azimuth by atan2 (WGSL ≈ 300 ULP on lavapipe: \
                      ≤ 2e-6 rad of elevation, ≤ 2e-5 rad of the horizon through the azimuth \
                      weight) moved by the disc's visible fraction, whose slope is at most \
                      (2/π)/r = 137 per radian at the sun's radius: 4e-3 at the disc's \
                      edge, exact where the disc is wholly above or below",
            },
        },
    ]
}
