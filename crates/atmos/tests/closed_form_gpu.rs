//! Rung 1 on the GPU against its CPU twin, per pixel and per vertex.

use atmos::closed_form_sky::{
    ClosedFormSkyParameters, closed_form_sky_radiance, closed_form_sky_transmittance,
    closed_form_sunlight,
};
use atmos::frame::{FrameCamera, frame_view_direction};
use atmos::gpu::{ClosedFormRenderer, EvaluationFrequency, FrameOutput};
use atmos::ladder::{SkyModel, SkyQuery};
use atmos::{Atmosphere, dome::DomeInterpolated, dome::DomeResolution};
use glam::DVec3;

const WIDTH: u32 = 32;
const HEIGHT: u32 = 18;

fn camera(altitude: f64, pitch: f64) -> FrameCamera {
    let earth = Atmosphere::earth();
    let forward = DVec3::new(pitch.cos(), 0.0, pitch.sin());
    FrameCamera::look_at(
        DVec3::new(0.0, 0.0, earth.planet_radius + altitude),
        forward,
        DVec3::Z,
        1.6,
        WIDTH,
        HEIGHT,
        DVec3::new(0.3, 0.4, 0.2).normalize(),
        None,
    )
    .unwrap()
}

fn render(
    gpu: &skyscape_harness::GpuContext,
    frequency: EvaluationFrequency,
    camera: &FrameCamera,
) -> (Vec<[f32; 4]>, Vec<[f32; 4]>) {
    let mut renderer =
        ClosedFormRenderer::new(&gpu.device, &Atmosphere::earth(), frequency).unwrap();
    let output = FrameOutput::new(&gpu.device, WIDTH, HEIGHT).unwrap();
    renderer.prepare(&gpu.queue, camera, &output).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    renderer.encode(&mut encoder, None).unwrap();
    gpu.queue.submit([encoder.finish()]);
    let read = |texture| {
        let raw = skyscape_harness::read_texture(gpu, "frame", texture).unwrap();
        bytemuck::cast_slice::<u8, [f32; 4]>(&raw).to_vec()
    };
    (read(output.radiance()), read(output.transmittance()))
}

#[test]
fn per_pixel_matches_the_cpu_twin() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("atmos::closed_form per pixel") else {
        return;
    };
    let params = ClosedFormSkyParameters::from_atmosphere(&Atmosphere::earth()).unwrap();
    for (altitude, pitch) in [(2.0, 0.1), (20_000.0, -0.4), (500_000.0, -1.2)] {
        let cam = camera(altitude, pitch);
        let (radiance, transmittance) = render(gpu, EvaluationFrequency::PerPixel, &cam);
        let r =
            (cam.position[0].powi(2) + cam.position[1].powi(2) + cam.position[2].powi(2)).sqrt();
        let up = cam.position.map(|c| c / r);
        let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let mut worst = 0.0f32;
        for y in 0..HEIGHT {
            for x in 0..WIDTH {
                let view = frame_view_direction([x, y], &cam);
                let sunlight = closed_form_sunlight(r, dot(cam.sun, up), &params);
                let cpu = closed_form_sky_radiance(
                    r,
                    dot(view, up),
                    dot(cam.sun, up),
                    dot(view, cam.sun),
                    cam.max_distance,
                    sunlight,
                    &params,
                );
                let cpu_t =
                    closed_form_sky_transmittance(r, dot(view, up), cam.max_distance, &params);
                let i = (x + WIDTH * y) as usize;
                for c in 0..3 {
                    // Near-tangent rays make the path length ill-conditioned in f32
                    // (see the ray_sphere_intersect parity case); compare with a
                    // tolerance relative to the frame's brightest value.
                    let scale = cpu[c].abs().max(1e-3);
                    worst = worst.max((radiance[i][c] - cpu[c]).abs() / scale);
                    assert!((transmittance[i][c] - cpu_t[c]).abs() < 2e-3, "{x},{y}");
                }
            }
        }
        assert!(
            worst < 2e-3,
            "altitude {altitude}: worst relative difference {worst}"
        );
    }
}

/// A 1,000 km camera above the terminator (sun on its horizon) looking down at the
/// night side: the GPU applies the planet's shadow as the CPU twin does, and the frame
/// is dark, not lit by the sunlight at the camera.
#[test]
fn night_side_from_orbit_is_dark_on_the_gpu() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("atmos::closed_form night side") else {
        return;
    };
    let earth = Atmosphere::earth();
    let params = ClosedFormSkyParameters::from_atmosphere(&earth).unwrap();
    let position = DVec3::new(0.0, 0.0, earth.planet_radius + 1.0e6);
    let (down, sun) = (50f64.to_radians(), DVec3::X);
    let look = |toward: f64| {
        FrameCamera::look_at(
            position,
            DVec3::new(toward * down.cos(), 0.0, -down.sin()),
            DVec3::Z,
            0.3,
            WIDTH,
            HEIGHT,
            sun,
            None,
        )
        .unwrap()
    };
    let mean = |pixels: &[[f32; 4]]| {
        pixels
            .iter()
            .map(|p| 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2])
            .sum::<f32>()
            / pixels.len() as f32
    };
    let (night, _) = render(gpu, EvaluationFrequency::PerPixel, &look(-1.0));
    let (day, _) = render(gpu, EvaluationFrequency::PerPixel, &look(1.0));
    let cam = look(-1.0);
    let r = position.length() as f32;
    let mut worst = 0.0f32;
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let view = frame_view_direction([x, y], &cam);
            let sunlight = closed_form_sunlight(r, 0.0, &params);
            let cpu = closed_form_sky_radiance(
                r,
                view[2],
                0.0,
                view[0],
                cam.max_distance,
                sunlight,
                &params,
            );
            let gpu_value = night[(x + WIDTH * y) as usize];
            for c in 0..3 {
                worst = worst.max((gpu_value[c] - cpu[c]).abs() / cpu[c].abs().max(1e-3));
            }
        }
    }
    let (night, day) = (mean(&night), mean(&day));
    eprintln!("night side {night:.3e}, day side {day:.3e}, GPU vs CPU worst {worst:.2e}");
    assert!(worst < 2e-3, "GPU vs CPU worst relative difference {worst}");
    assert!(
        night < 0.02 * day,
        "night side {night:e} vs day side {day:e}"
    );
}

#[test]
fn per_vertex_matches_the_cpu_dome() {
    let Some(gpu) = skyscape_harness::gpu_or_skip("atmos::closed_form per vertex") else {
        return;
    };
    let earth = Atmosphere::earth();
    let resolution = DomeResolution {
        rings: 8,
        segments: 16,
    };
    let dome = DomeInterpolated::new(
        atmos::closed_form_sky::ClosedFormSky::new(&earth).unwrap(),
        resolution,
        &earth,
    )
    .unwrap();
    // On the ground, inside the atmosphere and above it (the dome's rows then cover the
    // band between the horizon and the atmosphere's limb).
    for (altitude, pitch) in [(2.0, 0.2), (20_000.0, -0.3), (1.0e6, -0.55)] {
        let cam = camera(altitude, pitch);
        let (radiance, _) = render(gpu, EvaluationFrequency::PerVertex(resolution), &cam);
        let position = DVec3::from_array(cam.position.map(f64::from));
        let sun = DVec3::from_array(cam.sun.map(f64::from)).normalize();
        let cpu: Vec<[f64; 3]> = (0..HEIGHT)
            .flat_map(|y| (0..WIDTH).map(move |x| (x, y)))
            .map(|(x, y)| {
                let view = DVec3::from_array(frame_view_direction([x, y], &cam).map(f64::from));
                let q =
                    SkyQuery::new(earth.planet_radius, position, view.normalize(), sun).unwrap();
                dome.evaluate(&q).radiance
            })
            .collect();
        // The GPU evaluates the vertices in f32: near-tangent rays (the horizon, and the
        // limb seen from above the atmosphere, where the rows crowd) lose digits in f32
        // whatever the formula (the ray_sphere_intersect parity case), so differences
        // are relative to the value or to 1 % of the frame's brightest, whichever is larger.
        let brightest = cpu.iter().flatten().fold(0.0f64, |m, v| m.max(*v));
        let mut worst = 0.0f64;
        for (i, cpu) in cpu.iter().enumerate() {
            for c in 0..3 {
                let scale = cpu[c].abs().max(1e-2 * brightest).max(1e-3);
                worst = worst.max((f64::from(radiance[i][c]) - cpu[c]).abs() / scale);
            }
        }
        eprintln!("{altitude} m: worst relative difference {worst:.2e}");
        assert!(
            worst < 1e-3,
            "{altitude} m: worst relative difference {worst}"
        );
    }
}

#[test]
fn encode_reports_a_missing_prepare_and_prepare_a_mismatched_output() {
    let Some(gpu) = skyscape_harness::gpu_or_skip(
        "atmos::closed_form_gpu encode_reports_a_missing_prepare_and_prepare_a_mismatched_output",
    ) else {
        return;
    };
    let mut renderer = ClosedFormRenderer::new(
        &gpu.device,
        &Atmosphere::earth(),
        EvaluationFrequency::PerPixel,
    )
    .unwrap();
    let output = FrameOutput::new(&gpu.device, WIDTH, HEIGHT).unwrap();
    let mut encoder = gpu.device.create_command_encoder(&Default::default());
    let error = renderer.encode(&mut encoder, None).unwrap_err();
    assert!(error.to_string().contains("before prepare"), "{error}");
    let small = FrameOutput::new(&gpu.device, WIDTH / 2, HEIGHT).unwrap();
    let mismatch = renderer
        .prepare(&gpu.queue, &camera(2.0, 0.1), &small)
        .unwrap_err();
    assert!(
        mismatch.to_string().contains("does not match"),
        "{mismatch}"
    );
    // A failed prepare leaves nothing prepared.
    assert!(renderer.encode(&mut encoder, None).is_err());
    renderer
        .prepare(&gpu.queue, &camera(2.0, 0.1), &output)
        .unwrap();
    renderer.encode(&mut encoder, None).unwrap();
    gpu.queue.submit([encoder.finish()]);
}
