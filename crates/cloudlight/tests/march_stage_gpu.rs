//! The view march's two stages on a GPU (`cloudlight::gpu::MarchStage`): `new` chooses
//! the one the adapter supports, and the fragment and compute stages write the same
//! output, bit for bit, since both call one WGSL function per pixel (skipped without an
//! adapter, see skyscape-harness).
#![cfg(feature = "gpu")]

use std::num::NonZeroU32;

use cloudlight::cone::ConeWeights;
use cloudlight::gpu::{
    FieldMarchPass, MarchGpuError, MarchPass, MarchShellPass, MarchStage, MarchedField,
};
use cloudlight::march::{
    Jitter, LightMarch, Lighting, MarchConfig, MarchSettings, Octaves, PinholeCamera,
};
use cloudlight::{CloudShell, ShellSettings};

mod common;

use common::lumpy_blob;

/// The output buffer's bytes after one march of `field` on `pass`'s stage, stopped at
/// `max_distance` when given.
#[allow(clippy::too_many_arguments)] // the pass, the twin's five inputs, the limit
fn march_bytes<F: MarchedField>(
    gpu: &skyscape_harness::GpuContext,
    pass: &mut FieldMarchPass<F>,
    field: &F,
    camera: &PinholeCamera,
    size: [u32; 2],
    settings: &MarchSettings,
    lighting: &Lighting<f32>,
    max_distance: Option<&wgpu::Buffer>,
) -> Vec<u8> {
    pass.prepare_limited(
        &gpu.device,
        &gpu.queue,
        field,
        camera,
        size,
        settings,
        lighting,
        max_distance,
    )
    .unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    pass.encode(&mut encoder).unwrap();
    gpu.queue.submit([encoder.finish()]);
    skyscape_harness::read_buffer(
        gpu,
        "march stage image",
        pass.image_buffer().unwrap(),
        0,
        pass.image_size(),
    )
    .unwrap()
}

/// Pixels (32 bytes each) whose bytes differ.
fn differing_pixels(a: &[u8], b: &[u8]) -> usize {
    assert_eq!(a.len(), b.len());
    a.chunks_exact(32)
        .zip(b.chunks_exact(32))
        .filter(|(x, y)| x != y)
        .count()
}

/// Pixels (32 bytes each) of `image` with some cloud (transmittance below 0.999).
fn cloudy_pixels(image: &[u8]) -> usize {
    image
        .chunks_exact(32)
        .filter(|p| f32::from_ne_bytes([p[12], p[13], p[14], p[15]]) < 0.999)
        .count()
}

#[test]
fn new_chooses_the_stage_the_adapter_supports() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("march stage choice") else {
        return;
    };
    let supported = MarchStage::supported(&gpu.adapter.get_downlevel_capabilities());
    eprintln!(
        "{}: the march runs on the {supported} stage",
        skyscape_harness::describe_adapter(&gpu.info)
    );
    assert_eq!(MarchPass::new(&gpu.device).unwrap().stage(), supported);
    assert_eq!(MarchShellPass::new(&gpu.device).unwrap().stage(), supported);
    // The compute stage builds everywhere the march runs; the fragment stage exactly
    // where the adapter's flags allow it, otherwise the device's refusal is an error.
    let compute = MarchPass::with_stage(&gpu.device, MarchStage::Compute).unwrap();
    assert_eq!(compute.stage(), MarchStage::Compute);
    match MarchPass::with_stage(&gpu.device, MarchStage::Fragment) {
        Ok(pass) => {
            assert_eq!(supported, MarchStage::Fragment);
            assert_eq!(pass.stage(), MarchStage::Fragment);
        }
        Err(error) => {
            assert_eq!(supported, MarchStage::Compute, "{error}");
            assert!(
                matches!(
                    error,
                    MarchGpuError::Pipeline {
                        stage: MarchStage::Fragment,
                        ..
                    }
                ),
                "{error}"
            );
        }
    }
}

#[test]
fn an_image_beyond_the_stage_limit_is_an_error_naming_it() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("march stage image size") else {
        return;
    };
    let camera = PinholeCamera::look_at([0.0; 3], [0.0, 0.0, 1.0], [0.0, 1.0, 0.0], 1.0).unwrap();
    let lighting = Lighting::<f32>::white_sun([0.0, 0.0, 1.0]).unwrap();
    let limits = gpu.device.limits();
    for (stage, limit) in [
        (MarchStage::Fragment, limits.max_texture_dimension_2d),
        (
            MarchStage::Compute,
            limits.max_compute_workgroups_per_dimension * 8,
        ),
    ] {
        let Ok(mut pass) = MarchPass::with_stage(&gpu.device, stage) else {
            continue;
        };
        let err = pass
            .prepare(
                &gpu.device,
                &gpu.queue,
                &lumpy_blob(),
                &camera,
                [4, limit + 1],
                &MarchSettings::default(),
                &lighting,
            )
            .unwrap_err();
        let expected = limit + 1;
        assert!(
            matches!(
                err,
                MarchGpuError::ImageSize { field: "size.y", value, stage: s, limit: l }
                    if value == expected && s == stage && l == limit
            ),
            "{err}"
        );
    }
}

#[test]
fn the_fragment_and_compute_stages_write_the_same_bits() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("march stages agree") else {
        return;
    };
    let Ok(mut fragment) = MarchPass::with_stage(&gpu.device, MarchStage::Fragment) else {
        eprintln!("march stages agree: no fragment stage on this adapter; nothing to compare");
        return;
    };
    let mut compute = MarchPass::with_stage(&gpu.device, MarchStage::Compute).unwrap();
    // Not a multiple of the compute stage's 8×8 workgroups: its edge invocations return.
    let size = [37, 29];
    let lighting = Lighting::<f32>::new(
        [0.5, 0.1, 0.86],
        [1.0, 0.95, 0.9],
        [0.05, 0.08, 0.12],
        [0.0, 0.0, 1.0],
    )
    .unwrap();
    let volume = lumpy_blob();
    let camera = PinholeCamera::look_at(
        [-1500.0, -300.0, 1300.0],
        [0.0, 0.0, 1400.0],
        [0.0, 0.0, 1.0],
        0.8,
    )
    .unwrap();
    let configs = [
        MarchConfig {
            view_steps: 24,
            jitter: Jitter::Bayer4x4,
            light: LightMarch::Cone {
                step: 40.0,
                spread: 0.2,
                weights: ConeWeights::Partitioned,
            },
            powder: true,
            ..MarchConfig::default()
        },
        MarchConfig {
            view_steps: 16,
            jitter: Jitter::InterleavedGradient,
            light: LightMarch::Full {
                steps: NonZeroU32::new(6).unwrap(),
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
    ]
    .map(|c| MarchSettings::new(c).unwrap());
    // Every pixel's march stopped 1700 m along its ray, every fifth at 0.
    let limits: Vec<f32> = (0..size[0] * size[1])
        .map(|i| if i % 5 == 2 { 0.0 } else { 1700.0 })
        .collect();
    let distances = gpu.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("march stages max_distance"),
        size: (limits.len() * 4) as u64,
        usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    });
    gpu.queue
        .write_buffer(&distances, 0, bytemuck::cast_slice(&limits));
    let mut compared = 0;
    for (j, settings) in configs.iter().enumerate() {
        for limit in [None, Some(&distances)] {
            let on = |pass: &mut MarchPass| {
                march_bytes(
                    gpu, pass, &volume, &camera, size, settings, &lighting, limit,
                )
            };
            let (a, b) = (on(&mut fragment), on(&mut compute));
            assert!(
                cloudy_pixels(&a) > 100,
                "config {j}: too little cloud to compare"
            );
            assert_eq!(
                differing_pixels(&a, &b),
                0,
                "volume, config {j}, limited {}",
                limit.is_some()
            );
            compared += a.len() / 32;
        }
    }

    // The shell from the ground looking up at 30°, faded toward the horizon.
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
    let mut fragment = MarchShellPass::with_stage(&gpu.device, MarchStage::Fragment).unwrap();
    let mut compute = MarchShellPass::with_stage(&gpu.device, MarchStage::Compute).unwrap();
    let on = |pass: &mut MarchShellPass| {
        march_bytes(
            gpu,
            pass,
            &shell,
            &camera,
            size,
            &configs[0],
            &lighting,
            None,
        )
    };
    let (a, b) = (on(&mut fragment), on(&mut compute));
    assert!(
        cloudy_pixels(&a) > 100,
        "shell: too little cloud to compare"
    );
    assert_eq!(differing_pixels(&a, &b), 0, "shell");
    compared += a.len() / 32;
    eprintln!(
        "{}: fragment and compute stages identical over {compared} pixels (5 images {}x{})",
        skyscape_harness::describe_adapter(&gpu.info),
        size[0],
        size[1]
    );
}
