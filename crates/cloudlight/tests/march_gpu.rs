//! The view-march pass on a GPU against its f32 CPU twin `render_image::<f32>` (skipped
//! without an adapter, see skyscape-harness).
#![cfg(feature = "gpu")]

use std::num::NonZeroU32;

use cloudlight::CloudVolume;
use cloudlight::cone::ConeWeights;
use cloudlight::gpu::{MarchGpuError, MarchPass};
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchResult, MarchSettings, Octaves, PinholeCamera,
    render_image,
};

mod common;

use common::lumpy_blob;

fn run(
    gpu: &skyscape_harness::GpuContext,
    pass: &mut MarchPass,
    v: &CloudVolume,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
) -> Vec<MarchResult<f32>> {
    pass.prepare(&gpu.device, &gpu.queue, v, camera, size, settings, lighting)
        .unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "cloudlight march image",
        pass.image_buffer().unwrap(),
        0,
        pass.image_size(),
    )
    .unwrap();
    pass.decode(&bytes).unwrap()
}

#[test]
fn march_pass_matches_the_f32_twin() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("march_pass_matches_the_f32_twin") else {
        return;
    };
    let v = lumpy_blob();
    let mut pass = MarchPass::new(&gpu.device).unwrap();
    let size = [32, 32];
    let cameras = [
        // Below the cloud looking up, beside it looking across, inside it.
        PinholeCamera::look_at([0.0, -100.0, 0.0], [0.0, 0.0, 1400.0], [0.0, 0.0, 1.0], 0.9),
        PinholeCamera::look_at(
            [-1500.0, -300.0, 1300.0],
            [0.0, 0.0, 1400.0],
            [0.0, 0.0, 1.0],
            0.8,
        ),
        PinholeCamera::look_at(
            [10.0, 20.0, 1400.0],
            [300.0, 0.0, 1500.0],
            [0.0, 0.0, 1.0],
            1.4,
        ),
    ]
    .map(Result::unwrap);
    let configs = [
        MarchConfig {
            view_steps: 32,
            light: LightMarch::Full {
                steps: NonZeroU32::new(8).unwrap(),
            },
            octaves: Octaves {
                count: 3,
                a: 0.5,
                b: 0.6,
                c: 0.5,
            },
            ..MarchConfig::default()
        },
        MarchConfig {
            view_steps: 24,
            jitter: Jitter::Bayer4x4,
            light: LightMarch::Cone {
                step: 40.0,
                spread: 0.0,
                weights: ConeWeights::Partitioned,
            },
            powder: true,
            ambient_steps: 0,
            ..MarchConfig::default()
        },
        MarchConfig {
            view_steps: 16,
            jitter: Jitter::InterleavedGradient,
            transmittance_epsilon: 0.05,
            light: LightMarch::Cone {
                step: 25.0,
                spread: 0.3,
                weights: ConeWeights::Raw,
            },
            ..MarchConfig::default()
        },
    ]
    .map(|c| MarchSettings::new(c).unwrap());
    let suns: [[f64; 3]; 3] = [[0.5, 0.1, 0.86], [0.98, 0.0, 0.2], [0.3, 0.3, -0.905]];
    let mut worst_radiance = 0.0f64;
    let mut worst_transmittance = 0.0f64;
    let mut cloudy_pixels = 0usize;
    for (i, camera) in cameras.iter().enumerate() {
        for (j, settings) in configs.iter().enumerate() {
            let sun = suns[(i + j) % 3];
            let n = (sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2]).sqrt();
            let sun = sun.map(|c| c / n);
            let lighting =
                Lighting::<f32>::new(sun, [1.0, 0.95, 0.9], [0.05, 0.08, 0.12], [0.0, 0.0, 1.0])
                    .unwrap();
            let gpu_image = run(gpu, &mut pass, &v, camera, size, settings, &lighting);
            let cpu_image = render_image::<f32>(&v, camera, size, settings, &lighting);
            let peak = cpu_image
                .iter()
                .flat_map(|r| r.radiance)
                .fold(0.0f32, f32::max) as f64;
            assert!(
                peak > 0.0,
                "camera {i} config {j}: an empty image tests nothing"
            );
            for (k, (g, c)) in gpu_image.iter().zip(&cpu_image).enumerate() {
                if c.transmittance < 0.999 {
                    cloudy_pixels += 1;
                }
                for ch in 0..3 {
                    let e = (g.radiance[ch] - c.radiance[ch]).abs() as f64 / peak;
                    worst_radiance = worst_radiance.max(e);
                    // Lavapipe: 8.1e-7 of the peak (the f32 trilinear lookup against the
                    // f64 one rounded once, exp and HG within a few ULP, over 16–32 steps).
                    assert!(
                        e < 2e-5,
                        "camera {i} config {j} pixel {k} ch {ch}: GPU {g:?} CPU {c:?}"
                    );
                }
                let e = (g.transmittance - c.transmittance).abs() as f64;
                worst_transmittance = worst_transmittance.max(e);
                // Lavapipe: 9.5e-7.
                assert!(
                    e < 1e-5,
                    "camera {i} config {j} pixel {k}: GPU {g:?} CPU {c:?}"
                );
            }
        }
    }
    println!(
        "march pass vs f32 twin, 9 images 32x32 ({cloudy_pixels} cloudy pixels): radiance max \
         |diff|/peak {worst_radiance:.2e}, transmittance max |diff| {worst_transmittance:.2e}"
    );
    assert!(cloudy_pixels > 2000, "{cloudy_pixels}");
}

#[test]
fn encode_before_prepare_and_bad_sizes_are_errors() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("encode_before_prepare_and_bad_sizes_are_errors")
    else {
        return;
    };
    let mut pass = MarchPass::new(&gpu.device).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    assert!(matches!(
        pass.encode(&mut encoder),
        Err(MarchGpuError::EncodeBeforePrepare)
    ));
    let camera = PinholeCamera::look_at([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 1.0).unwrap();
    let lighting = Lighting::<f32>::white_sun([0.0, 0.0, 1.0]).unwrap();
    let err = pass
        .prepare(
            &gpu.device,
            &gpu.queue,
            &lumpy_blob(),
            &camera,
            [0, 4],
            &MarchSettings::default(),
            &lighting,
        )
        .unwrap_err();
    assert!(matches!(
        err,
        MarchGpuError::ImageSize {
            field: "size.x",
            value: 0,
            ..
        }
    ));
}

#[test]
fn march_shell_pass_matches_the_f32_twin() {
    use cloudlight::gpu::MarchShellPass;
    use cloudlight::march::faded;
    use cloudlight::{CloudShell, ShellSettings};
    let Some(gpu) = skyscape_harness::gpu_or_skip("march_shell_pass_matches_the_f32_twin") else {
        return;
    };
    let earth = atmos::Atmosphere::earth();
    let r = earth.planet_radius;
    let shell = CloudShell::new(&earth, ShellSettings::cumulus_over(r)).unwrap();
    let mut pass = MarchShellPass::new(&gpu.device).unwrap();
    let size = [24, 24];
    // From the ground looking up at 30°, and from inside the layer looking across it.
    let cameras = [
        PinholeCamera::look_at(
            [0.0, 0.0, r + 2.0],
            [8660.0, 0.0, r + 5000.0],
            [0.0, 0.0, 1.0],
            1.2,
        ),
        PinholeCamera::look_at(
            [1000.0, -2000.0, r + 2500.0],
            [9000.0, 3000.0, r + 2600.0],
            [0.0, 0.0, 1.0],
            1.0,
        ),
    ]
    .map(Result::unwrap);
    let configs = [
        MarchConfig {
            view_steps: 16,
            light: LightMarch::Full {
                steps: NonZeroU32::new(4).unwrap(),
            },
            ambient_steps: 2,
            octaves: Octaves {
                count: 2,
                a: 0.5,
                b: 0.5,
                c: 0.5,
            },
            ..MarchConfig::default()
        },
        MarchConfig {
            view_steps: 12,
            jitter: Jitter::InterleavedGradient,
            light: LightMarch::Cone {
                step: 150.0,
                spread: 0.2,
                weights: ConeWeights::Raw,
            },
            ambient_steps: 0,
            ..MarchConfig::default()
        },
    ]
    .map(|c| MarchSettings::new(c).unwrap());
    let sun = [0.5, 0.0, 0.75f64.sqrt()];
    let lighting =
        Lighting::<f32>::new(sun, [1.0, 0.95, 0.9], [0.05, 0.08, 0.12], [0.0, 0.0, 1.0]).unwrap();
    let mut worst_radiance = 0.0f64;
    let mut worst_transmittance = 0.0f64;
    let mut cloudy_pixels = 0usize;
    for (i, camera) in cameras.iter().enumerate() {
        for (j, settings) in configs.iter().enumerate() {
            pass.prepare(
                &gpu.device,
                &gpu.queue,
                &shell,
                camera,
                size,
                settings,
                &lighting,
            )
            .unwrap();
            let mut encoder = gpu.device.create_command_encoder(&Default::default());
            pass.encode(&mut encoder).unwrap();
            gpu.queue.submit([encoder.finish()]);
            let bytes = skyscape_harness::read_buffer(
                gpu,
                "cloudlight march shell image",
                pass.image_buffer().unwrap(),
                0,
                pass.image_size(),
            )
            .unwrap();
            let gpu_image = pass.decode(&bytes).unwrap();
            let cpu_image: Vec<MarchResult<f32>> =
                render_image::<f32>(&shell, camera, size, settings, &lighting)
                    .into_iter()
                    .map(|r| faded(r, shell.horizon_fade(r.depth)))
                    .collect();
            let peak = cpu_image
                .iter()
                .flat_map(|r| r.radiance)
                .fold(0.0f32, f32::max) as f64;
            assert!(
                peak > 0.0,
                "camera {i} config {j}: an empty image tests nothing"
            );
            let mut image_worst = 0.0f64;
            let mut errors = Vec::new();
            for (g, c) in gpu_image.iter().zip(&cpu_image) {
                if c.transmittance < 0.999 {
                    cloudy_pixels += 1;
                }
                for ch in 0..3 {
                    let e = (g.radiance[ch] - c.radiance[ch]).abs() as f64 / peak;
                    image_worst = image_worst.max(e);
                    errors.push(e);
                }
                worst_transmittance =
                    worst_transmittance.max((g.transmittance - c.transmittance).abs() as f64);
            }
            errors.sort_by(f64::total_cmp);
            println!(
                "camera {i} config {j}: radiance |diff|/peak max {image_worst:.2e}, 99th \
                 percentile {:.2e}",
                errors[errors.len() * 99 / 100]
            );
            worst_radiance = worst_radiance.max(image_worst);
        }
    }
    println!(
        "march shell pass vs f32 twin, 4 images 24x24 ({cloudy_pixels} cloudy pixels): radiance \
         max |diff|/peak {worst_radiance:.2e}, transmittance max |diff| {worst_transmittance:.2e}"
    );
    assert!(cloudy_pixels > 200, "{cloudy_pixels}");
    // Lavapipe: 1.3e-6 / 1.4e-5 of the peak with the full light march, 3.2e-4 / 1.9e-3
    // with the raw cone (99th percentiles 1.7e-4 / 2.3e-4): at 6.4e6 m a planet-centred f32
    // position has 0.5 m steps, so the slightest difference in a cone offset (an FMA where
    // Rust rounds twice) can move a sample by one step; transmittance 2.0e-6.
    assert!(worst_radiance < 5e-3, "{worst_radiance}");
    assert!(worst_transmittance < 2e-5, "{worst_transmittance}");
}

/// A read-only storage buffer holding `values` (the per-pixel `max_distance`).
fn distance_buffer(gpu: &skyscape_harness::GpuContext, values: &[f32]) -> wgpu::Buffer {
    let buffer = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("test max_distance"),
        size: (values.len() * 4) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    gpu.queue
        .write_buffer(&buffer, 0, bytemuck::cast_slice(values));
    buffer
}

/// Per-pixel distance to the plane through `point` with normal `normal` along each
/// pixel's f32 ray (`+∞` where the ray runs away from it), every seventh pixel 0.
fn plane_distances(
    camera: &PinholeCamera,
    size: [u32; 2],
    point: [f64; 3],
    normal: [f64; 3],
) -> Vec<f32> {
    use cloudlight::march::pixel_direction;
    let [forward, right, up] = camera.basis().map(|v| v.map(|c| c as f32));
    let tan_half = camera.tan_half(size).map(|c| c as f32);
    let o = camera.origin();
    let mut out = Vec::new();
    for y in 0..size[1] {
        for x in 0..size[0] {
            let d = pixel_direction([x, y], size, forward, right, up, tan_half).map(f64::from);
            let dn: f64 = (0..3).map(|a| d[a] * normal[a]).sum();
            let pn: f64 = (0..3).map(|a| (point[a] - o[a]) * normal[a]).sum();
            let t = pn / dn;
            out.push(if (x + size[0] * y) % 7 == 3 {
                0.0
            } else if dn != 0.0 && t > 0.0 {
                t as f32
            } else {
                f32::INFINITY
            });
        }
    }
    out
}

#[test]
fn march_passes_with_a_distance_buffer_match_render_image_limited() {
    use cloudlight::gpu::MarchShellPass;
    use cloudlight::march::{faded, render_image_limited};
    use cloudlight::{CloudShell, ShellSettings};
    let Some(gpu) = skyscape_harness::gpu_or_skip(
        "march_passes_with_a_distance_buffer_match_render_image_limited",
    ) else {
        return;
    };
    let size = [32, 24];
    let settings = MarchSettings::new(MarchConfig {
        view_steps: 24,
        jitter: Jitter::InterleavedGradient,
        light: LightMarch::Full {
            steps: NonZeroU32::new(6).unwrap(),
        },
        ..MarchConfig::default()
    })
    .unwrap();
    let lighting = Lighting::<f32>::new(
        [0.5, 0.0, 0.75f64.sqrt()],
        [1.0, 0.95, 0.9],
        [0.05, 0.08, 0.12],
        [0.0, 0.0, 1.0],
    )
    .unwrap();
    let compare = |name: &str,
                   gpu_image: &[MarchResult<f32>],
                   cpu_image: &[MarchResult<f32>],
                   limits: &[f32]| {
        let peak = cpu_image
            .iter()
            .flat_map(|r| r.radiance)
            .fold(0.0f32, f32::max) as f64;
        assert!(peak > 0.0, "{name}: an empty image tests nothing");
        let (mut radiance, mut transmittance) = (0.0f64, 0.0f64);
        let mut clipped_cloudy = 0;
        for (k, (g, c)) in gpu_image.iter().zip(cpu_image).enumerate() {
            for ch in 0..3 {
                radiance = radiance.max((g.radiance[ch] - c.radiance[ch]).abs() as f64 / peak);
            }
            transmittance = transmittance.max((g.transmittance - c.transmittance).abs() as f64);
            if limits[k] == 0.0 {
                assert_eq!(
                    (g.radiance, g.transmittance),
                    ([0.0; 3], 1.0),
                    "{name} pixel {k}"
                );
            } else if limits[k].is_finite() && c.transmittance < 0.999 {
                clipped_cloudy += 1;
            }
        }
        println!(
            "{name} with max_distance vs render_image_limited::<f32>, {}x{} ({clipped_cloudy} \
             cloudy pixels with a finite limit): radiance max |diff|/peak {radiance:.2e}, \
             transmittance max |diff| {transmittance:.2e}",
            size[0], size[1]
        );
        assert!(clipped_cloudy > 50, "{name}: {clipped_cloudy}");
        (radiance, transmittance)
    };

    // The volume, seen from beside it, cut by a tilted wall through its middle.
    let v = lumpy_blob();
    let camera = PinholeCamera::look_at(
        [-1500.0, -300.0, 1300.0],
        [0.0, 0.0, 1400.0],
        [0.0, 0.0, 1.0],
        0.8,
    )
    .unwrap();
    let limits = plane_distances(&camera, size, [0.0, 0.0, 1400.0], [0.9, 0.1, 0.3]);
    let buffer = distance_buffer(gpu, &limits);
    let mut pass = MarchPass::new(&gpu.device).unwrap();
    pass.prepare_limited(
        &gpu.device,
        &gpu.queue,
        &v,
        &camera,
        size,
        &settings,
        &lighting,
        Some(&buffer),
    )
    .unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode_timed(&mut encoder, None).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "march image",
        pass.image_buffer().unwrap(),
        0,
        pass.image_size(),
    )
    .unwrap();
    let gpu_image = pass.decode(&bytes).unwrap();
    let cpu_image =
        render_image_limited::<f32>(&v, &camera, size, &settings, &lighting, &limits).unwrap();
    let unlimited = render_image::<f32>(&v, &camera, size, &settings, &lighting);
    assert!(
        cpu_image
            .iter()
            .zip(&unlimited)
            .filter(|(a, b)| a != b)
            .count()
            > 100
    );
    let (radiance, transmittance) = compare("march pass", &gpu_image, &cpu_image, &limits);
    // Lavapipe: as the unlimited pass (8.1e-7, 9.5e-7).
    assert!(radiance < 2e-5, "{radiance}");
    assert!(transmittance < 1e-5, "{transmittance}");

    // A buffer with too few values is an error naming its size.
    let short = distance_buffer(gpu, &limits[..10]);
    let err = pass
        .prepare_limited(
            &gpu.device,
            &gpu.queue,
            &v,
            &camera,
            size,
            &settings,
            &lighting,
            Some(&short),
        )
        .unwrap_err();
    assert!(
        matches!(
            err,
            MarchGpuError::DistanceBuffer {
                bytes: 40,
                needed: 3072,
                ..
            }
        ),
        "{err}"
    );

    // The shell from the ground looking up at 30°, cut by a ridge 4 km away.
    let earth = atmos::Atmosphere::earth();
    let r = earth.planet_radius;
    let shell = CloudShell::new(&earth, ShellSettings::cumulus_over(r)).unwrap();
    let camera = PinholeCamera::look_at(
        [0.0, 0.0, r + 2.0],
        [8660.0, 0.0, r + 5000.0],
        [0.0, 0.0, 1.0],
        1.2,
    )
    .unwrap();
    let limits = plane_distances(&camera, size, [4000.0, 0.0, r], [1.0, 0.0, -0.2]);
    let buffer = distance_buffer(gpu, &limits);
    let mut pass = MarchShellPass::new(&gpu.device).unwrap();
    pass.prepare_limited(
        &gpu.device,
        &gpu.queue,
        &shell,
        &camera,
        size,
        &settings,
        &lighting,
        Some(&buffer),
    )
    .unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode_timed(&mut encoder, None).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let bytes = skyscape_harness::read_buffer(
        gpu,
        "march shell image",
        pass.image_buffer().unwrap(),
        0,
        pass.image_size(),
    )
    .unwrap();
    let gpu_image = pass.decode(&bytes).unwrap();
    let cpu_image: Vec<MarchResult<f32>> =
        render_image_limited::<f32>(&shell, &camera, size, &settings, &lighting, &limits)
            .unwrap()
            .into_iter()
            .map(|r| faded(r, shell.horizon_fade(r.depth)))
            .collect();
    let unlimited = render_image::<f32>(&shell, &camera, size, &settings, &lighting);
    let changed = cpu_image
        .iter()
        .zip(&unlimited)
        .filter(|(a, b)| (a.transmittance - b.transmittance).abs() > 1e-3)
        .count();
    assert!(
        changed > 100,
        "the ridge hides cloud in only {changed} pixels"
    );
    let (radiance, transmittance) = compare("march shell pass", &gpu_image, &cpu_image, &limits);
    // Lavapipe: 1.1e-6 of the peak, transmittance 1.0e-6 (the full light march; the
    // unlimited shell test's full-march bound is 1.4e-5).
    assert!(radiance < 5e-5, "{radiance}");
    assert!(transmittance < 2e-5, "{transmittance}");
}
