//! Parity passes of atmos' sky irradiance: the sky-irradiance LUT baked by the CPU f32
//! twin and by the GPU compute pass, and `sky_irradiance` / `sun_transmittance_at`
//! evaluated by a caller's own compute shader that binds the tables at groups 2 and 3.
//!
//! The reference is the CPU f32 twin (the f64 Reference's irradiance is the accuracy
//! check of `crates/atmos/tests/sky_irradiance.rs`, not a parity reference):
//! `Audit::CPU_IS_REFERENCE`, the CPU rows are "reference = this side".

use std::sync::OnceLock;

use super::*;
use atmos::Atmosphere;
use atmos::frame::FrameCamera;
use atmos::gpu::AtmosphereLuts;
use atmos::lut::drop_in::{sky_irradiance, sun_transmittance_at};
use atmos::lut::sky_irradiance::bake_sky_irradiance_lut;
use atmos::lut::{Lut2d, LutSettings, StaticLuts};
use glam::DVec3;

const PLANET_RADIUS: f64 = 6_360_000.0;

/// A camera on the ground, the sun 20° up: the sun every lookup reads.
fn camera() -> Result<FrameCamera, String> {
    let elevation = 20f64.to_radians();
    FrameCamera::look_at(
        DVec3::new(0.0, 0.0, PLANET_RADIUS + 2.0),
        DVec3::X,
        DVec3::Z,
        1.0,
        8,
        8,
        DVec3::new(elevation.cos(), 0.0, elevation.sin()),
        None,
    )
    .map_err(|e| e.to_string())
}

/// The CPU tables (small settings) and the sky-irradiance LUT, baked once per run.
fn cpu_tables() -> Result<&'static (StaticLuts, Lut2d), String> {
    static TABLES: OnceLock<Result<(StaticLuts, Lut2d), String>> = OnceLock::new();
    TABLES
        .get_or_init(|| {
            let luts = StaticLuts::bake(&Atmosphere::earth(), &LutSettings::small())
                .map_err(|e| e.to_string())?;
            let table = bake_sky_irradiance_lut(&luts.bindings());
            Ok((luts, table))
        })
        .as_ref()
        .map_err(Clone::clone)
}

fn gpu_tables(gpu: &skyscape_harness::GpuContext) -> Result<AtmosphereLuts, String> {
    let luts = AtmosphereLuts::new(&gpu.device, &Atmosphere::earth(), &LutSettings::small())
        .map_err(|e| e.to_string())?;
    luts.prepare(&gpu.queue, &camera()?);
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    luts.encode_static_luts(&mut encoder, None);
    luts.encode_sky_irradiance(&mut encoder, None);
    gpu.queue.submit([encoder.finish()]);
    Ok(luts)
}

fn bake_cpu() -> Result<PassCpu, String> {
    let (_, table) = cpu_tables()?;
    let values: Vec<f32> = bytemuck::cast_slice(&table.texels).to_vec();
    Ok(PassCpu {
        inputs: table.texels.len(),
        reference: values.iter().map(|&v| f64::from(v)).collect(),
        bounds: None,
        cpu: values,
    })
}

fn bake_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let luts = gpu_tables(gpu)?;
    // Texture readbacks are layer-major, the CPU twin's planar layout.
    let bytes =
        skyscape_harness::read_texture(gpu, "sky irradiance", luts.sky_irradiance_texture())
            .map_err(|e| e.to_string())?;
    Ok(bytemuck::cast_slice::<u8, f32>(&bytes).to_vec())
}

/// Points at altitudes 0 m … 100 km spread around the planet (the sun's zenith angle
/// from 20° to past the terminator) and normals over the sphere: (position, normal)
/// pairs, planet-frame, as two `vec4`s each.
fn points() -> Vec<[f32; 4]> {
    let mut points = Vec::new();
    for altitude in [0.0, 500.0, 5_000.0, 30_000.0, 99_000.0] {
        for angle in [0.0f64, 20.0, 45.0, 70.0, 85.0, 95.0, 110.0, 160.0] {
            let a = angle.to_radians();
            let up = DVec3::new(-a.sin(), 0.3 * a.sin(), a.cos()).normalize();
            let position = up * (PLANET_RADIUS + altitude);
            for k in 0..8 {
                let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / 8.0;
                let phi = f64::from(k) * 2.399_963_229_728_653;
                let local = DVec3::new(
                    (1.0 - z * z).sqrt() * phi.cos(),
                    (1.0 - z * z).sqrt() * phi.sin(),
                    z,
                );
                // The normal in the point's own frame: z along `up`.
                let east = DVec3::Y.cross(up).normalize();
                let north = up.cross(east);
                let normal = (east * local.x + north * local.y + up * local.z).normalize();
                points.push(position.as_vec3().extend(0.0).to_array());
                points.push(normal.as_vec3().extend(0.0).to_array());
            }
        }
    }
    points
}

fn lookup_cpu() -> Result<PassCpu, String> {
    let (luts, table) = cpu_tables()?;
    let camera = camera()?;
    let points = points();
    let mut values = Vec::new();
    for pair in points.chunks_exact(2) {
        let position = [pair[0][0], pair[0][1], pair[0][2]];
        let normal = [pair[1][0], pair[1][1], pair[1][2]];
        values.extend(sky_irradiance(luts, table, &camera, position, normal));
        values.extend(sun_transmittance_at(luts, &camera, position));
    }
    Ok(PassCpu {
        inputs: points.len() / 2,
        reference: values.iter().map(|&v| f64::from(v)).collect(),
        bounds: None,
        cpu: values,
    })
}

/// A caller's own compute shader: its buffers in group 0, nothing in group 1, the LUTs
/// at groups 2 (uniforms) and 3 (tables).
const CALLER_KERNEL: &str = r"
#import atmos::aerial_perspective

@group(0) @binding(0) var<storage, read> points: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> results: array<f32>;

@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    if 2u * id.x >= arrayLength(&points) {
        return;
    }
    let position = points[2u * id.x].xyz;
    let normal = points[2u * id.x + 1u].xyz;
    let values = array<vec3<f32>, 2>(sky_irradiance(position, normal), sun_transmittance_at(position));
    for (var k = 0u; k < 2u; k++) {
        for (var c = 0u; c < 3u; c++) {
            results[6u * id.x + 3u * k + c] = values[k][c];
        }
    }
}
";

fn lookup_gpu(gpu: &skyscape_harness::GpuContext) -> Result<Vec<f32>, String> {
    let luts = gpu_tables(gpu)?;
    let points = points();
    let count = points.len() / 2;
    super::atmos_drop_in_passes::run_lut_caller(
        gpu,
        &luts,
        CALLER_KERNEL,
        bytemuck::cast_slice(&points),
        count,
        (count * 6 * 4) as u64,
    )
}

/// The sky-irradiance pass cases, in report order.
pub fn cases() -> Vec<PassCase> {
    vec![
        PassCase {
            name: "atmos::lut sky-irradiance bake (64x32x256)",
            cpu: bake_cpu,
            gpu: bake_gpu,
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "each texel sums 1024 directions' view marches (24 steps reading the \
                      transmittance and multiple-scattering LUTs: the sky-view bake's 5e-4 \
                      budget) times clamped cosines; sums of non-negative terms keep the \
                      relative error; 1e-7 absolute where a normal sees almost nothing (up \
                      at the top of the atmosphere)",
            },
        },
        PassCase {
            name: "atmos::sky_irradiance + sun_transmittance_at (caller's shader, groups 2/3)",
            cpu: lookup_cpu,
            gpu: lookup_gpu,
            audit: Audit::CPU_IS_REFERENCE,
            tolerance: Tolerance {
                abs: 1e-7,
                rel: 5e-4,
                ulp: 0.0,
                bound: None,
                why: "the bake's 5e-4 through a bilinear lookup over (μ_s, r) and over the \
                      normal's (n_z, φ_n), whose weights move with the rounding of the \
                      normal's sun-frame direction (sun_frame_direction) and of atan2 \
                      (≈ 300 ULP on lavapipe, ≤ 1e-4 of a layer); sun transmittance: one \
                      transmittance lookup (the transmittance bake's 2e-5)",
            },
        },
    ]
}
