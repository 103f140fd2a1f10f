//! GPU tests: the WGSL horizon bake against the CPU, and the WGSL shadow/shading twins
//! against their Rust twins. Run with `WGPU_BACKEND=vulkan` (lavapipe) where there is
//! no GPU; without an adapter they print `SKIPPED` (or fail with SKYSCAPE_REQUIRE_GPU=1).
#![cfg(feature = "gpu")]

use glam::Vec3;
use terrain::generate::{GeneratorParams, generate};
use terrain::gpu::GpuHorizonBaker;
use terrain::shadow::{
    SUN_ANGULAR_RADIUS, azimuth_layers, self_shadow_east_west, soft_shadow, terrain_shading,
};
use terrain::twins::sun_disc_visible_fraction;
use terrain::{Algorithm, Heightfield, HorizonOptions, bake_east_west};

/// GPU vs CPU tolerance of the bake, radians: f32 evaluation of the same formula
/// (heights of a few km rounded to ~1e-4 m, the curvature drop in f32, then `atan`);
/// 3.2e-6 measured on lavapipe.
const BAKE_TOLERANCE: f32 = 1e-5;

fn read_f32(gpu: &skyscape_harness::GpuContext, buffer: &wgpu::Buffer, n: usize) -> Vec<f32> {
    let bytes =
        skyscape_harness::read_buffer(gpu, "terrain horizon", buffer, 0, (n * 4) as u64).unwrap();
    bytemuck::cast_slice(&bytes).to_vec()
}

#[test]
fn gpu_horizon_bake_matches_cpu() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("terrain::gpu_horizon_bake_matches_cpu") else {
        return;
    };
    let baker = GpuHorizonBaker::new(&gpu.device);
    let maps = [
        generate(&GeneratorParams {
            amplitude: 2000.0,
            ..GeneratorParams::new(64, 64, 30.0, 5)
        })
        .unwrap(),
        generate(&GeneratorParams {
            amplitude: 3000.0,
            ..GeneratorParams::new(61, 7, 1000.0, 6)
        })
        .unwrap(),
        Heightfield::from_fn(1, 3, 1.0, |_, _| 1.0).unwrap(),
    ];
    let options = [
        HorizonOptions::flat(),
        HorizonOptions::default(),
        HorizonOptions {
            max_distance: Some(400.0),
            ..HorizonOptions::default()
        },
        HorizonOptions {
            max_distance: Some(5000.0),
            ..HorizonOptions::flat()
        },
    ];
    let mut worst = 0.0f32;
    for hf in &maps {
        for opts in &options {
            let cpu = bake_east_west(hf, opts, Algorithm::HullSweep).unwrap();
            let mut encoder = gpu
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                    label: Some("test"),
                });
            let out = baker
                .record_east_west(&gpu.device, &gpu.queue, &mut encoder, hf, opts)
                .unwrap();
            gpu.queue.submit([encoder.finish()]);
            let n = hf.width() * hf.height();
            let east = read_f32(gpu, &out.east, n);
            let west = read_f32(gpu, &out.west, n);
            for (g, c) in east
                .iter()
                .zip(cpu.east.angles())
                .chain(west.iter().zip(cpu.west.angles()))
            {
                let d = (g - c).abs();
                assert!(
                    d <= BAKE_TOLERANCE,
                    "{}x{} {opts:?}: gpu {g} cpu {c}",
                    hf.width(),
                    hf.height()
                );
                worst = worst.max(d);
            }
        }
    }
    eprintln!("GPU vs CPU horizon bake: max |diff| = {worst:e} rad");
}

#[test]
fn wgsl_shadow_twins_match_rust() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("terrain::wgsl_shadow_twins_match_rust") else {
        return;
    };
    let root = "#import terrain::shadow\n#import terrain::shading\n\
        @group(0) @binding(0) var<storage, read> inputs: array<vec4<f32>>;\n\
        @group(0) @binding(1) var<storage, read_write> outputs: array<vec4<f32>>;\n\
        @compute @workgroup_size(64) fn main(@builtin(global_invocation_id) gid: vec3<u32>) {\n\
          let i = gid.x;\n\
          if i >= arrayLength(&inputs) { return; }\n\
          let v = inputs[i];\n\
          let sun = normalize(vec3<f32>(v.z, v.w, v.x));\n\
          let layers = azimuth_layers(v.z * 4.0, 16u);\n\
          let shade = terrain_shading(normalize(vec3<f32>(v.w, v.z, 1.0)), sun, vec3<f32>(0.3, 0.5, 0.7), 0.8, 0.9);\n\
          outputs[i] = vec4<f32>(soft_shadow(v.x, v.y, SUN_ANGULAR_RADIUS), sun_disc_visible_fraction(v.x * 300.0),\n\
            f32(layers.lower) + layers.weight, shade.y + self_shadow_east_west(v.y, -v.y, sun, SUN_ANGULAR_RADIUS));\n\
        }\n";
    let source = terrain::composer()
        .compose("terrain shadow parity", root)
        .unwrap();
    let mut inputs = Vec::new();
    for i in 0..4096 {
        let t = i as f32 / 4096.0;
        inputs.push([
            -0.01 + 0.02 * t,
            0.003 * (t * 37.0).sin(),
            (t * 13.0).fract() * 1.5 - 0.2,
            (t * 7.0).cos(),
        ]);
    }
    let bytes = skyscape_harness::run_compute(
        gpu,
        &skyscape_harness::ComputeJob {
            label: "terrain shadow parity",
            source: &source,
            entry: "main",
            constants: &[],
            inputs: &[bytemuck::cast_slice(&inputs)],
            output_bytes: (inputs.len() * 16) as u64,
            workgroups: skyscape_harness::workgroups_1d(inputs.len() as u32, 64),
        },
    )
    .unwrap();
    let out: &[[f32; 4]] = bytemuck::cast_slice(&bytes);
    let mut worst = [0.0f32; 4];
    for (v, g) in inputs.iter().zip(out) {
        let sun = Vec3::new(v[2], v[3], v[0]).normalize();
        let layers = azimuth_layers(v[2] * 4.0, 16).unwrap();
        let shade = terrain_shading(
            Vec3::new(v[3], v[2], 1.0).normalize(),
            sun,
            Vec3::new(0.3, 0.5, 0.7),
            0.8,
            0.9,
        );
        let cpu = [
            soft_shadow(v[0], v[1], SUN_ANGULAR_RADIUS),
            sun_disc_visible_fraction(v[0] * 300.0),
            layers.lower as f32 + layers.weight,
            shade.y + self_shadow_east_west(v[1], -v[1], sun, SUN_ANGULAR_RADIUS),
        ];
        for c in 0..4 {
            worst[c] = worst[c].max((g[c] - cpu[c]).abs());
        }
    }
    eprintln!("WGSL vs Rust twins: max |diff| per output = {worst:?}");
    // Measured on lavapipe: [1.03e-6, 9.5e-7, 0, 1.34e-5]. The disc fraction goes through
    // one atan2 (~300 ULP on lavapipe); the layer index is exact arithmetic; the last
    // output's sun elevation comes from atan2 and is divided by the sun's radius
    // (0.0047 rad), which amplifies a 1e-7 rad difference to ~1e-5.
    assert!(
        worst[0] < 1e-5 && worst[1] < 1e-5 && worst[2] == 0.0 && worst[3] < 1e-4,
        "{worst:?}"
    );
}

#[test]
fn gpu_any_azimuth_bake_matches_cpu() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("terrain::gpu_any_azimuth_bake_matches_cpu")
    else {
        return;
    };
    let baker = GpuHorizonBaker::new(&gpu.device);
    let maps = [
        generate(&GeneratorParams {
            amplitude: 2000.0,
            ..GeneratorParams::new(48, 40, 30.0, 9)
        })
        .unwrap(),
        generate(&GeneratorParams {
            amplitude: 500.0,
            ..GeneratorParams::new(5, 23, 10.0, 10)
        })
        .unwrap(),
        Heightfield::from_fn(1, 1, 1.0, |_, _| 1.0).unwrap(),
    ];
    let options = [
        HorizonOptions::default(),
        HorizonOptions {
            max_distance: Some(300.0),
            ..HorizonOptions::default()
        },
    ];
    let mut worst = 0.0f32;
    for hf in &maps {
        for opts in &options {
            for azimuth in [
                0.0,
                0.3,
                std::f64::consts::FRAC_PI_4,
                2.0,
                3.3,
                4.0,
                5.5,
                6.1,
            ] {
                let cpu = terrain::bake_horizon(hf, azimuth, opts, Algorithm::HullSweep).unwrap();
                let mut encoder =
                    gpu.device
                        .create_command_encoder(&wgpu::CommandEncoderDescriptor {
                            label: Some("test"),
                        });
                let out = baker
                    .record_azimuth(&gpu.device, &gpu.queue, &mut encoder, hf, azimuth, opts)
                    .unwrap();
                gpu.queue.submit([encoder.finish()]);
                let got = read_f32(gpu, &out.angles, hf.width() * hf.height());
                for (i, (g, c)) in got.iter().zip(cpu.angles()).enumerate() {
                    let d = (g - c).abs();
                    assert!(
                        d <= BAKE_TOLERANCE,
                        "azimuth {azimuth} texel {i}: gpu {g} cpu {c} ({opts:?})"
                    );
                    worst = worst.max(d);
                }
            }
        }
    }
    eprintln!("gpu any-azimuth bake: worst |gpu - cpu| = {worst:e} rad");
}
