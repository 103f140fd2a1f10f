//! The default sky on the GPU and on its CPU twin agree: ≥ 99.9 % of pixels within
//! 2 LSB per channel. Kept small (software rasterisers are slow).

use render::SkyScene;

fn gpu_sky(gpu: &skyscape_harness::GpuContext, scene: &SkyScene) -> Vec<u32> {
    let mut sky = render::gpu::SkyRenderer::new(&gpu.device).expect("sky pass compiles");
    sky.prepare(&gpu.device, &gpu.queue, scene)
        .expect("scene is valid");
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    sky.encode(&mut encoder).expect("prepared");
    gpu.queue.submit([encoder.finish()]);
    let size = u64::from(scene.width) * u64::from(scene.height) * 4;
    let bytes =
        skyscape_harness::read_buffer(gpu, "sky pixels", sky.pixel_buffer().unwrap(), 0, size)
            .expect("readback");
    bytemuck::cast_slice(&bytes).to_vec()
}

fn scenes() -> Vec<(&'static str, SkyScene)> {
    let small = SkyScene {
        width: 192,
        height: 108,
        ..SkyScene::default()
    };
    vec![
        ("default", small.clone()),
        (
            "low sun, hazy, wide",
            SkyScene {
                sun_elevation: 0.03,
                vertical_fov: 2.5,
                atmosphere: render::ClosedFormAtmosphere {
                    mie_scattering: 4e-5,
                    ..Default::default()
                },
                ..small.clone()
            },
        ),
        (
            "from 20 km (above the homogeneous shell)",
            SkyScene {
                camera_altitude: 20_000.0,
                camera_elevation: -0.6,
                ..small
            },
        ),
    ]
}

#[test]
fn gpu_and_cpu_sky_images_agree() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("sky_image::gpu_and_cpu_sky_images_agree") else {
        return;
    };
    for (name, scene) in scenes() {
        let cpu = render::sky::render_sky_cpu(&scene).unwrap();
        let gpu_pixels = gpu_sky(gpu, &scene);
        let within = render::tonemap::fraction_within_lsb(&cpu, &gpu_pixels, 2).unwrap();
        assert!(
            within >= 0.999,
            "{name}: only {:.4} % of pixels within 2 LSB",
            within * 100.0
        );
    }
}

#[test]
fn comparison_detects_a_different_image() {
    // The agreement measure is not vacuous: a changed exposure is caught.
    let scene = SkyScene {
        width: 64,
        height: 36,
        ..SkyScene::default()
    };
    let a = render::sky::render_sky_cpu(&scene).unwrap();
    let b = render::sky::render_sky_cpu(&SkyScene {
        exposure: 22.0,
        ..scene
    })
    .unwrap();
    assert!(render::tonemap::fraction_within_lsb(&a, &b, 2).unwrap() < 0.999);
}

#[test]
fn default_image_looks_like_a_daytime_sky() {
    // Blue zenith-ward sky (B > G > R at the top row), a brighter horizon band, the
    // sun glow brighter than the sky away from the sun.
    let scene = SkyScene {
        width: 192,
        height: 108,
        ..SkyScene::default()
    };
    let pixels = render::sky::render_sky_cpu(&scene).unwrap();
    let rgb = |x: u32, y: u32| {
        let p = pixels[(y * scene.width + x) as usize].to_le_bytes();
        [f32::from(p[0]), f32::from(p[1]), f32::from(p[2])]
    };
    let luma = |c: [f32; 3]| 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    let top = rgb(20, 0);
    assert!(top[2] > top[1] && top[1] > top[0], "top-left {top:?}");
    // The horizon sits around row 77 for this camera; a row just above it.
    let horizon = rgb(20, 74);
    assert!(
        luma(horizon) > luma(top) * 1.3,
        "horizon {horizon:?} vs top {top:?}"
    );
    // Find the sun direction's pixel: brightest in the sky region.
    let (mut best, mut best_xy) = (0.0, (0, 0));
    for y in 0..70 {
        for x in 0..scene.width {
            let l = luma(rgb(x, y));
            if l > best {
                best = l;
                best_xy = (x, y);
            }
        }
    }
    let glow = rgb(best_xy.0.saturating_sub(6), best_xy.1);
    assert!(luma(glow) > luma(rgb(20, best_xy.1)) * 1.2, "glow {glow:?}");
}
