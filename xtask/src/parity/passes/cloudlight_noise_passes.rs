//! Parity passes of `cloudlight`'s noise bake (the cloud shell's noise): every texel of a
//! 32³ shape and a 16³ detail texture. Reference: `cloud_shape_noise` /
//! `cloud_detail_noise` at f64 on the texel centres (unquantised); cpu: the f32 twins
//! (`bake_shape_noise`, `bake_detail_noise`) quantised as the `rgba8unorm` store does
//! (`unorm8`); gpu: `cloudlight::gpu::NoiseBake`, read back and divided by 255.

use super::*;
use cloudlight::gpu::{NoiseBake, NoiseBakeSettings};
use cloudlight::noise;

const U: f64 = super::super::compare::UNIT_ROUNDOFF;

const SETTINGS: NoiseBakeSettings = NoiseBakeSettings {
    seed: 2026,
    shape_size: 32,
    detail_size: 16,
};

/// Half a step of an 8-bit UNORM channel plus the f32 noise's error before quantising
/// (the cloud_shape_noise case's bounds are ≤ 2.5e-3 only near a Worley feature point,
/// where F1's square root amplifies; 1e-5 elsewhere): the quantisation dominates.
const BAKE: Tolerance = Tolerance {
    abs: 0.5 / 255.0 + 256.0 * U,
    rel: 0.0,
    ulp: 0.0,
    bound: None,
    why: "the rgba8unorm store rounds to the nearest 1/255 (½ step = 1.96e-3) after the f32 \
          noise's own error (≤ 256u away from feature points: the function cases' bounds); \
          reference: the generic noise at f64, unquantised",
};

/// The pass cases of the bake, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![PassCase {
        name: "cloudlight::noise_bake (shape 32³ rgba + detail 16³ rgb, rgba8unorm)",
        cpu: bake_cpu,
        gpu: bake_gpu,
        audit: Audit::INDEPENDENT,
        tolerance: BAKE,
    }]
}

fn bake_cpu() -> Result<PassCpu, String> {
    let s = SETTINGS;
    let mut reference = Vec::new();
    for (size, channels) in [(s.shape_size, 4usize), (s.detail_size, 3)] {
        for z in 0..size {
            for y in 0..size {
                for x in 0..size {
                    let u = noise::noise_texel_coordinate::<f64>([x, y, z], size);
                    if channels == 4 {
                        reference.extend(noise::cloud_shape_noise(u, s.seed));
                    } else {
                        reference.extend(noise::cloud_detail_noise(u, s.seed));
                    }
                }
            }
        }
    }
    let byte = |v: f32| f32::from(noise::unorm8(v)) / 255.0;
    let mut cpu: Vec<f32> = noise::bake_shape_noise(s.seed, s.shape_size)
        .into_iter()
        .flat_map(|t| t.map(byte))
        .collect();
    cpu.extend(
        noise::bake_detail_noise(s.seed, s.detail_size)
            .into_iter()
            .flat_map(|t| t.map(byte)),
    );
    Ok(PassCpu {
        inputs: (s.shape_size.pow(3) + s.detail_size.pow(3)) as usize,
        reference,
        bounds: None,
        cpu,
    })
}

fn bake_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let mut bake = NoiseBake::new(&gpu.device).map_err(|e| e.to_string())?;
    bake.prepare(&gpu.device, &gpu.queue, SETTINGS)
        .map_err(|e| e.to_string())?;
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    bake.encode(&mut encoder).map_err(|e| e.to_string())?;
    gpu.queue.submit([encoder.finish()]);
    let read = |label: &str, texture: Option<&wgpu::Texture>| {
        let texture = texture.ok_or("the bake was prepared")?;
        skyscape_harness::read_texture(gpu, label, texture).map_err(|e| e.to_string())
    };
    let shape = read("noise bake shape", bake.shape_texture())?;
    let detail = read("noise bake detail", bake.detail_texture())?;
    let mut out: Vec<f32> = shape.iter().map(|&b| f32::from(b) / 255.0).collect();
    // The detail texture's alpha (always 1) is not an output.
    out.extend(
        detail
            .chunks_exact(4)
            .flat_map(|t| t[..3].iter().map(|&b| f32::from(b) / 255.0)),
    );
    Ok(out)
}
